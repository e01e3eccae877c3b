//! Step 2, "the Minkowski sum of every pair of pieces": on the CPU, the hull of the
//! differences of the pieces' vertices, M_ij = hull(vertices(A_i) - vertices(B_j)), which is
//! A_i ⊕ (-B_j), by parry3d's quickhull. The union of the M_ij is A ⊕ (-B): B moved by t
//! overlaps A exactly when t lies in it, so the penetration depth is the distance from the
//! origin to its boundary. Each sum keeps its triangles (drawn on the GPU) and its face
//! planes (`n · x <= c`, n unit, coplanar triangles merged), and a sum that cannot come
//! nearer to the origin than a cheap upper bound on the depth is dropped.

use super::pieces::Piece;
use glam::{DVec3, Vec3};

/// A face plane of a sum: the points x with `normal · x <= offset` are inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub normal: DVec3,
    pub offset: f64,
}

impl Plane {
    /// Signed distance of `x` (negative inside).
    pub fn distance(&self, x: DVec3) -> f64 {
        self.normal.dot(x) - self.offset
    }
}

/// One Minkowski sum M_ij = A_i ⊕ (-B_j), a convex polytope.
#[derive(Clone, Debug)]
pub struct Polytope {
    /// (i, j): piece i of A, piece j of B.
    pub pieces: (usize, usize),
    pub vertices: Vec<DVec3>,
    /// Counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    pub planes: Vec<Plane>,
}

impl Polytope {
    /// Largest signed plane distance: <= 0 inside (the origin's is `-min offset`).
    pub fn depth_of(&self, x: DVec3) -> f64 {
        self.planes
            .iter()
            .map(|p| p.distance(x))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Whether the origin lies in the sum, within `tolerance`.
    pub fn contains_origin(&self, tolerance: f64) -> bool {
        self.depth_of(DVec3::ZERO) <= tolerance
    }
}

/// The sums of every pair of pieces (A_i, B_j).
pub fn minkowski_sums(a: &[Piece], b: &[Piece]) -> anyhow::Result<Vec<Polytope>> {
    let mut sums = Vec::with_capacity(a.len() * b.len());
    for (i, pa) in a.iter().enumerate() {
        for (j, pb) in b.iter().enumerate() {
            sums.push(minkowski_sum(pa, pb).map_err(|e| {
                anyhow::anyhow!(
                    "the Minkowski sum of piece '{}' of A and piece '{}' of B: {e}",
                    pa.name,
                    pb.name
                )
            })?);
            sums.last_mut().expect("just pushed").pieces = (i, j);
        }
    }
    Ok(sums)
}

/// hull(vertices(A_i) - vertices(B_j)): differences in f64, the hull by parry3d (fp32), the
/// planes again in f64 from the hull's vertices.
pub fn minkowski_sum(a: &Piece, b: &Piece) -> anyhow::Result<Polytope> {
    let mut differences = Vec::with_capacity(a.mesh.positions.len() * b.mesh.positions.len());
    for pa in &a.mesh.positions {
        for pb in &b.mesh.positions {
            differences.push(pa.as_dvec3() - pb.as_dvec3());
        }
    }
    // The hull is found on the differences scaled to at most 1 (fp32 products of coordinates
    // near 1e19 and beyond overflow, below 1e-19 underflow) and scaled back in f64; by a
    // power of two, so that the scaling itself rounds nothing.
    let largest = differences
        .iter()
        .map(|d| d.abs().max_element())
        .fold(0.0, f64::max);
    anyhow::ensure!(
        largest > 0.0,
        "every vertex of A minus every vertex of B is zero: the sum is a single point"
    );
    let unit = 2f64.powi(largest.log2().ceil() as i32);
    let points: Vec<_> = differences
        .iter()
        .map(|d| {
            let d = *d / unit;
            parry3d::math::Vector3::new(d.x as f32, d.y as f32, d.z as f32)
        })
        .collect();
    let (hull_vertices, hull_triangles) = parry3d::transformation::try_convex_hull(&points)
        .map_err(|e| anyhow::anyhow!("no convex hull ({e:?})"))?;
    let vertices: Vec<DVec3> = hull_vertices
        .iter()
        .map(|v| Vec3::new(v.x, v.y, v.z).as_dvec3() * unit)
        .collect();
    anyhow::ensure!(
        vertices.iter().all(|v| v.is_finite()),
        "the hull has a non-finite vertex"
    );
    let centre = vertices.iter().sum::<DVec3>() / vertices.len().max(1) as f64;
    let size = vertices
        .iter()
        .map(|v| (*v - centre).length())
        .fold(0.0, f64::max);
    anyhow::ensure!(
        size > 0.0,
        "the hull of the sum is a single point (every difference of vertices rounds to one)"
    );
    let mut triangles = Vec::with_capacity(hull_triangles.len());
    let mut planes: Vec<Plane> = Vec::new();
    for tri in hull_triangles {
        let [p, q, r] = tri.map(|v| vertices[v as usize]);
        let cross = (q - p).cross(r - p);
        let length = cross.length();
        if length <= 1e-12 * size * size {
            continue; // a sliver of the hull: no plane of its own, no fragments
        }
        // Outward: away from the centre of the vertices (inside a convex polytope).
        let (normal, tri) = if cross.dot(p - centre) >= 0.0 {
            (cross / length, tri)
        } else {
            (-cross / length, [tri[0], tri[2], tri[1]])
        };
        triangles.push(tri);
        let plane = Plane {
            normal,
            offset: normal.dot(p),
        };
        let same = |o: &Plane| {
            (o.normal - plane.normal).length() < 1e-6
                && (o.offset - plane.offset).abs() < 1e-6 * size
        };
        if !planes.iter().any(same) {
            planes.push(plane);
        }
    }
    anyhow::ensure!(
        planes.len() >= 4,
        "the hull is flat ({} planes)",
        planes.len()
    );
    Ok(Polytope {
        pieces: (0, 0),
        vertices,
        triangles,
        planes,
    })
}

/// A cheap upper bound on the depth: any point outside the union's bounding box is outside
/// the union, so the distance from the origin to the nearest side of the box (0 when the
/// origin is outside it).
pub fn box_bound(sums: &[Polytope]) -> f64 {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for v in sums.iter().flat_map(|s| s.vertices.iter()) {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    (-lo).min(hi).min_element().max(0.0)
}

/// Keep the sums that may hold a point nearer to the origin than `bound`. A plane with the
/// origin `g` outside it shows that the whole sum is at least `g` away (a cheap lower bound
/// on its distance), so a sum with `g > bound` cannot change the answer.
pub fn cull(sums: Vec<Polytope>, bound: f64) -> Vec<Polytope> {
    sums.into_iter()
        .filter(|s| s.depth_of(DVec3::ZERO) <= bound)
        .collect()
}
