//! Paper 1 live: the two deforming models of a Table III scene, their colliding triangles (red)
//! and the boxes of the colliding AABB pairs, with the pair texture P0 and its encodings P1..P3
//! (hierarchical) and P1' (reduced) as insets [Govindaraju et al. / Sec. 5, Fig. 6].

use crate::collide::pipeline::{FrameResult, Options, StreamingCollider};
use crate::collide::reduction::{encode4, encode8, Scheme};
use crate::collide::reduction_gpu::ReadbackMode;
use crate::collide::scenes::{Scene, SCENES};
use crate::collide::snapshot::{self, Orbit};
use crate::collide::stream_setup::auto_leaf_size_for_pair;
use crate::collide::tri_test::Predicate;
use crate::gl::picture::{fixed, Panel, Scale};
use crate::gl::{Context, Framebuffer, Rect, Texture, TextureFormat};
use crate::mesh::Mesh;
use crate::view::inset::{self, Shown};
use crate::view::{overlay, Canvas, Demo, ViewState};
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

    /// The buffers of paper Fig. 6: P0, the hierarchy's levels, the reduced P1'; each with
    /// what a texel is in its title, coloured by its pairs (P0) or by the set bits of its masks
    /// (the levels), the probe showing the masks beside the CPU encoding of the same P0.
    fn pictures(&self, short: bool) -> anyhow::Result<Vec<Shown>> {
        let p0 = &self.collider.target.p0;
        let (w, h) = (p0.width() as usize, p0.height() as usize);
        let p0_values = p0.download_f32()?;
        let title = |short_name: &str, long: String| {
            if short {
                short_name.to_string()
            } else {
                long
            }
        };
        let mut out = vec![Shown {
            panel: Panel {
                title: title(
                    "P0",
                    format!(
                        "P0 ({w}x{h}): texel (i, j) is 1 when box i of X (column) and box j of                          Y (row) overlap"
                    ),
                ),
                values: p0_values.clone(),
                width: w as u32,
                height: h as u32,
                scale: Scale::fixed(0.0, 1.0),
            },
            probe_values: None,
            reference: None,
        }];
        let bits = |v: f32| (v as u32).count_ones() as f32;
        let (mut below, mut bw, mut bh) = (p0_values.clone(), w, h);
        for (i, t) in self
            .collider
            .reduction
            .level_textures()
            .into_iter()
            .enumerate()
        {
            let masks = t.download_f32()?;
            let (cpu, cw, ch) = encode4(&below, bw, bh);
            out.push(Shown {
                panel: Panel {
                    title: title(
                        &format!("P{}", i + 1),
                        format!(
                            "P{} ({cw}x{ch}): set bits of the 16-bit mask of a 4x4 block of P{i}",
                            i + 1
                        ),
                    ),
                    values: masks.iter().map(|&m| bits(m)).collect(),
                    width: t.width(),
                    height: t.height(),
                    scale: Scale::fixed(0.0, 16.0),
                },
                probe_values: Some(masks),
                reference: Some(cpu.clone()),
            });
            (below, bw, bh) = (cpu, cw, ch);
        }
        let reduced = self.collider.reduction.reduced_texture();
        let masks = reduced.download_f32()?;
        let per_texel: Vec<f32> = masks
            .chunks_exact(4)
            .map(|c| c.iter().map(|&m| bits(m)).sum())
            .collect();
        let (cpu, rw, rh) = encode8(&p0_values, w, h);
        out.push(Shown {
            panel: Panel {
                title: title(
                    "P1'",
                    format!("P1' reduced ({rw}x{rh}): set bits of the 64-bit mask of an 8x8 block of P0"),
                ),
                values: per_texel.clone(),
                width: reduced.width(),
                height: reduced.height(),
                scale: Scale::fixed(0.0, 64.0),
            },
            probe_values: Some(per_texel),
            reference: Some(cpu.iter().map(|c| c.iter().map(|&m| bits(m)).sum()).collect()),
        });
        Ok(out)
    }

    /// The colliding triangles and the CAP boxes alone, framed to fill `rect` of `canvas`:
    /// where the collision is, drawn large (in the whole scene the boxes are a few pixels).
    fn draw_cap_zoom(
        &self,
        canvas: &Canvas,
        x: &snapshot::SnapshotModel,
        y: &snapshot::SnapshotModel,
        rect: Rect,
        view: &ViewState,
    ) -> anyhow::Result<()> {
        let only_colliding = |m: &snapshot::SnapshotModel| -> Vec<[glam::Vec3; 3]> {
            m.colliding
                .iter()
                .map(|&t| m.triangles[t as usize])
                .collect()
        };
        let (tx, ty) = (only_colliding(x), only_colliding(y));
        if tx.is_empty() && ty.is_empty() {
            return Ok(());
        }
        let all_x: Vec<u32> = (0..tx.len() as u32).collect();
        let all_y: Vec<u32> = (0..ty.len() as u32).collect();
        let zx = snapshot::SnapshotModel {
            triangles: tx,
            colliding: &all_x,
            cap_boxes: x.cap_boxes.clone(),
        };
        let zy = snapshot::SnapshotModel {
            triangles: ty,
            colliding: &all_y,
            cap_boxes: y.cap_boxes.clone(),
        };
        let ctx = canvas.context();
        let colour = Texture::new_2d(ctx, rect.w, rect.h, TextureFormat::Rgba8)?;
        let depth = Texture::new_2d(ctx, rect.w, rect.h, TextureFormat::Depth32F)?;
        let target = Framebuffer::new(ctx, "viewer CAP zoom", &[&colour], Some(&depth))?;
        target.clear_color(0, [0.1, 0.1, 0.13, 1.0])?;
        target.clear_depth_stencil(1.0, 0)?;
        let orbit = Orbit {
            yaw: view.yaw,
            pitch: view.pitch,
            zoom: 0.8,
        };
        snapshot::draw(&zx, &zy, &target, orbit)?;
        let mut pixels = target.read_u8(0, Rect::sized(rect.w, rect.h))?;
        // A grey frame around the zoomed view.
        for yy in 0..rect.h {
            for xx in 0..rect.w {
                if xx == 0 || yy == 0 || xx == rect.w - 1 || yy == rect.h - 1 {
                    let i = ((yy * rect.w + xx) * 4) as usize;
                    pixels[i..i + 4].copy_from_slice(&[150, 150, 150, 255]);
                }
            }
        }
        for px in pixels.chunks_exact_mut(4) {
            px[3] = 255;
        }
        overlay::draw_image(canvas, &pixels, rect.w, rect.h, (rect.x, rect.y))?;
        overlay::draw_text(
            canvas,
            &["CAPs, zoomed".into()],
            overlay::Corner::Probe(rect.x, rect.y + rect.h),
        )?;
        Ok(())
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
        if view.shown > 0 {
            let mut pictures = self.pictures(false)?;
            if view.shown - 1 < pictures.len() {
                let shown = pictures.swap_remove(view.shown - 1);
                let rect = canvas.below_text();
                inset::draw_picture(canvas, vec![shown], rect)?;
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
        let pictures = self.pictures(true)?;
        let strip = inset::strip_rect(canvas, pictures.len());
        // The zoom sits above the strip at the right, a quarter of the canvas wide.
        let side = (canvas.width() / 4).min(canvas.height().saturating_sub(strip.h) / 2);
        if side >= 32 {
            let zoom = Rect::new(canvas.width() - side, strip.h + 4, side, side);
            self.draw_cap_zoom(canvas, &mx, &my, zoom, view)?;
        }
        inset::draw_picture(canvas, pictures, strip)?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        let mut out = vec!["scene".to_string()];
        out.extend(["P0", "P1", "P2", "P3", "P1' (reduced)"].map(String::from));
        out
    }

    fn overlay(&self) -> Vec<String> {
        let mut lines = vec![
            format!(
                "{}: {} + {} triangles",
                self.scene.label,
                self.models.0.triangles.len(),
                self.models.1.triangles.len()
            ),
            "colliding triangles red; boxes of the CAPs: X orange, Y yellow".into(),
        ];
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
                "eta {}%  readback {scheme} ({} B), paper's switch",
                fixed(r.eta * 100.0, 4),
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
