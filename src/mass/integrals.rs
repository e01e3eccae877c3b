//! The ten volume integrals behind equations 4 and 6: the volume, the three first moments
//! and the six second moments of a solid. Both the GPU (pixel sums of the integrands of
//! section 3.1) and Mirtich's analytic algorithm produce this one type, so everything that
//! follows (assembly, buoyancy) is shared and the two can be compared field by field.

use glam::DVec3;
use serde::Serialize;
use std::ops::{Add, AddAssign, Mul};

/// `∫ f dV` over the solid for f = 1, x, y, z, x², y², z², xy, yz, zx (in that order), with
/// x, y, z measured from [`VolumeIntegrals::origin`].
///
/// The origin is a point near the solid (its bounding-box centre, the framing centre), not
/// the world origin: a unit cube 10^6 away has `∫x² dV` = 10^12 + 1/12 about the world
/// origin, and the 1/12 that the inertia tensor needs would not survive the subtraction of
/// `V r²`, even in f64. About a nearby origin every integral keeps its own digits.
///
/// Double precision: the GPU sums are fp32 per pixel, but the accumulation over peels and
/// the change of origin ([`VolumeIntegrals::about`]) cancel large terms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct VolumeIntegrals {
    /// The point the moments are taken about (world coordinates).
    pub origin: DVec3,
    /// `∫ dV`, the volume `V` of eq. 4.
    pub v: f64,
    /// `∫ x dV`, `∫ y dV`, `∫ z dV` (eq. 4 without the `1/V`).
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// `∫ x² dV`, `∫ y² dV`, `∫ z² dV` (the paper's `I_xx`, `I_yy`, `I_zz` of eq. 6).
    pub xx: f64,
    pub yy: f64,
    pub zz: f64,
    /// `∫ xy dV`, `∫ yz dV`, `∫ zx dV` (the paper's `I_xy`, `I_yz`, `I_xz` of eq. 6).
    pub xy: f64,
    pub yz: f64,
    pub zx: f64,
}

impl VolumeIntegrals {
    /// The first moments about the origin as a vector.
    pub fn first(&self) -> DVec3 {
        DVec3::new(self.x, self.y, self.z)
    }

    /// The centroid (centre of mass at uniform density) in world coordinates; the origin
    /// for a solid of zero volume.
    pub fn centroid(&self) -> DVec3 {
        if self.v != 0.0 {
            self.origin + self.first() / self.v
        } else {
            self.origin
        }
    }

    /// The same solid's integrals about `origin`: with `x' = x + t`, `t = self.origin -
    /// origin`, `∫x' = ∫x + t V`, `∫x'y' = ∫xy + t_y ∫x + t_x ∫y + t_x t_y V`, and so on.
    /// Exact but for rounding; the rounding is small when the two origins are close
    /// compared with the solid's size (and [`VolumeIntegrals::world`], about the world
    /// origin, is for comparing results, not for computing with them).
    pub fn about(&self, origin: DVec3) -> Self {
        let t = self.origin - origin;
        let v = self.v;
        let m = self.first();
        let second =
            |a: f64, ma: f64, ta: f64, mb: f64, tb: f64| a + ta * mb + tb * ma + ta * tb * v;
        Self {
            origin,
            v,
            x: m.x + t.x * v,
            y: m.y + t.y * v,
            z: m.z + t.z * v,
            xx: second(self.xx, m.x, t.x, m.x, t.x),
            yy: second(self.yy, m.y, t.y, m.y, t.y),
            zz: second(self.zz, m.z, t.z, m.z, t.z),
            xy: second(self.xy, m.x, t.x, m.y, t.y),
            yz: second(self.yz, m.y, t.y, m.z, t.z),
            zx: second(self.zx, m.z, t.z, m.x, t.x),
        }
    }

    /// About the world origin (to compare results computed about different points).
    pub fn world(&self) -> Self {
        self.about(DVec3::ZERO)
    }

    /// The integrals of the solid stretched by `s` per axis about the origin
    /// (`x' = s_x x`, ...): `∫ x'^a y'^b z'^c dV' = s_x^(1+a) s_y^(1+b) s_z^(1+c) ∫ x^a y^b
    /// z^c dV`. Exact when the factors are powers of two.
    pub fn stretched(&self, s: DVec3) -> Self {
        let dv = s.x * s.y * s.z;
        Self {
            origin: self.origin,
            v: dv * self.v,
            x: dv * s.x * self.x,
            y: dv * s.y * self.y,
            z: dv * s.z * self.z,
            xx: dv * s.x * s.x * self.xx,
            yy: dv * s.y * s.y * self.yy,
            zz: dv * s.z * s.z * self.zz,
            xy: dv * s.x * s.y * self.xy,
            yz: dv * s.y * s.z * self.yz,
            zx: dv * s.z * s.x * self.zx,
        }
    }

    /// The ten values (about the origin) in the order of the struct.
    pub fn to_array(&self) -> [f64; 10] {
        [
            self.v, self.x, self.y, self.z, self.xx, self.yy, self.zz, self.xy, self.yz, self.zx,
        ]
    }

    /// Whether every value is finite.
    pub fn is_finite(&self) -> bool {
        self.to_array().iter().all(|v| v.is_finite())
    }
}

/// The sum of two solids' integrals, about the first's origin.
impl Add for VolumeIntegrals {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let o = if o.origin == self.origin {
            o
        } else {
            o.about(self.origin)
        };
        Self {
            origin: self.origin,
            v: self.v + o.v,
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
            xx: self.xx + o.xx,
            yy: self.yy + o.yy,
            zz: self.zz + o.zz,
            xy: self.xy + o.xy,
            yz: self.yz + o.yz,
            zx: self.zx + o.zx,
        }
    }
}

impl AddAssign for VolumeIntegrals {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl Mul<f64> for VolumeIntegrals {
    type Output = Self;
    fn mul(self, s: f64) -> Self {
        let a = self.to_array().map(|v| v * s);
        Self {
            origin: self.origin,
            v: a[0],
            x: a[1],
            y: a[2],
            z: a[3],
            xx: a[4],
            yy: a[5],
            zz: a[6],
            xy: a[7],
            yz: a[8],
            zx: a[9],
        }
    }
}
