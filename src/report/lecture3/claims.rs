//! What the sources say (the VRST 2006 and Visual Computer 2008 abstracts, the lecture's
//! programme), judged on this run. The texts are not available: each claim is the abstract's
//! or the programme's, in our words.

use super::prefilter::PrefilterRow;
use super::results::{DepthMaskRow, Lecture3Results, LightRun};
use crate::lecture3::depth_mask::{runs_fit_mask, RunCounter};
use crate::report::versions::TIMING_POLICY;
use crate::report::{Basis, Claim, ClaimDef, Evidence};
use crate::timing::{end, faster, judge_ends, Ends, Load};

/// Every claim of the section, with what decides it.
pub const CLAIMS: &[ClaimDef] = &[
    PYRAMID_EXACT,
    ARTIFACT_FREE,
    FRAME_RATE,
    RESOLUTION,
    PREFILTER_QUALITY,
    PREFILTER_QUALITY_GRAZING,
    PREFILTER_SPEED,
    LIGHT_GROUPS,
    LIGHT_USES,
    LOOKUP_CHEAPER,
    RANDOM_NUMBERS,
    DEPTH_MASK,
    DEPTH_MASK_TIME,
    BLENDING_HISTOGRAM,
];

pub fn claims(r: &Lecture3Results) -> Vec<Claim> {
    vec![
        pyramids_are_exact(r),
        artifact_free(r),
        frame_rate(r),
        resolution_independence(r),
        prefilter_quality(&r.prefilter, false),
        prefilter_quality(&r.prefilter, true),
        prefilter_speed(&r.prefilter, r.load),
        few_light_groups(&r.light),
        other_uses(&r.light_uses),
        lookup_cheaper(r),
        random_numbers(r),
        depth_test_masks(r),
        depth_test_saves_time(r),
        blending_histogram(r),
    ]
}

// region: rule pyramid-exact
/// Technique 1: image pyramids built on the GPU as the CPU builds them.
const PYRAMID_EXACT: ClaimDef = ClaimDef {
    id: "lecture3.pyramid-exact",
    rule: &["src/report/lecture3/claims.rs#rule pyramid-exact"],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload pyramid"],
    band: None,
};

/// The largest |GPU - CPU| a mean pyramid of a 0..1 map may show: fp32 rounding of one
/// weighted mean per level (a few units of 6e-8), over up to 12 levels, with margin.
const MEAN_PYRAMID_TOL: f64 = 1e-5;

fn pyramids_are_exact(r: &Lecture3Results) -> Claim {
    let all = r.pyramid.iter().all(|p| p.equal_to_cpu);
    let means = r
        .pyramid
        .iter()
        .all(|p| p.mean_max_error <= MEAN_PYRAMID_TOL);
    let worst_mean = r
        .pyramid
        .iter()
        .map(|p| p.mean_max_error)
        .fold(0.0, f64::max);
    Claim {
        id: PYRAMID_EXACT.id.into(),
        claim: "1. An image pyramid is built on the GPU, each level from the one below".into(),
        paper: "lecture 3: image pyramids (no numbers)".into(),
        measured: format!(
            "max and min pyramids of {} map sizes (up to {}x{}) equal to the CPU's bit for bit: \
             {}; mean pyramids within {:.1e} of the CPU's f64 means (allowed {:.0e})",
            r.pyramid.len(),
            r.pyramid.last().map_or(0, |p| p.size),
            r.pyramid.last().map_or(0, |p| p.size),
            if all { "all" } else { "NOT all" },
            worst_mean,
            MEAN_PYRAMID_TOL
        ),
        decided_by: Basis::Error,
        holds: Some(all && means),
        evidence: vec![
            Evidence::exact("max and min pyramids equal to the CPU's bit for bit", all),
            Evidence::error(
                "mean pyramids, largest difference from the CPU's",
                worst_mean,
                MEAN_PYRAMID_TOL,
            ),
        ],
        ..Claim::default()
    }
}
// endregion

// region: rule artifact-free
/// VRST 2006: pyramidal displacement mapping free of artifacts at grazing angles.
const ARTIFACT_FREE: ClaimDef = ClaimDef {
    id: "lecture3.displacement-artifact-free",
    rule: &["src/report/lecture3/claims.rs#rule artifact-free"],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload displacement-views"],
    band: None,
};

fn artifact_free(r: &Lecture3Results) -> Claim {
    let d = &r.displacement;
    let pyramid_wrong: usize = d
        .artifacts
        .iter()
        .map(|a| {
            let c = &a.methods[0].comparison;
            c.wrong_surface + c.outside_tolerance + c.wrong_kind + c.wrong_normal + c.wrong_colour
        })
        .sum();
    let compared: usize = d
        .artifacts
        .iter()
        .map(|a| a.methods[0].comparison.compared)
        .sum();
    let relief = d
        .artifacts
        .iter()
        .map(|a| {
            format!(
                "{} deg: {}",
                a.elevation,
                a.methods[1..]
                    .iter()
                    .map(|m| m.comparison.wrong_surface.to_string())
                    .collect::<Vec<_>>()
                    .join(" / ")
            )
        })
        .collect::<Vec<_>>()
        .join(", ");
    Claim {
        id: ARTIFACT_FREE.id.into(),
        claim: "2. Pyramidal displacement mapping is free of artifacts, even at grazing angles"
            .into(),
        paper: "VRST 2006 abstract: correct images at steep grazing angles, unlike linear \
                search"
            .into(),
        measured: format!(
            "pyramid traversal: {pyramid_wrong} of {compared} compared pixels off the exact hit \
             or drawn otherwise (wall for surface, normal, colour) over {} elevations down to \
             {} degrees; relief mapping ({}) on the wrong surface: {relief}",
            d.artifacts.len(),
            d.artifacts.last().map_or(0.0, |a| a.elevation),
            d.artifacts
                .first()
                .map(|a| a.methods[1..]
                    .iter()
                    .map(|m| m.method.clone())
                    .collect::<Vec<_>>()
                    .join(" / "))
                .unwrap_or_default()
        ),
        decided_by: Basis::Count,
        holds: Some(pyramid_wrong == 0),
        evidence: vec![
            Evidence::count(
                "pyramid traversal: pixels off the exact hit or drawn otherwise",
                pyramid_wrong as f64,
            ),
            Evidence::count("pixels compared", compared as f64),
        ],
        ..Claim::default()
    }
}
// endregion

// region: rule frame-rate
/// VRST 2006: pyramidal displacement mapping at hundreds of frames per second.
const FRAME_RATE: ClaimDef = ClaimDef {
    id: "lecture3.displacement-frame-rate",
    rule: &[
        "src/report/lecture3/claims.rs#rule frame-rate",
        TIMING_POLICY,
    ],
    published: &[],
    workload: &[
        "src/report/lecture3/bench.rs#workload displacement-views",
        "src/report/lecture3/bench.rs#workload displacement-maps",
    ],
    band: Some(0.25),
};

fn frame_rate(r: &Lecture3Results) -> Claim {
    let d = &r.displacement;
    let best = d.speed.first();
    let fps = best.map_or(0.0, |s| 1e3 / s.pyramid_ms);
    let runs = best.map_or("no run".to_string(), |s| s.pyramid_spread.in_words(" ms"));
    let verdict = judge_ends(
        Ends::of(|favour| best.is_some_and(|s| 1e3 / end(&s.pyramid_spread, !favour) >= 100.0)),
        &runs,
        "the runs fall on both sides of 100 frames/s",
        r.load,
    );
    Claim {
        id: FRAME_RATE.id.into(),
        claim: "2. Pyramidal displacement mapping runs at hundreds of frames per second".into(),
        paper: "VRST 2006 abstract (GPUs of 2006, their screen sizes)".into(),
        measured: format!(
            "{fps:.0} frames/s of GPU time at {0}x{0} pixels with the {1}x{1} map on {2} ({3})",
            d.image,
            best.map_or(0, |s| s.map_size),
            r.renderer,
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: vec![FRAME_RATE.timing(
            "frames per second of GPU time, the smallest map",
            fps,
            " frames/s",
            true,
            r.load,
        )],
        ..Claim::default()
    }
}
// endregion

// region: rule resolution
/// VRST 2006: speed nearly independent of the map's resolution.
const RESOLUTION: ClaimDef = ClaimDef {
    id: "lecture3.displacement-resolution-independent",
    rule: &[
        "src/report/lecture3/claims.rs#rule resolution",
        TIMING_POLICY,
    ],
    published: &[],
    workload: &[
        "src/report/lecture3/bench.rs#workload displacement-views",
        "src/report/lecture3/bench.rs#workload displacement-maps",
    ],
    band: Some(0.25),
};

fn resolution_independence(r: &Lecture3Results) -> Claim {
    let s = &r.displacement.speed;
    let (first, last) = (s.first(), s.last());
    let (time_ratio, cpu_ratio, side_ratio, it) = match (first, last) {
        (Some(a), Some(b)) => (
            b.pyramid_ms / a.pyramid_ms,
            b.cpu_ms / a.cpu_ms,
            b.map_size as f64 / a.map_size as f64,
            (a.pyramid_iterations, b.pyramid_iterations),
        ),
        _ => (f64::NAN, f64::NAN, f64::NAN, (0.0, 0.0)),
    };
    // The growth of the frame time from the ends of both maps' runs: the large map's fastest
    // over the small map's slowest favours the claim.
    let ends = Ends::of(|favour| {
        first.zip(last).is_some_and(|(a, b)| {
            end(&b.pyramid_spread, !favour) / end(&a.pyramid_spread, favour) < side_ratio / 4.0
        })
    });
    let runs = first.zip(last).map_or("no run".to_string(), |(a, b)| {
        format!(
            "{}x{} map {}; {}x{} map {}",
            a.map_size,
            a.map_size,
            a.pyramid_spread.in_words(" ms"),
            b.map_size,
            b.map_size,
            b.pyramid_spread.in_words(" ms")
        )
    });
    let verdict = judge_ends(
        ends,
        &runs,
        "the runs give growths on both sides of a quarter of the side's factor",
        r.load,
    );
    Claim {
        id: RESOLUTION.id.into(),
        claim: "2. Its speed depends little on the map's resolution".into(),
        paper: "VRST 2006 abstract".into(),
        measured: format!(
            "from a {}x{} to a {}x{} map: GPU frame time x{time_ratio:.2}, iterations per pixel \
             {:.1} -> {:.1}, while the exact CPU tracer (a walk over every patch crossed) takes \
             x{cpu_ratio:.1}; judged: frame time grows by less than a quarter of the map side's \
             factor (x{side_ratio:.0}) ({})",
            first.map_or(0, |a| a.map_size),
            first.map_or(0, |a| a.map_size),
            last.map_or(0, |a| a.map_size),
            last.map_or(0, |a| a.map_size),
            it.0,
            it.1,
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: if time_ratio.is_finite() {
            vec![RESOLUTION.timing(
                "GPU frame time, the largest map / the smallest",
                time_ratio,
                "x",
                false,
                r.load,
            )]
        } else {
            Vec::new()
        },
        ..Claim::default()
    }
}
// endregion

// region: rule prefilter-quality
/// VRST 2006: the minification prefilter improves quality.
const PREFILTER_QUALITY: ClaimDef = ClaimDef {
    id: "lecture3.prefilter-quality",
    rule: &["src/report/lecture3/claims.rs#rule prefilter-quality"],
    published: &[],
    workload: &[
        "src/report/lecture3/prefilter.rs#workload prefilter-distances",
        "src/report/lecture3/prefilter.rs#workload prefilter-image",
    ],
    band: None,
};

/// VRST 2006: the minification prefilter improves quality, at grazing views.
const PREFILTER_QUALITY_GRAZING: ClaimDef = ClaimDef {
    id: "lecture3.prefilter-quality-grazing",
    rule: &["src/report/lecture3/claims.rs#rule prefilter-quality"],
    published: &[],
    workload: &[
        "src/report/lecture3/prefilter.rs#workload prefilter-distances",
        "src/report/lecture3/prefilter.rs#workload prefilter-image",
    ],
    band: None,
};

/// The minification prefilter's quality, judged where it acts (some pixel stops above level
/// 0), at the views that are not grazing or (`grazing`) at those that are: its frame is closer
/// to the supersampled unfiltered image than the unfiltered frame is, at every distance.
fn prefilter_quality(rows: &[PrefilterRow], grazing: bool) -> Claim {
    let acting: Vec<&PrefilterRow> = rows
        .iter()
        .filter(|r| r.max_level > 0 && (r.elevation < super::prefilter::GRAZING) == grazing)
        .collect();
    let measured = acting
        .iter()
        .map(|r| {
            format!(
                "{:.0} degrees, distance {:.1} (stop levels up to {}): {:.3} -> {:.3}",
                r.elevation,
                r.distance,
                r.max_level,
                r.quality.unfiltered_error,
                r.quality.prefiltered_error,
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let (claim, views) = if grazing {
        (
            "2. At minification a mipmap-like prefilter improves quality, seen at a grazing angle",
            "grazing views",
        )
    } else {
        (
            "2. At minification a mipmap-like prefilter improves quality",
            "the views",
        )
    };
    // The prefiltered error over the unfiltered, at the view where it helps least: under 1
    // everywhere for the claim.
    let worst = acting
        .iter()
        .map(|r| r.quality.prefiltered_error / r.quality.unfiltered_error)
        .fold(0.0, f64::max);
    let def = if grazing {
        PREFILTER_QUALITY_GRAZING
    } else {
        PREFILTER_QUALITY
    };
    Claim {
        id: def.id.into(),
        claim: claim.into(),
        paper: "VRST 2006 abstract".into(),
        measured: if acting.is_empty() {
            format!("no distance of {views} is far enough for the prefilter to act")
        } else {
            format!(
                "RMS error against {0}x{0} unfiltered rays per pixel averaged, unfiltered -> \
                 prefiltered (prefiltered patches only on the nodes a pixel's footprint \
                 covers, their height range seen from the side included): {measured}",
                acting[0].quality.samples
            )
        },
        decided_by: if acting.is_empty() {
            Basis::RunSize
        } else {
            Basis::Error
        },
        holds: (!acting.is_empty()).then(|| {
            acting
                .iter()
                .all(|r| r.quality.prefiltered_error < r.quality.unfiltered_error)
        }),
        evidence: vec![
            Evidence::count("views where the prefilter acts", acting.len() as f64),
            Evidence::error(
                "prefiltered / unfiltered RMS error, the view where it helps least",
                worst,
                1.0,
            ),
        ],
        ..Claim::default()
    }
}
// endregion

// region: rule prefilter-speed
/// VRST 2006: the prefilter speeds the traversal up.
const PREFILTER_SPEED: ClaimDef = ClaimDef {
    id: "lecture3.prefilter-speed",
    rule: &[
        "src/report/lecture3/claims.rs#rule prefilter-speed",
        TIMING_POLICY,
    ],
    published: &[],
    workload: &[
        "src/report/lecture3/prefilter.rs#workload prefilter-distances",
        "src/report/lecture3/prefilter.rs#workload prefilter-image",
    ],
    band: Some(0.25),
};

/// The minification prefilter's speed, judged where it acts: its hit pixels take fewer
/// traversal steps, and its frames (drawing the shading pyramid included) are faster by the
/// GL timer at both ends of their runs (not judged while the machine is loaded or the runs
/// overlap).
fn prefilter_speed(rows: &[PrefilterRow], load: Option<Load>) -> Claim {
    let acting: Vec<&PrefilterRow> = rows.iter().filter(|r| r.max_level > 0).collect();
    let fewer_steps = acting
        .iter()
        .all(|r| r.quality.prefiltered_steps < r.quality.unfiltered_steps);
    let ends = Ends::of(|favour| {
        acting
            .iter()
            .all(|r| faster(&r.prefiltered_spread, &r.unfiltered_spread, favour))
    });
    let runs = acting
        .iter()
        .map(|r| {
            format!(
                "{:.0} degrees, distance {:.1}: steps per hit pixel {:.1} -> {:.1}, unfiltered {}, \
                 prefiltered {} (of which drawing the shading pyramid toward the camera {})",
                r.elevation,
                r.distance,
                r.quality.unfiltered_steps,
                r.quality.prefiltered_steps,
                r.unfiltered_spread.in_words(" ms"),
                r.prefiltered_spread.in_words(" ms"),
                r.shading_spread.in_words(" ms")
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let verdict = judge_ends(
        ends,
        &runs,
        "the runs of the prefiltered and the unfiltered frames overlap",
        load,
    );
    let more_steps = acting
        .iter()
        .filter(|r| r.quality.prefiltered_steps >= r.quality.unfiltered_steps)
        .count();
    let slowest = acting
        .iter()
        .map(|r| r.prefiltered_ms / r.unfiltered_ms)
        .fold(0.0, f64::max);
    let mut evidence = vec![Evidence::count(
        "views where prefiltered hit pixels take as many steps or more",
        more_steps as f64,
    )];
    if !acting.is_empty() {
        evidence.push(PREFILTER_SPEED.timing(
            "prefiltered / unfiltered frame time, the slowest view",
            slowest,
            "x",
            false,
            load,
        ));
    }
    Claim {
        id: PREFILTER_SPEED.id.into(),
        claim: "2. ... and speed: fewer traversal steps per hit pixel (counted), and frames \
                faster by the GL timer"
            .into(),
        paper: "VRST 2006 abstract".into(),
        measured: if acting.is_empty() {
            "no distance of the sweep is far enough for the prefilter to act (run size)".into()
        } else if !fewer_steps {
            format!(
                "decided by the step counts: the prefiltered frames take as many traversal \
                 steps or more at {more_steps} of {} views, so the claim fails whatever the \
                 timings say. Unfiltered -> prefiltered: {}{}",
                acting.len(),
                verdict.note,
                why_slower(&acting)
            )
        } else {
            format!(
                "fewer steps at every view (counted); decided by the timings: unfiltered -> \
                 prefiltered: {}{}",
                verdict.note,
                why_slower(&acting)
            )
        },
        decided_by: match (acting.is_empty(), fewer_steps) {
            (true, _) => Basis::RunSize,
            (false, false) => Basis::Count,
            (false, true) => Basis::Timing,
        },
        holds: if acting.is_empty() {
            None
        } else if !fewer_steps {
            Some(false)
        } else {
            verdict.holds
        },
        evidence,
        ..Claim::default()
    }
}

/// Why prefiltered frames are slower where they are, from the medians: the steps they save,
/// or drawing the shading pyramid for each view (empty where none is slower).
fn why_slower(acting: &[&PrefilterRow]) -> String {
    let slower: Vec<&&PrefilterRow> = acting
        .iter()
        .filter(|r| r.prefiltered_ms > r.unfiltered_ms)
        .collect();
    if slower.is_empty() {
        return String::new();
    }
    let traversal_faster = slower
        .iter()
        .all(|r| r.prefiltered_ms - r.shading_ms < r.unfiltered_ms);
    if traversal_faster {
        format!(
            ". Where the prefiltered frame is slower ({} of {} views), its traversal alone (its \
             time less the shading pyramid's) is faster: drawing the shading pyramid for each \
             view (one pass over the patches, the mean pyramid's passes, the atlas copies) costs \
             more than the steps save",
            slower.len(),
            acting.len()
        )
    } else {
        format!(
            ". Where the prefiltered frame is slower ({} of {} views), its traversal alone (its \
             time less the shading pyramid's) is not faster either at some view",
            slower.len(),
            acting.len()
        )
    }
}
// endregion

// region: rule light-error
/// The error the light-group claim allows (relative RMS, against every VPL).
const LIGHT_ERROR: f64 = 0.05;
// endregion

// region: rule light-groups
/// Ki & Oh 2008: a few light groups stand in for every light.
const LIGHT_GROUPS: ClaimDef = ClaimDef {
    id: "lecture3.few-light-groups",
    rule: &[
        "src/report/lecture3/claims.rs#rule light-groups",
        "src/report/lecture3/claims.rs#rule light-error",
    ],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload light"],
    band: None,
};

fn few_light_groups(l: &LightRun) -> Claim {
    // The cheapest criterion within the error allowed.
    let row = l
        .rows
        .iter()
        .filter(|row| row.theta > 0.0 && row.relative_rms_error <= LIGHT_ERROR)
        .min_by(|a, b| a.mean_nodes.total_cmp(&b.mean_nodes));
    let mut evidence = vec![Evidence::count(
        "criteria within the error allowed",
        l.rows
            .iter()
            .filter(|row| row.theta > 0.0 && row.relative_rms_error <= LIGHT_ERROR)
            .count() as f64,
    )];
    if let Some(row) = row {
        evidence.push(Evidence::count(
            "nodes visited per receiver, the cheapest criterion",
            row.mean_nodes,
        ));
        evidence.push(Evidence::error(
            "relative RMS error, the cheapest criterion",
            row.relative_rms_error,
            LIGHT_ERROR,
        ));
    }
    Claim {
        id: LIGHT_GROUPS.id.into(),
        claim: "3. A few light groups found by a tree traversal stand in for every light".into(),
        paper: "Ki & Oh 2008 abstract: approximate illumination from a small number of light \
                groups"
            .into(),
        measured: match row {
            Some(row) => format!(
                "the cheapest criterion within {:.0}% relative RMS error, theta {}: {:.0} nodes \
                 visited per receiver for {} VPLs, error {:.1}%, GPU {:.2} ms against {:.2} ms \
                 for every VPL",
                100.0 * LIGHT_ERROR,
                row.theta,
                row.mean_nodes,
                l.vpls,
                100.0 * row.relative_rms_error,
                row.gpu_ms,
                l.brute_gpu_ms
            ),
            None => format!(
                "no criterion stays within {:.0}% relative RMS error (of {} tried)",
                100.0 * LIGHT_ERROR,
                l.rows.iter().filter(|row| row.theta > 0.0).count()
            ),
        },
        // No criterion within the error allowed is a failure of the claim, not a gap.
        decided_by: Basis::Count,
        holds: Some(row.is_some_and(|row| {
            row.mean_nodes < l.vpls as f64 / 4.0
                && row.relative_rms_error < LIGHT_ERROR
                && row.gpu_ms < l.brute_gpu_ms
        })),
        evidence,
        ..Claim::default()
    }
}
// endregion

// region: rule light-uses
/// Ki & Oh 2008: subsurface scattering and environment light from a few light groups.
const LIGHT_USES: ClaimDef = ClaimDef {
    id: "lecture3.light-other-uses",
    rule: &[
        "src/report/lecture3/claims.rs#rule light-uses",
        "src/report/lecture3/claims.rs#rule light-error",
    ],
    published: &[],
    workload: &["src/report/lecture3/light_uses.rs#workload light-uses"],
    band: None,
};

/// Subsurface scattering and environment light: for each, the criterion that sums the fewest
/// lights within the error allowed; the claim holds when both sum under a quarter of their
/// lights.
fn other_uses(u: &super::light_uses::LightUsesRun) -> Claim {
    let best = |run: &super::light_uses::UseRun| {
        run.rows
            .iter()
            .filter(|row| row.theta > 0.0 && row.relative_rms_error <= LIGHT_ERROR)
            .min_by(|a, b| a.mean_gathered.total_cmp(&b.mean_gathered))
            .map(|row| (row.clone(), run.lights))
    };
    let found = [best(&u.subsurface), best(&u.environment)];
    let measured = [&u.subsurface, &u.environment]
        .iter()
        .zip(&found)
        .map(|(run, found)| match found {
            Some((row, lights)) => format!(
                "{}: theta {}, {:.0} summed per receiver for {} lights, error {:.1}%",
                run.mode,
                row.theta,
                row.mean_gathered,
                lights,
                100.0 * row.relative_rms_error
            ),
            None => format!(
                "{}: no criterion within {:.0}% relative RMS error",
                run.mode,
                100.0 * LIGHT_ERROR
            ),
        })
        .collect::<Vec<_>>()
        .join("; ");
    let evidence = [&u.subsurface, &u.environment]
        .iter()
        .zip(&found)
        .map(|(run, found)| {
            Evidence::count(
                &format!(
                    "{}: lights summed per receiver, the cheapest criterion",
                    run.mode
                ),
                found.as_ref().map_or(0.0, |(row, _)| row.mean_gathered),
            )
        })
        .collect();
    Claim {
        id: LIGHT_USES.id.into(),
        claim: "3. The same hierarchy gathers subsurface scattering and environment light from \
                a few light groups"
            .into(),
        paper: "Ki & Oh 2008 abstract: environment light, indirect light and subsurface \
                scattering approximated by a small number of light groups"
            .into(),
        measured,
        decided_by: Basis::Count,
        holds: Some(found.iter().all(|f| {
            f.as_ref()
                .is_some_and(|(row, lights)| row.mean_gathered < *lights as f64 / 4.0)
        })),
        evidence,
        ..Claim::default()
    }
}
// endregion

// region: rule lookup-cheaper
/// Technique 4: a function in a texture, cheaper to look up than to compute.
const LOOKUP_CHEAPER: ClaimDef = ClaimDef {
    id: "lecture3.function-lookup-cheaper",
    rule: &[
        "src/report/lecture3/claims.rs#rule lookup-cheaper",
        TIMING_POLICY,
    ],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload function"],
    band: Some(0.25),
};

fn lookup_cheaper(r: &Lecture3Results) -> Claim {
    let rows = &r.function.speed;
    let last = rows.last();
    let verdict = judge_ends(
        Ends::of(|favour| last.is_some_and(|s| faster(&s.lookup_spread, &s.exact_spread, favour))),
        &last.map_or("no run".to_string(), |s| {
            format!(
                "{}: computed {}, looked up {}",
                s.function,
                s.exact_spread.in_words(" ms"),
                s.lookup_spread.in_words(" ms")
            )
        }),
        "the runs of the lookup and of the computation overlap",
        r.load,
    );
    Claim {
        id: LOOKUP_CHEAPER.id.into(),
        claim: "4. A function stored in a texture is cheaper to look up than to compute".into(),
        paper: "lecture 3: storing a function in a texture (no numbers)".into(),
        measured: format!(
            "{} ({})",
            rows.iter()
                .map(|s| {
                    format!(
                        "{}: computed {:.2} ms, looked up {:.2} ms",
                        s.function, s.exact_ms, s.lookup_ms
                    )
                })
                .collect::<Vec<_>>()
                .join("; "),
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: if last.is_some() { verdict.holds } else { None },
        evidence: last
            .map(|s| {
                LOOKUP_CHEAPER.timing(
                    &format!("{}: looked up / computed time", s.function),
                    s.lookup_ms / s.exact_ms,
                    "x",
                    false,
                    r.load,
                )
            })
            .into_iter()
            .collect(),
        ..Claim::default()
    }
}
// endregion

// region: rule random-numbers
/// Technique 5: random numbers generated into a texture.
const RANDOM_NUMBERS: ClaimDef = ClaimDef {
    id: "lecture3.random-numbers",
    rule: &["src/report/lecture3/claims.rs#rule random-numbers"],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload random"],
    band: None,
};

fn random_numbers(r: &Lecture3Results) -> Claim {
    let x = &r.random;
    let pass = x.bit_exact
        && x.chi_square < x.chi_square_critical
        && x.serial_correlation.abs() < x.correlation_bound
        && x.neighbour_correlation.abs() < x.correlation_bound;
    Claim {
        id: RANDOM_NUMBERS.id.into(),
        claim: "5. Random numbers can be generated into a texture by render passes".into(),
        paper: "lecture 3: generating random numbers into a texture (no numbers)".into(),
        measured: format!(
            "bit-exact with the CPU generator: {}; chi-square {:.1} (< {:.1}); correlations \
             {:.1e} and {:.1e} (|r| < {:.1e})",
            x.bit_exact,
            x.chi_square,
            x.chi_square_critical,
            x.serial_correlation,
            x.neighbour_correlation,
            x.correlation_bound
        ),
        decided_by: Basis::Count,
        holds: Some(pass),
        evidence: vec![
            Evidence::exact("bit-exact with the CPU generator", x.bit_exact),
            Evidence::count("chi-square", x.chi_square),
        ],
        ..Claim::default()
    }
}
// endregion

// region: rule depth-mask
/// Debugging tips: the depth buffer removes an if.
const DEPTH_MASK: ClaimDef = ClaimDef {
    id: "lecture3.depth-mask-removes-if",
    rule: &["src/report/lecture3/claims.rs#rule depth-mask"],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload depth-mask"],
    band: None,
};

fn depth_test_masks(r: &Lecture3Results) -> Claim {
    let rows = &r.depth_mask.rows;
    let max_error = rows.iter().map(|x| x.max_error).fold(0.0, f64::max);
    let counter = rows.first().map(|x| x.counted_by.clone());
    let counted = |x: &DepthMaskRow| x.masked_runs.zip(x.unmasked_runs);
    let claim = "6. The depth buffer removes an if: masked pixels never run the shader".into();
    let paper = "lecture 3, debugging tips: removing if with the depth buffer".into();
    if let Some(RunCounter::Unavailable(why)) = &counter {
        return Claim {
            id: DEPTH_MASK.id.into(),
            claim,
            paper,
            measured: format!(
                "not judged on this renderer: the expensive shader's runs cannot be counted \
                 ({why}); the pictures equal the CPU's within {max_error:.1e}"
            ),
            decided_by: Basis::Count,
            holds: None,
            ..Claim::default()
        };
    }
    let fits = |x: &DepthMaskRow| {
        counted(x).is_some_and(|(masked, all)| {
            runs_fit_mask(masked, x.active, x.active_quads)
                && runs_fit_mask(all, x.pixels, x.pixels.div_ceil(4))
        })
    };
    let exact = !rows.is_empty() && rows.iter().all(fits);
    let off = rows
        .iter()
        .filter(|x| !fits(x))
        .map(|x| {
            format!(
                "{:?} {:.0}%: {} runs for {} active pixels in {} quads",
                x.mask,
                100.0 * x.fraction,
                x.masked_runs.unwrap_or(0),
                x.active,
                x.active_quads
            )
        })
        .collect::<Vec<_>>();
    let helpers = rows
        .iter()
        .filter_map(|x| x.masked_runs.map(|m| m.saturating_sub(x.active)))
        .sum::<u64>();
    let statistics =
        if rows.iter().any(|x| x.masked_invocations.is_some()) {
            format!(
            "; the driver's pipeline statistics count {} invocations of the plain shader behind \
             the mask for {} active pixels in all (beside, not judged: a driver may count \
             fragments its early depth test then drops, as llvmpipe does)",
            rows.iter().filter_map(|x| x.masked_invocations).sum::<u64>(),
            rows.iter().map(|x| x.active).sum::<u64>()
        )
        } else {
            String::new()
        };
    Claim {
        id: DEPTH_MASK.id.into(),
        claim,
        paper,
        measured: format!(
            "runs of the expensive shader counted by {}: behind the depth mask at least the \
             active pixels (CPU) and nothing outside the 2x2 quads that hold one, without it \
             every pixel, in all {} cases: {exact}{}; runs beyond the active pixels (helper \
             invocations of partly active quads) {helpers} in all{statistics}; the pictures \
             equal the CPU's within {max_error:.1e}",
            counter.map_or_else(|| "nothing".into(), |c| c.describe()),
            rows.len(),
            if off.is_empty() {
                String::new()
            } else {
                format!(" ({})", off.join("; "))
            }
        ),
        decided_by: Basis::Count,
        holds: Some(exact),
        evidence: vec![
            Evidence::exact("shader runs fit the mask in every case", exact),
            Evidence::count(
                "runs beyond the active pixels (helper invocations)",
                helpers as f64,
            ),
        ],
        ..Claim::default()
    }
}
// endregion

// region: rule depth-mask-time
/// Debugging tips: the depth mask saves time where few pixels take the branch.
const DEPTH_MASK_TIME: ClaimDef = ClaimDef {
    id: "lecture3.depth-mask-saves-time",
    rule: &[
        "src/report/lecture3/claims.rs#rule depth-mask-time",
        TIMING_POLICY,
    ],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload depth-mask"],
    band: Some(0.25),
};

fn depth_test_saves_time(r: &Lecture3Results) -> Claim {
    let sparse: Vec<&DepthMaskRow> = r
        .depth_mask
        .rows
        .iter()
        .filter(|x| x.fraction == 0.05)
        .collect();
    let ratios = sparse
        .iter()
        .map(|x| format!("{:?} x{:.1}", x.mask, x.branching_ms / x.masked_ms))
        .collect::<Vec<_>>()
        .join(", ");
    let ends = Ends::of(|favour| {
        sparse
            .iter()
            .all(|x| faster(&x.masked_spread, &x.branching_spread, favour))
    });
    let runs = sparse
        .iter()
        .map(|x| {
            format!(
                "{:?}: branching {}, masked {}",
                x.mask,
                x.branching_spread.in_words(" ms"),
                x.masked_spread.in_words(" ms")
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let verdict = judge_ends(
        ends,
        &runs,
        "the runs of the masked and the branching versions overlap",
        r.load,
    );
    let slowest = sparse
        .iter()
        .map(|x| x.masked_ms / x.branching_ms)
        .fold(0.0, f64::max);
    Claim {
        id: DEPTH_MASK_TIME.id.into(),
        claim: "6. ... and so saves time where few pixels take the branch".into(),
        paper: "lecture 3, debugging tips (implied; GPUs of 2007 paid for both sides of a \
                divergent branch)"
            .into(),
        measured: format!(
            "branching / depth-masked time at 5% active: {ratios} (the masked version pays a \
             second pass; {})",
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: if sparse.is_empty() {
            None
        } else {
            verdict.holds
        },
        evidence: if sparse.is_empty() {
            Vec::new()
        } else {
            vec![DEPTH_MASK_TIME.timing(
                "depth-masked / branching time at 5% active, the slowest mask",
                slowest,
                "x",
                false,
                r.load,
            )]
        },
        ..Claim::default()
    }
}
// endregion

// region: rule blending-histogram
/// Debugging tips: alpha blending turns a scatter into one draw call.
const BLENDING_HISTOGRAM: ClaimDef = ClaimDef {
    id: "lecture3.blending-histogram",
    rule: &["src/report/lecture3/claims.rs#rule blending-histogram"],
    published: &[],
    workload: &["src/report/lecture3/bench.rs#workload histogram"],
    band: None,
};

fn blending_histogram(r: &Lecture3Results) -> Claim {
    let equal = r
        .histogram
        .iter()
        .all(|h| h.blend_equal && h.gather_equal != Some(false));
    let speed = r
        .histogram
        .iter()
        .filter_map(|h| {
            h.gather_ms
                .map(|g| format!("{} values: x{:.0}", h.values, g / h.blend_ms))
        })
        .collect::<Vec<_>>()
        .join(", ");
    // One draw call per histogram, as the gl layer counted them (None: not counted).
    let draws: Vec<Option<u64>> = r.histogram.iter().map(|h| h.blend_draws).collect();
    let one_draw = !draws.is_empty() && draws.iter().all(|&d| d == Some(1));
    Claim {
        id: BLENDING_HISTOGRAM.id.into(),
        claim: "7. Alpha blending simplifies code: a scatter becomes points added by the \
                blender, in one draw call"
            .into(),
        paper: "lecture 3, debugging tips: simplifying code with alpha blending".into(),
        measured: format!(
            "draw calls per blended histogram, counted by the gl layer: {}; counts equal to the \
             CPU's: {equal}; gather pass (a loop over every value per bin) / blending time: \
             {speed}",
            draws
                .iter()
                .map(|d| d.map_or("not counted".into(), |d| d.to_string()))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        decided_by: Basis::Count,
        holds: Some(equal && one_draw),
        evidence: vec![
            Evidence::exact("counts equal to the CPU's", equal),
            Evidence::exact("one draw call per histogram", one_draw),
        ],
        ..Claim::default()
    }
}
// endregion

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::lecture3::results::LightRow;
    use crate::timing::Spread;

    fn light_run(rows: &[(f32, f64, f64, f64)]) -> LightRun {
        LightRun {
            vpl_side: 32,
            vpls: 1024,
            image: (64, 64),
            receivers: 4096,
            build_ms: 1.0,
            build_spread: Spread::default(),
            brute_gpu_ms: 10.0,
            brute_gpu_spread: Spread::default(),
            brute_cpu_ms: 100.0,
            brute_cpu_threads: 2,
            brute_gpu_vs_cpu: 1e-6,
            rows: rows
                .iter()
                .map(|&(theta, error, nodes, ms)| LightRow {
                    theta,
                    relative_rms_error: error,
                    mean_nodes: nodes,
                    gpu_ms: ms,
                    gpu_spread: Spread::default(),
                })
                .collect(),
        }
    }

    fn prefilter_row(max_level: u32, errors: (f64, f64), steps: (f64, f64)) -> PrefilterRow {
        PrefilterRow {
            distance: 6.4,
            elevation: 35.0,
            max_level,
            quality: super::super::PrefilterQuality {
                samples: 4,
                unfiltered_error: errors.0,
                prefiltered_error: errors.1,
                unfiltered_steps: steps.0,
                prefiltered_steps: steps.1,
            },
            unfiltered_ms: 1.0,
            unfiltered_spread: Spread::default(),
            prefiltered_ms: 1.0,
            prefiltered_spread: Spread::default(),
            shading_ms: 0.5,
            shading_spread: Spread::default(),
            comparison: Default::default(),
        }
    }

    #[test]
    fn the_prefilter_claims_are_judged_only_where_they_act_and_fail_if_it_errs_more() {
        let near = prefilter_row(0, (0.05, 0.05), (14.0, 14.0));
        assert_eq!(
            prefilter_quality(std::slice::from_ref(&near), false).holds,
            None
        );
        let better = prefilter_row(2, (0.10, 0.06), (14.0, 9.0));
        assert_eq!(
            prefilter_quality(&[near.clone(), better.clone()], false).holds,
            Some(true)
        );
        let worse = prefilter_row(2, (0.10, 0.20), (14.0, 9.0));
        assert_eq!(
            prefilter_quality(&[better.clone(), worse.clone()], false).holds,
            Some(false)
        );
        // A grazing row is judged by the grazing claim only.
        let grazing_worse = PrefilterRow {
            elevation: 15.0,
            ..worse
        };
        let rows = [better.clone(), grazing_worse];
        assert_eq!(prefilter_quality(&rows, false).holds, Some(true));
        assert_eq!(prefilter_quality(&rows, true).holds, Some(false));
        assert_eq!(
            prefilter_quality(std::slice::from_ref(&better), true).holds,
            None
        );
        // Speed: more steps fail whatever the timings; fewer steps with disjoint quiet runs hold.
        let slower = prefilter_row(1, (0.10, 0.06), (14.0, 15.0));
        assert_eq!(
            prefilter_speed(&[better.clone(), slower], None).holds,
            Some(false)
        );
        let spread = |ms: f64| Spread::of(&[ms, ms + 0.1]);
        let timed = PrefilterRow {
            unfiltered_spread: spread(2.0),
            prefiltered_spread: spread(1.0),
            ..better
        };
        assert_eq!(
            prefilter_speed(std::slice::from_ref(&timed), None).holds,
            Some(true)
        );
        let overlapping = PrefilterRow {
            prefiltered_spread: Spread::of(&[1.0, 2.05]),
            ..timed
        };
        assert_eq!(prefilter_speed(&[overlapping], None).holds, None);
        // Why a slower prefiltered frame is slower: the shading pyramid, or the traversal.
        let pyramid_costs = PrefilterRow {
            unfiltered_ms: 1.0,
            prefiltered_ms: 1.2,
            shading_ms: 0.5,
            ..better.clone()
        };
        assert!(why_slower(&[&pyramid_costs])
            .contains("its traversal alone (its time less the shading pyramid's) is faster"));
        let traversal_costs = PrefilterRow {
            shading_ms: 0.1,
            ..pyramid_costs.clone()
        };
        assert!(why_slower(&[&pyramid_costs, &traversal_costs]).contains("not faster"));
        assert!(why_slower(&[&better]).is_empty());
    }

    #[test]
    fn the_light_group_claim_fails_when_no_criterion_is_accurate_enough() {
        let none_within = few_light_groups(&light_run(&[
            (0.0, 0.0, 1024.0, 10.0),
            (0.5, 0.2, 50.0, 1.0),
        ]));
        assert_eq!(none_within.holds, Some(false), "{}", none_within.measured);
        assert!(
            none_within.measured.contains("no criterion"),
            "{}",
            none_within.measured
        );
        let within = few_light_groups(&light_run(&[
            (0.0, 0.0, 1024.0, 10.0),
            (0.5, 0.02, 50.0, 1.0),
        ]));
        assert_eq!(within.holds, Some(true), "{}", within.measured);
        let too_many_nodes = few_light_groups(&light_run(&[(0.5, 0.02, 600.0, 1.0)]));
        assert_eq!(too_many_nodes.holds, Some(false));
    }
}
