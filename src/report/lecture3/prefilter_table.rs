//! Table 2: the minification prefilter as the camera moves away ([`super::prefilter`]).

use super::prefilter::SUPERSAMPLES;
use super::results::Lecture3Results;
use crate::report::Table;

pub fn table(results: &Lecture3Results) -> Table {
    let d = &results.displacement;
    let image = if results.quick { 64 } else { 128 };
    Table {
        caption: format!(
            "2. The minification prefilter as the camera moves away: RMS difference (RGB in \
             0..1) from {0}x{0} unfiltered rays per pixel averaged, frame time (GL timer \
             query; the prefiltered frame's includes drawing its shading pyramid toward the \
             camera) and steps per hit pixel, without and with the prefilter; {image}x{image} \
             pixels, {1}; on {2}. The last column judges the prefiltered frame against the CPU \
             reference of the same rule (pixels counted by what differs).",
            SUPERSAMPLES, d.map, results.renderer
        ),
        header: [
            "elevation",
            "distance",
            "deepest stop level",
            "error, unfiltered",
            "error, prefiltered",
            "ms, unfiltered",
            "ms, prefiltered",
            "ms, of which the shading pyramid",
            "steps, unfiltered",
            "steps, prefiltered",
            "vs CPU: wrong surface / outside tolerance / kind / normal / colour",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .prefilter
            .iter()
            .map(|r| {
                let c = &r.comparison;
                vec![
                    format!("{:.0}", r.elevation),
                    format!("{:.1}", r.distance),
                    r.max_level.to_string(),
                    format!("{:.4}", r.quality.unfiltered_error),
                    format!("{:.4}", r.quality.prefiltered_error),
                    format!("{:.2}", r.unfiltered_ms),
                    format!("{:.2}", r.prefiltered_ms),
                    format!("{:.2}", r.shading_ms),
                    format!("{:.1}", r.quality.unfiltered_steps),
                    format!("{:.1}", r.quality.prefiltered_steps),
                    format!(
                        "{} / {} / {} / {} / {} of {}",
                        c.wrong_surface,
                        c.outside_tolerance,
                        c.wrong_kind,
                        c.wrong_normal,
                        c.wrong_colour,
                        c.compared
                    ),
                ]
            })
            .collect(),
    }
}
