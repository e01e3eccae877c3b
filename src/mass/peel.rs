//! The peeling driver [section 3.2, and the n + 2 passes of 5.2]: every body of a batch is
//! drawn into its own tile (viewport) of one set of render targets, so each peel is one
//! pass for all bodies and one reduction serves them all. (One body alone is a batch of
//! one whose tile is the whole target.)
//!
//! - Pass 0 (with water): the fluid surface's depth into `T_dw`.
//! - Passes 1..n: every body is drawn with the listing wrapped by the peel test (the GL
//!   layer's `peel_discard`, against the previous layer's depth) and the water test, in
//!   one pass: a draw per group of the [`Soup`] (which holds the bodies posed in their
//!   tiles; a group per body in the buoyancy batch), each counted by its own occlusion
//!   query. From pass 2 on, the stencil counts the fragments met at each pixel, and a
//!   group with no pixel that met two ([`super::peel_end`]) is done and is not drawn
//!   again, nor is one whose layer drew nothing; peeling ends when every group is done.
//!   Pass 1 writes the paper's stencil bit instead, by two-sided stencil: 1 where the
//!   kept fragment faces down (a back face seen from above), 0 where it faces up.
//! - Pass n + 1 (with water): the fluid surface where that stencil bit is 1 (`T_w`).
//!
//! Two orders of the sums ([`PeelOrder`]): by default each peel is added into running sums
//! as soon as it is drawn (one blended pass, and two sets of peel targets whatever n);
//! `KeepLayers` is the paper's: the n textures `T_1 .. T_n` and `T_w` are kept and each
//! is reduced. Both give the same sums up to fp32 rounding; the first keeps memory and
//! passes independent of n.
//!
//! Peeling stops at [`PeelSettings::max_peels`] layers; the result says whether a layer
//! beyond the limit still drew something (`truncated`), so the caller can warn.

use super::framing::Framing;
use super::integrals::VolumeIntegrals;
use super::integrands::{self, Integrands, Soup};
use super::peel_depth::PeelDepth;
use super::peel_end::{self, PeelEnd};
use super::reduce::{Accumulator, REDUCTION_PASS};
use crate::gl::dump;
use crate::gl::picture::{Panel, Scale};
use crate::gl::profile;
use crate::gl::{
    ensure_finite, Blend, Compare, Context, DepthTest, DrawState, Framebuffer, GlError,
    OcclusionQuery, Pass, Primitive, Program, Rect, StencilOp, StencilTest, Texture, TextureFormat,
};
use serde::Serialize;
use std::cell::{Cell, Ref, RefCell};
use std::path::{Path, PathBuf};

/// A peel's draws go to the renderer in this many parts (of its bodies), a flush between
/// two: a software rasterizer (llvmpipe) starts on a scene only when it is flushed, so its
/// threads rasterize the first bodies while the rest are still being set up (one body is one
/// part, with nothing to flush). The 50-body buoyancy race against the CPU solver went from
/// 0.99-1.02x to 1.12-1.21x on llvmpipe (2 cores; 2 to 50 parts all gained, 4 the most), and
/// from 3.71x to 4.58x on an H100.
const PEEL_FLUSH_PARTS: usize = 4;

/// The default limit on peels (the deepest of the paper's objects has 8).
pub const DEFAULT_MAX_PEELS: usize = 64;

/// In which order peels and sums meet.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PeelOrder {
    /// Each peel is added into running sums at once; one reduction at the end (default:
    /// memory and passes do not grow with n).
    #[default]
    RunningSums,
    /// The paper's order [3.2-3.3]: keep the n peel textures and `T_w`, then reduce each.
    KeepLayers,
}

impl PeelOrder {
    pub fn name(self) -> &'static str {
        match self {
            PeelOrder::RunningSums => "running-sums",
            PeelOrder::KeepLayers => "keep-layers",
        }
    }
}

/// How a [`Peeler`] peels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PeelSettings {
    /// Stop after this many layers (at least 1).
    pub max_peels: usize,
    pub order: PeelOrder,
}

impl Default for PeelSettings {
    fn default() -> Self {
        PeelSettings {
            max_peels: DEFAULT_MAX_PEELS,
            order: PeelOrder::default(),
        }
    }
}

/// One body of a batch: how it is framed and where its tile lies in the render targets
/// (its triangles are in the [`Soup`], posed and placed there).
#[derive(Clone, Copy, Debug)]
pub struct Job<'a> {
    /// The body, as errors name it ("body 3 (torus)").
    pub body: &'a str,
    /// Its group in the [`Soup`].
    pub group: usize,
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
    /// A layer past `max_peels` still drew something: the integrals miss it.
    pub truncated: bool,
    /// `KeepLayers` only: the integrals of each kept texture, `T_1 .. T_n` then `T_w`
    /// (with water), each a list over the jobs.
    pub layers: Vec<Vec<VolumeIntegrals>>,
}

/// The peel textures of the paper's order: `T_k` (three RGBA32F targets and the depth
/// `T_d(k)`, the first also holding the stencil bit), and `T_w` (sharing `T_1`'s stencil).
struct Kept {
    layers: Vec<Framebuffer>,
    water: Framebuffer,
}

/// Render targets and programs for batches of up to `width x height` pixels.
pub struct Peeler {
    ctx: Context,
    peel_program: Program,
    water_depth_program: Program,
    water_patch_program: Program,
    /// `T_dw`.
    water: Framebuffer,
    /// The peel targets with the depth `T_d(k)`: pass 1's (with its stencil bit), then
    /// two for even and odd k (ping-pong).
    layers: [Framebuffer; 3],
    /// The running sums with pass 1's stencil, for the water patch.
    water_patch_target: Framebuffer,
    /// `KeepLayers`: made on first use, grown to the deepest batch.
    kept: RefCell<Option<Kept>>,
    /// Per body, the tile and framing the water passes read (`glsl/mass/water_surface.vert`).
    tile_data: RefCell<Option<Texture>>,
    /// One occlusion query per group (grown on demand).
    queries: RefCell<Vec<OcclusionQuery>>,
    /// Which groups have a layer behind the last peel.
    peel_end: PeelEnd,
    width: u32,
    height: u32,
    accumulator: Accumulator,
    /// Tiles are reduced in aligned blocks of this side (a power of two); `None` reduces
    /// the whole target (one body).
    block: Option<u32>,
    settings: PeelSettings,
    /// Which integrands the passes evaluate (the ten of eq. 4 and 6, or eq. 4's four).
    integrands: Integrands,
    /// How the peel depths are stored and compared.
    depth: PeelDepth,
    /// When on, each peel's integrand targets are kept as floats (the viewer's insets and the
    /// dumps).
    capture: RefCell<Option<Vec<CapturedPeel>>>,
    /// A layer count given in advance ([`Peeler::set_known_layers`]): the passes without
    /// the stopping test.
    known_layers: Cell<Option<usize>>,
}

/// One peel's integrand targets read back: RGBA floats (the channels of
/// [`integrands::CHANNELS`]), rows from the bottom, `width x height` of the whole target
/// (one target when only eq. 4's integrands were evaluated).
#[derive(Clone, Debug)]
pub struct CapturedPeel {
    pub width: u32,
    pub height: u32,
    pub targets: Vec<Vec<f32>>,
}

impl CapturedPeel {
    /// Channel `channel` of target `target` as a picture panel, on `scale`.
    pub fn panel(&self, target: usize, channel: usize, title: &str, scale: Scale) -> Panel {
        Panel::channel(
            title,
            &self.targets[target],
            4,
            channel,
            (self.width, self.height),
            scale,
        )
    }

    /// The scale shared by channel `channel` of target `target` in all `peels` (one set of
    /// related pictures, as [`crate::gl::dump`] says).
    pub fn scale(peels: &[CapturedPeel], target: usize, channel: usize) -> Scale {
        let values: Vec<Vec<f32>> = peels
            .iter()
            .map(|p| {
                p.targets[target]
                    .iter()
                    .skip(channel)
                    .step_by(4)
                    .copied()
                    .collect()
            })
            .collect();
        Scale::of(values.iter().map(|v| v.as_slice()))
    }
}

/// The file of [`write_peel_pictures`]'s picture of how many peels reach each texel.
pub const LAYERS_PNG: &str = "layers.png";

/// Fig. 10: each target of each peel as a picture, `peel<k>_target<i>.png` in `dir`, one panel
/// per channel, each channel on one scale for all the peels, and its exact values beside it as
/// `peel<k>_target<i>.npy`; and [`LAYERS_PNG`], one panel of how many peels reach each texel
/// (a fragment with a non-zero integrand), which shows where the deep peels are, however few
/// their texels.
pub fn write_peel_pictures(dir: &Path, peels: &[CapturedPeel]) -> Result<(), GlError> {
    if let Some(first) = peels.first() {
        let layers: Vec<f32> = (0..(first.width * first.height) as usize)
            .map(|texel| {
                peels
                    .iter()
                    .filter(|p| {
                        p.targets[0][4 * texel..4 * texel + 4]
                            .iter()
                            .any(|v| *v != 0.0)
                    })
                    .count() as f32
            })
            .collect();
        let panel = Panel {
            title: format!("peels reaching each texel (of {})", peels.len()),
            values: layers,
            width: first.width,
            height: first.height,
            scale: Scale::fixed(0.0, peels.len() as f32),
        };
        // At least 640 wide, so its title and key are in the large font.
        dump::picture_png(&[panel], (640, 700), &dir.join(LAYERS_PNG))?;
    }
    let targets = peels.first().map_or(0, |p| p.targets.len());
    for target in 0..targets {
        let names = integrands::CHANNELS[target];
        let scales: Vec<Scale> = (0..names.len())
            .map(|c| CapturedPeel::scale(peels, target, c))
            .collect();
        for (k, peel) in peels.iter().enumerate() {
            let panels: Vec<Panel> = names
                .iter()
                .enumerate()
                .map(|(c, name)| {
                    peel.panel(target, c, &format!("peel {} {name}", k + 1), scales[c])
                })
                .collect();
            let side = 2 * peel.width.clamp(64, 160) + 24;
            let size = (side * panels.len() as u32, side + 60);
            let path: PathBuf = dir.join(format!("peel{}_target{target}.png", k + 1));
            dump::picture_png(&panels, size, &path)?;
            // The exact values beside the picture (the layout of `gl::npy`).
            let shape = [peel.height as usize, peel.width as usize, 4];
            crate::files::write_npy(&path.with_extension("npy"), &shape, &peel.targets[target])
                .map_err(|e| GlError::Io {
                    path: path.with_extension("npy").display().to_string(),
                    message: format!("{e:#}"),
                })?;
        }
    }
    Ok(())
}

/// The names of the passes (errors and the profile).
const PEEL_PASS: &str = "mass: passes 1..n, depth peel";
const WATER_DEPTH_PASS: &str = "mass: pass 0, fluid surface depth";
const WATER_PATCH_PASS: &str = "mass: pass n+1, fluid surface patch";
const CLEAR_PASS: &str = "mass: clear a peel's targets";

/// What a [`Peeler`] evaluates and how it stores it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeelerOptions {
    /// The integrands the passes evaluate (eq. 4's four need one render target).
    pub integrands: Integrands,
    /// The format of the running sums ([`Accumulator::with_format`]; RGBA16F is the float
    /// format a GeForce 7800 could blend into).
    pub sum_format: TextureFormat,
    /// How the peel depths are stored and compared; `None`: as the context allows
    /// ([`PeelDepth::for_context`]: 24-bit under a period GPU without float depth).
    pub depth: Option<PeelDepth>,
}

impl Default for PeelerOptions {
    /// The ten integrals of eq. 4 and 6, fp32 sums, peel depths as the context allows.
    fn default() -> Self {
        PeelerOptions {
            integrands: Integrands::All,
            sum_format: TextureFormat::Rgba32F,
            depth: None,
        }
    }
}

impl Peeler {
    /// Targets of `width x height`, reduced per `block x block` tile (`None`: as a whole),
    /// for the ten integrals of eq. 4 and 6 ([`PeelerOptions::default`]).
    pub fn new(
        ctx: &Context,
        width: u32,
        height: u32,
        block: Option<u32>,
    ) -> Result<Peeler, GlError> {
        Peeler::with_options(ctx, width, height, block, PeelerOptions::default())
    }

    /// [`Peeler::new`] evaluating and storing what `options` says.
    pub fn with_options(
        ctx: &Context,
        width: u32,
        height: u32,
        block: Option<u32>,
        options: PeelerOptions,
    ) -> Result<Peeler, GlError> {
        let PeelerOptions {
            integrands,
            sum_format,
            depth,
        } = options;
        let depth = depth.unwrap_or_else(|| PeelDepth::for_context(ctx));
        let targets = integrands.targets();
        let accumulator = Accumulator::with(ctx, width, height, targets, sum_format)?;
        let layer = |name| peel_layer(ctx, width, height, targets, depth, name);
        let layers = [
            layer("mass: peel 1")?,
            layer("mass: peels (even)")?,
            layer("mass: peels (odd)")?,
        ];
        let water_depth = Texture::new_2d(ctx, width, height, depth.water_format())?;
        let sums: Vec<&Texture> = accumulator.sums().iter().collect();
        let water_patch_target = Framebuffer::new(
            ctx,
            "mass: sums with pass 1's stencil",
            &sums,
            layers[0].depth(),
        )?;
        Ok(Peeler {
            ctx: ctx.clone(),
            peel_program: integrands::peel_program_at(ctx, integrands, depth)?,
            water_depth_program: integrands::water_depth_program(ctx)?,
            water_patch_program: integrands::water_patch_program(ctx, integrands)?,
            water: Framebuffer::new(
                ctx,
                "mass: fluid surface depth T_dw",
                &[],
                Some(&water_depth),
            )?,
            layers,
            water_patch_target,
            kept: RefCell::new(None),
            tile_data: RefCell::new(None),
            queries: RefCell::new(Vec::new()),
            peel_end: PeelEnd::new(ctx)?,
            width,
            height,
            accumulator,
            block,
            settings: PeelSettings::default(),
            integrands,
            depth,
            capture: RefCell::new(None),
            known_layers: Cell::new(None),
        })
    }

    /// Peel exactly `layers` layers from now on, without the stopping test (no occlusion
    /// query read between two peels, no stencil count); `None`: the paper's test again. Each
    /// peel still reads the last one's depth and is added into the sums, so a software
    /// renderer still draws each peel before the next is set up. Only for timing what the test costs: with the count of an earlier run of
    /// the same body and framing the passes and the result are the same, and a wrong count
    /// gives a wrong result.
    pub fn set_known_layers(&self, layers: Option<usize>) {
        self.known_layers.set(layers);
    }

    /// Peel with `settings` from now on. Errors on a limit of zero peels.
    pub fn set_settings(&mut self, settings: PeelSettings) -> Result<(), GlError> {
        if settings.max_peels == 0 {
            return Err(GlError::Invalid("the peel limit must be at least 1".into()));
        }
        self.settings = settings;
        Ok(())
    }

    pub fn settings(&self) -> PeelSettings {
        self.settings
    }

    /// Which integrands the passes evaluate.
    pub fn integrands(&self) -> Integrands {
        self.integrands
    }

    /// How the peel depths are stored and compared.
    pub fn depth(&self) -> PeelDepth {
        self.depth
    }

    /// A profile scope named `name` around `work` (`gl::profile`; draws are recorded under
    /// their pass names on their own, this groups clears and several draws).
    fn pass<T>(&self, name: &str, work: impl FnOnce() -> Result<T, GlError>) -> Result<T, GlError> {
        let _scope = profile::scope(&self.ctx, name);
        work()
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
        let keep = self.settings.order == PeelOrder::KeepLayers;
        if !keep {
            self.pass(CLEAR_PASS, || self.accumulator.clear())?;
        }
        self.water_depth_pass(jobs, water)?;
        // The dumps share one scale over all the peels: kept until the last, then written.
        let capturing = self.capture.borrow().is_some();
        let first = self.capture.borrow().as_ref().map_or(0, |c| c.len());
        if dump.is_some() && !capturing {
            self.set_capture(true);
        }
        let passes = self.peel_passes(soup, jobs);
        let captured: Vec<CapturedPeel> = match dump {
            Some(_) if capturing => self.capture.borrow().as_ref().expect("on")[first..].to_vec(),
            Some(_) => {
                let c = self.take_captured();
                self.set_capture(false);
                c
            }
            None => Vec::new(),
        };
        let (peels, truncated) = passes?;
        if let Some(dir) = dump {
            write_peel_pictures(dir, &captured)?;
        }
        if let Some(level) = water {
            self.water_patch_pass(jobs, level)?;
        }
        let decode = |sums: &[[[f64; 4]; integrands::TARGETS]]| -> Vec<VolumeIntegrals> {
            jobs.iter()
                .map(|job| integrands::decode(sums[self.tile_index(job)], &job.framing))
                .collect()
        };
        let (integrals, layers) = if keep {
            let kept = self.kept.borrow();
            let kept = kept.as_ref().expect("made by the peel passes");
            let mut reduced: Vec<&Framebuffer> = kept.layers.iter().take(peels).collect();
            if water.is_some() {
                reduced.push(&kept.water);
            }
            let layers = reduced
                .iter()
                .map(|t| Ok(decode(&self.accumulator.reduce_from(t, self.block)?)))
                .collect::<Result<Vec<_>, GlError>>()?;
            let total = jobs
                .iter()
                .enumerate()
                .map(|(k, job)| {
                    let zero = VolumeIntegrals {
                        origin: job.framing.center,
                        ..VolumeIntegrals::default()
                    };
                    layers.iter().map(|l| l[k]).fold(zero, |a, b| a + b)
                })
                .collect();
            (total, layers)
        } else {
            (decode(&self.accumulator.reduce(self.block)?), Vec::new())
        };
        for (job, i) in jobs.iter().zip(&integrals) {
            ensure_finite(
                i.to_array(),
                &format!("mass: the volume integrals of {}", job.body),
                REDUCTION_PASS,
            )?;
        }
        Ok(BatchResult {
            integrals,
            peels,
            truncated,
            layers,
        })
    }

    /// Which reduced texel holds `job`'s sums.
    fn tile_index(&self, job: &Job) -> usize {
        match self.block {
            Some(b) => {
                let columns = self.width.div_ceil(b);
                ((job.tile.y / b) * columns + job.tile.x / b) as usize
            }
            None => 0,
        }
    }

    /// Pass 0: `T_dw`, cleared to 0 (nothing is above the water) and, with water, the
    /// fluid surface drawn over every tile.
    fn water_depth_pass(&self, jobs: &[Job], water: Option<f64>) -> Result<(), GlError> {
        self.pass("mass: pass 0 (all bodies)", || {
            self.water.clear_depth_stencil(0.0, 0)?;
            let Some(level) = water else { return Ok(()) };
            self.upload_tile_data(jobs)?;
            let mut pass = self
                .water
                .pass(&self.water_depth_program, WATER_DEPTH_PASS)?;
            pass.state(DrawState {
                depth: Some(DepthTest {
                    func: Compare::Always,
                    write: true,
                }),
                color_write: false,
                ..DrawState::default()
            });
            self.water_quads(&mut pass, jobs.len(), level)
        })
    }

    /// The framebuffer of peel `layer`: one of the two ping-pong sets, or (paper's order)
    /// the kept `T_layer`, made when first needed.
    fn layer_target(&self, layer: usize) -> Result<LayerTarget<'_>, GlError> {
        if self.settings.order == PeelOrder::RunningSums {
            let k = if layer == 0 { 0 } else { 1 + layer % 2 };
            return Ok(LayerTarget::PingPong(&self.layers[k]));
        }
        {
            let mut slot = self.kept.borrow_mut();
            if slot.is_none() {
                let targets = self.integrands.targets();
                let (w, h, depth) = (self.width, self.height, self.depth);
                let first = peel_layer(&self.ctx, w, h, targets, depth, "mass: T_1")?;
                let colors: Vec<Texture> = (0..targets)
                    .map(|_| {
                        Texture::new_2d(&self.ctx, self.width, self.height, TextureFormat::Rgba32F)
                    })
                    .collect::<Result<_, _>>()?;
                let water = Framebuffer::new(
                    &self.ctx,
                    "mass: T_w",
                    &colors.iter().collect::<Vec<_>>(),
                    first.depth(),
                )?;
                *slot = Some(Kept {
                    layers: vec![first],
                    water,
                });
            }
            let kept = slot.as_mut().expect("made above");
            while kept.layers.len() <= layer {
                let name = format!("mass: T_{}", kept.layers.len() + 1);
                let targets = self.integrands.targets();
                kept.layers.push(peel_layer(
                    &self.ctx,
                    self.width,
                    self.height,
                    targets,
                    self.depth,
                    &name,
                )?);
            }
        }
        Ok(LayerTarget::Kept(Ref::map(self.kept.borrow(), |k| {
            &k.as_ref().expect("made above").layers[layer]
        })))
    }

    /// The depth `T_d(layer)` the next layer peels against.
    fn layer_depth(&self, layer: usize) -> Result<Texture, GlError> {
        Ok(self
            .layer_target(layer)?
            .depth()
            .expect("peel targets have depth")
            .clone())
    }

    /// Passes 1..n: peel until no body has a layer left or a layer past the limit still
    /// draws something; each peel goes into the sums (or is kept). Returns (n, truncated).
    fn peel_passes(&self, soup: &Soup, jobs: &[Job]) -> Result<(usize, bool), GlError> {
        let keep = self.settings.order == PeelOrder::KeepLayers;
        let groups = soup.groups();
        if let Some(job) = jobs.iter().find(|j| j.group >= groups.len()) {
            return Err(GlError::Invalid(format!(
                "mass: {} is in group {} of a soup of {} groups",
                job.body,
                job.group,
                groups.len()
            )));
        }
        let mut queries = self.queries.borrow_mut();
        while queries.len() < groups.len() {
            queries.push(OcclusionQuery::new(&self.ctx)?);
        }
        // Each group's tiles, for the test of where its peeling ends.
        let mut tiles: Vec<Vec<Rect>> = vec![Vec::new(); groups.len()];
        for job in jobs {
            tiles[job.group].push(job.tile);
        }
        self.peel_end.set_tiles(&tiles, (self.width, self.height))?;
        let mut active: Vec<bool> = vec![true; groups.len()];
        let water_depth = self.water.depth().expect("T_dw has a depth attachment");
        // Counting each fragment with the facing it was drawn with needs a renderer whose
        // gl_FrontFacing says it.
        let facing_sign = self.ctx.fragment_facing()?.sign();
        let max = self.settings.max_peels;
        let known = self.known_layers.get().map(|n| n.min(max));
        for layer in 0..=max {
            if known == Some(layer) {
                return Ok((layer, false));
            }
            let previous = self.layer_depth(if layer == 0 { 1 } else { layer - 1 })?;
            let target = self.layer_target(layer)?;
            self.pass(CLEAR_PASS, || {
                // Only the depth for the running sums: the accumulation ignores pixels
                // this peel did not reach. Kept layers are reduced whole, so their
                // colours start at zero.
                target.clear_depth_stencil(1.0, 0)?;
                if keep || self.capture.borrow().is_some() {
                    target.clear_colors([0.0; 4])?;
                }
                Ok(())
            })?;
            // The groups still drawing something, each counted by its own query.
            let drawing: Vec<usize> = (0..groups.len()).filter(|&g| active[g]).collect();
            let counted = &queries[..drawing.len()];
            self.pass("mass: one peel (all bodies)", || {
                // region: peel-pass
                let mut pass = target.pass(&self.peel_program, PEEL_PASS)?;
                pass.state(peel_state(layer == 0))
                    .texture("u_peel_depth", &previous)
                    .texture("u_water_depth", water_depth)
                    .uniform("u_peel_layer", layer as i32)
                    .uniform("u_facing_sign", facing_sign);
                let ranges: Vec<(usize, usize)> = drawing.iter().map(|&g| groups[g]).collect();
                let per = ranges.len().div_ceil(PEEL_FLUSH_PARTS).max(1);
                let parts = ranges.chunks(per).zip(counted.chunks(per));
                for (k, (part, queries)) in parts.enumerate() {
                    if k > 0 {
                        self.ctx.flush();
                    }
                    let triangles = Primitive::Triangles;
                    if known.is_some() {
                        pass.draw_element_ranges(&soup.vertices, triangles, part)?;
                    } else {
                        pass.draw_elements_counted(&soup.vertices, triangles, part, queries)?;
                    }
                }
                if known.is_some() {
                    return Ok(());
                }
                if layer > 0 {
                    self.peel_end.test(&target, &drawing)?;
                }
                Ok(())
                // endregion
            })?;
            let (samples, more) = if known.is_some() {
                (vec![1; drawing.len()], vec![true; drawing.len()])
            } else {
                self.pass("mass: occlusion queries", || {
                    let samples = OcclusionQuery::samples_of(counted)?;
                    let more = if layer > 0 {
                        self.peel_end.another_layer(drawing.len())?
                    } else {
                        vec![true; drawing.len()]
                    };
                    Ok((samples, more))
                })?
            };
            let mut drew = vec![false; groups.len()];
            for ((&g, pixels), another) in drawing.iter().zip(samples).zip(more) {
                drew[g] = pixels > 0;
                active[g] = drew[g] && another;
            }
            if !drew.iter().any(|&d| d) {
                return Ok((layer, false));
            }
            if layer == max {
                return Ok((max, true));
            }
            if !keep {
                let tiles = row_runs(jobs.iter().filter(|j| drew[j.group]).map(|j| j.tile));
                let depth = target.depth().expect("peel targets have depth");
                self.accumulator.add_peel(target.colors(), depth, &tiles)?;
            }
            if let Some(peels) = self.capture.borrow_mut().as_mut() {
                let targets = target
                    .colors()
                    .iter()
                    .map(|t| t.download_f32())
                    .collect::<Result<_, _>>()?;
                peels.push(CapturedPeel {
                    width: self.width,
                    height: self.height,
                    targets,
                });
            }
            if !active.iter().any(|&a| a) {
                return Ok((layer + 1, false));
            }
        }
        unreachable!("the loop returns at layer == max")
    }

    /// The last pass: the fluid surface inside each body (where pass 1's stencil bit is
    /// 1), added into the sums or drawn into `T_w`.
    fn water_patch_pass(&self, jobs: &[Job], level: f64) -> Result<(), GlError> {
        self.pass("mass: pass n+1 (all bodies)", || {
            let kept = self.kept.borrow();
            let (target, blend) = match self.settings.order {
                PeelOrder::RunningSums => (&self.water_patch_target, Some(Blend::Add)),
                PeelOrder::KeepLayers => {
                    let t = &kept.as_ref().expect("made by the peel passes").water;
                    t.clear_colors([0.0; 4])?;
                    (t, None)
                }
            };
            let mut pass = target.pass(&self.water_patch_program, WATER_PATCH_PASS)?;
            pass.state(DrawState {
                stencil: Some(StencilTest::equal(1)),
                blend,
                ..DrawState::default()
            });
            self.water_quads(&mut pass, jobs.len(), level)
        })
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

    /// Pass 1's stencil bit (1: the first surface below the water faces down), row by row
    /// from the bottom over the whole target: what the water patch is drawn through.
    pub fn first_peel_faces_down(&self) -> Result<Vec<u8>, GlError> {
        let rect = Rect::sized(self.width, self.height);
        match self.settings.order {
            PeelOrder::RunningSums => self.layers[0].read_stencil(rect),
            PeelOrder::KeepLayers => self.layer_target(0)?.read_stencil(rect),
        }
    }
}

/// The framebuffer a peel draws into.
enum LayerTarget<'a> {
    PingPong(&'a Framebuffer),
    Kept(Ref<'a, Framebuffer>),
}

impl std::ops::Deref for LayerTarget<'_> {
    type Target = Framebuffer;
    fn deref(&self) -> &Framebuffer {
        match self {
            LayerTarget::PingPong(f) => f,
            LayerTarget::Kept(f) => f,
        }
    }
}

/// `targets` RGBA32F integrand targets (3, or 1 for eq. 4 alone) and the depth `T_d(k)`
/// (32-bit float, as the peel test compares fragment depths with it exactly, or the
/// period's 24-bit: [`PeelDepth`]), with a stencil: pass 1's faces-down bit, the later
/// passes' fragment counts ([`super::peel_end`]).
fn peel_layer(
    ctx: &Context,
    width: u32,
    height: u32,
    targets: usize,
    depth: PeelDepth,
    name: &str,
) -> Result<Framebuffer, GlError> {
    let colors: Vec<Texture> = (0..targets)
        .map(|_| Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F))
        .collect::<Result<_, _>>()?;
    let depth = Texture::new_2d(ctx, width, height, depth.layer_format())?;
    Framebuffer::new(ctx, name, &colors.iter().collect::<Vec<_>>(), Some(&depth))
}

/// The state of a peel pass: the nearest remaining fragment wins (LESS); pass 1 also
/// writes the stencil bit by facing (two-sided stencil: the last fragment to pass the
/// depth test, the nearest, decides), the later passes count fragments in it.
fn peel_state(first: bool) -> DrawState {
    let write = |reference| StencilTest {
        pass: StencilOp::Replace,
        ..StencilTest::write(reference)
    };
    let (front, back) = if first {
        (write(0), Some(write(1)))
    } else {
        (peel_end::counting(), None)
    };
    DrawState {
        depth: Some(DepthTest {
            func: Compare::Less,
            write: true,
        }),
        stencil: Some(front),
        stencil_back: back,
        ..DrawState::default()
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
