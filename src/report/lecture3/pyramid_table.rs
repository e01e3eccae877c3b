//! Technique 1's table: the max/min/mean pyramids of generated maps, GPU against CPU.

use super::images::PYRAMID_PNG;
use super::results::Lecture3Results;
use crate::report::{Figure, Table};

pub fn table(results: &Lecture3Results) -> Table {
    Table {
        caption: format!(
            "1. Image pyramid of the generated map at several sizes: levels drawn one pass each \
             from the level below (max and min exact; the mean in fp32, against the CPU's f64 \
             means of the pixels each node covers), on {}",
            results.renderer
        ),
        header: [
            "map",
            "levels",
            "GPU = CPU (bit for bit)",
            "mean: max |GPU - CPU|",
            "GPU passes (ms)",
            "CPU (ms)",
            "CPU / GPU",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .pyramid
            .iter()
            .map(|r| {
                vec![
                    format!("{0}x{0}", r.size),
                    r.levels.to_string(),
                    if r.equal_to_cpu { "yes" } else { "NO" }.into(),
                    format!("{:.1e}", r.mean_max_error),
                    format!("{:.3}", r.gpu_ms),
                    format!("{:.3}", r.cpu_ms),
                    format!("{:.2}", r.cpu_ms / r.gpu_ms),
                ]
            })
            .collect(),
    }
}

pub fn figure() -> Figure {
    Figure {
        file: PYRAMID_PNG.into(),
        caption: "1. The max (left), min (middle) and mean (right) pyramids of the height map as \
                  the GPU drew them, every level laid out as the traversals read them (level 0, \
                  the levels above to its right), on one colour key from 0 to 1; the atlas's \
                  empty corner and any padding to a power of two are left at 0, the neutral \
                  dark grey"
            .into(),
    }
}
