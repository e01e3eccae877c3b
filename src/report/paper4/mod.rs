//! Paper 4's section (Kim, Kim, Ko & Terzopoulos 2006): Table 1 (objects and peels), Fig. 4
//! (relative error against resolution), Fig. 5 (time against resolution beside Mirtich's
//! analytic method), the buoyancy scene's steps per second (section 5.3) and Fig. 9-10, each
//! beside the published numbers (`[paper4]` of `assets/paper_tables.toml`).

mod bench;
mod break_even;
mod buoyancy;
mod claims;
mod fidelity;
mod fig10;
mod fig4;
mod fig5;
pub mod period;
mod speed;
mod table1;
mod then_and_now;
pub mod then_and_now_buoyancy;
mod timed;

pub use bench::{BuoyancyRun, ObjectRun, Paper4Results, PeelOrderRun, ResolutionRow, SpeedTargets};

use super::period::WithPeriod;
use super::published::Published;
use super::{BenchOptions, NoOptions, Paper, Section};

/// The paper-4 section.
pub struct Paper4;

impl Paper for Paper4 {
    const PERIOD_PAPER: Option<u8> = Some(4);
    const ID: &'static str = "paper4";
    const CLAIMS: &'static [super::ClaimDef] = claims::CLAIMS;
    const TITLE: &'static str =
        "Paper 4: Kim, Kim, Ko & Terzopoulos 2006, mass properties by depth peeling, and buoyancy";
    type Options = NoOptions;
    type Results = WithPeriod<Paper4Results>;

    fn measure(opts: &BenchOptions, _: &NoOptions) -> anyhow::Result<Self::Results> {
        crate::timing::mark("paper4: start");
        let results = bench::measure(opts)?;
        crate::timing::mark("paper4: measured");
        let with = WithPeriod::measure(results, opts, period::measure);
        crate::timing::mark("paper4: period");
        with
    }

    fn section(opts: &BenchOptions, results: &Self::Results) -> anyhow::Result<Section> {
        let paper = &Published::get()?.paper4;
        let mut figures = fig4::figures(opts, results)?;
        figures.push(fig5::figure(opts, results)?);
        figures.extend(fig10::figures(opts, results));
        Ok(Section {
            summary: summary(opts, results),
            tables: vec![
                table1::table(results, paper),
                fig4::table(results),
                fig5::table(results),
                break_even::table(results),
                buoyancy::table(results, paper),
                results.then_and_now.table(&results.renderer),
                results.then_and_now_buoyancy.table(&results.renderer),
                speed::targets(results),
                speed::peel_orders(results),
                speed::profile(
                    "Where the time goes: one bunny at 64x64, per pass",
                    &results.profile_bunny_64,
                ),
                speed::profile(
                    "Where the time goes: ten buoyancy steps of the 50-body scene, per pass",
                    &results.profile_buoyancy,
                ),
            ]
            .into_iter()
            .chain(results.period_tables())
            .chain([super::not_built::table(
                "paper 4 names",
                super::not_built::PAPER4,
            )])
            .collect(),
            claims: claims::claims(results, paper),
            figures,
            fidelity: fidelity::rows(),
            paths: paths_taken(results).into_iter().map(String::from).collect(),
            ..Section::default()
        })
    }
}

/// The paths a paper-4 run can take; each is covered by a fidelity row.
pub mod paths {
    pub const MASS_LISTING: &str = "mass properties: the section 3.1 listing, three targets";
    pub const PEEL: &str = "depth peeling, peels summed as they come";
    pub const REDUCE: &str = "ping-pong reduction of the integrand targets";
    pub const ANALYTIC: &str = "Mirtich's analytic method as the baseline";
    pub const BUOYANCY_PASSES: &str = "buoyancy: n + 2 passes, eq. 4's integrands in one target";
    pub const FORCES: &str = "buoyancy: gravity, buoyancy and quadratic drag (c = 1)";
    pub const INTEGRATOR: &str = "buoyancy: semi-implicit Euler, dt = 1/60 s";
    pub const SCENE: &str = "buoyancy: the 50-body scene with a closed teapot";
    pub const COMPUTE: &str = "mass properties and buoyancy as compute passes";
}

/// Every path a run can take.
pub const ALL_PATHS: &[&str] = &[
    paths::MASS_LISTING,
    paths::PEEL,
    paths::REDUCE,
    paths::ANALYTIC,
    paths::BUOYANCY_PASSES,
    paths::FORCES,
    paths::INTEGRATOR,
    paths::SCENE,
    paths::COMPUTE,
];

/// The paths the run in `results` took: every one but the compute passes, which run only
/// where OpenGL 4.3 does.
pub fn paths_taken(results: &Paper4Results) -> Vec<&'static str> {
    ALL_PATHS
        .iter()
        .copied()
        .filter(|&p| p != paths::COMPUTE || results.then_and_now.unavailable.is_none())
        .collect()
}

/// Every fidelity row of the section.
pub fn fidelity_rows() -> Vec<super::Fidelity> {
    fidelity::rows()
}

fn summary(opts: &BenchOptions, results: &Paper4Results) -> String {
    format!(
        "The seven test objects of Table 1 (the mesh module's generators and the shipped \
         Stanford bunny, the bunny and the pipe refined to the paper's counts; the exact meshes \
         are not published) integrated by the section 3.1 fragment shader under \
         depth peeling at {} resolutions, against Mirtich's analytic method on the CPU (f64). \
         Times are medians ({}) after a warm-up, on {}{}. The buoyancy scene is the 50 \
         bodies of section 5.3 at 32x32 per body, all bodies as tiles of one target, timed after \
         60 steps that bring them into the water, one step per frame and each frame drawn \
         off-screen (what the paper's frames/s compares with); the scene's teapot is a closed one (Newell's \
         profile turned about z, no handle or spout), since Newell's surface is open. Peels \
         are added into running sums by default; the paper's order (keep the n layers, then \
         reduce each) is run beside it and agrees to fp32 rounding. On a software renderer the GL layer raises \
         glibc's trim and mmap thresholds, so the driver's per-draw buffers are not faulted in \
         afresh every time (about 30 -> 40 steps/s on llvmpipe, 2 cores), and each peel's draws \
         go in four parts with a flush between, so that its threads rasterize the first bodies \
         while the rest are set up (the race 1.0x -> 1.1-1.2x on llvmpipe).{}",
        bench::resolutions(opts.quick).len(),
        opts.runs(timed::QUICK_RUNS).in_words(),
        results.renderer,
        if opts.gl.info().is_software() {
            ": a software rasterizer runs the 'GPU' passes on the CPU, so the ratios are not the \
             paper's"
        } else {
            ""
        },
        if opts.quick {
            " Quick mode: resolutions up to 128 and a short buoyancy run."
        } else {
            ""
        }
    )
}
