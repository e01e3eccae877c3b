//! Sharp edges and corners of the extracted boundary, after Kobbelt, Botsch, Schwanecke &
//! Seidel, "Feature sensitive surface extraction from volume data" (SIGGRAPH 2001). Not part
//! of Kim et al.'s method (their fifth stage refines topology, not features); added because
//! without it the volume's error does not fall steadily with the resolution.
//!
//! Why: a polyhedron's sweep has sharp edges (where two faces, or a face and a ruled
//! surface, meet at an angle). Marching tetrahedra put every vertex on a grid edge, so a sharp
//! edge between samples is cut off, by up to half a voxel's square per unit of its length,
//! and how much depends on where the edge falls between the samples: a finer grid can lose
//! more than a coarser one.
//!
//! The steps, in the paper's terms (on tetrahedra here, where the paper uses cubes):
//! 1. each crossing keeps the normal of the primitive it lies on (Hermite data);
//! 2. a cell's polygon whose normals differ by more than an angle gets one extra vertex,
//!    where the tangent planes through its crossings meet (least squares, the free
//!    directions taken nearest the crossings' centroid), and becomes a fan around it;
//! 3. an edge whose two triangles each reach a feature vertex is flipped to join them, so
//!    that the sharp edge runs along the mesh instead of being cut at every cell face.
//!
//! A fan and a flip change neither the vertices' links nor `V - E + F`: the topology stays
//! that of the marching tetrahedra. Not in the paper: a feature vertex that would share its
//! place with another vertex (several cells' feature vertices at one corner of the model)
//! or make a flat fan triangle is drawn inside its own tetrahedron ([`within_tetrahedron`]),
//! so that the mesh, welded by position, does not fold there.

use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Normals closer than this cosine (about 3.6 degrees) are one flat sheet: no feature. The
/// normals are the primitives' own, so even a shallow edge between two facets is a real
/// edge of the swept surface (the paper takes a larger angle for normals estimated from a
/// sampled field); only the splits of a ruled quad within ε stay below it.
pub const SHARP_COSINE: f64 = 0.998;

/// Eigenvalues of the normals' matrix below this fraction of the largest count as zero: the
/// planes leave that direction free. Two planes at the angle above give `(1 - cos) / (1 +
/// cos)`, about 1e-3: the threshold keeps every edge the angle calls sharp.
const RANK_FRACTION: f64 = 1e-3;

/// Where the tangent planes through `points` (unit `normals`, facing outwards) meet, or
/// `None` when every two normals are within [`SHARP_COSINE`] (a smooth sheet).
pub fn feature_point(points: &[DVec3], normals: &[DVec3]) -> Option<DVec3> {
    let sharp = normals
        .iter()
        .enumerate()
        .any(|(i, a)| normals[..i].iter().any(|b| a.dot(*b) < SHARP_COSINE));
    if !sharp {
        return None;
    }
    let centre = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    // Minimise the sum of (n . (x - p))^2: A x = b with A the sum of n n^T.
    let mut a = [[0.0; 3]; 3];
    let mut b = DVec3::ZERO;
    for (p, n) in points.iter().zip(normals) {
        let n_arr = n.to_array();
        for (i, row) in a.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v += n_arr[i] * n_arr[j];
            }
        }
        b += *n * n.dot(*p - centre);
    }
    let (values, vectors) = symmetric_eigen(a);
    let largest = values.iter().copied().fold(0.0, f64::max);
    let mut x = DVec3::ZERO;
    for (value, vector) in values.iter().zip(vectors) {
        if *value > RANK_FRACTION * largest {
            x += vector * vector.dot(b) / value;
        }
    }
    let point = centre + x;
    point.is_finite().then_some(point)
}

/// How far inside its tetrahedron a feature vertex drawn into it stays: every barycentric
/// coordinate at least this (a thousandth of the way from a face to the opposite corner).
/// Its fan's triangles stay clear of zero area in fp32 (their heights are about 1e-3 voxel,
/// against fp32's 1e-7 relative), and the volume moved is of that order too, so a
/// translated convex model still converges to its exact prism.
pub const TETRAHEDRON_DEPTH: f64 = 1e-3;

/// Barycentric coordinates of `p` in the tetrahedron `a b c d`.
fn barycentric(p: DVec3, [a, b, c, d]: [DVec3; 4]) -> [f64; 4] {
    let l = glam::DMat3::from_cols(b - a, c - a, d - a).inverse() * (p - a);
    [1.0 - l.x - l.y - l.z, l.x, l.y, l.z]
}

/// Whether `point` is inside the tetrahedron by [`TETRAHEDRON_DEPTH`] at least.
pub fn inside_tetrahedron(point: DVec3, corners: [DVec3; 4]) -> bool {
    barycentric(point, corners)
        .iter()
        .all(|&l| l >= TETRAHEDRON_DEPTH)
}

/// `point`, or where the segment from the tetrahedron's centroid to it leaves the
/// tetrahedron shrunk to barycentric coordinates of at least [`TETRAHEDRON_DEPTH`].
pub fn within_tetrahedron(point: DVec3, corners: [DVec3; 4]) -> DVec3 {
    let [a, b, c, d] = corners;
    let centroid = (a + b + c + d) / 4.0;
    // Along centroid + s (point - centroid) each coordinate goes from 1/4 to its value at
    // the point; the largest s in [0, 1] that keeps all of them at the depth or above.
    let s = barycentric(point, corners)
        .iter()
        .filter(|&&l| l < TETRAHEDRON_DEPTH)
        .map(|&l| (0.25 - TETRAHEDRON_DEPTH) / (0.25 - l))
        .fold(1.0, f64::min);
    if s == 1.0 {
        return point;
    }
    centroid + s * (point - centroid)
}

/// Twice a triangle's area at most this fraction of its longest side squared: too flat to
/// make by a fan or a flip (fp32 rounding of the written positions must not bring it to
/// zero area, `mesh check`'s 4.8e-7).
pub const FLAT: f64 = 1e-3;

/// Whether the triangle `a b c` is flat by [`FLAT`].
pub fn flat(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    (b - a).cross(c - a).length() <= FLAT * longest
}

/// Eigenvalues and unit eigenvectors of a symmetric 3x3 matrix (cyclic Jacobi rotations).
fn symmetric_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [DVec3; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        let scale = a.iter().flatten().map(|x| x * x).sum::<f64>();
        if off <= 1e-30 * scale {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            // The rotation that zeroes a[p][q].
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for row in a.iter_mut() {
                let (kp, kq) = (row[p], row[q]);
                row[p] = c * kp - s * kq;
                row[q] = s * kp + c * kq;
            }
            let (row_p, row_q) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * row_p[k] - s * row_q[k]);
            a[q] = std::array::from_fn(|k| s * row_p[k] + c * row_q[k]);
            for row in v.iter_mut() {
                let (kp, kq) = (row[p], row[q]);
                row[p] = c * kp - s * kq;
                row[q] = s * kp + c * kq;
            }
        }
    }
    let column = |k: usize| DVec3::new(v[0][k], v[1][k], v[2][k]);
    (
        [a[0][0], a[1][1], a[2][2]],
        [column(0), column(1), column(2)],
    )
}

/// Step 3: flip every edge between two non-feature vertices whose two triangles' third
/// vertices are both feature vertices (and not yet joined), until none is left; a flip that
/// would make a flat triangle (at `positions`) is not made. Triangles keep their
/// orientation.
pub fn flip_towards_features(
    triangles: &mut [[u32; 3]],
    is_feature: &[bool],
    positions: &[DVec3],
) -> usize {
    let at = |v: u32| positions[v as usize];
    let feature = |v: u32| is_feature[v as usize];
    let key = |u: u32, v: u32| (u.min(v), u.max(v));
    let mut flips = 0;
    loop {
        // Each directed edge: its triangle and the vertex opposite it.
        let mut opposite: HashMap<(u32, u32), (usize, u32)> = HashMap::new();
        let mut edges = HashSet::new();
        for (i, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (u, v, w) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                opposite.insert((u, v), (i, w));
                edges.insert(key(u, v));
            }
        }
        let mut touched = HashSet::new();
        let mut candidates: Vec<_> = opposite.iter().map(|(&e, &o)| (e, o)).collect();
        candidates.sort_unstable();
        let before = flips;
        for ((u, v), (i, w)) in candidates {
            if feature(u) || feature(v) || !feature(w) || u > v {
                continue;
            }
            let Some(&(j, x)) = opposite.get(&(v, u)) else {
                continue;
            };
            if !feature(x) || w == x || edges.contains(&key(w, x)) {
                continue;
            }
            if touched.contains(&i) || touched.contains(&j) {
                continue;
            }
            if flat(at(w), at(u), at(x)) || flat(at(x), at(v), at(w)) {
                continue;
            }
            // (u, v, w) and (v, u, x) become (w, u, x) and (x, v, w).
            triangles[i] = [w, u, x];
            triangles[j] = [x, v, w];
            edges.insert(key(w, x));
            touched.extend([i, j]);
            flips += 1;
        }
        if flips == before {
            return flips;
        }
    }
}
