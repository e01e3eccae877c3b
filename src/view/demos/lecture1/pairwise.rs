//! Pairwise triangle tests in textures live: two interlocking tori deforming, the triangles of
//! intersecting pairs red, and the pair quad's result P0 (a texel per triangle pair) with its
//! hierarchical levels as insets; P0's probe shows brute force's exact answer beside it.

use super::{draw_scene, shown, sides, snapshot_model};
use crate::collide::scenes::Scene;
use crate::gl::Context;
use crate::lecture1::pairwise::{PairwiseResult, PairwiseTester, DEFAULT_TILE};
use crate::lecture1::pictures::pair_buffers;
use crate::lecture1::reference::pairs_between;
use crate::mesh::Mesh;
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

/// Triangles per torus: one tile, and quick on a software renderer.
const TRIANGLES: usize = 300;

pub struct PairwiseDemo {
    scene: Scene,
    tester: PairwiseTester,
    frame: usize,
    models: (Mesh, Mesh),
    result: Option<PairwiseResult>,
    /// The buffers of this frame's pair quad.
    pictures: Vec<Shown>,
    short_pictures: Vec<Shown>,
}

impl PairwiseDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let scene = Scene::build("interlocking-tori", Some(TRIANGLES))?;
        let models = (scene.x.rest.clone(), scene.y.rest.clone());
        Ok(PairwiseDemo {
            scene,
            tester: PairwiseTester::new(ctx, DEFAULT_TILE)?,
            frame: 0,
            models,
            result: None,
            pictures: Vec::new(),
            short_pictures: Vec::new(),
        })
    }

    /// P0 and its levels for this frame; P0's reference is brute force's exact pairs.
    fn pair_pictures(&self, short: bool, exact: &[(u32, u32)]) -> anyhow::Result<Vec<Shown>> {
        let (a, b) = &self.models;
        let tile = self.tester.first_tile(a, Some(b))?;
        let mut out: Vec<Shown> = pair_buffers(
            &tile.target.p0,
            &tile.reduction,
            "(triangle i of X, row; triangle j of Y, column)",
            short,
        )?
        .into_iter()
        .map(shown)
        .collect();
        let w = tile.target.width();
        let mut reference = vec![0.0f32; w * tile.target.height()];
        for &(i, j) in exact {
            reference[i as usize * w + j as usize] = 1.0;
        }
        out[0].reference = Some(reference);
        Ok(out)
    }
}

impl Demo for PairwiseDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        let (px, py) = self.scene.frame(self.frame);
        self.frame += 1;
        self.models.0.positions = px;
        self.models.1.positions = py;
        let (a, b) = &self.models;
        let result = self.tester.run(a, Some(b))?;
        let exact = pairs_between(a, b);
        self.pictures = self.pair_pictures(false, &exact)?;
        self.short_pictures = self.pair_pictures(true, &exact)?;
        self.result = Some(result);
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.05, 0.05, 0.07, 1.0])?;
        let take = |pictures: &[Shown]| -> Vec<Shown> {
            pictures
                .iter()
                .map(|s| Shown {
                    panel: s.panel.clone(),
                    probe_values: s.probe_values.clone(),
                    reference: s.reference.clone(),
                })
                .collect()
        };
        if view.shown > 0 {
            let mut pictures = take(&self.pictures);
            if view.shown - 1 < pictures.len() {
                let picture = pictures.swap_remove(view.shown - 1);
                inset::draw_picture(canvas, vec![picture], canvas.below_text())?;
            }
            return Ok(());
        }
        let pairs = self.result.as_ref().map_or(&[][..], |r| &r.pairs[..]);
        let (cx, cy) = (sides(pairs, true), sides(pairs, false));
        let (a, b) = &self.models;
        let (mx, my) = (
            snapshot_model(a, &a.positions, &cx),
            snapshot_model(b, &b.positions, &cy),
        );
        draw_scene(canvas, (&mx, &my), take(&self.short_pictures), view)
    }

    fn buffers(&self) -> Vec<String> {
        ["tori", "P0", "P1", "P2", "P3"].map(String::from).to_vec()
    }

    fn overlay(&self) -> Vec<String> {
        let mut lines = vec![
            format!(
                "lecture 1, pairwise tests in textures: {}, {} + {} triangles",
                self.scene.label,
                self.models.0.triangles.len(),
                self.models.1.triangles.len()
            ),
            "triangles of intersecting pairs red; P0 probe: CPU = brute force".into(),
        ];
        if let Some(r) = &self.result {
            lines.push(format!(
                "reported by the quad {}  intersecting {}  readback {} B",
                r.candidates,
                r.pairs.len(),
                r.readback_bytes
            ));
        }
        lines
    }

    fn timings(&self) -> String {
        self.result.as_ref().map_or(String::new(), |r| {
            format!("pair passes {:.2} ms", r.test_ms)
        })
    }
}
