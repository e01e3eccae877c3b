//! The unsigned distance field of a triangle mesh on a uniform 3D grid, rasterized slice by
//! slice: the building block of the lecture's swept volumes (Kim, Varadhan, Lin & Manocha
//! 2003, stage 2) in the style of DiFi (Sud, Otaduy & Manocha, EG 2004) and Hoff et al.
//! (SIGGRAPH 1999). `lecture1-sources.md`, sections 2 and 5.
//!
//! What the sources confirm: DiFi rasterizes distance functions slice by slice, each
//! primitive over a bounded region, the hardware keeping the minimum. What is ours (a
//! reconstruction): the per-fragment exact point-triangle distance ([`point_triangle`],
//! `glsl/lecture1/point_triangle.glsl`) instead of Hoff's distance meshes, the bound of each
//! triangle's region (its screen rectangle in a slice grown by the clamp distance, or the whole
//! slice without a clamp), GL_MIN blending into an R32F target, one readback per slice
//! ([`slices`]); and the compute-shader counterpart ([`compute`], OpenGL 4.3, one invocation
//! per voxel over every triangle). Hoff's own method is [`meshes`] and [`mesh_slices`]
//! (`--method mesh`): every vertex, edge and face's distance drawn as a bounded-error mesh,
//! the depth test keeping the nearest. [`reference`](mod@reference) is brute force on the CPU in f64
//! with the same point-triangle distance (it checks the GPU's arithmetic, not the method);
//! [`independent`] is the independent check, parry3d's closest-point query on the mesh.
//!
//! The grid ([`Grid`]) is a cube of `n^3` voxels over the mesh's bounding box grown by a
//! margin, centred on the box; values are indexed `[z][y][x]` (x fastest).

pub mod compute;
pub mod grid;
pub mod independent;
pub mod mesh_slices;
pub mod meshes;
pub mod point_triangle;
pub mod reference;
pub mod slices;

pub use grid::Grid;

use crate::mesh::Mesh;

/// A distance field: the grid and its `n^3` values, `[z][y][x]`.
#[derive(Clone, Debug)]
pub struct DistanceField {
    pub grid: Grid,
    /// Distance from each voxel centre to the mesh, or `min(distance, clamp)` with a clamp.
    pub values: Vec<f32>,
    /// The clamp the field was computed with (mesh units), if any.
    pub clamp: Option<f64>,
}

/// Where the time of a GPU field went.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct FieldTimings {
    /// GPU time of the slice passes (timer queries), or of the compute dispatch (wall clock
    /// between two glFinish calls: llvmpipe's timer queries do not see dispatches), ms.
    pub passes_ms: f64,
    /// Wall-clock time of the readback (glReadPixels per slice, or the storage buffer), ms.
    pub readback_ms: f64,
    /// Upload of the triangles, ms (wall clock).
    pub upload_ms: f64,
    /// Rasterized rectangles that reached a slice (classic path), summed over slices; the
    /// compute path evaluates every triangle at every voxel.
    pub triangles_drawn: u64,
}

/// The mesh must have a triangle, finite positions and indices in range; the clamp must be
/// positive and finite.
pub fn check_input(mesh: &Mesh, clamp: Option<f64>) -> anyhow::Result<()> {
    anyhow::ensure!(!mesh.triangles.is_empty(), "the model has no triangle");
    if let Some(i) = mesh.positions.iter().position(|p| !p.is_finite()) {
        anyhow::bail!("vertex {i} is not finite ({:?})", mesh.positions[i]);
    }
    let n = mesh.positions.len();
    if let Some(t) = mesh
        .triangles
        .iter()
        .position(|t| t.iter().any(|&v| v as usize >= n))
    {
        anyhow::bail!("triangle {t} names a vertex beyond the {n} vertices");
    }
    if let Some(d) = clamp {
        anyhow::ensure!(
            d.is_finite() && d > 0.0,
            "the clamp distance must be positive and finite, not {d}"
        );
    }
    Ok(())
}

/// The triangles' corners in voxel units (`(p - origin) / spacing`, computed in f64): the
/// GPU works in these coordinates, where voxel `(x, y, z)` is the point `(x, y, z)`, so that
/// a model far from the origin or at an extreme scale keeps fp32's precision.
pub fn corners_in_voxels(mesh: &Mesh, grid: &Grid) -> Vec<[f32; 4]> {
    let mut out = Vec::with_capacity(3 * mesh.triangles.len());
    for tri in &mesh.triangles {
        for &v in tri {
            let p = (mesh.positions[v as usize].as_dvec3() - grid.origin) / grid.spacing;
            out.push([p.x as f32, p.y as f32, p.z as f32, 0.0]);
        }
    }
    out
}
