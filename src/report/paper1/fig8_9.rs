//! Fig. 8-9: a snapshot of each scene's last frame (written by the bench, which holds the GL
//! state): the models, their colliding triangles and the CAP boxes.

use super::bench::SceneRun;
use crate::report::Figure;

pub fn figure(run: &SceneRun) -> Option<Figure> {
    run.snapshot.as_ref().map(|file| Figure {
        file: file.clone(),
        caption: format!(
            "Fig. 8-9: {} at the last frame; colliding triangles red, drawn over the surfaces \
             in front of them (they lie where the models pass through each other), CAP boxes \
             orange (X) and yellow (Y)",
            run.label
        ),
    })
}
