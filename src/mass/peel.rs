//! The peeling driver [section 3.2, and the n + 2 passes of 5.2]: every body of a batch is
//! drawn into its own tile (viewport) of one set of render targets, so each peel is one
//! pass for all bodies and one reduction serves them all. (One body alone is a batch of
//! one whose tile is the whole target.)
//!
//! - Pass 0 (with water): the fluid surface's depth into `T_dw`.
//! - Passes 1..n: every body is drawn with the listing wrapped by the peel test (the GL
//!   layer's `peel_discard`, against the previous layer's depth) and the water test. Each
//!   body has its own occlusion query: a body whose layer drew nothing is done and is not
//!   drawn again, and peeling ends when every body is done. Each peel is added into the
//!   running sums.
//! - Pass n + 1 (with water): the fluid surface where the first peel faced down (`T_w`),
//!   added straight into the sums (one quad: at most one fragment per pixel).

use super::framing::Framing;
use super::integrals::VolumeIntegrals;
use super::integrands::{self, Soup, TARGETS};
use super::reduce::{Accumulator, REDUCTION_PASS};
use crate::gl::dump::{self, DumpRange};
use crate::gl::{
    ensure_finite, Blend, Compare, Context, DepthTest, DrawState, Framebuffer, GlError,
    OcclusionQuery, Pass, Primitive, Program, Rect, Texture, TextureFormat,
};
use glam::Mat4;
use std::cell::RefCell;
use std::path::{Path, PathBuf};

/// One body of a batch: which triangles of the soup (a range of its index buffer), where
/// it is, how it is framed, and where its tile lies in the render targets.
#[derive(Clone, Copy, Debug)]
pub struct Job<'a> {
    /// The body, as errors name it ("body 3 (torus)").
    pub body: &'a str,
    /// (first index, index count) in [`Soup::set_indices`]'s list.
    pub indices: (usize, usize),
    /// Body frame -> world.
    pub model: Mat4,
    pub framing: Framing,
    /// Its viewport: `framing.resolution` square, at a multiple of the tile block.
    pub tile: Rect,
}

/// What a batch produced.
#[derive(Clone, Debug)]
pub struct BatchResult {
    /// The ten integrals of each job, world coordinates.
    pub integrals: Vec<VolumeIntegrals>,
    /// The number of peels (n): the deepest body's.
    pub peels: usize,
}

/// Render targets and programs for batches of up to `width x height` pixels.
pub struct Peeler {
    ctx: Context,
    peel_program: Program,
    water_depth_program: Program,
    water_patch_program: Program,
    /// The current peel's integrands (`T_k`) and faces-down mark.
    peel_targets: Vec<Texture>,
    /// `T_dw`.
    water: Framebuffer,
    /// The peel targets with depth `T_d(k)` for even and odd k (ping-pong).
    layers: [Framebuffer; 2],
    /// Per body, the tile and framing the water passes read (`glsl/mass/water_surface.vert`).
    tile_data: RefCell<Option<Texture>>,
    /// One occlusion query per body (grown on demand).
    queries: RefCell<Vec<OcclusionQuery>>,
    width: u32,
    height: u32,
    accumulator: Accumulator,
    /// Tiles are reduced in aligned blocks of this side (a power of two); `None` reduces
    /// the whole target (one body).
    block: Option<u32>,
    max_layers: usize,
    /// When on, each peel's integrand targets are kept as RGBA bytes (the viewer's insets).
    capture: RefCell<Option<Vec<CapturedPeel>>>,
}

/// One peel's integrand targets as [`crate::gl::dump`] maps them (each channel from its own
/// minimum to maximum), rows from the bottom, `width x height` of the whole target.
#[derive(Clone, Debug)]
pub struct CapturedPeel {
    pub width: u32,
    pub height: u32,
    pub targets: Vec<Vec<u8>>,
}

impl Peeler {
    /// Targets of `width x height`, reduced per `block x block` tile (`None`: as a whole).
    pub fn new(
        ctx: &Context,
        width: u32,
        height: u32,
        block: Option<u32>,
    ) -> Result<Peeler, GlError> {
        let mut peel_targets = Vec::new();
        for _ in 0..TARGETS {
            peel_targets.push(Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F)?);
        }
        peel_targets.push(Texture::new_2d(ctx, width, height, TextureFormat::R32F)?);
        let water_depth = Texture::new_2d(ctx, width, height, TextureFormat::Depth32F)?;
        let colors: Vec<&Texture> = peel_targets.iter().collect();
        let layer = |name| -> Result<Framebuffer, GlError> {
            let depth = Texture::new_2d(ctx, width, height, TextureFormat::Depth32F)?;
            Framebuffer::new(ctx, name, &colors, Some(&depth))
        };
        let layers = [layer("mass: peels (even)")?, layer("mass: peels (odd)")?];
        Ok(Peeler {
            ctx: ctx.clone(),
            peel_program: integrands::peel_program(ctx)?,
            water_depth_program: integrands::water_depth_program(ctx)?,
            water_patch_program: integrands::water_patch_program(ctx)?,
            peel_targets,
            water: Framebuffer::new(
                ctx,
                "mass: fluid surface depth T_dw",
                &[],
                Some(&water_depth),
            )?,
            layers,
            tile_data: RefCell::new(None),
            queries: RefCell::new(Vec::new()),
            width,
            height,
            accumulator: Accumulator::new(ctx, width, height)?,
            block,
            max_layers: 64,
            capture: RefCell::new(None),
        })
    }

    /// The ten integrals of every job's body (below `water`, the level of a flat fluid
    /// surface, when given). `dump` receives the colour-encoded integrands of each peel.
    /// A body whose integrals are not finite is an error naming it.
    pub fn run(
        &self,
        soup: &Soup,
        jobs: &[Job],
        water: Option<f64>,
        dump: Option<&Path>,
    ) -> Result<BatchResult, GlError> {
        self.accumulator.clear()?;
        self.water_depth_pass(jobs, water)?;
        let peels = self.peel_passes(soup, jobs, dump)?;
        if let Some(level) = water {
            self.water_patch_pass(jobs, level)?;
        }
        let sums = self.accumulator.reduce(self.block)?;
        let integrals = jobs
            .iter()
            .map(|job| {
                let index = match self.block {
                    Some(b) => {
                        let columns = self.width.div_ceil(b);
                        ((job.tile.y / b) * columns + job.tile.x / b) as usize
                    }
                    None => 0,
                };
                integrands::decode(sums[index], &job.framing)
            })
            .collect::<Vec<VolumeIntegrals>>();
        for (job, i) in jobs.iter().zip(&integrals) {
            ensure_finite(
                i.to_array(),
                &format!("mass: the volume integrals of {}", job.body),
                REDUCTION_PASS,
            )?;
        }
        Ok(BatchResult { integrals, peels })
    }

    /// Pass 0: `T_dw`, cleared to 0 (nothing is above the water) and, with water, the
    /// fluid surface drawn over every tile.
    fn water_depth_pass(&self, jobs: &[Job], water: Option<f64>) -> Result<(), GlError> {
        self.water.clear_depth_stencil(0.0, 0)?;
        let Some(level) = water else { return Ok(()) };
        self.upload_tile_data(jobs)?;
        let mut pass = self.water.pass(
            &self.water_depth_program,
            "mass: pass 0, fluid surface depth",
        )?;
        pass.state(DrawState {
            depth: Some(DepthTest {
                func: Compare::Always,
                write: true,
            }),
            color_write: false,
            ..DrawState::default()
        });
        self.water_quads(&mut pass, jobs.len(), level)
    }

    /// Passes 1..n: peel until no body draws anything; each peel goes into the sums.
    fn peel_passes(
        &self,
        soup: &Soup,
        jobs: &[Job],
        dump: Option<&Path>,
    ) -> Result<usize, GlError> {
        let mut queries = self.queries.borrow_mut();
        while queries.len() < jobs.len() {
            queries.push(OcclusionQuery::new(&self.ctx)?);
        }
        let water_depth = self.water.depth().expect("T_dw has a depth attachment");
        let state = DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            ..DrawState::default()
        };
        let mut active: Vec<bool> = vec![true; jobs.len()];
        for layer in 0..self.max_layers {
            let target = &self.layers[layer % 2];
            // Only the depth: the accumulation ignores pixels this peel did not reach
            // (the colours too when they are to be looked at).
            target.clear_depth_stencil(1.0, 0)?;
            let capturing = self.capture.borrow().is_some();
            if dump.is_some() || capturing {
                target.clear_colors([0.0; 4])?;
            }
            {
                let mut pass = target.pass(&self.peel_program, "mass: depth peel")?;
                pass.state(state)
                    .texture(
                        "u_peel_depth",
                        self.layers[(layer + 1) % 2].depth().expect("depth"),
                    )
                    .texture("u_water_depth", water_depth)
                    .uniform("u_peel_layer", layer as i32);
                for (k, job) in jobs.iter().enumerate().filter(|(k, _)| active[*k]) {
                    let (first, count) = job.indices;
                    pass.viewport(job.tile)
                        .uniform("u_model", job.model)
                        .uniform("u_frame_center", job.framing.center.as_vec3())
                        .uniform("u_projection", job.framing.projection());
                    queries[k].begin();
                    let drawn = pass.draw_elements_instanced(
                        &soup.vertices,
                        Primitive::Triangles,
                        first,
                        count,
                        1,
                    );
                    queries[k].end();
                    drawn?;
                }
            }
            for (k, a) in active.iter_mut().enumerate() {
                if *a {
                    *a = queries[k].samples()? > 0;
                }
            }
            if !active.iter().any(|&a| a) {
                return Ok(layer);
            }
            if let Some(dir) = dump {
                self.dump_peel(dir, layer)?;
            }
            if let Some(peels) = self.capture.borrow_mut().as_mut() {
                let targets = self.peel_targets[..TARGETS]
                    .iter()
                    .map(|t| dump::to_rgba8(t, DumpRange::Auto))
                    .collect::<Result<_, _>>()?;
                peels.push(CapturedPeel {
                    width: self.width,
                    height: self.height,
                    targets,
                });
            }
            let tiles = row_runs(
                jobs.iter()
                    .zip(&active)
                    .filter(|(_, &a)| a)
                    .map(|(j, _)| j.tile),
            );
            let depth = target.depth().expect("peel targets have depth");
            self.accumulator
                .add_peel(&self.peel_targets, depth, layer == 0, &tiles)?;
        }
        Ok(self.max_layers)
    }

    /// The last pass: the fluid surface inside each body, added into the sums.
    fn water_patch_pass(&self, jobs: &[Job], level: f64) -> Result<(), GlError> {
        let target = self.accumulator.sums_target();
        let mut pass = target.pass(
            &self.water_patch_program,
            "mass: pass n+1, fluid surface patch",
        )?;
        pass.state(DrawState {
            blend: Some(Blend::Add),
            ..DrawState::default()
        })
        .texture(
            "u_first_peel_faces_down",
            self.accumulator.first_peel_faces_down(),
        );
        self.water_quads(&mut pass, jobs.len(), level)
    }

    /// Every body's tile and framing as rows of a small float texture, so that the water
    /// quads of all bodies are one instanced draw.
    fn upload_tile_data(&self, jobs: &[Job]) -> Result<(), GlError> {
        let mut slot = self.tile_data.borrow_mut();
        let fits = matches!(slot.as_ref(), Some(t) if t.height() as usize >= jobs.len());
        if !fits {
            let rows = jobs.len().next_power_of_two().max(16) as u32;
            *slot = Some(Texture::new_2d(&self.ctx, 3, rows, TextureFormat::Rgba32F)?);
        }
        let data: Vec<f32> = jobs
            .iter()
            .flat_map(|j| {
                let (t, f) = (j.tile, j.framing);
                let c = f.center.as_vec3();
                [
                    t.x as f32,
                    t.y as f32,
                    t.w as f32,
                    0.0,
                    c.x,
                    c.y,
                    c.z,
                    f.half_width as f32,
                    f.half_depth as f32,
                    0.0,
                    0.0,
                    0.0,
                ]
            })
            .collect();
        slot.as_ref()
            .expect("made above")
            .upload_region_f32(0, 0, 3, jobs.len() as u32, &data)
    }

    /// The fluid surface quads of `bodies` bodies, one instanced draw over the whole target.
    fn water_quads(&self, pass: &mut Pass, bodies: usize, level: f64) -> Result<(), GlError> {
        let slot = self.tile_data.borrow();
        let tiles = slot.as_ref().expect("tile data uploaded in pass 0");
        pass.texture("u_tiles", tiles)
            .uniform(
                "u_target_size",
                glam::Vec2::new(self.width as f32, self.height as f32),
            )
            .uniform("u_water_level", level as f32);
        pass.draw_attributeless(Primitive::TriangleStrip, 4, bodies)
    }

    /// Fig. 10: each target of peel `layer` as a PNG, each channel mapped to [0, 255].
    fn dump_peel(&self, dir: &Path, layer: usize) -> Result<(), GlError> {
        for (i, texture) in self.peel_targets.iter().take(TARGETS).enumerate() {
            let path: PathBuf = dir.join(format!("peel{}_target{i}.png", layer + 1));
            dump::texture_png(texture, &path, DumpRange::Auto)?;
        }
        Ok(())
    }

    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// Keep each peel's integrand targets from the next [`Peeler::run`] on (see
    /// [`Peeler::take_captured`]); off by default, since reading them back costs time.
    pub fn set_capture(&self, on: bool) {
        *self.capture.borrow_mut() = on.then(Vec::new);
    }

    /// The peels captured since the last call, first peel first.
    pub fn take_captured(&self) -> Vec<CapturedPeel> {
        self.capture
            .borrow_mut()
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }
}

/// The rectangles covering `tiles` row by row: one per row of tiles, from its leftmost to
/// its rightmost tile (pixels in between add nothing, the accumulation being masked by the
/// peel's depth), so a peel's accumulation is a few draws, not one per body.
fn row_runs(tiles: impl Iterator<Item = Rect>) -> Vec<Rect> {
    let mut rows: std::collections::BTreeMap<(u32, u32), (u32, u32)> = Default::default();
    for t in tiles {
        let span = rows.entry((t.y, t.h)).or_insert((t.x, t.x + t.w));
        span.0 = span.0.min(t.x);
        span.1 = span.1.max(t.x + t.w);
    }
    rows.into_iter()
        .map(|((y, h), (x0, x1))| Rect::new(x0, y, x1 - x0, h))
        .collect()
}
