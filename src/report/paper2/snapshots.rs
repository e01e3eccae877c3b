//! The PNGs taken during the run: Fig. 2's render target, Fig. 3-5's frames, the impostor
//! atlases, captioned in the order they were written.

use super::bench::{Paper2Results, Shows};
use crate::report::Figure;

pub fn figures(results: &Paper2Results) -> Vec<Figure> {
    results
        .snapshots
        .iter()
        .map(|s| Figure {
            file: s.file.clone(),
            caption: caption(&s.shows),
        })
        .collect()
}

fn caption(shows: &Shows) -> String {
    match shows {
        Shows::Fig3 { characters } => {
            format!("Fig. 3: {characters} soldiers without LOD and frustum culling (two-pass)")
        }
        Shows::RenderTarget { model } => format!(
            "Fig. 2: the pass-1 render target after the last {} run, the skinned positions' x, y \
             and z as three panels (a column per character, a row per vertex index, blocks of \
             128 characters stacked)",
            model.name()
        ),
        Shows::ImpostorAtlas {
            model,
            views,
            frames,
        } => format!(
            "Sprite level: impostor atlas of the {} ({views} view directions x {frames} \
             animation phases)",
            model.name()
        ),
        Shows::LodRun {
            figure,
            model,
            characters,
            sprites: false,
        } => format!(
            "{figure}: {characters} {}s with the three LOD meshes and frustum culling, the \
             paper's setup (two-pass)",
            model.name()
        ),
        Shows::LodRun {
            figure,
            model,
            characters,
            sprites: true,
        } => format!(
            "{figure} setup plus sprites beyond the last mesh distance (this project's \
             extension, not in the paper): {characters} {}s (two-pass)",
            model.name()
        ),
    }
}
