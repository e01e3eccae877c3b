//! The whole method for one body [sections 3-4]: frame it, peel it, reduce, assemble.
//! (`--below`: the same with the fluid-surface passes of 5.2.)

use super::framing::Framing;
use super::integrals::VolumeIntegrals;
use super::integrands::Soup;
use super::peel::{Job, Peeler};
use crate::gl::{query, Context, GlError, Rect};
use crate::mesh::Mesh;
use glam::Mat4;
use serde::Serialize;
use std::path::Path;

/// What the GPU computed for one body.
#[derive(Clone, Debug, Serialize)]
pub struct GpuResult {
    pub integrals: VolumeIntegrals,
    pub peels: usize,
    pub framing: Framing,
    /// GPU time of all passes (timer query), milliseconds.
    pub gpu_ms: f64,
}

/// A reusable set of targets for one body at one resolution.
pub struct GpuMass {
    peeler: Peeler,
    resolution: u32,
}

impl GpuMass {
    pub fn new(ctx: &Context, resolution: u32) -> Result<GpuMass, GlError> {
        Ok(GpuMass {
            peeler: Peeler::new(ctx, resolution, resolution, None)?,
            resolution,
        })
    }

    /// The ten integrals of `mesh` (below the plane `z = below` when given). Errors on a
    /// mesh that cannot be framed (empty, non-finite).
    pub fn integrate(
        &self,
        mesh: &Mesh,
        below: Option<f64>,
        dump: Option<&Path>,
    ) -> Result<GpuResult, GlError> {
        let framing = Framing::fit(mesh, self.resolution).map_err(GlError::Invalid)?;
        let soup = Soup::new(self.peeler.context(), &[mesh])?;
        let world: Vec<glam::DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let mut indices = Vec::new();
        let keep = |tri: &[u32; 3]| framing.may_cover_pixel_centre(tri.map(|i| world[i as usize]));
        soup.push_triangles(0, &world, keep, &mut indices);
        soup.set_indices(&indices)?;
        let job = Job {
            indices: (0, indices.len()),
            model: Mat4::IDENTITY,
            framing,
            tile: Rect::sized(self.resolution, self.resolution),
        };
        let (batch, gpu_ms) = query::time_gpu(self.peeler.context(), || {
            self.peeler.run(&soup, &[job], below, dump)
        })?;
        Ok(GpuResult {
            integrals: batch.integrals[0],
            peels: batch.peels,
            framing,
            gpu_ms,
        })
    }
}
