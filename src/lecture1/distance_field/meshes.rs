//! Hoff et al.'s distance meshes for one z slice of a 3D field (SIGGRAPH 1999, their 3D
//! case done slice by slice): every feature of the model (vertex, edge, face) draws its
//! distance function over the slice as triangles whose depth is the distance, and the depth
//! test keeps the nearest. Coordinates are the slice's pixels: voxel `(x, y, z)` is the point
//! `(x + 0.5, y + 0.5, z)`, the target the square `[0, n]^2`.
//!
//! Each feature draws only where it is the nearest point of its own triangle, so no piece
//! lies below the distance to the model:
//! - a face, over its prism (the points that project into it): the distance to its plane,
//!   planar on each side of the line where the plane cuts the slice, hence exact;
//! - an edge, over its slab (the points that project onto it): the distance to its line. On
//!   the slice that is `|q|` for a point `q` of the plane that moves affinely with the pixel
//!   (`q = (τ, u_z σ - h |u_xy|)`, τ and σ across and along the edge's shadow, `h` the slice's
//!   height above the edge's start): a cone in `q`, elliptic on the slice;
//! - a vertex, everywhere: `sqrt(|q|^2 + h^2)` with `q` the pixel's offset from the vertex's
//!   shadow and `h` its height, a hyperboloid.
//!
//! Both curved functions are meshed the same way (`polar`): `k` sectors in `q`, each cut
//! into bands at rings `r_0 = 0 < r_1 < ... < r_m`. In a sector the gauge of the regular
//! `k`-gon whose corners lie on the circle, `ρ(q) = q · m_j / cos(π/k)` (`m_j` the sector's
//! middle direction), is linear, and `|q| <= ρ <= |q| / cos(π/k)`; across a band the profile
//! `g(r) = sqrt(r^2 + h^2)` is replaced by its chord. So every band of every sector is one
//! planar piece, and since `g` is convex, increasing and 1-Lipschitz, the mesh value `G(ρ)`
//! satisfies `g(|q|) <= G(ρ) <= g(|q|) + e_r + r_m (1 - cos(π/k))`, `e_r` the largest chord
//! error. `k` is chosen for half the asked error, the rings for what remains: every drawn
//! distance is at least the true one and at most the asked error above it.

use super::Grid;
use crate::mesh::Mesh;
use glam::{DVec2, DVec3};
use std::collections::HashSet;
use std::f64::consts::{PI, TAU};

/// The default tessellation error, voxels.
pub const DEFAULT_ERROR_VOXELS: f64 = 0.5;

/// The fewest sectors of a cone.
const MIN_SECTORS: usize = 3;

/// The model in the slices' coordinates, with its features listed once.
pub struct Features {
    /// Vertices `(x + 0.5, y + 0.5, z)` in voxels.
    points: Vec<DVec3>,
    /// Each edge once (the smaller vertex index first).
    edges: Vec<[usize; 2]>,
    /// Faces of non-zero area.
    faces: Vec<[usize; 3]>,
    /// The target's side, pixels.
    n: f64,
    /// The asked error, voxels.
    error: f64,
}

/// One slice's meshes.
#[derive(Debug, Default)]
pub struct SliceMeshes {
    /// Three vertices per triangle: x, y (pixels), distance (voxels), 0.
    pub vertices: Vec<[f32; 4]>,
    /// The largest tessellation bound of any feature drawn (voxels; 0 when only faces).
    pub bound: f64,
    /// The deepest vertex (voxels).
    pub deepest: f64,
}

impl Features {
    /// The features of `mesh` on `grid`, meshed within `error` voxels.
    pub fn new(mesh: &Mesh, grid: &Grid, error: f64) -> anyhow::Result<Features> {
        anyhow::ensure!(
            error.is_finite() && error > 0.0,
            "the distance meshes' error must be a positive number of voxels, not {error}"
        );
        let points: Vec<DVec3> = mesh
            .positions
            .iter()
            .map(|p| (p.as_dvec3() - grid.origin) / grid.spacing + DVec3::new(0.5, 0.5, 0.0))
            .collect();
        let mut seen = HashSet::new();
        let mut edges = Vec::new();
        let mut faces = Vec::new();
        for t in &mesh.triangles {
            let t = t.map(|v| v as usize);
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                let key = [a.min(b), a.max(b)];
                if key[0] != key[1] && seen.insert(key) {
                    edges.push(key);
                }
            }
            let [a, b, c] = t.map(|v| points[v]);
            if (b - a).cross(c - a).length_squared() > 0.0 {
                faces.push(t);
            }
        }
        Ok(Features {
            points,
            edges,
            faces,
            n: grid.n as f64,
            error,
        })
    }

    /// Features drawn per slice (vertices, edges, faces).
    pub fn counts(&self) -> [usize; 3] {
        [self.points.len(), self.edges.len(), self.faces.len()]
    }

    /// The meshes of slice `z` (voxels), reaching `clamp` voxels (everything without one).
    pub fn slice(&self, z: f64, clamp: Option<f64>) -> anyhow::Result<SliceMeshes> {
        let mut out = SliceMeshes::default();
        let square = self.square();
        for &p in &self.points {
            self.vertex(p, z, clamp, &square, &mut out)?;
        }
        for &[a, b] in &self.edges {
            self.edge(self.points[a], self.points[b], z, clamp, &square, &mut out)?;
        }
        for &f in &self.faces {
            face(f.map(|v| self.points[v]), z, clamp, &square, &mut out);
        }
        anyhow::ensure!(
            out.vertices.iter().flatten().all(|v| v.is_finite()),
            "a distance mesh of slice {z} is not finite in fp32"
        );
        Ok(out)
    }

    /// The target's square as a polygon.
    fn square(&self) -> Vec<DVec2> {
        let n = self.n;
        vec![
            DVec2::ZERO,
            DVec2::new(n, 0.0),
            DVec2::new(n, n),
            DVec2::new(0.0, n),
        ]
    }

    /// A vertex's hyperboloid over the whole slice (or the disk the clamp allows).
    fn vertex(
        &self,
        p: DVec3,
        z: f64,
        clamp: Option<f64>,
        square: &[DVec2],
        out: &mut SliceMeshes,
    ) -> anyhow::Result<()> {
        let h = z - p.z;
        let reach = match clamp {
            Some(d) if h.abs() > d => return Ok(()),
            Some(d) => Some((d * d - h * h).sqrt()),
            None => None,
        };
        let q = Affine {
            matrix: [DVec2::X, DVec2::Y],
            offset: -p.truncate(),
        };
        polar(q, h, square, reach, self.error, out)
    }

    /// An edge's cone over its slab.
    fn edge(
        &self,
        a: DVec3,
        b: DVec3,
        z: f64,
        clamp: Option<f64>,
        square: &[DVec2],
        out: &mut SliceMeshes,
    ) -> anyhow::Result<()> {
        let length = (b - a).length();
        if length == 0.0 {
            return Ok(()); // its vertices' meshes cover it
        }
        let u = (b - a) / length;
        // The slab 0 <= (P - a) · u <= length, P = (x, y, z).
        let along = HalfPlane {
            normal: u.truncate(),
            offset: u.z * z - u.dot(a),
        };
        let slab = clip(clip(square.to_vec(), along), along.flipped(length));
        if slab.len() < 3 {
            return Ok(());
        }
        let across = u.truncate().length();
        let e1 = if across > 0.0 {
            u.truncate() / across
        } else {
            DVec2::X
        };
        let e2 = e1.perp();
        let h = z - a.z;
        let a2 = a.truncate();
        // q = (τ, u_z σ - h |u_xy|), τ = e2 · (p - a), σ = e1 · (p - a).
        let q = Affine {
            matrix: [e2, u.z * e1],
            offset: DVec2::new(-e2.dot(a2), -u.z * e1.dot(a2) - h * across),
        };
        polar(q, 0.0, &slab, clamp, self.error, out)
    }
}

/// `q(p) = (rows[0] · p, rows[1] · p) + offset`.
#[derive(Clone, Copy)]
struct Affine {
    matrix: [DVec2; 2],
    offset: DVec2,
}

impl Affine {
    fn at(&self, p: DVec2) -> DVec2 {
        DVec2::new(self.matrix[0].dot(p), self.matrix[1].dot(p)) + self.offset
    }

    /// The half-plane `w · q(p) + c >= 0` of pixels.
    fn half_plane(&self, w: DVec2, c: f64) -> HalfPlane {
        HalfPlane {
            normal: self.matrix[0] * w.x + self.matrix[1] * w.y,
            offset: w.dot(self.offset) + c,
        }
    }
}

/// The pixels `p` with `normal · p + offset >= 0`.
#[derive(Clone, Copy, Debug)]
struct HalfPlane {
    normal: DVec2,
    offset: f64,
}

impl HalfPlane {
    fn at(&self, p: DVec2) -> f64 {
        self.normal.dot(p) + self.offset
    }

    /// `normal · p + offset <= width`.
    fn flipped(self, width: f64) -> HalfPlane {
        HalfPlane {
            normal: -self.normal,
            offset: width - self.offset,
        }
    }
}

/// The part of a convex polygon in a half-plane (one Sutherland-Hodgman step). A cut point
/// is found from the cut edge's endpoints in a fixed order, so that two pieces on either side
/// of a line get the same point.
fn clip(polygon: Vec<DVec2>, plane: HalfPlane) -> Vec<DVec2> {
    if polygon.len() < 3 {
        return Vec::new();
    }
    let mut kept = Vec::with_capacity(polygon.len() + 1);
    for (i, &p) in polygon.iter().enumerate() {
        let q = polygon[(i + 1) % polygon.len()];
        let (fp, fq) = (plane.at(p), plane.at(q));
        if fp >= 0.0 {
            kept.push(p);
        }
        if (fp >= 0.0) != (fq >= 0.0) {
            let ((a, fa), (b, fb)) = if (p.x, p.y) < (q.x, q.y) {
                ((p, fp), (q, fq))
            } else {
                ((q, fq), (p, fp))
            };
            kept.push(a + (b - a) * (fa / (fa - fb)));
        }
    }
    if kept.len() < 3 {
        Vec::new()
    } else {
        kept
    }
}

/// Draw `polygon` with the linear `depth` at its corners.
fn emit(polygon: &[DVec2], depth: impl Fn(DVec2) -> f64, out: &mut SliceMeshes) {
    // Corners closer than fp32 can tell apart make triangles of no area: one of them goes.
    let mut corners: Vec<DVec3> = Vec::with_capacity(polygon.len());
    for &p in polygon {
        if corners
            .last()
            .is_none_or(|c| c.truncate().distance(p) > 1e-6)
        {
            corners.push(p.extend(depth(p).max(0.0)));
        }
    }
    while corners.len() > 3
        && corners[0]
            .truncate()
            .distance(corners[corners.len() - 1].truncate())
            <= 1e-6
    {
        corners.pop();
    }
    if corners.len() < 3 {
        return;
    }
    for t in fans(&corners) {
        for c in t {
            out.deepest = out.deepest.max(c.z);
            out.vertices.push([c.x as f32, c.y as f32, c.z as f32, 0.0]);
        }
    }
}

/// A face's two planar pieces over its prism, `|n · (P - a)|`.
fn face(
    [a, b, c]: [DVec3; 3],
    z: f64,
    clamp: Option<f64>,
    square: &[DVec2],
    out: &mut SliceMeshes,
) {
    let normal = (b - a).cross(c - a);
    // The prism: the inner side of each edge's plane along the normal.
    let mut prism = square.to_vec();
    for (p, q) in [(a, b), (b, c), (c, a)] {
        let inward = normal.cross(q - p);
        prism = clip(
            prism,
            HalfPlane {
                normal: inward.truncate(),
                offset: inward.z * z - inward.dot(p),
            },
        );
    }
    let n = normal.normalize();
    let signed = HalfPlane {
        normal: n.truncate(),
        offset: n.z * z - n.dot(a),
    };
    for side in [1.0, -1.0] {
        let facing = HalfPlane {
            normal: signed.normal * side,
            offset: signed.offset * side,
        };
        let mut piece = clip(prism.clone(), facing);
        if let Some(d) = clamp {
            piece = clip(piece, facing.flipped(d));
        }
        emit(&piece, |p| facing.at(p), out);
    }
}

/// A convex polygon as triangles: a fan from its first corner, and when it has more than
/// three corners a second fan from the next one, so that a pixel centre lying on an inner
/// edge of one fan lies inside a triangle of the other (softpipe leaves such centres
/// uncovered by both halves). The overlap is harmless: both fans lie on the same plane.
fn fans(polygon: &[DVec3]) -> Vec<[DVec3; 3]> {
    let m = polygon.len();
    let fan = |first: usize| {
        (1..m - 1).map(move |k| [first, first + k, first + k + 1].map(|i| polygon[i % m]))
    };
    if m == 3 {
        fan(0).collect()
    } else {
        fan(0).chain(fan(1)).collect()
    }
}

/// The polar mesh of `sqrt(|q(p)|^2 + h^2)` over `region` (module docs), covering the pixels
/// with `|q| <= reach` (all of the region without a reach), within `error`.
fn polar(
    q: Affine,
    h: f64,
    region: &[DVec2],
    reach: Option<f64>,
    error: f64,
    out: &mut SliceMeshes,
) -> anyhow::Result<()> {
    // |q| is convex: its largest value on the region is at a corner.
    let farthest = region.iter().map(|&p| q.at(p).length()).fold(0.0, f64::max);
    let need = reach.map_or(farthest, |r| r.min(farthest));
    let sectors = sectors(need, error / 2.0)?;
    let half = PI / sectors as f64;
    let rim = need / half.cos();
    let angular = rim * (1.0 - half.cos());
    let rings = rings(h, rim, error - angular)?;
    let chord = chord_bound(h, &rings);
    out.bound = out.bound.max(angular + chord);
    let profile: Vec<f64> = rings.iter().map(|&r| (r * r + h * h).sqrt()).collect();
    for j in 0..sectors {
        let (from, to) = (
            TAU * j as f64 / sectors as f64,
            TAU * (j + 1) as f64 / sectors as f64,
        );
        // The sector: left of the ray at `from`, right of the ray at `to`.
        let sector = clip(
            clip(
                region.to_vec(),
                q.half_plane(DVec2::new(-from.sin(), from.cos()), 0.0),
            ),
            q.half_plane(DVec2::new(to.sin(), -to.cos()), 0.0),
        );
        if sector.is_empty() {
            continue;
        }
        let middle = DVec2::from_angle(from + half) / half.cos();
        for i in 0..rings.len() - 1 {
            let (r0, r1) = (rings[i], rings[i + 1]);
            // r0 <= ρ <= r1, ρ = middle · q.
            let band = clip(
                clip(sector.clone(), q.half_plane(middle, -r0)),
                q.half_plane(-middle, r1),
            );
            let slope = (profile[i + 1] - profile[i]) / (r1 - r0);
            emit(
                &band,
                |p| profile[i] + slope * (middle.dot(q.at(p)) - r0),
                out,
            );
        }
    }
    Ok(())
}

/// The fewest sectors (at least three) whose polygon, with corners at `need / cos(π/k)`,
/// stays within `error` of the circle of radius `need`: `need (1 / cos(π/k) - 1) <= error`.
fn sectors(need: f64, error: f64) -> anyhow::Result<usize> {
    if need <= 0.0 {
        return Ok(MIN_SECTORS);
    }
    let sectors = (PI / (need / (need + error)).acos()).ceil();
    anyhow::ensure!(
        sectors <= 1e5,
        "an error of {error} voxels over {need} voxels needs {sectors} sectors: ask for a \
         larger error"
    );
    Ok((sectors as usize).max(MIN_SECTORS))
}

/// Rings `0 = r_0 < ... < r_m = rim` such that each chord of `g(r) = sqrt(r^2 + h^2)` lies
/// within `error` of it (one band when `h = 0`: the cone is straight).
fn rings(h: f64, rim: f64, error: f64) -> anyhow::Result<Vec<f64>> {
    let mut rings = vec![0.0];
    if rim <= 0.0 {
        rings.push(error.max(1e-9));
        return Ok(rings);
    }
    while let Some(&last) = rings.last().filter(|&&r| r < rim) {
        if chord_error(h, last, rim) <= error {
            rings.push(rim);
            break;
        }
        // The chord's error grows with its length: bisect for the longest within `error`.
        let (mut lo, mut hi) = (last, rim);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if chord_error(h, last, mid) <= error {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        anyhow::ensure!(
            lo > last && rings.len() < 100_000,
            "the rings of a vertex {h} voxels from the slice do not fit an error of {error}"
        );
        rings.push(lo);
    }
    Ok(rings)
}

/// The largest gap between `g(r) = sqrt(r^2 + h^2)` and its chord over `[a, b]`: where
/// `g'(r) = r / g(r)` equals the chord's slope `s`, at `r = |h| s / sqrt(1 - s^2)`.
fn chord_error(h: f64, a: f64, b: f64) -> f64 {
    let g = |r: f64| (r * r + h * h).sqrt();
    if b <= a || h == 0.0 {
        return 0.0;
    }
    let s = ((g(b) - g(a)) / (b - a)).clamp(0.0, 1.0 - 1e-15);
    let r = (h.abs() * s / (1.0 - s * s).sqrt()).clamp(a, b);
    (g(a) + s * (r - a) - g(r)).max(0.0)
}

/// The largest chord error over the rings.
fn chord_bound(h: f64, rings: &[f64]) -> f64 {
    rings
        .windows(2)
        .map(|w| chord_error(h, w[0], w[1]))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chords_stay_within_the_asked_error() {
        for h in [0.0, 0.01, 0.7, 5.0, 40.0] {
            let rim = 90.0;
            let r = rings(h, rim, 0.1).unwrap();
            assert_eq!(*r.last().unwrap(), rim);
            assert!(chord_bound(h, &r) <= 0.1 + 1e-12, "h = {h}");
            // Sampled: the chord is above g and within the error.
            for w in r.windows(2) {
                let g = |x: f64| (x * x + h * h).sqrt();
                for k in 0..=50 {
                    let x = w[0] + (w[1] - w[0]) * k as f64 / 50.0;
                    let chord = g(w[0]) + (g(w[1]) - g(w[0])) * (x - w[0]) / (w[1] - w[0]);
                    assert!(chord >= g(x) - 1e-9 && chord <= g(x) + 0.1 + 1e-9);
                }
            }
        }
    }
}

/// The slice's meshes rasterized on the CPU: at each pixel centre the least distance of the
/// triangles that contain it (edges included), `f64::INFINITY` where none does; `n x n`,
/// rows from the bottom. The CPU reference of what the depth test keeps.
pub fn lowest_on_cpu(slice: &SliceMeshes, n: usize) -> Vec<f64> {
    let mut out = vec![f64::INFINITY; n * n];
    for t in slice.vertices.chunks_exact(3) {
        let [a, b, c] =
            [t[0], t[1], t[2]].map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64));
        let area = (b - a).truncate().perp_dot((c - a).truncate());
        if area.abs() < 1e-9 {
            continue;
        }
        let lo = a.min(b).min(c);
        let hi = a.max(b).max(c);
        let (x0, x1) = (
            (lo.x - 0.5).ceil().max(0.0) as usize,
            (hi.x - 0.5).floor().min(n as f64 - 1.0),
        );
        let (y0, y1) = (
            (lo.y - 0.5).ceil().max(0.0) as usize,
            (hi.y - 0.5).floor().min(n as f64 - 1.0),
        );
        if x1 < 0.0 || y1 < 0.0 {
            continue;
        }
        for y in y0..=y1 as usize {
            for x in x0..=x1 as usize {
                let p = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                let w = [(b, c), (c, a), (a, b)]
                    .map(|(u, v)| (v - u).truncate().perp_dot(p - u.truncate()) / area);
                if w.iter().all(|&w| w >= -1e-9) {
                    let d = w[0] * a.z + w[1] * b.z + w[2] * c.z;
                    let at = &mut out[y * n + x];
                    *at = at.min(d);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod slice_tests {
    use super::*;
    use crate::lecture1::distance_field::reference::brute_force;
    use glam::Vec3;

    /// Three triangles at odd angles (slanted edges and faces, a vertex near a slice).
    fn tilted() -> Mesh {
        let positions = vec![
            Vec3::new(0.1, 0.2, 0.3),
            Vec3::new(0.9, 0.1, 0.5),
            Vec3::new(0.4, 0.8, 0.1),
            Vec3::new(0.5, 0.5, 0.9),
            Vec3::new(0.2, 0.9, 0.7),
            Vec3::new(0.8, 0.7, 0.2),
        ];
        Mesh::new(positions, vec![[0, 1, 2], [3, 4, 5], [1, 3, 5]])
    }

    /// The meshes rasterized on the CPU keep every pixel centre in `[d, d + error]` (the
    /// GPU adds only the coverage error and fp32 rounding), with and without a clamp.
    #[test]
    fn meshes_on_the_cpu_lie_within_the_error_above_the_distance() {
        let mesh = tilted();
        let n = 11;
        let grid = Grid::around(&mesh, n, 0.1).unwrap();
        for clamp in [None, Some(0.2)] {
            let exact = brute_force(&mesh, &grid, clamp);
            for error in [0.5, 0.05] {
                let features = Features::new(&mesh, &grid, error).unwrap();
                for z in 0..n {
                    let slice = features
                        .slice(z as f64, clamp.map(|d| d / grid.spacing))
                        .unwrap();
                    assert!(slice.bound <= error + 1e-12);
                    let cpu = lowest_on_cpu(&slice, n);
                    for y in 0..n {
                        for x in 0..n {
                            let d = exact.values[grid.index(x, y, z)] as f64 / grid.spacing;
                            let m = match clamp {
                                Some(c) => cpu[y * n + x].min(c / grid.spacing),
                                None => cpu[y * n + x],
                            };
                            assert!(
                                m >= d - 1e-5 && m <= d + error + 1e-5,
                                "({x}, {y}, {z}), error {error}, clamp {clamp:?}: {m} vs {d}"
                            );
                        }
                    }
                }
            }
        }
    }
}
