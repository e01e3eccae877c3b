//! How fast, and where the time goes: the speed targets as ratios of this run (what the code
//! aims at on llvmpipe, where most users run it),
//! the two orders of peels and sums, and per-pass profiles.

use super::bench::Paper4Results;
use crate::gl::profile::ProfileRow;
use crate::mass::buoyancy::race::Race;
use crate::report::Table;
use crate::timing::{judge, Load, Target};

/// The project's speed targets on llvmpipe (a fixed cost per pass must not swamp the
/// papers' work), each a ratio measured in this run.
pub fn targets(results: &Paper4Results) -> Table {
    let t = &results.targets;
    let race = &t.buoyancy_race;
    let status = race_status(race, t.buoyancy_target);
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
                "none".into(),
                format!(
                    "dropped: the same passes without the paper's stopping test (the layer \
                     count given in advance, no occlusion query read between two peels) are \
                     {:.1}x in this run against {:.1}x with it: the test's waits are the \
                     difference, the passes themselves (each peel drawn before the next reads \
                     its depth) the rest; the paper's crossover is a claim about GPUs (Fig. 5)",
                    t.mass_bunny_64_without_stopping_test, t.mass_bunny_64_gpu_over_analytic
                ),
            ],
            vec![
                format!(
                    "buoyancy, 50 bodies at 32x32, first {} steps: GPU solver / CPU reference \
                     solver, steps per second, interleaved pairs ({:.1} / {:.1})",
                    t.buoyancy_steps,
                    t.buoyancy_gpu_steps_per_second,
                    t.buoyancy_cpu_steps_per_second
                ),
                race.in_words(),
                format!(">= {}x in every round", t.buoyancy_target),
                status,
            ],
        ],
    }
}

/// "met" when every round of the race reaches `target`, "not met" when none does, else why
/// it is not judged (rounds on both sides, or a loaded machine).
fn race_status(race: &Race, target: f64) -> String {
    let verdict = judge(
        &race.gpu_over_cpu,
        Target::AtLeast(target),
        Load::worst(race.load_before, race.load_after),
        "x",
    );
    match verdict.holds {
        Some(true) => "met".into(),
        Some(false) => "not met".into(),
        None => verdict
            .note
            .rsplit("; ")
            .next()
            .unwrap_or("not judged")
            .into(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mass::buoyancy::race::RaceSetup;
    use crate::timing::Spread;

    fn race(ratios: &[f64], load: f64) -> Race {
        let load = Some(Load {
            one_minute: load,
            cores: 2,
        });
        Race {
            setup: RaceSetup {
                bodies: 50,
                resolution: 32,
                steps: 120,
                rounds: ratios.len(),
                dt: 1.0 / 60.0,
                extra_damping: false,
            },
            gpu_over_cpu: Spread::of(ratios),
            gpu_steps_per_second: 1.0,
            cpu_steps_per_second: 1.0,
            load_before: load,
            load_after: load,
        }
    }

    #[test]
    fn the_buoyancy_target_is_judged_on_every_round_and_the_load() {
        assert_eq!(race_status(&race(&[1.02, 1.05, 1.1], 0.5), 1.0), "met");
        assert_eq!(race_status(&race(&[0.85, 0.86, 0.87], 0.5), 1.0), "not met");
        let straddles = race_status(&race(&[0.97, 1.0, 1.03], 0.5), 1.0);
        assert!(
            straddles.starts_with("not judged: the runs fall on both sides"),
            "{straddles}"
        );
        let loaded = race_status(&race(&[1.2, 1.3, 1.4], 9.0), 1.0);
        assert!(loaded.starts_with("not judged: machine loaded"), "{loaded}");
    }
}
