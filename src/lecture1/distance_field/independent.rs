//! An independent reference for the distance field: the nearest point of the mesh from
//! parry3d's point projection (another library's code: its own triangle projection and BVH,
//! in fp32), not this project's point-triangle distance run again. [`reference`] runs the
//! GPU's algorithm in f64, so it checks the GPU's arithmetic; this checks the method.
//!
//! [`reference`]: mod@super::reference

use super::{check_input, DistanceField, Grid};
use crate::mesh::Mesh;
use parry3d::math::Vector;
use parry3d::query::PointQuery;
use parry3d::shape::TriMesh;

/// The unsigned field of `mesh` on `grid` from parry3d's closest points (`min(distance,
/// clamp)` with a clamp). The distance is taken in f64 from each voxel centre to the point
/// parry3d projects it on (a surface point, `solid = false`, so inside points too).
pub fn parry_field(mesh: &Mesh, grid: &Grid, clamp: Option<f64>) -> anyhow::Result<DistanceField> {
    check_input(mesh, clamp)?;
    let vertices = mesh
        .positions
        .iter()
        .map(|p| Vector::new(p.x, p.y, p.z))
        .collect();
    let trimesh = TriMesh::new(vertices, mesh.triangles.clone())
        .map_err(|e| anyhow::anyhow!("parry3d refused the mesh as a TriMesh: {e:?}"))?;
    let mut values = vec![0.0f32; grid.len()];
    for z in 0..grid.n {
        for y in 0..grid.n {
            for x in 0..grid.n {
                let p = grid.point(x, y, z);
                let q = Vector::new(p.x as f32, p.y as f32, p.z as f32);
                let nearest = trimesh.project_local_point(q, false).point;
                let d = p.distance(glam::DVec3::new(
                    nearest.x as f64,
                    nearest.y as f64,
                    nearest.z as f64,
                ));
                values[grid.index(x, y, z)] = d.min(clamp.unwrap_or(f64::INFINITY)) as f32;
            }
        }
    }
    Ok(DistanceField {
        grid: *grid,
        values,
        clamp,
    })
}
