//! Lecture 1, continuous collision for an avatar (a reconstruction of Kim, Redon, Lin,
//! Manocha & Templeman 2007): the first time of contact found with swept bounds, the BVH, the
//! GPU visibility culling, exact distances and conservative advancement, against brute force
//! over densely sampled times with parry3d's distances (an independent library); the
//! visibility culling never drops a touching pair; the speed bound holds; the exact
//! segment–triangle distance against parry3d; contact, no contact, grazing and contact at
//! t = 0; bad keyframes refused.
//!
//! Tolerances. parry3d works in fp32 on coordinates of a few units: its distances are good to
//! about 1e-6, so a slack of 1e-4 covers them. The query promises a time s with a gap at most
//! the tolerance δ and no overlap before s: so s is no later than the first sample with an
//! overlap, and no earlier than one sample step before the first sample within δ (the sample
//! before that had a gap above δ, and the gap first reaches δ after it).

use classic_gpgpu::lecture1::avatar_ccd::body::{Body, Capsule, Keyframes, Link, Pose};
use classic_gpgpu::lecture1::avatar_ccd::environment::{room, Environment};
use classic_gpgpu::lecture1::avatar_ccd::exact::segment_triangle;
use classic_gpgpu::lecture1::avatar_ccd::reference::{gap_at, sample, shapes};
use classic_gpgpu::lecture1::avatar_ccd::sweep_bound::{link_speeds, swept_capsule};
use classic_gpgpu::lecture1::avatar_ccd::visibility::VisibilityCuller;
use classic_gpgpu::lecture1::avatar_ccd::{AvatarCcd, Contact, Options};
use classic_gpgpu::mesh::Mesh;
use common::{classic_gpgpu, context, json_of};
use glam::{DVec3, Vec3};

mod common;

/// Slack for parry3d's fp32 distances.
const SLACK: f64 = 1e-4;
/// Reference samples per keyframe interval.
const SAMPLES: usize = 64;

fn options(gpu: bool) -> Options {
    Options {
        tolerance: 1e-3,
        steps: 8,
        resolution: 32,
        gpu,
    }
}

fn walk(strides: usize, start_z: f64) -> (Body, Keyframes) {
    let body = Body::walker();
    let keyframes = Keyframes::walk(&body, DVec3::new(0.0, 1.06, start_z), strides, 0.35);
    (body, keyframes)
}

fn run(body: &Body, keyframes: &Keyframes, env: &Environment, gpu: bool) -> Contact {
    let ctx = context();
    ctx.set_checks(true);
    let o = options(gpu);
    AvatarCcd::new(&ctx, &o)
        .unwrap()
        .run(body, keyframes, env, &o)
        .unwrap()
}

/// The answer against brute force: within the tolerance at s, no overlap before s, and s
/// no earlier than a sample step before the first sample within the tolerance.
fn assert_matches_reference(body: &Body, keyframes: &Keyframes, env: &Environment, c: &Contact) {
    let tolerance = c.tolerance;
    let reference = sample(body, keyframes, env, SAMPLES, tolerance);
    let triangles = shapes(env);
    match c.time_of_contact {
        None => assert!(
            reference.min_gap > tolerance - SLACK,
            "no contact reported, but the samples come within {} (tolerance {tolerance})",
            reference.min_gap
        ),
        Some(s) => {
            let (gap, _) = gap_at(body, keyframes, &triangles, s);
            assert!(
                gap <= tolerance + SLACK,
                "gap {gap} at the reported time {s}"
            );
            let (first, _) = reference
                .first_within_tolerance
                .expect("the reference sees the contact too");
            assert!(
                s >= first - reference.step - 1e-12,
                "reported {s}, but the samples are farther than the tolerance until {first}"
            );
            if let Some(overlap) = reference.first_overlap {
                assert!(
                    s <= overlap + 1e-12,
                    "reported {s}, but an overlap at {overlap}"
                );
            }
            // No overlap at any sample before s.
            let mut t = 0.0;
            while t < s {
                let (g, link) = gap_at(body, keyframes, &triangles, t);
                assert!(
                    g > 0.0,
                    "an overlap of {} at {t} < {s}",
                    body.links[link].name
                );
                t += reference.step / 4.0;
            }
            assert!(c.link.is_some() && c.contact_point.is_some() && c.gap.unwrap() <= tolerance);
        }
    }
}

#[test]
fn walking_into_the_wall_matches_brute_force() {
    let (body, keyframes) = walk(8, 0.0);
    let env = Environment::new(&room()).unwrap();
    let gpu = run(&body, &keyframes, &env, true);
    let s = gpu.time_of_contact.expect("the walk reaches the wall");
    assert!(s > 0.0 && s < keyframes.end(), "contact at {s}");
    assert_matches_reference(&body, &keyframes, &env, &gpu);
    // The contact point is on the wall (z = 2.5 is its near face).
    let p = gpu.contact_point.unwrap();
    assert!((p[2] - 2.5).abs() < 1e-9, "contact point {p:?}");
    // The GPU culling kept no more than the BVH, and the CPU-only run agrees with brute
    // force too.
    assert!(gpu.counts.pairs_after_gpu <= gpu.counts.pairs_after_bvh);
    assert!(gpu.counts.occlusion_queries > 0);
    let cpu = run(&body, &keyframes, &env, false);
    assert_matches_reference(&body, &keyframes, &env, &cpu);
    assert_eq!(gpu.link, cpu.link);
}

#[test]
fn a_short_walk_touches_nothing() {
    let (body, keyframes) = walk(3, 0.0);
    let env = Environment::new(&room()).unwrap();
    let c = run(&body, &keyframes, &env, true);
    assert_eq!(c.time_of_contact, None, "{c:?}");
    assert_matches_reference(&body, &keyframes, &env, &c);
}

#[test]
fn starting_inside_the_wall_is_contact_at_zero() {
    let (body, keyframes) = walk(2, 2.5);
    let env = Environment::new(&room()).unwrap();
    let c = run(&body, &keyframes, &env, true);
    assert_eq!(c.time_of_contact, Some(0.0), "{c:?}");
    assert_matches_reference(&body, &keyframes, &env, &c);
}

/// One horizontal capsule (radius 0.1, along z) sliding along x at height 0.1 + `clearance`
/// over a triangle in the plane y = 0 turned about y by 0.3 radians.
fn grazing(clearance: f64) -> (Body, Keyframes, Environment) {
    let body = Body {
        links: vec![Link {
            name: "bar".into(),
            parent: None,
            joint: DVec3::ZERO,
            segment: [DVec3::new(0.0, 0.0, -0.3), DVec3::new(0.0, 0.0, 0.3)],
            radius: 0.1,
        }],
    };
    let pose = |x: f64| Pose {
        root: DVec3::new(x, 0.1 + clearance, 0.0),
        angles: vec![DVec3::ZERO],
    };
    let keyframes = Keyframes {
        poses: vec![pose(-3.0), pose(3.0)],
    };
    let turn = glam::Quat::from_rotation_y(0.3);
    let mesh = Mesh::new(
        [
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(-1.0, 0.0, 1.0),
        ]
        .map(|p| turn * p)
        .to_vec(),
        vec![[0, 2, 1]],
    );
    (body, keyframes, Environment::new(&mesh).unwrap())
}

#[test]
fn grazing_within_the_tolerance_is_contact_and_beyond_it_is_not() {
    for (clearance, contact) in [(0.5e-3, true), (2e-3, false)] {
        let (body, keyframes, env) = grazing(clearance);
        let c = run(&body, &keyframes, &env, true);
        assert_eq!(
            c.time_of_contact.is_some(),
            contact,
            "clearance {clearance}: {c:?}"
        );
        assert_matches_reference(&body, &keyframes, &env, &c);
    }
}

#[test]
fn the_visibility_culling_keeps_every_touching_pair() {
    let ctx = context();
    ctx.set_checks(true);
    let mut culler = VisibilityCuller::new(&ctx, 16).unwrap();
    let mut seed = 7u64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let mut touching_pairs = 0;
    let mut pruned = 0;
    // 100 random scenes: about 25 touching pairs, every one of which must survive.
    for _ in 0..100 {
        let links: Vec<Capsule> = (0..4)
            .map(|_| {
                let a = DVec3::new(next(), next(), next());
                Capsule {
                    a,
                    b: a + 0.4 * DVec3::new(next(), next(), next()),
                    radius: 0.02 + 0.05 * next().abs(),
                }
            })
            .collect();
        let triangles: Vec<[DVec3; 3]> = (0..30)
            .map(|_| {
                let c = DVec3::new(next(), next(), next());
                [0, 1, 2].map(|_| c + 0.3 * DVec3::new(next(), next(), next()))
            })
            .collect();
        let kept = culler.cull(&links, &triangles).unwrap();
        pruned += links.len() - kept.links.len() + triangles.len() - kept.triangles.len();
        for (l, c) in links.iter().enumerate() {
            for (t, tri) in triangles.iter().enumerate() {
                if segment_triangle(c.a, c.b, *tri).distance <= c.radius {
                    touching_pairs += 1;
                    assert!(
                        kept.links.contains(&l),
                        "link {l} touches triangle {t} but was culled"
                    );
                    assert!(
                        kept.triangles.contains(&t),
                        "triangle {t} touches link {l} but was culled"
                    );
                }
            }
        }
    }
    assert!(
        touching_pairs > 10,
        "too few touching pairs to mean anything: {touching_pairs}"
    );
    assert!(pruned > 0, "the culling pruned nothing");
}

#[test]
fn the_swept_bound_holds_every_sampled_pose() {
    let (body, keyframes) = walk(3, 0.0);
    for k in 0..3 {
        let speeds = link_speeds(&body, &keyframes, k);
        let (t0, t1) = (k as f64 + 0.25, k as f64 + 0.75);
        let mid = body.capsules(&keyframes.pose_at(0.5 * (t0 + t1)));
        for i in 0..=50 {
            let t = t0 + (t1 - t0) * i as f64 / 50.0;
            for (l, c) in body.capsules(&keyframes.pose_at(t)).iter().enumerate() {
                let bound = swept_capsule(mid[l], speeds[l], t0, t1);
                for end in [c.a, c.b] {
                    let d = segment_triangle(end, end, [bound.a, bound.b, bound.b]).distance;
                    assert!(
                        d + c.radius <= bound.radius + 1e-12,
                        "link {l} at {t} leaves its bound by {}",
                        d + c.radius - bound.radius
                    );
                }
            }
        }
    }
}

#[test]
fn segment_triangle_distance_is_reached_and_is_the_minimum() {
    use parry3d::math::{Pose as PPose, Vector};
    use parry3d::query::PointQuery;
    use parry3d::shape::{Capsule as PCapsule, Triangle};
    let mut seed = 11u64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let v = |p: DVec3| Vector::new(p.x as f32, p.y as f32, p.z as f32);
    let round = |p: DVec3| p.as_vec3().as_dvec3();
    let mut worst_gjk = 0.0f64;
    for _ in 0..2000 {
        let a = round(DVec3::new(next(), next(), next()));
        let b = round(DVec3::new(next(), next(), next()));
        let t = [0, 1, 2].map(|_| round(DVec3::new(next(), next(), next())));
        let ours = segment_triangle(a, b, t);
        let radius = 1e-3;
        let theirs = parry3d::query::distance(
            &PPose::identity(),
            &PCapsule::new(v(a), v(b), radius as f32),
            &PPose::identity(),
            &Triangle::new(v(t[0]), v(t[1]), v(t[2])),
        )
        .unwrap()
        .distance as f64;
        // Our closest points lie on the segment and in the triangle, so our distance is one
        // the two sets reach: it can never be below the true one.
        assert!(((ours.on_segment - ours.on_triangle).length() - ours.distance).abs() < 1e-12);
        assert!(
            on_segment(ours.on_segment, a, b),
            "{:?} not on {a} {b}",
            ours.on_segment
        );
        assert!(
            in_triangle(ours.on_triangle, t),
            "{:?} not in {t:?}",
            ours.on_triangle
        );
        // And equal to an independent minimum: the distance from the segment's point at s to
        // the triangle (parry3d's closed-form projection) is convex in s, so a ternary search
        // over s finds the segment's distance.
        let tri = Triangle::new(v(t[0]), v(t[1]), v(t[2]));
        let at = |s: f64| tri.distance_to_local_point(v(a + s * (b - a)), true) as f64;
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..100 {
            let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if at(m1) <= at(m2) {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        let reference = at(0.5 * (lo + hi)).min(at(0.0)).min(at(1.0));
        assert!(
            (ours.distance - reference).abs() < 1e-5,
            "segment {a} {b}, triangle {t:?}: ours {}, ternary search {reference}",
            ours.distance
        );
        // parry3d's own capsule-triangle distance (fp32 GJK) is only an upper bound here:
        // its iteration stops within its tolerance, above the true distance.
        let expected = (ours.distance - radius).max(0.0);
        assert!(
            expected < theirs + SLACK,
            "segment {a} {b}, triangle {t:?}: ours {expected}, parry3d {theirs}"
        );
        worst_gjk = worst_gjk.max(theirs - expected);
    }
    assert!(
        worst_gjk < 1e-2,
        "parry3d's GJK {worst_gjk} above the distance"
    );
}

/// `p` on the segment `a`-`b` (to within f64 rounding).
fn on_segment(p: DVec3, a: DVec3, b: DVec3) -> bool {
    let ab = b - a;
    let s = (p - a).dot(ab) / ab.length_squared();
    (-1e-9..=1.0 + 1e-9).contains(&s) && (a + s * ab - p).length() < 1e-9
}

/// `p` in the triangle `t` (to within f64 rounding): in its plane, barycentrics >= 0.
fn in_triangle(p: DVec3, t: [DVec3; 3]) -> bool {
    let (e0, e1, d) = (t[1] - t[0], t[2] - t[0], p - t[0]);
    let (d00, d01, d11) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
    let (d20, d21) = (d.dot(e0), d.dot(e1));
    let denom = d00 * d11 - d01 * d01;
    let v = (d11 * d20 - d01 * d21) / denom;
    let w = (d00 * d21 - d01 * d20) / denom;
    let plane = (t[0] + v * e0 + w * e1 - p).length();
    v >= -1e-9 && w >= -1e-9 && v + w <= 1.0 + 1e-9 && plane < 1e-9
}

#[test]
fn the_cli_prints_the_contact_and_refuses_bad_keyframes() {
    let report = json_of(&["lecture1", "avatar-ccd", "--resolution", "16", "--json"]);
    assert!(report["time_of_contact"].as_f64().is_some(), "{report}");
    assert!(report["link"].as_str().is_some(), "{report}");
    assert_eq!(report["contact_point"].as_array().unwrap().len(), 3);
    let dir = std::env::temp_dir().join(format!("avatar_ccd_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.json");
    std::fs::write(
        &bad,
        r#"{"keyframes": [{"root": [0, 1, 0], "angles": {"tail": [0, 0, 0]}}]}"#,
    )
    .unwrap();
    let out = classic_gpgpu(&[
        "lecture1",
        "avatar-ccd",
        "--keyframes",
        bad.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("tail") && err.contains("bad.json"), "{err}");
    // A pose without contact: one keyframe standing in the open.
    let alone = dir.join("alone.json");
    std::fs::write(&alone, r#"{"keyframes": [{"root": [0, 1.06, -2]}]}"#).unwrap();
    let report = json_of(&[
        "lecture1",
        "avatar-ccd",
        "--keyframes",
        alone.to_str().unwrap(),
        "--json",
    ]);
    assert!(report["time_of_contact"].is_null(), "{report}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A keyframe whose thigh turns by `angle` radians from the rest pose, walking into the wall.
fn spinning_thigh(angle: f64) -> String {
    format!(
        r#"{{"keyframes": [{{"root": [0, 1.06, 1.9]}},
            {{"root": [0, 1.06, 2.3], "angles": {{"left thigh": [{angle:e}, 0, 0]}}}}]}}"#
    )
}

/// Conservative advancement takes at most speed / tolerance steps per keyframe interval: a
/// turn that makes that bound pass the limit is refused before anything runs, naming the
/// keyframes, the link and its angles (no minutes of silence, no "no contact" from bounds
/// beyond fp32); a turn inside the range runs and finds the wall.
#[test]
fn a_turn_beyond_the_advancements_range_is_refused_naming_the_keyframe_and_the_angle() {
    let body = Body::walker();
    let env = Environment::new(&room()).unwrap();
    let ctx = context();
    let o = options(false);
    let mut ccd = AvatarCcd::new(&ctx, &o).unwrap();
    for angle in [1e6, 1e20, 1e40, 1e308] {
        let keyframes = Keyframes::from_json(&body, &spinning_thigh(angle), "test").unwrap();
        let err = ccd
            .run(&body, &keyframes, &env, &o)
            .expect_err("a turn beyond the range is refused")
            .to_string();
        assert!(
            err.contains("keyframes 0 to 1")
                && err.contains("left thigh")
                && err.contains(&format!("{angle:?}"))
                && err.contains("tolerance"),
            "{angle}: {err}"
        );
    }
    // Ten radians between keyframes: inside the range, and the leg still meets the wall.
    let keyframes = Keyframes::from_json(&body, &spinning_thigh(10.0), "test").unwrap();
    let c = ccd.run(&body, &keyframes, &env, &o).unwrap();
    assert!(c.time_of_contact.is_some(), "{c:?}");
    assert_matches_reference(&body, &keyframes, &env, &c);
    // The command line names the file.
    let dir = std::env::temp_dir().join(format!("avatar_ccd_range_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("spin.json");
    std::fs::write(&file, spinning_thigh(1e40)).unwrap();
    let out = classic_gpgpu(&[
        "lecture1",
        "avatar-ccd",
        "--no-gpu",
        "--keyframes",
        file.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("spin.json") && err.contains("left thigh") && err.contains("1e40"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The published scale (Presence 2007: a 16-link avatar among hundreds of thousands of
/// polygons; generated here): 16 links and over 100k triangles; the first contact against
/// brute force on the triangles near the motion (the subset cannot change it, see
/// `near_the_motion`), and the same wall as in the default room.
#[test]
fn the_published_scale_matches_brute_force_on_the_triangles_near_the_motion() {
    use classic_gpgpu::lecture1::avatar_ccd::environment::published_room;
    use classic_gpgpu::lecture1::avatar_ccd::reference::near_the_motion;
    let body = Body::avatar16();
    assert_eq!(body.links.len(), 16);
    body.validate().unwrap();
    let keyframes = Keyframes::walk(&body, DVec3::new(0.0, 1.06, 0.0), 8, 0.35);
    let env = Environment::new(&published_room()).unwrap();
    assert!(env.triangles.len() >= 100_000, "{}", env.triangles.len());
    let c = run(&body, &keyframes, &env, true);
    let near = near_the_motion(&body, &keyframes, &env, 256, 0.25).unwrap();
    assert!(
        near.triangles.len() < env.triangles.len() / 10,
        "{} triangles near the motion",
        near.triangles.len()
    );
    assert_matches_reference(&body, &keyframes, &near, &c);
    let s = c.time_of_contact.expect("the walk reaches the wall");
    assert!((c.contact_point.unwrap()[2] - 2.5).abs() < 1e-9, "{c:?}");
    assert!(s > 0.0 && s < keyframes.end());
    // The BVH kept the tori out: no more pairs than the default room's scene would give
    // plus the floor's and the wall's.
    assert!(c.counts.pairs_after_bvh > 0 && c.counts.occlusion_queries > 0);
}

#[test]
fn the_command_counts_links_and_triangles_at_the_published_scale() {
    let report = json_of(&[
        "--json",
        "lecture1",
        "avatar-ccd",
        "--scale",
        "published",
        "--check",
        "8",
    ]);
    assert_eq!(report["links"], 16);
    assert!(report["triangles"].as_u64().unwrap() >= 100_000, "{report}");
    let reference = &report["reference"];
    assert!(
        reference["reference_triangles"].as_u64().unwrap() < 1000,
        "{reference}"
    );
    let s = report["time_of_contact"].as_f64().unwrap();
    let overlap = reference["first_overlap"].as_f64().unwrap();
    assert!(s <= overlap + 1e-12, "{report}");
}
