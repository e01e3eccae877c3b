//! Refinement to a requested triangle count. Paper 1 (section 7.2, Table III) runs its
//! collision benchmarks on models of 15K, 20K and 50K triangles; paper 4 (Table 1) uses a
//! bunny of 2557 vertices and 5110 triangles, which is exactly
//! `retessellate(&load_bunny(), 5110)` (a closed genus-0 mesh has `F / 2 + 2` vertices), the
//! bunny paper 4 runs (`mass::models::table1_bunny`).
//!
//! [`retessellate`] splits the longest edge of the mesh at its midpoint, again and again,
//! until the count is reached. Each split cuts the two triangles on that edge in two
//! (one triangle on a boundary edge), so the count grows by two and any even count can
//! be hit exactly. Splitting the longest edge first evens out triangle sizes (useful to
//! paper 1, whose per-triangle boxes should be alike) and keeps shapes from degrading
//! (longest-edge bisection, Rivara). A midpoint lies in the plane of both triangles it
//! splits, so the surface does not move: volume, area and closedness are kept.
//!
//! [`subdivide`] is the uniform alternative: every triangle into four at its edge
//! midpoints.

use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

use glam::Vec3;

use super::{Mesh, MeshError};

/// `mesh` refined by longest-edge midpoint splits to exactly `target` triangles (see the
/// module docs). The input is welded first (vertices at identical positions merged, so
/// seams split on both sides) and triangles that collapse are dropped; the first
/// triangles of the result are pieces of the input's triangles in order, new pieces are
/// appended. A closed mesh always has an even triangle count, so an odd target on a
/// closed mesh gives `target - 1`. Errors: an unusable mesh, a target below the current
/// count, or non-manifold / inconsistently oriented edges (a split needs to know the
/// two sides of an edge).
pub fn retessellate(mesh: &Mesh, target: usize) -> Result<Mesh, MeshError> {
    let mut work = Splitter::new(mesh, target)?;
    while work.mesh.triangles.len() + 2 <= target {
        if !work.split_longest(false) {
            break;
        }
    }
    if work.mesh.triangles.len() + 1 == target {
        work.split_longest(true); // one boundary edge left to split, if the mesh has one
    }
    Ok(work.mesh)
}

/// Uniform 1-to-4 subdivision at edge midpoints: 4x the triangles, the same surface.
/// Welds first like [`retessellate`]; triangle `t` of the input becomes `4t .. 4t + 4`.
pub fn subdivide(mesh: &Mesh) -> Result<Mesh, MeshError> {
    mesh.check("mesh")?;
    let base = mesh.welded().without_degenerate();
    let mut positions = base.positions.clone();
    let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
    let mut midpoint = |a: u32, b: u32| {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            positions.push(0.5 * (base.positions[a as usize] + base.positions[b as usize]));
            positions.len() as u32 - 1
        })
    };
    let mut triangles = Vec::with_capacity(4 * base.triangles.len());
    for &[a, b, c] in &base.triangles {
        let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    Ok(Mesh::new(positions, triangles))
}

/// An edge in the split queue, ordered by squared length (then by ids, so that ties
/// break the same way on every run).
#[derive(PartialEq)]
struct QueuedEdge {
    length_squared: f32,
    a: u32,
    b: u32,
}

impl Eq for QueuedEdge {}

impl Ord for QueuedEdge {
    fn cmp(&self, other: &Self) -> Ordering {
        self.length_squared
            .total_cmp(&other.length_squared)
            .then_with(|| (other.a, other.b).cmp(&(self.a, self.b)))
    }
}

impl PartialOrd for QueuedEdge {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

struct Splitter {
    mesh: Mesh,
    /// Directed edge `a -> b` to the triangle that has it.
    owner: HashMap<(u32, u32), u32>,
    queue: BinaryHeap<QueuedEdge>,
}

impl Splitter {
    fn new(input: &Mesh, target: usize) -> Result<Self, MeshError> {
        input.check("mesh")?;
        let refuse = |reason: String| MeshError::Retessellate {
            source_name: "mesh".into(),
            requested: target,
            reason,
        };
        let mesh = input.welded().without_degenerate();
        if target < mesh.triangles.len() {
            return Err(refuse(format!(
                "it only refines, and the mesh already has {} triangles",
                mesh.triangles.len()
            )));
        }
        let edges = mesh.closedness();
        if edges.non_manifold_edges > 0 || edges.misoriented_edges > 0 {
            return Err(refuse(format!(
                "{} non-manifold and {} inconsistently oriented edges",
                edges.non_manifold_edges, edges.misoriented_edges
            )));
        }
        let mut owner = HashMap::with_capacity(3 * mesh.triangles.len());
        for (t, &[a, b, c]) in mesh.triangles.iter().enumerate() {
            for e in [(a, b), (b, c), (c, a)] {
                owner.insert(e, t as u32);
            }
        }
        let mut splitter = Splitter {
            mesh,
            owner,
            queue: BinaryHeap::new(),
        };
        let keys: Vec<(u32, u32)> = splitter.owner.keys().copied().collect();
        for (a, b) in keys {
            if a < b || !splitter.owner.contains_key(&(b, a)) {
                splitter.enqueue(a, b);
            }
        }
        Ok(splitter)
    }

    fn enqueue(&mut self, a: u32, b: u32) {
        let (a, b) = (a.min(b), a.max(b));
        let length_squared =
            self.mesh.positions[a as usize].distance_squared(self.mesh.positions[b as usize]);
        self.queue.push(QueuedEdge {
            length_squared,
            a,
            b,
        });
    }

    /// Splits the longest remaining edge (only boundary edges when `boundary_only`);
    /// false when there is none.
    fn split_longest(&mut self, boundary_only: bool) -> bool {
        let mut skipped = Vec::new();
        let mut done = false;
        while let Some(edge) = self.queue.pop() {
            let (ab, ba) = (
                self.owner.contains_key(&(edge.a, edge.b)),
                self.owner.contains_key(&(edge.b, edge.a)),
            );
            if !ab && !ba {
                continue; // split earlier
            }
            if boundary_only && ab && ba {
                skipped.push(edge);
                continue;
            }
            self.split(edge.a, edge.b);
            done = true;
            break;
        }
        self.queue.extend(skipped);
        done
    }

    /// Splits edge `{a, b}` at its midpoint `m`: triangle `(a, b, c)` becomes `(a, m, c)`
    /// and `(m, b, c)`, and the triangle on the other side likewise.
    fn split(&mut self, a: u32, b: u32) {
        let m = self.mesh.positions.len() as u32;
        let middle: Vec3 =
            0.5 * (self.mesh.positions[a as usize] + self.mesh.positions[b as usize]);
        self.mesh.positions.push(middle);
        let mut opposite = Vec::with_capacity(2);
        for (from, to) in [(a, b), (b, a)] {
            let Some(t) = self.owner.remove(&(from, to)) else {
                continue;
            };
            let c = third_corner(self.mesh.triangles[t as usize], from, to);
            let piece = self.mesh.triangles.len() as u32;
            self.mesh.triangles[t as usize] = [from, m, c];
            self.mesh.triangles.push([m, to, c]);
            for (edge, owner) in [
                ((from, m), t),
                ((m, c), t),
                ((m, to), piece),
                ((to, c), piece),
                ((c, m), piece),
            ] {
                self.owner.insert(edge, owner);
            }
            opposite.push(c);
        }
        self.enqueue(a, m);
        self.enqueue(m, b);
        for c in opposite {
            self.enqueue(m, c);
        }
    }
}

/// The corner of `tri` that is not on its directed edge `from -> to`.
fn third_corner(tri: [u32; 3], from: u32, to: u32) -> u32 {
    let k = tri
        .iter()
        .position(|&v| v == from)
        .expect("edge belongs to the triangle");
    debug_assert_eq!(tri[(k + 1) % 3], to);
    tri[(k + 2) % 3]
}
