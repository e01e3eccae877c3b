//! The outer boundary as a mesh (Kim et al. 2003, stage 4): the zero level of the signed
//! field by marching tetrahedra, then its volume by the divergence theorem and its topology
//! ([`super::topology`]).
//!
//! Why tetrahedra: marching cubes and surface nets must guess how an ambiguous cube connects
//! its corners, and surface nets then pinch two sheets into one edge (a non-manifold surface
//! whose `V - E + F` means nothing). Each grid cube here is split into the six tetrahedra of
//! Kuhn's (Freudenthal's) triangulation, which all share the diagonal from its corner
//! `(0, 0, 0)` to `(1, 1, 1)` and match their neighbours face to face. The field is linear on
//! each tetrahedron, and the zero level of a piecewise-linear function that is zero at no
//! sample (the signed field never is) is a closed 2-manifold when the border is outside.
//! One vertex per crossed edge, shared by every tetrahedron around that edge, keeps it
//! connected.
//!
//! Where the crossings lie: given the primitives, each crossed edge's vertex is where the edge,
//! walked from its outside sample, first meets one (exact for every surface, where the
//! signed field's linear interpolation is exact only for a plane), with that primitive's
//! normal; sharp edges and corners then get their own vertices ([`super::features`]).
//!
//! Manifold by position, not only by index: no two vertices may share a place, or the mesh,
//! welded by position as a reader of the OBJ does, folds there (two cells' feature vertices
//! at one corner of the model made edges of four triangles). A crossing lies inside its own
//! grid edge, never on a sample, and the edges' interiors are disjoint. A feature vertex
//! lies where its tangent planes meet, which may be outside its tetrahedron and on another
//! vertex (the model's corner is one point for every cell around it); every feature vertex
//! at the fp32 place of another vertex, or whose fan would have a flat triangle, is drawn
//! into the inside of its own tetrahedron ([`features::within_tetrahedron`]), where no
//! other vertex can be and no fan triangle is flat. The topology is then computed on the
//! welded fp32 mesh, the one written, with its zero-area triangles counted: it is measured,
//! not assumed.

use super::super::distance_field::Grid;
use super::classify::Buckets;
use super::features;
use super::topology::{self, Topology};
use crate::mesh::Mesh;
use glam::{DVec3, IVec3};
use std::collections::HashMap;

/// The extracted surface.
#[derive(Clone, Debug)]
pub struct Surface {
    /// Outward-facing triangles, mesh units.
    pub mesh: Mesh,
    /// Enclosed volume (divergence theorem), mesh units cubed.
    pub volume: f64,
    /// Counts, manifoldness, and the Euler characteristic and genus where they mean
    /// something.
    pub topology: Topology,
    /// Vertices placed on sharp edges and corners, and edges flipped to join them.
    pub feature_vertices: usize,
    pub feature_flips: usize,
}

impl Surface {
    /// No edge used by one triangle only, none used twice the same way: the volume is
    /// enclosed.
    pub fn watertight(&self) -> bool {
        self.topology.watertight()
    }
}

/// The six tetrahedra of a cube (corner `i` at `(i & 1, i >> 1 & 1, i >> 2 & 1)`): for each
/// order of the three axes, the path 0 → one axis → two axes → 7.
const TETRAHEDRA: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 1, 5, 7],
    [0, 2, 3, 7],
    [0, 2, 6, 7],
    [0, 4, 5, 7],
    [0, 4, 6, 7],
];

/// How far from a sample a crossing may lie, as a fraction of its edge: crossings never
/// land on a sample, so two edges never give the same point (a thousandth of an edge moves
/// the surface by far less than the field's own error).
const END_SLACK: f64 = 1e-3;

/// The zero level of `signed` (`[z][y][x]` on `grid`, negative inside, never zero); with
/// `primitives`, its vertices where the grid's edges meet them and its sharp features kept,
/// else by linear interpolation of `signed`.
pub fn extract(
    grid: &Grid,
    signed: &[f32],
    primitives: Option<&Buckets>,
) -> anyhow::Result<Surface> {
    let n = grid.n;
    anyhow::ensure!(
        signed.len() == grid.len(),
        "the signed field has {} values for {n}^3 voxels",
        signed.len()
    );
    anyhow::ensure!(
        signed.iter().all(|v| v.is_finite() && *v != 0.0),
        "the signed field has a zero or non-finite value"
    );
    let mut march = March {
        grid,
        signed,
        primitives,
        vertices: HashMap::new(),
        lattice: Vec::new(),
        normals: Vec::new(),
        tetrahedra: HashMap::new(),
        triangles: Vec::new(),
    };
    for z in 0..n - 1 {
        for y in 0..n - 1 {
            for x in 0..n - 1 {
                march.cube(IVec3::new(x as i32, y as i32, z as i32));
            }
        }
    }
    march.separate_coincident();
    let is_feature: Vec<bool> = march.normals.iter().map(Option::is_none).collect();
    let feature_vertices = match primitives {
        Some(_) => march.lattice.len() - march.vertices.len(),
        None => 0,
    };
    let feature_flips = if feature_vertices > 0 {
        features::flip_towards_features(&mut march.triangles, &is_feature, &march.lattice)
    } else {
        0
    };
    let volume = march.volume();
    anyhow::ensure!(volume.is_finite(), "the extracted volume is not finite");
    let positions = march
        .lattice
        .iter()
        .map(|p| (grid.origin + grid.spacing * *p).as_vec3())
        .collect();
    // Welded by fp32 position, as the OBJ is written and read back.
    let mesh = Mesh::new(positions, march.triangles).welded();
    let topology = topology::of_mesh(&mesh);
    Ok(Surface {
        mesh,
        volume,
        topology,
        feature_vertices,
        feature_flips,
    })
}

/// The bits of the fp32 mesh position of lattice point `p`, `-0` as `0`: the key of
/// welding by position.
fn position_key(grid: &Grid, p: DVec3) -> [u32; 3] {
    let q = (grid.origin + grid.spacing * p).as_vec3();
    q.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() })
}

/// The state of one extraction.
struct March<'a> {
    grid: &'a Grid,
    signed: &'a [f32],
    primitives: Option<&'a Buckets>,
    /// The vertex on each crossed edge, by its samples' indices (smaller first).
    vertices: HashMap<(usize, usize), u32>,
    /// Vertex positions in voxel units from the grid's origin.
    lattice: Vec<DVec3>,
    /// Each vertex's outward unit normal when it lies on a primitive; `None` for a feature
    /// vertex or one placed by interpolation.
    normals: Vec<Option<DVec3>>,
    /// Each feature vertex's tetrahedron (lattice corners).
    tetrahedra: HashMap<u32, [DVec3; 4]>,
    triangles: Vec<[u32; 3]>,
}

impl March<'_> {
    fn value(&self, p: IVec3) -> f32 {
        self.signed[self.index(p)]
    }

    fn index(&self, p: IVec3) -> usize {
        self.grid.index(p.x as usize, p.y as usize, p.z as usize)
    }

    /// The cube whose corner `(0, 0, 0)` is the sample `at`.
    fn cube(&mut self, at: IVec3) {
        let corners: [IVec3; 8] = std::array::from_fn(|i| {
            at + IVec3::new(i as i32 & 1, i as i32 >> 1 & 1, i as i32 >> 2 & 1)
        });
        let inside = corners.map(|c| self.value(c) < 0.0);
        if inside.iter().all(|&i| i) || inside.iter().all(|&i| !i) {
            return;
        }
        for tet in TETRAHEDRA {
            self.tetrahedron(tet.map(|c| (corners[c], inside[c])));
        }
    }

    /// One tetrahedron: one corner apart gives a triangle, two and two a quad.
    fn tetrahedron(&mut self, corners: [(IVec3, bool); 4]) {
        let side = |want: bool| -> Vec<IVec3> {
            corners
                .iter()
                .filter(|c| c.1 == want)
                .map(|c| c.0)
                .collect()
        };
        let (inside, outside) = (side(true), side(false));
        match (inside.as_slice(), outside.as_slice()) {
            ([], _) | (_, []) => {}
            ([a], [b, c, d]) | ([b, c, d], [a]) => {
                let (a, b, c, d) = (*a, *b, *c, *d);
                self.polygon(
                    &[(a, b), (a, c), (a, d)],
                    inside[0],
                    outside[0],
                    [a, b, c, d],
                );
            }
            ([a, b], [c, d]) => {
                let (a, b, c, d) = (*a, *b, *c, *d);
                // The crossings on a-c, a-d, b-d, b-c form a cycle.
                self.polygon(&[(a, c), (a, d), (b, d), (b, c)], a, c, [a, b, c, d]);
            }
            _ => unreachable!("four corners"),
        }
    }

    /// The polygon through the crossings of a cycle of three or four edges, facing from the
    /// inside corner `inner` towards the outside corner `outer`: a fan from its first vertex,
    /// or around its feature vertex when it has one. Its orientation is decided on the first
    /// three edges' midpoints in exact integers: moving each crossing along its own edge
    /// never turns a triangle of a tetrahedron over, and the midpoints' plane separates the
    /// inside corners from the outside ones. `tet` is the tetrahedron's corners.
    fn polygon(&mut self, edges: &[(IVec3, IVec3)], inner: IVec3, outer: IVec3, tet: [IVec3; 4]) {
        let mid: Vec<_> = edges.iter().map(|&(p, q)| (p + q).as_i64vec3()).collect();
        let normal = (mid[1] - mid[0]).cross(mid[2] - mid[0]);
        let towards_outside = normal.dot((outer - inner).as_i64vec3());
        let mut ids: Vec<u32> = edges.iter().map(|&(p, q)| self.vertex(p, q)).collect();
        if towards_outside < 0 {
            ids.reverse();
        }
        let k = ids.len();
        match self.feature_vertex(&ids, tet) {
            Some(f) => (0..k).for_each(|i| self.triangles.push([f, ids[i], ids[(i + 1) % k]])),
            None => (1..k - 1).for_each(|i| self.triangles.push([ids[0], ids[i], ids[i + 1]])),
        }
    }

    /// A vertex where the tangent planes of the polygon `ids` meet, when they meet at a sharp
    /// angle within a voxel's diagonal of its crossings (else the plain polygon is kept),
    /// drawn into the tetrahedron `tet` when a triangle of its fan would be flat.
    fn feature_vertex(&mut self, ids: &[u32], tet: [IVec3; 4]) -> Option<u32> {
        let normals: Option<Vec<DVec3>> = ids.iter().map(|&i| self.normals[i as usize]).collect();
        let points: Vec<DVec3> = ids.iter().map(|&i| self.lattice[i as usize]).collect();
        let point = features::feature_point(&points, &normals?)?;
        let centre = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        if (point - centre).length() > 3f64.sqrt() {
            return None;
        }
        let tet = tet.map(|c| c.as_dvec3());
        let k = points.len();
        let flat = (0..k).any(|i| features::flat(point, points[i], points[(i + 1) % k]));
        let point = if flat {
            features::within_tetrahedron(point, tet)
        } else {
            point
        };
        let id = self.lattice.len() as u32;
        self.lattice.push(point);
        self.normals.push(None);
        self.tetrahedra.insert(id, tet);
        Some(id)
    }

    /// Draw every feature vertex that shares its fp32 place (as written) with another vertex,
    /// but one, into its own tetrahedron, until no two vertices share a place.
    fn separate_coincident(&mut self) {
        // Inside their tetrahedra, feature vertices are apart from each other and from the
        // crossings; a second round only catches one moved onto an unmoved one.
        for _ in 0..4 {
            let mut at: HashMap<[u32; 3], Vec<u32>> = HashMap::new();
            for (i, p) in self.lattice.iter().enumerate() {
                at.entry(position_key(self.grid, *p))
                    .or_default()
                    .push(i as u32);
            }
            let mut moved = 0;
            for ids in at.values_mut().filter(|ids| ids.len() > 1) {
                // One feature vertex keeps the place (the model's corner stays in the mesh
                // once) unless a crossing has it: the one whose tetrahedron holds it, else
                // the first.
                ids.sort_unstable();
                let at_home = |i: &u32| {
                    self.tetrahedra.get(i).is_some_and(|t| {
                        features::inside_tetrahedron(self.lattice[*i as usize], *t)
                    })
                };
                let keep = ids.iter().all(|i| self.tetrahedra.contains_key(i));
                if let Some(k) = ids.iter().position(at_home) {
                    ids.swap(0, k);
                }
                for i in &ids[usize::from(keep)..] {
                    let Some(tet) = self.tetrahedra.get(i) else {
                        continue;
                    };
                    let p = &mut self.lattice[*i as usize];
                    let inside = features::within_tetrahedron(*p, *tet);
                    if inside != *p {
                        *p = inside;
                        moved += 1;
                    }
                }
            }
            if moved == 0 {
                return;
            }
        }
    }

    /// The vertex where the field crosses zero on the edge `p q` (linear interpolation).
    fn vertex(&mut self, p: IVec3, q: IVec3) -> u32 {
        let (ip, iq) = (self.index(p), self.index(q));
        let key = (ip.min(iq), ip.max(iq));
        if let Some(&id) = self.vertices.get(&key) {
            return id;
        }
        let (vp, vq) = (self.value(p) as f64, self.value(q) as f64);
        let (at, normal) = match self.crossing(p, q) {
            Some(hit) => hit,
            None => {
                let t = (vp / (vp - vq)).clamp(END_SLACK, 1.0 - END_SLACK);
                (p.as_dvec3() + t * (q - p).as_dvec3(), None)
            }
        };
        let id = self.lattice.len() as u32;
        self.lattice.push(at);
        self.normals.push(normal);
        self.vertices.insert(key, id);
        id
    }

    /// Where the edge `p q` (one sample outside, one inside), walked from its outside sample,
    /// first meets a primitive (lattice units), with that primitive's normal turned to face
    /// the outside sample.
    fn crossing(&self, p: IVec3, q: IVec3) -> Option<(DVec3, Option<DVec3>)> {
        let primitives = self.primitives?;
        let (outer, inner) = if self.value(p) > 0.0 { (p, q) } else { (q, p) };
        let point = |c: IVec3| self.grid.point(c.x as usize, c.y as usize, c.z as usize);
        let from = outer.to_array().map(|c| c as usize);
        let (t, normal) = primitives.first_crossing(point(outer), point(inner), from)?;
        let t = t.clamp(END_SLACK, 1.0 - END_SLACK);
        let step = (inner - outer).as_dvec3();
        let outward = if normal.dot(step) > 0.0 {
            -normal
        } else {
            normal
        };
        Some((outer.as_dvec3() + t * step, Some(outward)))
    }

    /// The enclosed volume from the lattice positions (f64), mesh units.
    fn volume(&self) -> f64 {
        let at = |i: u32| self.lattice[i as usize];
        let lattice: f64 = self
            .triangles
            .iter()
            .map(|t| at(t[0]).dot(at(t[1]).cross(at(t[2]))) / 6.0)
            .sum();
        lattice * self.grid.spacing.powi(3)
    }
}
