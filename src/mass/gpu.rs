//! The whole method for one body [sections 3-4]: frame it, peel it, reduce, assemble.
//! (`--below`: the same with the fluid-surface passes of 5.2.)
//!
//! The GPU works in fp32, so the body is drawn in a unit frame: its coordinates relative
//! to the framing centre (subtracted in f64), divided per axis by a power of two that
//! brings the window and the depth range into [-1, 1]. The integrands then stay below 1
//! wherever the body lies and whatever its size (a cube of side 10^38, a unit cube 10^6
//! from the origin), the pixel centres are the world framing's exactly (powers of two
//! scale without rounding), and the integrals are scaled back in f64.

use super::framing::{covers_pixel_centre, Framing, PixelVertex};
use super::integrals::VolumeIntegrals;
use super::integrands::{Integrands, Placement, Soup};
use super::peel::{Job, PeelSettings, Peeler, PeelerOptions};
use super::peel_depth::PeelDepth;
use crate::gl::{profile, query, Context, GlError, Rect, TextureFormat};
use crate::mesh::Mesh;
use glam::DVec3;
use serde::Serialize;
use std::path::Path;

/// What the GPU computed for one body.
#[derive(Clone, Debug, Serialize)]
pub struct GpuResult {
    /// About the framing centre.
    pub integrals: VolumeIntegrals,
    pub peels: usize,
    /// Peeling stopped at the limit with fragments left: the integrals miss deeper layers.
    pub truncated: bool,
    /// The limit and order it peeled with.
    pub settings: PeelSettings,
    /// The paper's order only: the integrals of each kept texture `T_1 .. T_n` (then
    /// `T_w` with `below`), about the framing centre.
    pub layers: Vec<VolumeIntegrals>,
    /// The world framing (the unit frame the GPU draws in is this one scaled).
    pub framing: Framing,
    /// GPU time of all passes (timer query), milliseconds.
    pub gpu_ms: f64,
}

/// A reusable set of targets and buffers for one body at one resolution.
pub struct GpuMass {
    peeler: Peeler,
    soup: Soup,
    resolution: u32,
}

impl GpuMass {
    pub fn new(ctx: &Context, resolution: u32) -> Result<GpuMass, GlError> {
        Self::with_sum_format(ctx, resolution, TextureFormat::Rgba32F)
    }

    /// The passes evaluating `integrands` ([`Integrands::Constant`]: the same passes with
    /// no arithmetic, whose sums are no integrals).
    pub fn with_integrands(
        ctx: &Context,
        resolution: u32,
        integrands: Integrands,
    ) -> Result<GpuMass, GlError> {
        let options = PeelerOptions {
            integrands,
            ..PeelerOptions::default()
        };
        Self::with_options(ctx, resolution, options)
    }

    /// Running sums stored as `sum_format` (RGBA16F: the float format a GeForce 7800 could
    /// blend into; see [`crate::mass::reduce::Accumulator::with_format`]).
    pub fn with_sum_format(
        ctx: &Context,
        resolution: u32,
        sum_format: TextureFormat,
    ) -> Result<GpuMass, GlError> {
        let options = PeelerOptions {
            sum_format,
            ..PeelerOptions::default()
        };
        Self::with_options(ctx, resolution, options)
    }

    /// Running sums stored as `sum_format` and peel depths as `depth` (24-bit: the period's
    /// way, [`crate::mass::peel_depth`]), whatever the context's profile.
    pub fn with_depth(
        ctx: &Context,
        resolution: u32,
        sum_format: TextureFormat,
        depth: PeelDepth,
    ) -> Result<GpuMass, GlError> {
        let options = PeelerOptions {
            sum_format,
            depth: Some(depth),
            ..PeelerOptions::default()
        };
        Self::with_options(ctx, resolution, options)
    }

    /// A square target of `resolution` peeled with `options`, as a whole (no tiles).
    fn with_options(
        ctx: &Context,
        resolution: u32,
        options: PeelerOptions,
    ) -> Result<GpuMass, GlError> {
        Ok(GpuMass {
            peeler: Peeler::with_options(ctx, resolution, resolution, None, options)?,
            soup: Soup::new(ctx)?,
            resolution,
        })
    }

    /// Peel with `settings` from now on ([`Peeler::set_settings`]).
    pub fn set_settings(&mut self, settings: PeelSettings) -> Result<(), GlError> {
        self.peeler.set_settings(settings)
    }

    /// Peel exactly `layers` layers, without the stopping test ([`Peeler::set_known_layers`]);
    /// `None`: the paper's test.
    pub fn set_known_layers(&self, layers: Option<usize>) {
        self.peeler.set_known_layers(layers);
    }

    /// The depth peeler (to capture its peels).
    pub fn peeler(&self) -> &Peeler {
        &self.peeler
    }

    /// The same with a peel limit and order ([`PeelSettings`]).
    pub fn with_settings(
        ctx: &Context,
        resolution: u32,
        settings: PeelSettings,
    ) -> Result<GpuMass, GlError> {
        let mut gpu = GpuMass::new(ctx, resolution)?;
        gpu.peeler.set_settings(settings)?;
        Ok(gpu)
    }

    /// Pass 1's stencil bit of the last call with `below` (1 where the first surface below
    /// the water faces down), row by row from the bottom.
    pub fn first_peel_faces_down(&self) -> Result<Vec<u8>, GlError> {
        self.peeler.first_peel_faces_down()
    }

    /// The ten integrals of `mesh` (below the plane `z = below` when given). Errors on a
    /// mesh that cannot be framed (empty, non-finite), and on a body the frame cannot see
    /// (one that covers no pixel centre: thinner than a pixel across).
    pub fn integrate(
        &self,
        mesh: &Mesh,
        below: Option<f64>,
        dump: Option<&Path>,
    ) -> Result<GpuResult, GlError> {
        let framing = Framing::fit(mesh, self.resolution).map_err(GlError::Invalid)?;
        let unit = UnitFrame::of(&framing);
        let job = Job {
            body: "the body",
            group: 0,
            framing: unit.framing,
            tile: Rect::sized(self.resolution, self.resolution),
        };
        {
            let _scope = profile::cpu_scope(self.peeler.context(), "mass: unit frame, upload");
            self.prepare(mesh, &unit, &job)?;
        }
        let water = below.map(|level| unit.to_unit(DVec3::new(0.0, 0.0, level)).z);
        let (batch, gpu_ms) = query::time_gpu(self.peeler.context(), || {
            self.peeler.run(&self.soup, &[job], water, dump)
        })?;
        if batch.peels == 0 && below.is_none() && !mesh.triangles.is_empty() {
            return Err(GlError::Invalid(format!(
                "the body covers no pixel centre of the {n}x{n} frame (pixels {s:.3e} wide): \
                 it is thinner than a pixel across (x extent {x:.3e}, y extent {y:.3e}), so \
                 the image-based method cannot see it; a higher --resolution may resolve it",
                n = self.resolution,
                s = framing.pixel_size(),
                x = framing_extent(mesh).x,
                y = framing_extent(mesh).y,
            )));
        }
        Ok(GpuResult {
            integrals: unit.to_world(&batch.integrals[0]),
            peels: batch.peels,
            truncated: batch.truncated,
            settings: self.peeler.settings(),
            layers: batch.layers.iter().map(|l| unit.to_world(&l[0])).collect(),
            framing,
            gpu_ms,
        })
    }

    /// The body in the unit frame, placed as `job` says, in the soup's buffers, with the
    /// triangles that may cover a pixel centre.
    fn prepare(&self, mesh: &Mesh, unit: &UnitFrame, job: &Job) -> Result<(), GlError> {
        let local: Vec<DVec3> = mesh
            .positions
            .iter()
            .map(|p| unit.to_unit(p.as_dvec3()))
            .collect();
        let place = Placement {
            framing: job.framing,
            tile: job.tile,
            target: (self.resolution, self.resolution),
        };
        let pixels: Vec<PixelVertex> = local
            .iter()
            .map(|&p| unit.framing.pixel_vertex(p))
            .collect();
        let keep = |tri: &[u32; 3]| {
            let [a, b, c] = tri.map(|i| &pixels[i as usize]);
            covers_pixel_centre(a, b, c)
        };
        self.soup.clear();
        self.soup.push_body(&mesh.triangles, &local, &place, keep);
        self.soup.upload()
    }
}

/// The world framing scaled into [-1, 1]: `unit = (world - centre) / scale` per axis.
struct UnitFrame {
    center: DVec3,
    /// Powers of two: (window, window, depth).
    scale: DVec3,
    framing: Framing,
}

impl UnitFrame {
    fn of(world: &Framing) -> Self {
        let power_of_two_above = |x: f64| 2f64.powi(x.log2().ceil() as i32);
        let (xy, z) = (
            power_of_two_above(world.half_width),
            power_of_two_above(world.half_depth),
        );
        UnitFrame {
            center: world.center,
            scale: DVec3::new(xy, xy, z),
            framing: Framing {
                center: DVec3::ZERO,
                half_width: world.half_width / xy,
                half_depth: world.half_depth / z,
                resolution: world.resolution,
            },
        }
    }

    fn to_unit(&self, world: DVec3) -> DVec3 {
        (world - self.center) / self.scale
    }

    /// Integrals computed in the unit frame (about its centre), as world-unit integrals
    /// about the world framing centre.
    fn to_world(&self, unit: &VolumeIntegrals) -> VolumeIntegrals {
        VolumeIntegrals {
            origin: self.center,
            ..unit.stretched(self.scale)
        }
    }
}

/// The extent of the mesh's bounding box (for messages).
fn framing_extent(mesh: &Mesh) -> DVec3 {
    let b = mesh.bounds();
    (b.max - b.min).as_dvec3()
}
