//! Paper 1's section (Zhang & Kim 2007, streaming AABBs): Table III per scene, CULLIDE's
//! Table IV and its resolution, the SOLID and CULLIDE comparisons of Fig. 10-12, the
//! readback-vs-eta curves of Fig. 7 and the three schemes on real frames, the leaf-size sweep
//! behind the default `n`, and the Fig. 8-9 snapshots, all measured in one run on one renderer,
//! beside the published numbers (`[paper1]` of `assets/paper_tables.toml`).

mod bench;
mod claims;
mod cullide_resolution;
mod fidelity;
mod fig10_12;
mod fig7;
mod fig8_9;
mod leaf_sweep;
pub mod period;
mod profile;
mod readback_schemes;
mod table3;
mod table4;
mod then_and_now;
mod tiles;

pub use bench::{
    Fig7, Fig7Curve, FrameTimes, Paper1Results, SceneRun, Setup, SweepPoint, TileStudy,
};

use super::period::WithPeriod;
use super::published::Published;
use super::{checks, BenchOptions, Paper, Section};
use crate::collide::cullide::PAPER_RESOLUTION;
use crate::values::ranges;

/// What `collide-bench` can change; `reproduce` uses the defaults for its size.
#[derive(Clone, Debug, clap::Args)]
pub struct Paper1Args {
    /// Scenes to run (comma separated); default all six of Table III.
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Frames per scene (after one warm-up frame); default 20, or 3 with --quick.
    #[arg(long, value_parser = ranges::FRAMES.of::<usize>())]
    pub frames: Option<usize>,
    /// Triangles per model instead of the paper's counts.
    #[arg(long, value_parser = ranges::triangles(TRIANGLE_BYTES).of::<usize>())]
    pub triangles: Option<usize>,
    /// Leaf size `n` of the streaming pipeline and of SOLID (default: per model, 32 doubled
    /// until the stream has at most 512 slots on a software renderer, 4096 on a GPU).
    #[arg(long, value_parser = ranges::LEAF_SIZE.of::<usize>())]
    pub leaf_size: Option<usize>,
    /// CULLIDE's image resolution (the paper: 512).
    #[arg(long, default_value_t = PAPER_RESOLUTION,
          value_parser = ranges::TEXTURE_SIDE.of::<u32>())]
    pub cullide_resolution: u32,
    /// Skip the leaf-size sweep.
    #[arg(long)]
    pub no_leaf_sweep: bool,
}

/// Memory per triangle of each model of a Table III scene, measured: 160 bytes for the pair
/// (interlocking tori, 20,000 against 200,000 triangles each), rounded up for the streams and
/// the deformation (`--triangles` of `collide-bench` and `collide-scene`).
pub const TRIANGLE_BYTES: u64 = 512;

impl Default for Paper1Args {
    fn default() -> Paper1Args {
        Paper1Args {
            scenes: Vec::new(),
            frames: None,
            triangles: None,
            leaf_size: None,
            cullide_resolution: PAPER_RESOLUTION,
            no_leaf_sweep: false,
        }
    }
}

/// The paper-1 section.
pub struct Paper1;

impl Paper for Paper1 {
    const PERIOD_PAPER: Option<u8> = Some(1);
    const ID: &'static str = "paper1";
    const CLAIMS: &'static [super::ClaimDef] = claims::CLAIMS;
    const TITLE: &'static str =
        "Paper 1: collision detection with streaming AABBs (Zhang & Kim 2007)";
    type Options = Paper1Args;
    type Results = WithPeriod<Paper1Results>;

    fn measure(opts: &BenchOptions, args: &Paper1Args) -> anyhow::Result<Self::Results> {
        crate::timing::mark("paper1: start");
        let results = bench::measure(opts, args)?;
        crate::timing::mark("paper1: measured");
        let with = WithPeriod::measure(results, opts, period::measure);
        crate::timing::mark("paper1: period");
        with
    }

    fn section(opts: &BenchOptions, results: &Self::Results) -> anyhow::Result<Section> {
        let paper = &Published::get()?.paper1;
        let mut tables = vec![
            table3::table(results, paper),
            table4::table(results, paper),
            cullide_resolution::table(results),
            fig10_12::table(results),
        ];
        tables.extend(fig7::tables(results));
        tables.push(readback_schemes::table(results));
        tables.push(tiles::table(results));
        tables.push(results.then_and_now.table(&results.renderer));
        if !results.leaf_sweep.is_empty() {
            tables.push(leaf_sweep::table(results));
        }
        tables.extend(profile::table(results));
        tables.extend(results.period_tables());
        let mut figures = fig7::figures(opts, results)?;
        for run in &results.scenes {
            figures.extend(fig8_9::figure(run));
            figures.extend(fig10_12::figures(opts, run)?);
        }
        Ok(Section {
            summary: summary(results),
            tables,
            claims: claims::claims(results),
            figures,
            fidelity: fidelity::rows(),
            checks_listed: checks::ids(&listed_checks(results)),
            checks_made: checks_made(results),
            ..Section::default()
        })
    }
}

/// The checks of [`checks::PAPER1`] this run can make: the then-and-now comparison only where
/// the compute formulation runs (OpenGL 4.3).
pub fn listed_checks(results: &Paper1Results) -> Vec<checks::Check> {
    let skip: &[&str] = match results.then_and_now.unavailable {
        Some(_) => &["then and now same pairs"],
        None => &[],
    };
    checks::without(checks::PAPER1, skip)
}

/// The checks of [`checks::PAPER1`] whose comparisons are in `results`.
pub fn checks_made(results: &Paper1Results) -> Vec<String> {
    let frames = results.scenes.iter().any(|s| s.frames > 0);
    checks::made(&[
        (frames, "solid vs streaming"),
        (frames, "cullide vs streaming"),
        (
            results.then_and_now.same_answer.is_some(),
            "then and now same pairs",
        ),
    ])
}

fn summary(results: &Paper1Results) -> String {
    let setup = &results.setup;
    let leaf_size = match setup.forced_leaf_size {
        Some(n) => format!("n = {n}"),
        None => {
            let sizes: Vec<String> = results
                .scenes
                .iter()
                .map(|r| format!("{} {}", r.label, r.leaf_size))
                .collect();
            format!(
                "per model, 32 doubled until a stream has at most {} slots ({})",
                setup.max_slots,
                sizes.join(", ")
            )
        }
    };
    format!(
        "Two deforming models per scene, {} frames after a warm-up frame{}; every method in the \
         same run on {}. The happy buddhas and intimate animals are stand-ins of the same \
         triangle counts (scanned models not available), named as such. Streaming pairs are \
         exact (tests compare them with brute force); SOLID and CULLIDE are measured against \
         them. Leaf size {leaf_size}; readback auto (calibrated per P0 size on clustered CAPs, \
         like the scenes' own: {clustering} CAPs per set P1 texel here; each calibration point \
         is measured when a frame first needs it, outside the frame's time). SOLID: the same \
         leaves in a CPU tree, refitted bottom-up and traversed as a tree pair each frame. \
         CULLIDE: {res}x{res} views along x, y, z over the overlap of the two global boxes, two \
         passes per view, pruning objects, then leaves, then triangles. GPU passes are timed \
         with timer queries; CPU stages and whole frames by wall clock. ",
        setup.frames,
        if results.quick {
            ", quick mode (small models)"
        } else {
            ""
        },
        results.renderer,
        res = setup.cullide_resolution,
        clustering = clustering(results),
    ) + &checks::sentence(&listed_checks(results))
}

/// The range of the scenes' CAPs per set `P1` texel, "2.1-3.7".
fn clustering(results: &Paper1Results) -> String {
    let (lo, hi) = results
        .scenes
        .iter()
        .map(|r| r.caps_per_set_p1_texel)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if lo > hi {
        "-".into()
    } else {
        format!("{lo:.1}-{hi:.1}")
    }
}

/// Two decimals, the tables' usual precision.
fn f2(v: f64) -> String {
    format!("{v:.2}")
}

fn header(names: &[&str]) -> Vec<String> {
    names.iter().map(|s| s.to_string()).collect()
}

/// Every fidelity row of the section.
pub fn fidelity_rows() -> Vec<super::Fidelity> {
    fidelity::rows()
}
