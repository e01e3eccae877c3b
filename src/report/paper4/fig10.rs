//! Fig. 9 and 10: the buoyancy scene's last frame, and the peels of a buoyant bunny.

use super::bench::{Paper4Results, FIG10_DIR as DIR};
use crate::report::Figure;

pub fn figures(results: &Paper4Results) -> Vec<Figure> {
    let mut figures = vec![Figure {
        file: results.buoyancy.frame.clone(),
        caption: "Fig. 9: the 50-body scene after the benchmark run (gravity blue, buoyancy \
                  yellow)"
            .into(),
    }];
    for k in 1..=results.fig10_peels {
        figures.push(Figure {
            file: format!("{DIR}/peel{k}_target0.png"),
            caption: format!(
                "Fig. 10: bunny below the water, peel {k} of {}, target 0 at 128x128: one panel \
                 per integrand (rx, ry, rz, V), each on one scale for all the peels (its key \
                 below it; zero dark grey, positive red to yellow, negative blue to cyan)",
                results.fig10_peels
            ),
        });
    }
    figures
}
