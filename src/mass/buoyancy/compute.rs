//! Section 5.2's submerged integrals in the compute formulation (OpenGL 4.3), "then and now"
//! for buoyancy: every body posed on the CPU (in f64, as the classic solver does), all bodies'
//! triangles in one buffer, one integrand pass that clips each triangle against the water
//! plane and sums eq. 4's four integrands (the volume and the first moments: the submerged
//! volume and the centre of buoyancy), and one shared-memory reduction to a sum per body
//! ([`crate::mass::compute`]). Where the paper renders the n + 2 passes (the water depth, the
//! peels below it, the water patch over the faces that look down), the kernel clips, and the
//! origin on the water plane makes the water patch add nothing. The forces and the rigid-body
//! step afterwards are the same code.

use super::forces::{Submerged, Water};
use super::simulation::{Body, Shape, SubmergedSolver};
use crate::gl::{Context, GlError};
use crate::mass::compute::{self, ComputeMass, Moments};
use glam::DVec3;

/// The compute solver: every body's submerged part in one dispatch and one reduction.
pub struct ComputeSolver {
    mass: ComputeMass,
    /// GPU time of the last step's pass and reduction (between `glFinish` calls), ms.
    pub last_gpu_ms: f64,
}

impl ComputeSolver {
    /// On a context below OpenGL 4.3, the error naming it.
    pub fn new(ctx: &Context) -> Result<ComputeSolver, GlError> {
        Ok(ComputeSolver {
            mass: ComputeMass::new(ctx)?,
            last_gpu_ms: 0.0,
        })
    }
}

impl SubmergedSolver for ComputeSolver {
    fn submerged(
        &mut self,
        shapes: &[Shape],
        bodies: &[Body],
        water: &Water,
    ) -> Result<Vec<Submerged>, String> {
        let posed: Vec<Vec<DVec3>> = bodies
            .iter()
            .map(|b| b.rigid.posed(&shapes[b.shape].mesh.positions))
            .collect();
        let parts: Vec<compute::Body> = bodies
            .iter()
            .zip(&posed)
            .map(|(b, world)| compute::Body::posed(&shapes[b.shape].mesh.triangles, world))
            .collect();
        let result = self
            .mass
            .integrate_bodies(&parts, Some(water.level), Moments::First)
            .map_err(|e| format!("buoyancy (compute): {e}"))?;
        self.last_gpu_ms = result.gpu_ms;
        Ok(result.integrals.iter().map(Submerged::of).collect())
    }
}
