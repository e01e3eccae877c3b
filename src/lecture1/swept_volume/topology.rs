//! The extracted boundary's topology: whether it is a closed, oriented 2-manifold with no
//! zero-area triangle, and then its Euler characteristic `V - E + F` and the genus that
//! implies. Reported only for a manifold, where it means something: a sphere has 2, a torus
//! 0, and each closed component of genus `g` adds `2 - 2g`.
//!
//! [`of_mesh`] asks it of a mesh by position (vertices at one fp32 position are one vertex,
//! as in a written OBJ read back), [`analyse`] of bare indices.

use crate::mesh::validate::UnionFind;
use crate::mesh::Mesh;
use serde::Serialize;
use std::collections::{HashMap, HashSet};

/// Counts and checks of a triangle mesh.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Topology {
    /// Vertices used by a triangle.
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    /// Connected pieces (through shared edges).
    pub components: usize,
    /// Edges of one triangle only.
    pub boundary_edges: usize,
    /// Edges used twice the same way round.
    pub misoriented_edges: usize,
    /// Edges of three or more triangles.
    pub non_manifold_edges: usize,
    /// Vertices whose triangles make more than one fan (two sheets touching at a point).
    pub non_manifold_vertices: usize,
    /// Triangles of three distinct vertices but no area (by `mesh check`'s rule; counted by
    /// [`of_mesh`] only).
    pub zero_area_triangles: usize,
    /// `V - E + F`, only for a closed oriented manifold.
    pub euler_characteristic: Option<i64>,
    /// The summed genus of the components, `components - χ / 2`, only for a closed oriented
    /// manifold.
    pub genus: Option<i64>,
}

impl Topology {
    /// A closed, consistently oriented 2-manifold, no triangle of zero area.
    pub fn is_manifold(&self) -> bool {
        self.faces > 0
            && self.boundary_edges == 0
            && self.misoriented_edges == 0
            && self.non_manifold_edges == 0
            && self.non_manifold_vertices == 0
            && self.zero_area_triangles == 0
    }

    /// No boundary and no edge used twice the same way: it encloses a volume (it may still
    /// pinch).
    pub fn watertight(&self) -> bool {
        self.faces > 0 && self.boundary_edges == 0 && self.misoriented_edges == 0
    }
}

/// The topology of `mesh` by position: welded first, zero-area triangles counted.
pub fn of_mesh(mesh: &Mesh) -> Topology {
    let welded = mesh.welded();
    let zero_area = welded.validate().zero_area_triangles;
    analyse_counting(&welded.triangles, welded.positions.len(), zero_area)
}

/// The topology of `triangles` over `vertex_count` vertices. Triangles with a repeated
/// vertex are refused as not manifold (they are counted as non-manifold edges).
pub fn analyse(triangles: &[[u32; 3]], vertex_count: usize) -> Topology {
    analyse_counting(triangles, vertex_count, 0)
}

/// [`analyse`], with `zero_area` triangles known to be flat (no Euler characteristic then).
fn analyse_counting(triangles: &[[u32; 3]], vertex_count: usize, zero_area: usize) -> Topology {
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    let mut used = vec![false; vertex_count];
    // Each vertex's link: the edge opposite it in each of its triangles, in order.
    let mut link: Vec<Vec<(u32, u32)>> = vec![Vec::new(); vertex_count];
    let mut pieces = UnionFind::new(vertex_count);
    let mut degenerate = 0;
    for &[a, b, c] in triangles {
        if a == b || b == c || a == c {
            degenerate += 1;
            continue;
        }
        for (u, v, w) in [(a, b, c), (b, c, a), (c, a, b)] {
            *directed.entry((u, v)).or_default() += 1;
            used[u as usize] = true;
            link[u as usize].push((v, w));
            pieces.union(u, v);
        }
    }
    let mut t = Topology {
        faces: triangles.len() - degenerate,
        non_manifold_edges: degenerate,
        zero_area_triangles: zero_area,
        ..Topology::default()
    };
    for (&(u, v), &forward) in &directed {
        let backward = directed.get(&(v, u)).copied().unwrap_or(0);
        if u > v && backward > 0 {
            continue; // counted from (v, u)
        }
        t.edges += 1;
        match (forward, backward) {
            (1, 0) => t.boundary_edges += 1,
            (1, 1) => {}
            (2, 0) => t.misoriented_edges += 1,
            _ => t.non_manifold_edges += 1,
        }
    }
    t.vertices = used.iter().filter(|&&u| u).count();
    t.components = (0..vertex_count as u32)
        .filter(|&v| used[v as usize] && pieces.find(v) == v)
        .count();
    t.non_manifold_vertices = link.iter().filter(|l| fans(l) > 1).count();
    if t.is_manifold() {
        let chi = t.vertices as i64 - t.edges as i64 + t.faces as i64;
        t.euler_characteristic = Some(chi);
        t.genus = Some(t.components as i64 - chi / 2);
    }
    t
}

/// How many cycles a vertex's link edges make (each link vertex starts one edge and ends one
/// on a manifold; anything else counts as two, not manifold).
fn fans(link: &[(u32, u32)]) -> usize {
    if link.is_empty() {
        return 0;
    }
    let next: HashMap<u32, u32> = link.iter().copied().collect();
    if next.len() != link.len() {
        return 2;
    }
    let mut seen = 0;
    let mut cycles = 0;
    let mut visited = HashSet::new();
    for &(start, _) in link {
        if visited.contains(&start) {
            continue;
        }
        cycles += 1;
        let mut at = start;
        loop {
            visited.insert(at);
            seen += 1;
            match next.get(&at) {
                Some(&n) if n == start => break,
                Some(&n) if !visited.contains(&n) => at = n,
                _ => return 2, // an open fan or a branch
            }
        }
    }
    debug_assert_eq!(seen, link.len());
    cycles
}
