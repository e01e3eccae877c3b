//! The CPU reference for the submerged integrals: transform the body's mesh to the world,
//! clip it below the water plane and integrate it with Mirtich's algorithm.

use super::forces::Submerged;
use super::rigid_body::RigidBody;
use crate::mass::{analytic, clip};
use crate::mesh::Mesh;

/// Submerged volume and centre of buoyancy of `mesh` (body frame) posed as `body`, below
/// the plane `z = level`.
pub fn submerged(mesh: &Mesh, body: &RigidBody, level: f64) -> Submerged {
    let world = Mesh::new(
        mesh.positions
            .iter()
            .map(|p| body.to_world(p.as_dvec3()).as_vec3())
            .collect(),
        mesh.triangles.clone(),
    );
    let i = analytic::volume_integrals(&clip::below_plane(&world, level as f32));
    if i.v <= 0.0 {
        return Submerged::default();
    }
    Submerged {
        volume: i.v,
        center: i.centroid(),
    }
}
