//! Section 5.3: the 50-body buoyancy scene beside the paper's frame rate.

use super::bench::Paper4Results;
use crate::report::published;
use crate::report::Table;

pub fn table(results: &Paper4Results, paper: &published::Paper4) -> Table {
    let b = &results.buoyancy;
    let row = |measure: &str, ours: String, paper: String| vec![measure.to_string(), ours, paper];
    Table {
        caption: format!(
            "Section 5.3: {} bodies at {}x{} on {} (paper: GeForce 7800 GTX)",
            b.bodies, b.resolution, b.resolution, results.renderer
        ),
        header: ["measure", "ours", "paper"].map(String::from).to_vec(),
        rows: vec![
            row(
                &format!(
                    "frames per second: one step (dt = 1/60 s) and the scene drawn at {}x{}                      (shaded bodies, force arrows, water)",
                    b.frame_size.0, b.frame_size.1
                ),
                format!("{:.1}", b.frames_per_second),
                format!("{}", paper.buoyancy.frames_per_second),
            ),
            row(
                "steps per second (the step alone, nothing drawn)",
                format!("{:.1}", b.steps_per_second),
                "-".into(),
            ),
            row(
                "steps per second, CPU reference solver (clip + Mirtich), in the race's \
                 interleaved rounds from the drop (the GPU solver beside it)",
                format!(
                    "{:.1} ({:.1})",
                    b.cpu_solver_steps_per_second, b.race_gpu_steps_per_second
                ),
                "-".into(),
            ),
            row(
                "share of frame time in buoyancy",
                format!("{:.0}%", 100.0 * b.buoyancy_share),
                format!("over {:.0}%", 100.0 * paper.buoyancy.buoyancy_share),
            ),
            row(
                "buoyancy of 50 bodies: tiles of one target vs one body at a time (ms, median)",
                format!(
                    "{:.1} vs {:.1} ({} runs)",
                    b.batched_ms, b.one_body_at_a_time_ms, b.batching_runs
                ),
                "-".into(),
            ),
            row(
                "deepest peel (mean)",
                format!("{} ({:.1})", b.max_peels, b.mean_peels),
                format!(
                    "{} (teapot, bunny; mostly {})",
                    paper.buoyancy.peels_teapot_bunny_max,
                    paper
                        .buoyancy
                        .peels_teapot_bunny_typical
                        .replace(" or ", "-")
                ),
            ),
            row(
                "steps whose peeling stopped at the peel limit with fragments left",
                if b.truncated_steps == 0 {
                    format!("none (limit {} peels)", b.max_peels_limit)
                } else {
                    format!(
                        "{} of {}: their submerged parts miss the deeper layers (limit {} peels)",
                        b.truncated_steps,
                        b.settle_steps + b.steps,
                        b.max_peels_limit
                    )
                },
                "-".into(),
            ),
            race_row(results),
        ],
    }
}

/// The GPU solver against the CPU one, in interleaved pairs, with the ratio's spread and
/// the load it was taken under.
fn race_row(results: &Paper4Results) -> Vec<String> {
    let r = &results.targets.buoyancy_race;
    vec![
        format!(
            "GPU solver / CPU reference solver (clip + Mirtich), steps per second, first {}              steps from the drop, interleaved pairs",
            r.setup.steps
        ),
        r.in_words(),
        "-".into(),
    ]
}
