//! Pieces of one model that overlap. The divergence theorem (eq. 4 and the analytic method)
//! sums the signed volume each closed piece bounds, so two pieces that share space count the
//! shared part twice: two unit cubes sharing 0.28 of their space give 2.0, not the 1.72 of
//! the solid they draw. This module finds such pieces so that no result is called reliable
//! while it is the sum of the pieces.
//!
//! Depth peeling sums the same way (each layer's integrand is signed by the way its surface
//! faces), so the GPU results carry the same double count.
//!
//! A piece is a connected set of triangles (through shared vertex positions). Two pieces overlap
//! when an edge of one passes through a face of the other (its ends strictly on both sides of
//! the face's plane, decided by exact orientation predicates, so pieces that only touch do not
//! count), or when one lies inside the other with the same orientation (a cavity, an inner piece
//! turned inside out, is how a hollow solid is written and is not an overlap).

use crate::mesh::Mesh;
use glam::{DVec3, Vec3};
use robust::Coord3D;

/// Pairs of pieces (by index in [`pieces`]) that overlap, at most `limit` of them.
pub fn overlapping_pieces(mesh: &Mesh, limit: usize) -> Vec<(usize, usize)> {
    let pieces = pieces(mesh);
    let boxes: Vec<(Vec3, Vec3)> = pieces.iter().map(|p| bounds(mesh, p)).collect();
    let mut found = Vec::new();
    for a in 0..pieces.len() {
        for b in a + 1..pieces.len() {
            if found.len() >= limit {
                return found;
            }
            let (lo, hi) = (boxes[a].0.max(boxes[b].0), boxes[a].1.min(boxes[b].1));
            if lo.cmpgt(hi).any() {
                continue;
            }
            let overlap = crosses(mesh, &pieces[a], &pieces[b], (lo, hi))
                || crosses(mesh, &pieces[b], &pieces[a], (lo, hi))
                || nested(mesh, &pieces[a], &pieces[b])
                || nested(mesh, &pieces[b], &pieces[a]);
            if overlap {
                found.push((a, b));
            }
        }
    }
    found
}

/// The connected pieces of `mesh`: triangle indices, grouped through shared positions.
pub fn pieces(mesh: &Mesh) -> Vec<Vec<usize>> {
    let ids = super::surface::weld_by_position(mesh);
    let mut parent: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    fn root(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            parent[i as usize] = parent[parent[i as usize] as usize];
            i = parent[i as usize];
        }
        i
    }
    for tri in &mesh.triangles {
        let r0 = root(&mut parent, ids[tri[0] as usize]);
        for &v in &tri[1..] {
            let r = root(&mut parent, ids[v as usize]);
            parent[r as usize] = r0;
        }
    }
    let mut by_root: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let r = root(&mut parent, ids[tri[0] as usize]);
        by_root.entry(r).or_default().push(t);
    }
    by_root.into_values().collect()
}

fn corners(mesh: &Mesh, t: usize) -> [DVec3; 3] {
    mesh.triangle(t).map(|v| v.as_dvec3())
}

fn bounds(mesh: &Mesh, piece: &[usize]) -> (Vec3, Vec3) {
    piece.iter().flat_map(|&t| mesh.triangle(t)).fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// Whether segment `p q` passes through triangle `t`: its ends strictly on both sides of the
/// plane, and the crossing in the closed triangle.
fn pierces(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if !(sp > 0.0 && sq < 0.0 || sp < 0.0 && sq > 0.0) {
        return false;
    }
    // The line through p, q meets the triangle iff it passes on the same side of its three
    // edges (or on one of them).
    let sides = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
    sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0)
}

/// Whether an edge of piece `a` pierces a face of piece `b`, looking only inside `region`.
/// The edges and faces there are swept along x (sorted by their smallest x), so the cost is
/// the pairs whose x ranges overlap, not every pair.
fn crosses(mesh: &Mesh, a: &[usize], b: &[usize], (lo, hi): (Vec3, Vec3)) -> bool {
    let inside = |l: Vec3, h: Vec3| !(l.cmpgt(hi).any() || h.cmplt(lo).any());
    let mut edges: Vec<(f64, f64, DVec3, DVec3)> = Vec::new();
    for &t in a {
        let c = corners(mesh, t);
        for k in 0..3 {
            let (p, q) = (c[k], c[(k + 1) % 3]);
            if inside(p.min(q).as_vec3(), p.max(q).as_vec3()) {
                edges.push((p.x.min(q.x), p.x.max(q.x), p, q));
            }
        }
    }
    let mut faces: Vec<(f64, f64, [DVec3; 3])> = b
        .iter()
        .map(|&t| corners(mesh, t))
        .filter(|c| {
            let (l, h) = (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
            inside(l.as_vec3(), h.as_vec3())
        })
        .map(|c| {
            (
                c[0].x.min(c[1].x).min(c[2].x),
                c[0].x.max(c[1].x).max(c[2].x),
                c,
            )
        })
        .collect();
    edges.sort_by(|x, y| x.0.total_cmp(&y.0));
    faces.sort_by(|x, y| x.0.total_cmp(&y.0));
    // Sweep: for each face, the edges that start before it ends and end after it starts.
    let mut first = 0;
    for &(f_lo, f_hi, face) in &faces {
        while first < edges.len() && edges[first].0 < f_lo && edges[first].1 < f_lo {
            first += 1;
        }
        for &(e_lo, e_hi, p, q) in &edges[first..] {
            if e_lo > f_hi {
                break;
            }
            if e_hi >= f_lo && pierces(p, q, face) {
                return true;
            }
        }
    }
    false
}

/// Whether piece `a` lies inside piece `b` and both bound volume of the same sign (a vertex
/// of `a` strictly inside `b` by the parity of a ray's crossings).
fn nested(mesh: &Mesh, a: &[usize], b: &[usize]) -> bool {
    let signed_volume = |piece: &[usize]| -> f64 {
        piece
            .iter()
            .map(|&t| {
                let [p, q, r] = corners(mesh, t);
                p.dot(q.cross(r))
            })
            .sum()
    };
    let point = corners(mesh, a[0])[0];
    let (lo, hi) = bounds(mesh, b);
    if point.cmplt(lo.as_dvec3()).any() || point.cmpgt(hi.as_dvec3()).any() {
        return false;
    }
    // A ray far past `b`'s box, in a direction unlikely to graze an edge.
    let reach = (hi - lo).as_dvec3().length() * 4.0 + 1.0;
    let far = point + DVec3::new(1.0, 0.307_411, 0.161_803).normalize() * reach;
    let crossings = b
        .iter()
        .filter(|&&t| pierces(point, far, corners(mesh, t)))
        .count();
    crossings % 2 == 1 && signed_volume(a) * signed_volume(b) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(offset: Vec3) -> Mesh {
        let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z) + offset;
        let positions = vec![
            p(0., 0., 0.),
            p(1., 0., 0.),
            p(1., 1., 0.),
            p(0., 1., 0.),
            p(0., 0., 1.),
            p(1., 0., 1.),
            p(1., 1., 1.),
            p(0., 1., 1.),
        ];
        // Outward, counter-clockwise seen from outside.
        let triangles = vec![
            [0, 2, 1],
            [0, 3, 2],
            [4, 5, 6],
            [4, 6, 7],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ];
        Mesh::new(positions, triangles)
    }

    fn both(a: &Mesh, b: &Mesh) -> Mesh {
        let n = a.positions.len() as u32;
        let mut positions = a.positions.clone();
        positions.extend(&b.positions);
        let mut triangles = a.triangles.clone();
        triangles.extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
        Mesh::new(positions, triangles)
    }

    fn scaled(m: &Mesh, s: f32, at: Vec3) -> Mesh {
        Mesh::new(
            m.positions.iter().map(|&p| p * s + at).collect(),
            m.triangles.clone(),
        )
    }

    #[test]
    fn overlapping_cubes_are_found_and_touching_ones_are_not() {
        let unit = cube(Vec3::ZERO);
        let overlapping = both(&unit, &cube(Vec3::new(0.25, 0.25, 0.5)));
        assert_eq!(pieces(&overlapping).len(), 2);
        assert_eq!(overlapping_pieces(&overlapping, 10), vec![(0, 1)]);
        // Stacked face to face, side by side along an edge, apart: no overlap.
        for offset in [Vec3::Z, Vec3::new(1.0, 1.0, 0.0), Vec3::new(3.0, 0.0, 0.0)] {
            let m = both(&unit, &cube(offset));
            assert!(overlapping_pieces(&m, 10).is_empty(), "{offset}");
        }
        // One cube inside another: an overlap; turned inside out it is a cavity, which is not.
        let inner = scaled(&unit, 0.5, Vec3::splat(0.25));
        assert_eq!(overlapping_pieces(&both(&unit, &inner), 10), vec![(0, 1)]);
        let mut cavity = inner.clone();
        cavity.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        assert!(overlapping_pieces(&both(&unit, &cavity), 10).is_empty());
        // One closed piece alone.
        assert!(overlapping_pieces(&unit, 10).is_empty());
    }
}
