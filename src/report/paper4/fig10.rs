//! Fig. 9 and 10: the buoyancy scene's last frame, and the peels of a buoyant bunny: each peel
//! that covers enough of the target to be seen as a picture, and one picture of how many peels
//! reach each texel, where the deep peels of a few texels show.

use super::bench::{Paper4Results, FIG10_DIR as DIR};
use crate::gl::drawn::{self, Drawn, MOSTLY_EMPTY};
use crate::mass::peel::LAYERS_PNG;
use crate::report::{BenchOptions, Figure};

pub fn figures(opts: &BenchOptions, results: &Paper4Results) -> Vec<Figure> {
    let mut figures = vec![Figure {
        file: results.buoyancy.frame.clone(),
        caption: "Fig. 9: the 50-body scene after the benchmark run (gravity blue, buoyancy \
                  yellow)"
            .into(),
    }];
    let n = results.fig10_peels;
    let mut sparse = Vec::new();
    for k in 1..=n {
        let file = format!("{DIR}/peel{k}_target0.png");
        // A peel of a few texels shows nothing as a picture of its own (the layers picture
        // below shows where it is); where the picture's record is gone, it is shown.
        if let Some(texels) = few_texels(&drawn::recorded(&opts.out_dir.join(&file))) {
            sparse.push(format!("peel {k}: {texels} texels"));
            continue;
        }
        figures.push(Figure {
            file,
            caption: format!(
                "Fig. 10: bunny below the water, peel {k} of {n}, target 0 at 128x128: one panel \
                 per integrand (rx, ry, rz, V), each on one scale for all the peels (its key \
                 below it; zero dark grey, positive red to yellow, negative blue to cyan)"
            ),
        });
    }
    figures.push(Figure {
        file: format!("{DIR}/{LAYERS_PNG}"),
        caption: format!(
            "Fig. 10: how many of the {n} peels reach each texel of the bunny below the water{}",
            if sparse.is_empty() {
                String::new()
            } else {
                format!(
                    " ({}: too few to draw as pictures of their own, which are written beside \
                     the others in {DIR}/ with their exact values as .npy)",
                    sparse.join(", ")
                )
            }
        ),
    });
    figures
}

/// The texels a peel's picture shows, when they are too few to be seen (a panel
/// [`MOSTLY_EMPTY`]).
fn few_texels(drawn: &Option<Drawn>) -> Option<usize> {
    let Some(Drawn::Picture(picture)) = drawn else {
        return None;
    };
    let first = picture.panels.first()?;
    let texels = (first.texels.0 * first.texels.1) as f32;
    (first.filled < MOSTLY_EMPTY).then(|| (first.filled * texels).round() as usize)
}
