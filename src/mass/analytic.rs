//! Mirtich's analytic algorithm (B. Mirtich, "Fast and accurate computation of polyhedral
//! mass properties", J. Graphics Tools 1(2), 1996), the paper's baseline [section 4].
//!
//! Three reductions: the volume integrals become surface integrals by the divergence
//! theorem, each face integral becomes an integral over the face's projection onto the
//! coordinate plane where it is largest, and that becomes a sum over the projected edges
//! (Green's theorem). Mirtich's names are kept: `A`, `B`, `C` are the projection axes
//! (`C` the one dropped), `P..` the projection integrals, `F..` the face integrals,
//! `T0`, `T1`, `T2`, `TP` the volume integrals.

use super::integrals::VolumeIntegrals;
use crate::mesh::Mesh;
use glam::DVec3;

/// The ten volume integrals of a closed, outward-oriented triangle mesh, exactly (up to
/// f64 rounding), about the centre of its bounding box: far from the world origin the
/// products of coordinates in the projection integrals would otherwise cancel away the
/// body's own moments. Zero-area triangles contribute nothing and are skipped.
pub fn volume_integrals(mesh: &Mesh) -> VolumeIntegrals {
    let origin = bounding_box_centre(mesh);
    let mut t = VolumeSums::default();
    for tri in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(tri).map(|p| p.as_dvec3() - origin);
        t.add_face(&[a, b, c]);
    }
    VolumeIntegrals {
        origin,
        ..t.finish()
    }
}

/// The centre of the vertices' bounding box (the origin for an empty mesh), in f64.
fn bounding_box_centre(mesh: &Mesh) -> DVec3 {
    let mut points = mesh.positions.iter().map(|p| p.as_dvec3());
    let Some(first) = points.next() else {
        return DVec3::ZERO;
    };
    let (lo, hi) = points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
    (lo + hi) / 2.0
}

/// The running sums `T0`, `T1`, `T2`, `TP` over the faces.
#[derive(Default)]
struct VolumeSums {
    t0: f64,
    t1: [f64; 3],
    t2: [f64; 3],
    tp: [f64; 3],
}

impl VolumeSums {
    /// Adds one planar polygon (counter-clockwise seen from outside).
    fn add_face(&mut self, verts: &[DVec3]) {
        let Some(n) = face_normal(verts) else { return };
        let w = -n.dot(verts[0]);
        let m = n.abs();
        let c = if m.x >= m.y && m.x >= m.z {
            0
        } else if m.y >= m.z {
            1
        } else {
            2
        };
        let a = (c + 1) % 3;
        let b = (a + 1) % 3;
        let p = ProjectionIntegrals::of(verts, a, b);
        let f = FaceIntegrals::of(&p, n, w, a, b, c);

        self.t0 += n.x
            * if a == 0 {
                f.fa
            } else if b == 0 {
                f.fb
            } else {
                f.fc
            };
        self.t1[a] += n[a] * f.faa;
        self.t1[b] += n[b] * f.fbb;
        self.t1[c] += n[c] * f.fcc;
        self.t2[a] += n[a] * f.faaa;
        self.t2[b] += n[b] * f.fbbb;
        self.t2[c] += n[c] * f.fccc;
        self.tp[a] += n[a] * f.faab;
        self.tp[b] += n[b] * f.fbbc;
        self.tp[c] += n[c] * f.fcca;
    }

    fn finish(self) -> VolumeIntegrals {
        let (t1, t2, tp) = (
            self.t1.map(|v| v / 2.0),
            self.t2.map(|v| v / 3.0),
            self.tp.map(|v| v / 2.0),
        );
        VolumeIntegrals {
            origin: DVec3::ZERO,
            v: self.t0,
            x: t1[0],
            y: t1[1],
            z: t1[2],
            xx: t2[0],
            yy: t2[1],
            zz: t2[2],
            // Mirtich's TP[X] = ∫xy, TP[Y] = ∫yz, TP[Z] = ∫zx.
            xy: tp[0],
            yz: tp[1],
            zx: tp[2],
        }
    }
}

/// Unit normal of a planar polygon (Newell's method on the edges from its first vertex,
/// so it does not depend on where the polygon lies), `None` when its area is zero.
/// A sliver is kept however thin: its contribution is proportional to its area, whatever
/// the direction its rounded normal takes, and a sliver 10^38 long can hold most of a
/// body's volume.
fn face_normal(verts: &[DVec3]) -> Option<DVec3> {
    let mut n = DVec3::ZERO;
    for i in 1..verts.len() - 1 {
        n += (verts[i] - verts[0]).cross(verts[i + 1] - verts[0]);
    }
    let len = n.length();
    (len > 0.0 && len.is_finite()).then(|| n / len)
}

/// Integrals of `1, a, b, a², ab, b², a³, a²b, ab², b³` over the face's projection onto
/// the `ab` plane, from its edges.
#[derive(Default)]
struct ProjectionIntegrals {
    p1: f64,
    pa: f64,
    pb: f64,
    paa: f64,
    pab: f64,
    pbb: f64,
    paaa: f64,
    paab: f64,
    pabb: f64,
    pbbb: f64,
}

impl ProjectionIntegrals {
    fn of(verts: &[DVec3], a: usize, b: usize) -> Self {
        let mut p = Self::default();
        for (i, v0) in verts.iter().enumerate() {
            let v1 = verts[(i + 1) % verts.len()];
            let (a0, b0, a1, b1) = (v0[a], v0[b], v1[a], v1[b]);
            let (da, db) = (a1 - a0, b1 - b0);
            let (a0_2, b0_2, a1_2, b1_2) = (a0 * a0, b0 * b0, a1 * a1, b1 * b1);
            let (a0_3, b0_3, a1_3, b1_3) = (a0_2 * a0, b0_2 * b0, a1_2 * a1, b1_2 * b1);
            let (a0_4, b0_4) = (a0_3 * a0, b0_3 * b0);

            let c1 = a1 + a0;
            let ca = a1 * c1 + a0_2;
            let caa = a1 * ca + a0_3;
            let caaa = a1 * caa + a0_4;
            let cb = b1 * (b1 + b0) + b0_2;
            let cbb = b1 * cb + b0_3;
            let cbbb = b1 * cbb + b0_4;
            let cab = 3.0 * a1_2 + 2.0 * a1 * a0 + a0_2;
            let kab = a1_2 + 2.0 * a1 * a0 + 3.0 * a0_2;
            let caab = a0 * cab + 4.0 * a1_3;
            let kaab = a1 * kab + 4.0 * a0_3;
            let cabb = 4.0 * b1_3 + 3.0 * b1_2 * b0 + 2.0 * b1 * b0_2 + b0_3;
            let kabb = b1_3 + 2.0 * b1_2 * b0 + 3.0 * b1 * b0_2 + 4.0 * b0_3;

            p.p1 += db * c1;
            p.pa += db * ca;
            p.paa += db * caa;
            p.paaa += db * caaa;
            p.pb += da * cb;
            p.pbb += da * cbb;
            p.pbbb += da * cbbb;
            p.pab += db * (b1 * cab + b0 * kab);
            p.paab += db * (b1 * caab + b0 * kaab);
            p.pabb += da * (a1 * cabb + a0 * kabb);
        }
        p.p1 /= 2.0;
        p.pa /= 6.0;
        p.paa /= 12.0;
        p.paaa /= 20.0;
        p.pb /= -6.0;
        p.pbb /= -12.0;
        p.pbbb /= -20.0;
        p.pab /= 24.0;
        p.paab /= 60.0;
        p.pabb /= -60.0;
        p
    }
}

/// Integrals over the face itself of `a, b, c, a², b², c², a³, b³, c³, a²b, b²c, c²a`.
struct FaceIntegrals {
    fa: f64,
    fb: f64,
    fc: f64,
    faa: f64,
    fbb: f64,
    fcc: f64,
    faaa: f64,
    fbbb: f64,
    fccc: f64,
    faab: f64,
    fbbc: f64,
    fcca: f64,
}

impl FaceIntegrals {
    /// From the projection integrals, using the face plane `n·p + w = 0` to express `c`.
    fn of(p: &ProjectionIntegrals, n: DVec3, w: f64, a: usize, b: usize, c: usize) -> Self {
        let (na, nb) = (n[a], n[b]);
        let k1 = 1.0 / n[c];
        let (k2, k3, k4) = (k1 * k1, k1 * k1 * k1, k1 * k1 * k1 * k1);
        let lin = na * p.pa + nb * p.pb;
        let quad = na * na * p.paa + 2.0 * na * nb * p.pab + nb * nb * p.pbb;
        Self {
            fa: k1 * p.pa,
            fb: k1 * p.pb,
            fc: -k2 * (lin + w * p.p1),
            faa: k1 * p.paa,
            fbb: k1 * p.pbb,
            fcc: k3 * (quad + w * (2.0 * lin + w * p.p1)),
            faaa: k1 * p.paaa,
            fbbb: k1 * p.pbbb,
            fccc: -k4
                * (na.powi(3) * p.paaa
                    + 3.0 * na * na * nb * p.paab
                    + 3.0 * na * nb * nb * p.pabb
                    + nb.powi(3) * p.pbbb
                    + 3.0 * w * quad
                    + w * w * (3.0 * lin + w * p.p1)),
            faab: k1 * p.paab,
            fbbc: -k2 * (na * p.pabb + nb * p.pbbb + w * p.pbb),
            fcca: k3
                * (na * na * p.paaa
                    + 2.0 * na * nb * p.paab
                    + nb * nb * p.pabb
                    + w * (2.0 * (na * p.paa + nb * p.pab) + w * p.pa)),
        }
    }
}
