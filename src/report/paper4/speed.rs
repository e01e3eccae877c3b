//! How fast, and where the time goes: the speed targets as ratios of this run (what the code
//! aims at on llvmpipe, where most users run it),
//! the two orders of peels and sums, and per-pass profiles.

use super::bench::Paper4Results;
use crate::gl::profile::ProfileRow;
use crate::report::Table;

/// The project's speed targets on llvmpipe (a fixed cost per pass must not swamp the
/// papers' work), each a ratio measured in this run.
pub fn targets(results: &Paper4Results) -> Table {
    let t = &results.targets;
    let met = |ok: bool| if ok { "met" } else { "not met" }.to_string();
    Table {
        caption: format!(
            "Speed targets of this project (not the paper's claims), ratios of one run on {}",
            results.renderer
        ),
        header: ["target", "measured", "goal", ""]
            .map(String::from)
            .to_vec(),
        rows: vec![
            vec![
                "mass, bunny at 64x64: GPU wall / Mirtich's analytic time".into(),
                format!("{:.1}x", t.mass_bunny_64_gpu_over_analytic),
                format!("<= {}x", t.mass_target),
                met(t.mass_bunny_64_gpu_over_analytic <= t.mass_target),
            ],
            vec![
                format!(
                    "buoyancy, 50 bodies at 32x32, first {} steps: GPU solver / CPU reference \
                     solver, steps per second, interleaved pairs ({:.1} / {:.1})",
                    t.buoyancy_steps,
                    t.buoyancy_gpu_steps_per_second,
                    t.buoyancy_cpu_steps_per_second
                ),
                t.buoyancy_race.in_words(),
                format!(">= {}x", t.buoyancy_target),
                met(t.buoyancy_gpu_over_cpu >= t.buoyancy_target),
            ],
        ],
    }
}

/// The two orders of peels and sums on the bunny at 64x64.
pub fn peel_orders(results: &Paper4Results) -> Table {
    Table {
        caption: "Order of peels and sums, bunny at 64x64: the paper keeps the n peel textures \
                  and reduces each; the default adds each peel into running sums as it is drawn \
                  (one reduction, and peel memory that does not grow with n)"
            .into(),
        header: [
            "order",
            "default",
            "wall (ms)",
            "largest difference (of the largest integral)",
            "peel target sets held",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .peel_orders
            .iter()
            .map(|r| {
                vec![
                    r.order.name().into(),
                    if r.default { "yes" } else { "no" }.into(),
                    format!("{:.3}", r.wall_ms),
                    format!("{:.1e}", r.max_difference),
                    r.peel_target_sets.to_string(),
                ]
            })
            .collect(),
    }
}

/// A per-pass profile as a table (nested scopes indented).
pub fn profile(caption: &str, rows: &[ProfileRow]) -> Table {
    Table {
        caption: caption.into(),
        header: [
            "pass",
            "calls",
            "GPU (ms, timestamps)",
            "wall (ms)",
            "waiting (ms)",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    format!("{}{}", "  ".repeat(r.depth), r.name),
                    r.calls.to_string(),
                    r.gpu_ms.map_or("-".into(), |g| format!("{g:.3}")),
                    format!("{:.3}", r.wall_ms),
                    format!("{:.3}", r.wait_ms),
                ]
            })
            .collect(),
    }
}
