//! Table 3's other two: normal-aware clustering on the room, and the light hierarchy's other
//! uses on the bunny ([`super::light_uses`]).

use super::results::Lecture3Results;
use crate::lecture3::light_hierarchy::normal_cone::MIN_COHERENCE;
use crate::report::Table;

/// Normal-aware clustering against the fixed merge.
pub fn clustering_table(results: &Lecture3Results) -> Table {
    let rows = &results.light_uses.clustering;
    Table {
        caption: format!(
            "3. Normal-aware clustering on the room (corners where walls, floor and block \
             meet): a cluster is one light when radius < theta x distance and its mean unit \
             normal is at least {} long, against the fixed merge (distance alone); relative RMS \
             error of the GPU tree search against the brute-force sum, lights summed per \
             receiver (CPU traversal of the same hierarchy), nodes visited (GPU); on {}",
            rows.first().map_or(MIN_COHERENCE, |r| r.min_coherence),
            results.renderer
        ),
        header: [
            "theta",
            "error, fixed merge",
            "error, normal-aware",
            "lights, fixed",
            "lights, normal-aware",
            "nodes, fixed",
            "nodes, normal-aware",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.theta.to_string(),
                    format!("{:.2e}", r.fixed_error),
                    format!("{:.2e}", r.normal_aware_error),
                    format!("{:.1}", r.fixed_lights),
                    format!("{:.1}", r.normal_aware_lights),
                    format!("{:.1}", r.fixed_nodes),
                    format!("{:.1}", r.normal_aware_nodes),
                ]
            })
            .collect(),
    }
}

/// Subsurface scattering and environment light: tree against brute force, GPU against CPU.
pub fn uses_table(results: &Lecture3Results) -> Table {
    let u = &results.light_uses;
    let rows = [&u.subsurface, &u.environment]
        .iter()
        .flat_map(|run| {
            run.rows.iter().map(move |r| {
                vec![
                    format!(
                        "{} (GPU brute force within {:.1e} of the CPU's)",
                        run.mode, run.brute_gpu_vs_cpu
                    ),
                    format!(
                        "{} {} (of a {}x{} image)",
                        run.lights,
                        lights_label(&run.mode),
                        run.side,
                        run.side
                    ),
                    r.theta.to_string(),
                    format!("{:.2e}", r.relative_rms_error),
                    format!("{:.2e}", r.cpu_relative_rms_error),
                    format!("{:.1e}", r.tree_gpu_vs_cpu),
                    format!("{:.1}", r.mean_gathered),
                    format!("{:.1}", r.mean_nodes),
                ]
            })
        })
        .collect();
    Table {
        caption: format!(
            "3. The hierarchy's other uses on the bunny ({}x{} receivers): subsurface scattering \
             (Jensen et al.'s dipole, skin 1, summed over irradiance samples: the spot light's \
             image of the model, its frustum fitted to the model) and environment light (a procedural sky on a lat-long grid, visibility \
             ignored); relative RMS error of the tree search against the brute-force sum on \
             the GPU and on the CPU (f64), largest GPU - CPU difference of the tree search over \
             the largest value, samples or clusters summed and nodes visited per receiver; on {}",
            u.subsurface.image.0, u.subsurface.image.1, results.renderer
        ),
        header: [
            "use",
            "lights that carry light",
            "theta",
            "relative RMS error (GPU)",
            "relative RMS error (CPU)",
            "GPU vs CPU",
            "summed per receiver",
            "nodes visited",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

fn lights_label(mode: &str) -> &'static str {
    match mode {
        "sss" => "irradiance samples",
        "environment" => "sky directions",
        _ => "VPLs",
    }
}
