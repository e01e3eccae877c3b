//! Technique 7: the histogram by additive blending against the gather formulation and the
//! CPU.

use super::results::Lecture3Results;
use crate::report::Table;

pub fn table(results: &Lecture3Results) -> Table {
    let yes = |b: bool| if b { "yes" } else { "NO" }.to_string();
    Table {
        caption: format!(
            "7. Histogram by additive blending of one point per value (skewed values in [0, 1)), \
             against a gather pass without blending and the CPU, on {}",
            results.renderer
        ),
        header: [
            "values",
            "bins",
            "blended = CPU",
            "gathered = CPU",
            "blending (ms)",
            "gather (ms)",
            "CPU (ms)",
            "CPU / blending",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .histogram
            .iter()
            .map(|r| {
                vec![
                    r.values.to_string(),
                    r.bins.to_string(),
                    yes(r.blend_equal),
                    r.gather_equal.map_or("not run".into(), yes),
                    format!("{:.3}", r.blend_ms),
                    r.gather_ms.map_or("-".into(), |m| format!("{m:.2}")),
                    format!("{:.3}", r.cpu_ms),
                    format!("{:.2}", r.cpu_ms / r.blend_ms),
                ]
            })
            .collect(),
    }
}
