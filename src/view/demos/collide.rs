//! Paper 1 live: the two deforming models of a Table III scene, their colliding triangles (red)
//! and the boxes of the colliding AABB pairs, with the pair texture P0 and its encodings P1..P3
//! (hierarchical) and P1' (reduced) as insets [Govindaraju et al. / Sec. 5, Fig. 6].

use crate::collide::pipeline::{FrameResult, Options, StreamingCollider};
use crate::collide::reduction::Scheme;
use crate::collide::reduction_gpu::ReadbackMode;
use crate::collide::scenes::{Scene, SCENES};
use crate::collide::snapshot::{self, Orbit};
use crate::collide::stream_setup::auto_leaf_size_for_pair;
use crate::collide::tri_test::Predicate;
use crate::gl::dump::DumpRange;
use crate::gl::{Context, Rect, Texture};
use crate::mesh::Mesh;
use crate::view::{inset, Canvas, Demo, ViewState};
use anyhow::Context as _;

pub struct CollideDemo {
    scene: Scene,
    collider: StreamingCollider,
    frame: usize,
    /// The models at the current frame, and the last frame's result.
    models: (Mesh, Mesh),
    result: Option<FrameResult>,
}

impl CollideDemo {
    pub fn new(ctx: &Context, name: &str, triangles: Option<usize>) -> anyhow::Result<Self> {
        let scene = Scene::build(name, triangles)
            .with_context(|| format!("scenes: {}", SCENES.join(", ")))?;
        let (x, y) = (&scene.x.rest, &scene.y.rest);
        // The paper's fixed switch, not the calibrated choice: a window and a headless run of
        // one frame must pick the same scheme to draw the same picture.
        let options = Options {
            leaf_size: auto_leaf_size_for_pair(x, y, ctx.info().is_software())?,
            readback: ReadbackMode::PaperSwitch,
            predicate: Predicate::Exact,
            max_tile: None,
        };
        let collider = StreamingCollider::new(ctx, x, y, options)?;
        let models = (x.clone(), y.clone());
        Ok(CollideDemo {
            scene,
            collider,
            frame: 0,
            models,
            result: None,
        })
    }

    /// The buffers of paper Fig. 6: P0, the hierarchy's levels, the reduced P1'.
    fn textures(&self) -> Vec<(String, &Texture, DumpRange)> {
        let mut out = vec![(
            "P0".to_string(),
            &self.collider.target.p0,
            DumpRange::Fixed(0.0, 1.0),
        )];
        for (i, t) in self
            .collider
            .reduction
            .level_textures()
            .into_iter()
            .enumerate()
        {
            out.push((format!("P{}", i + 1), t, DumpRange::Auto));
        }
        out.push((
            "P1' (reduced)".to_string(),
            self.collider.reduction.reduced_texture(),
            DumpRange::Auto,
        ));
        out
    }
}

impl Demo for CollideDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        let (px, py) = self.scene.frame(self.frame);
        self.frame += 1;
        let result = self.collider.frame(&px, &py)?;
        self.models.0.positions = px;
        self.models.1.positions = py;
        // Fill both encodings from this frame's P0, so that every inset shows this frame.
        let ctx = self.collider.context().clone();
        for scheme in [Scheme::Hierarchical, Scheme::Reduced] {
            self.collider
                .reduction
                .read(&ctx, &self.collider.target, scheme)?;
        }
        self.result = Some(result);
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.05, 0.05, 0.07, 1.0])?;
        let textures = self.textures();
        let full = Rect::sized(canvas.width(), canvas.height());
        if view.shown > 0 {
            if let Some((name, texture, range)) = textures.get(view.shown - 1) {
                inset::draw_texture(canvas, texture, *range, full, name)?;
            }
            return Ok(());
        }
        let empty = FrameResult::default();
        let result = self.result.as_ref().unwrap_or(&empty);
        let (cx, cy) = snapshot::frame_colliding(result);
        let (mx, my) = snapshot::frame_models(
            &self.collider,
            result,
            (&self.models.0, &self.models.1),
            (&cx, &cy),
        );
        let orbit = Orbit {
            yaw: view.yaw,
            pitch: view.pitch,
            zoom: view.zoom * 0.8,
        };
        snapshot::draw(&mx, &my, canvas.target(), orbit)?;
        for ((name, texture, range), rect) in
            textures.iter().zip(inset::strip(canvas, textures.len()))
        {
            inset::draw_texture(canvas, texture, *range, rect, name)?;
        }
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        let mut out = vec!["scene".to_string()];
        out.extend(self.textures().into_iter().map(|(name, ..)| name));
        out
    }

    fn overlay(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "{}: {} + {} triangles",
            self.scene.label,
            self.models.0.triangles.len(),
            self.models.1.triangles.len()
        )];
        if let Some(r) = &self.result {
            let scheme = r.scheme.map_or("none (no CAP)".to_string(), |s| {
                format!("{s:?}").to_lowercase()
            });
            lines.push(format!(
                "CAPs {}  PCTPs {}  CTPs {}  pairs {}",
                r.caps,
                r.pctps,
                r.ctps,
                r.pairs.len()
            ));
            lines.push(format!(
                "eta {:.4}%  readback {scheme} ({} B), paper's switch",
                r.eta * 100.0,
                r.readback_bytes
            ));
        }
        lines
    }

    fn timings(&self) -> String {
        let Some(r) = &self.result else {
            return String::new();
        };
        let t = &r.timings;
        format!(
            "overlap {:.2} encode {:.2} read {:.2} tri {:.2} update {:.2} total {:.2} ms",
            t.overlap, t.encode, t.readback, t.tri_test, t.update, t.total
        )
    }
}
