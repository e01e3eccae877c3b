//! What is wrong with a mesh, and whether it is closed.
//!
//! [`Mesh::validate`] gathers everything in a [`ValidationReport`]; [`Mesh::check`] turns
//! the fatal problems (empty, non-finite, index out of range) into a [`MeshError`].
//! Degenerate triangles are counted, not rejected: they are harmless to the papers'
//! algorithms (zero area, no fragments) but worth reporting.
//!
//! Closedness is a question about the surface, not the indexing: generators duplicate
//! vertices along texture seams, so the query first welds vertices at identical
//! positions, then asks that every undirected edge be shared by exactly two triangles
//! that traverse it in opposite directions (a closed, consistently oriented 2-manifold
//! edge structure). Triangles that collapse after welding are left out of the count.

use std::collections::HashMap;

use glam::Vec3;

use super::error::Location;
use super::{Mesh, MeshError};

/// A triangle is counted as zero-area when twice its area is at most this fraction of
/// its longest edge squared: a few f32 ulps, so collinear corners count even after
/// rounding, while thin but real slivers (relative height above ~1e-6) do not.
pub const ZERO_AREA_RELATIVE: f32 = 4.0 * f32::EPSILON;

#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ValidationReport {
    pub vertices: usize,
    pub triangles: usize,
    /// Vertex ids with a NaN or infinite coordinate.
    pub non_finite_vertices: Vec<usize>,
    /// Triangle ids with an index `>= vertices`.
    pub out_of_range_triangles: Vec<usize>,
    /// Triangles that use one vertex twice (e.g. `[4, 4, 7]`).
    pub repeated_index_triangles: usize,
    /// Triangles with three distinct indices but no area (coincident or collinear corners).
    pub zero_area_triangles: usize,
    /// Vertices no triangle uses.
    pub unreferenced_vertices: usize,
    /// Edge structure after welding; `None` when indices are out of range.
    pub closedness: Option<Closedness>,
}

impl ValidationReport {
    /// No fatal problem: not empty, all finite, all indices in range.
    pub fn is_usable(&self) -> bool {
        self.vertices > 0
            && self.triangles > 0
            && self.non_finite_vertices.is_empty()
            && self.out_of_range_triangles.is_empty()
    }

    pub fn degenerate_triangles(&self) -> usize {
        self.repeated_index_triangles + self.zero_area_triangles
    }
}

impl std::fmt::Display for ValidationReport {
    /// One line per finding, e.g. for a CLI: counts, then problems, then closedness.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{} vertices, {} triangles",
            self.vertices, self.triangles
        )?;
        if !self.non_finite_vertices.is_empty() {
            writeln!(
                f,
                "{} non-finite vertices (first: {})",
                self.non_finite_vertices.len(),
                self.non_finite_vertices[0]
            )?;
        }
        if !self.out_of_range_triangles.is_empty() {
            let (count, first) = (
                self.out_of_range_triangles.len(),
                self.out_of_range_triangles[0],
            );
            writeln!(
                f,
                "{count} triangles with an index out of range (first: {first})"
            )?;
        }
        writeln!(
            f,
            "{} degenerate triangles ({} repeat a vertex, {} have zero area)",
            self.degenerate_triangles(),
            self.repeated_index_triangles,
            self.zero_area_triangles
        )?;
        writeln!(f, "{} unreferenced vertices", self.unreferenced_vertices)?;
        match &self.closedness {
            Some(c) if c.is_closed() => match c.genus() {
                Some(g) => write!(f, "closed, genus {g}"),
                None => write!(f, "closed, {} pieces", c.components),
            },
            Some(c) => write!(
                f,
                "open: {} boundary, {} non-manifold, {} misoriented edges",
                c.boundary_edges, c.non_manifold_edges, c.misoriented_edges
            ),
            None => write!(f, "closedness unknown (indices out of range)"),
        }
    }
}

/// The edge structure of a mesh after welding identical positions.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Closedness {
    /// Distinct positions among the referenced vertices.
    pub welded_vertices: usize,
    /// Undirected edges of the welded mesh.
    pub edges: usize,
    /// Triangles counted (those that do not collapse after welding).
    pub faces: usize,
    /// Edges used by one triangle only (holes, open seams).
    pub boundary_edges: usize,
    /// Edges used by three or more triangles.
    pub non_manifold_edges: usize,
    /// Edges used by two triangles that traverse it the same way (flipped neighbours).
    pub misoriented_edges: usize,
    /// Connected pieces (through shared edges and vertices).
    pub components: usize,
}

impl Closedness {
    /// Watertight: every edge shared by exactly two oppositely oriented triangles.
    pub fn is_closed(&self) -> bool {
        self.faces > 0
            && self.boundary_edges == 0
            && self.non_manifold_edges == 0
            && self.misoriented_edges == 0
    }

    /// `V - E + F` of the welded mesh.
    pub fn euler_characteristic(&self) -> i64 {
        self.welded_vertices as i64 - self.edges as i64 + self.faces as i64
    }

    /// Genus of a closed, connected mesh (`V - E + F = 2 - 2g`); `None` otherwise.
    pub fn genus(&self) -> Option<i64> {
        (self.is_closed() && self.components == 1).then(|| (2 - self.euler_characteristic()) / 2)
    }
}

impl Mesh {
    /// Everything [`ValidationReport`] lists.
    pub fn validate(&self) -> ValidationReport {
        let n = self.positions.len();
        let mut report = ValidationReport {
            vertices: n,
            triangles: self.triangles.len(),
            non_finite_vertices: (0..n).filter(|&i| !self.positions[i].is_finite()).collect(),
            out_of_range_triangles: (0..self.triangles.len())
                .filter(|&t| self.triangles[t].iter().any(|&i| i as usize >= n))
                .collect(),
            ..Default::default()
        };
        let mut used = vec![false; n];
        for (t, tri) in self.triangles.iter().enumerate() {
            if tri.iter().any(|&i| i as usize >= n) {
                continue;
            }
            tri.iter().for_each(|&i| used[i as usize] = true);
            let [a, b, c] = *tri;
            if a == b || b == c || a == c {
                report.repeated_index_triangles += 1;
            } else if is_zero_area(self.triangle(t)) {
                report.zero_area_triangles += 1;
            }
        }
        report.unreferenced_vertices = used.iter().filter(|&&u| !u).count();
        if report.out_of_range_triangles.is_empty() {
            report.closedness = Some(self.closedness());
        }
        report
    }

    /// `Ok` when the mesh is usable: not empty, finite, indices in range. `name` is how
    /// errors refer to the mesh.
    pub fn check(&self, name: &str) -> Result<(), MeshError> {
        let at = Location {
            source: name.to_owned(),
            line: None,
        };
        if self.positions.is_empty() || self.triangles.is_empty() {
            return Err(MeshError::Empty {
                at,
                vertices: self.positions.len(),
                triangles: self.triangles.len(),
            });
        }
        if let Some((i, p)) = self
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite())
        {
            return Err(MeshError::NonFinite {
                at,
                vertex: i,
                x: p.x,
                y: p.y,
                z: p.z,
            });
        }
        let n = self.positions.len();
        for (t, tri) in self.triangles.iter().enumerate() {
            if let Some(&i) = tri.iter().find(|&&i| i as usize >= n) {
                return Err(MeshError::IndexOutOfRange {
                    at,
                    face: t,
                    index: i as i64,
                    vertex_count: n,
                });
            }
        }
        Ok(())
    }

    /// The edge structure after welding identical positions (see the module docs).
    /// Indices must be in range ([`Mesh::check`]).
    pub fn closedness(&self) -> Closedness {
        let (weld, welded_vertices) = self.weld_map();
        let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
        let mut faces = 0;
        let mut components = UnionFind::new(welded_vertices);
        // Vertices of the counted triangles (unused and collapsed ones are not part of
        // the surface).
        let mut referenced = vec![false; welded_vertices];
        for tri in &self.triangles {
            let [a, b, c] = tri.map(|i| weld[i as usize]);
            if a == b || b == c || a == c {
                continue;
            }
            faces += 1;
            [a, b, c]
                .iter()
                .for_each(|&v| referenced[v as usize] = true);
            for (u, v) in [(a, b), (b, c), (c, a)] {
                *directed.entry((u, v)).or_default() += 1;
                components.union(u, v);
            }
        }
        let mut report = Closedness {
            welded_vertices,
            faces,
            ..Default::default()
        };
        for (&(u, v), &forward) in &directed {
            let backward = directed.get(&(v, u)).copied().unwrap_or(0);
            if u > v && backward > 0 {
                continue; // counted from the (v, u) side
            }
            report.edges += 1;
            match forward + backward {
                1 => report.boundary_edges += 1,
                2 if forward == 1 => {}
                2 => report.misoriented_edges += 1,
                _ => report.non_manifold_edges += 1,
            }
        }
        report.welded_vertices = referenced.iter().filter(|&&r| r).count();
        report.components = (0..welded_vertices as u32)
            .filter(|&v| referenced[v as usize] && components.find(v) == v)
            .count();
        report
    }

    /// Shorthand for `closedness().is_closed()`.
    pub fn is_closed(&self) -> bool {
        self.closedness().is_closed()
    }

    /// For each vertex, the id of the first vertex at the same position (positions
    /// compared exactly, with -0.0 equal to 0.0), renumbered densely; and the count.
    pub fn weld_map(&self) -> (Vec<u32>, usize) {
        let mut first: HashMap<[u32; 3], u32> = HashMap::with_capacity(self.positions.len());
        let map = self
            .positions
            .iter()
            .map(|p| {
                let next = first.len() as u32;
                *first.entry(position_key(*p)).or_insert(next)
            })
            .collect();
        (map, first.len())
    }

    /// This mesh with vertices at identical positions merged into one (the first), so
    /// that seams become shared edges. Triangle order and winding are kept.
    pub fn welded(&self) -> Mesh {
        let (map, count) = self.weld_map();
        let mut positions = vec![Vec3::ZERO; count];
        for (i, &w) in map.iter().enumerate() {
            positions[w as usize] = self.positions[i];
        }
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|i| map[i as usize]))
            .collect();
        Mesh::new(positions, triangles)
    }
}

impl Mesh {
    /// Like [`Mesh::welded`], but vertices closer than `tolerance` merge too (each into the
    /// first earlier vertex within reach, whose position is kept). For surfaces built
    /// from patches, whose shared edges are evaluated twice and may differ in the last
    /// bits. Triangles that collapse are kept (see [`Mesh::without_degenerate`]).
    pub fn welded_within(&self, tolerance: f32) -> Mesh {
        let cell = tolerance.max(f32::MIN_POSITIVE);
        let key = |p: Vec3| (p / cell).floor().as_ivec3();
        let mut grid: HashMap<glam::IVec3, Vec<u32>> = HashMap::new();
        let mut positions: Vec<Vec3> = Vec::new();
        let mut map = Vec::with_capacity(self.positions.len());
        for &p in &self.positions {
            let k = key(p);
            let mut found = None;
            'search: for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let near = grid.get(&(k + glam::IVec3::new(dx, dy, dz)));
                        for &w in near.into_iter().flatten() {
                            if positions[w as usize].distance(p) <= tolerance {
                                found = Some(w);
                                break 'search;
                            }
                        }
                    }
                }
            }
            let w = found.unwrap_or_else(|| {
                positions.push(p);
                let w = positions.len() as u32 - 1;
                grid.entry(k).or_default().push(w);
                w
            });
            map.push(w);
        }
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|i| map[i as usize]))
            .collect();
        Mesh::new(positions, triangles)
    }

    /// This mesh without the triangles that use a vertex twice.
    pub fn without_degenerate(&self) -> Mesh {
        let triangles = self
            .triangles
            .iter()
            .copied()
            .filter(|&[a, b, c]| a != b && b != c && a != c)
            .collect();
        Mesh::new(self.positions.clone(), triangles)
    }
}

/// Bit pattern of a position, with -0.0 folded onto 0.0 so that they weld.
fn position_key(p: Vec3) -> [u32; 3] {
    p.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() })
}

/// In f64: the squares of f32 coordinates near 1e30 overflow f32, and those near 1e-30
/// underflow to zero, which would make every triangle of a scaled model zero-area; in f64
/// the relative test holds at every scale f32 can express.
fn is_zero_area([a, b, c]: [Vec3; 3]) -> bool {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    (b - a).cross(c - a).length() <= ZERO_AREA_RELATIVE as f64 * longest
}

/// Union-find over vertex ids (path halving).
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
        }
    }
    pub(crate) fn find(&mut self, mut v: u32) -> u32 {
        while self.parent[v as usize] != v {
            let grand = self.parent[self.parent[v as usize] as usize];
            self.parent[v as usize] = grand;
            v = grand;
        }
        v
    }
    pub(crate) fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}
