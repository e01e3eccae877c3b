//! The part of a mesh below a horizontal plane, closed with the water-plane cap: the
//! analytic side of `--below` and of the buoyancy tests [section 5.2, done on the CPU].
//!
//! Each triangle is clipped to the half-space `z <= level` (Sutherland-Hodgman); cut points
//! are shared between neighbours (keyed by the edge, vertices welded by position), so a
//! closed input gives a closed output. The cap closes the boundary that the clipping left
//! (all of it on the plane): a fan from one point on the plane over the reversed boundary
//! edges. As a chain of signed triangles it covers the water-plane section exactly once,
//! holes included (a torus cut through its hole), which is all the divergence theorem
//! asks of it. It is meant for integration, not for rendering.

use super::surface::weld_by_position;
use crate::mesh::Mesh;
use glam::{DVec3, Vec3};
use std::collections::HashMap;

/// The closed part of `mesh` with `z <= level`.
pub fn below_plane(mesh: &Mesh, level: f32) -> Mesh {
    let mut clip = Clipper {
        mesh,
        weld: weld_by_position(mesh),
        level,
        out: Mesh::default(),
        kept: HashMap::new(),
        cuts: HashMap::new(),
    };
    for t in 0..mesh.triangles.len() {
        clip.triangle(t);
    }
    clip.cap();
    clip.out
}

struct Clipper<'a> {
    mesh: &'a Mesh,
    weld: Vec<u32>,
    level: f32,
    out: Mesh,
    /// Welded input vertex -> output vertex.
    kept: HashMap<u32, u32>,
    /// Welded input edge (low, high) -> output vertex on the plane.
    cuts: HashMap<(u32, u32), u32>,
}

impl Clipper<'_> {
    /// Signed height above the plane.
    fn side(&self, i: u32) -> f32 {
        self.mesh.positions[i as usize].z - self.level
    }

    fn keep(&mut self, i: u32) -> u32 {
        let out = &mut self.out;
        let p = self.mesh.positions[i as usize];
        *self.kept.entry(i).or_insert_with(|| {
            out.positions.push(p);
            (out.positions.len() - 1) as u32
        })
    }

    /// The point where edge (i, j) crosses the plane, computed from the edge's lower index
    /// so that both triangles sharing the edge get the same vertex.
    fn cut(&mut self, i: u32, j: u32) -> u32 {
        let key = (i.min(j), i.max(j));
        let p = self.mesh.positions[key.0 as usize].as_dvec3();
        let q = self.mesh.positions[key.1 as usize].as_dvec3();
        let level = self.level;
        let out = &mut self.out;
        *self.cuts.entry(key).or_insert_with(|| {
            let t = ((level as f64 - p.z) / (q.z - p.z)).clamp(0.0, 1.0);
            let x = p.lerp(q, t);
            out.positions.push(Vec3::new(x.x as f32, x.y as f32, level));
            (out.positions.len() - 1) as u32
        })
    }

    /// Clips one triangle and fans the clipped polygon (at most a quadrilateral).
    fn triangle(&mut self, t: usize) {
        let tri = self.mesh.triangles[t].map(|i| self.weld[i as usize]);
        let side = tri.map(|i| self.side(i));
        let mut polygon: Vec<u32> = Vec::with_capacity(4);
        for k in 0..3 {
            let (i, j) = (tri[k], tri[(k + 1) % 3]);
            let (si, sj) = (side[k], side[(k + 1) % 3]);
            if si <= 0.0 {
                polygon.push(self.keep(i));
            }
            if (si < 0.0 && sj > 0.0) || (si > 0.0 && sj < 0.0) {
                polygon.push(self.cut(i, j));
            }
        }
        for k in 1..polygon.len().saturating_sub(1) {
            self.out
                .triangles
                .push([polygon[0], polygon[k], polygon[k + 1]]);
        }
    }

    /// The water-plane cap over the boundary left by clipping, fanned from its mean point.
    fn cap(&mut self) {
        let boundary = boundary_edges(&self.out);
        if boundary.is_empty() {
            return;
        }
        let mean = boundary
            .iter()
            .map(|&(i, _)| self.out.positions[i as usize].as_dvec3())
            .sum::<DVec3>()
            / boundary.len() as f64;
        self.out
            .positions
            .push(Vec3::new(mean.x as f32, mean.y as f32, self.level));
        let centre = (self.out.positions.len() - 1) as u32;
        for (i, j) in boundary {
            self.out.triangles.push([centre, j, i]);
        }
    }
}

/// Directed edges of `mesh` whose reverse is missing, in a deterministic order.
fn boundary_edges(mesh: &Mesh) -> Vec<(u32, u32)> {
    let mut count: HashMap<(u32, u32), i32> = HashMap::new();
    for tri in &mesh.triangles {
        for k in 0..3 {
            let (i, j) = (tri[k], tri[(k + 1) % 3]);
            if i != j {
                *count.entry((i, j)).or_default() += 1;
                *count.entry((j, i)).or_default() -= 1;
            }
        }
    }
    let mut edges: Vec<(u32, u32)> = count
        .into_iter()
        .filter(|&(_, c)| c > 0)
        .flat_map(|(e, c)| (0..c).map(move |_| e))
        .collect();
    edges.sort_unstable();
    edges
}
