//! Technique 2, speed: frame times of the pyramid traversal and relief mapping against the
//! exact CPU tracer, for maps of growing resolution.

use super::images::ORBIT_PNG;
use super::results::Lecture3Results;
use crate::report::{Figure, Table};

pub fn table(results: &Lecture3Results) -> Table {
    let d = &results.displacement;
    Table {
        caption: format!(
            "2. Frame times, {0}x{0} pixels, elevation 30 degrees, generated maps, on {1}",
            d.image, results.renderer
        ),
        header: [
            "map",
            "levels",
            "pyramid (ms)",
            "frames/s",
            "iterations per hit pixel",
            "relief 32+8 (ms)",
            "exact CPU tracer (ms)",
            "CPU / pyramid",
        ]
        .map(String::from)
        .to_vec(),
        rows: d
            .speed
            .iter()
            .map(|r| {
                vec![
                    format!("{0}x{0}", r.map_size),
                    r.levels.to_string(),
                    format!("{:.2}", r.pyramid_ms),
                    format!("{:.0}", 1e3 / r.pyramid_ms),
                    format!("{:.1}", r.pyramid_iterations),
                    format!("{:.2}", r.relief_ms),
                    format!("{:.1}", r.cpu_ms),
                    format!("{:.1}", r.cpu_ms / r.pyramid_ms),
                ]
            })
            .collect(),
    }
}

pub fn figure() -> Figure {
    Figure {
        file: ORBIT_PNG.into(),
        caption: "2. The camera orbiting the displaced box (pyramid traversal, 35 degrees)".into(),
    }
}
