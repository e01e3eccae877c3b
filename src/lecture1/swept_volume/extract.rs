//! The outer boundary as a mesh (Kim et al. 2003, stage 4): the zero level of the signed
//! field by naive surface nets (the `fast-surface-nets` crate), then its volume by the
//! divergence theorem and its Euler characteristic `V - E + F`. The paper's stage 5
//! (topological refinement) is not done; the Euler characteristic is reported instead.

use super::super::distance_field::Grid;
use crate::mesh::Mesh;
use fast_surface_nets::ndshape::{RuntimeShape, Shape};
use fast_surface_nets::{surface_nets, SurfaceNetsBuffer};
use glam::{DVec3, Vec3};

/// The extracted surface.
#[derive(Clone, Debug)]
pub struct Surface {
    /// Outward-facing triangles, mesh units.
    pub mesh: Mesh,
    /// Enclosed volume (divergence theorem), mesh units cubed.
    pub volume: f64,
    pub euler_characteristic: i64,
    /// No edge used by one triangle only, none used twice the same way: the volume is
    /// enclosed. Naive surface nets guarantee this, but not a manifold surface.
    pub watertight: bool,
    /// Edges used by four or more triangles (where surface nets pinch the surface).
    pub non_manifold_edges: usize,
}

/// The zero level of `signed` (`[z][y][x]` on `grid`, negative inside).
pub fn extract(grid: &Grid, signed: &[f32]) -> anyhow::Result<Surface> {
    let n = grid.n as u32;
    let shape = RuntimeShape::<u32, 3>::new([n, n, n]);
    anyhow::ensure!(
        shape.usize() == signed.len(),
        "the signed field has {} values for {n}^3 voxels",
        signed.len()
    );
    let mut buffer = SurfaceNetsBuffer::default();
    surface_nets(signed, &shape, [0; 3], [n - 1; 3], &mut buffer);
    let positions: Vec<Vec3> = buffer
        .positions
        .iter()
        .map(|p| {
            let world = grid.origin + grid.spacing * DVec3::from(p.map(f64::from));
            world.as_vec3()
        })
        .collect();
    let triangles: Vec<[u32; 3]> = buffer
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    let mut mesh = Mesh::new(positions, triangles);
    let mut volume = signed_volume(grid, &buffer);
    if volume < 0.0 {
        // The crate's winding faces inward for negative-inside fields: turn it outward.
        mesh = mesh.flipped();
        volume = -volume;
    }
    anyhow::ensure!(volume.is_finite(), "the extracted volume is not finite");
    let closedness = mesh.closedness();
    Ok(Surface {
        euler_characteristic: closedness.euler_characteristic(),
        watertight: closedness.faces > 0
            && closedness.boundary_edges == 0
            && closedness.misoriented_edges == 0,
        non_manifold_edges: closedness.non_manifold_edges,
        mesh,
        volume,
    })
}

/// The signed volume of the surface nets' triangles, from their lattice positions (f64).
fn signed_volume(grid: &Grid, buffer: &SurfaceNetsBuffer) -> f64 {
    let at = |i: u32| DVec3::from(buffer.positions[i as usize].map(f64::from));
    let lattice: f64 = buffer
        .indices
        .chunks_exact(3)
        .map(|t| at(t[0]).dot(at(t[1]).cross(at(t[2]))) / 6.0)
        .sum();
    lattice * grid.spacing.powi(3)
}
