//! The ten volume integrals behind equations 4 and 6: the volume, the three first moments
//! and the six second moments of a solid. Both the GPU (pixel sums of the integrands of
//! section 3.1) and Mirtich's analytic algorithm produce this one type, so everything that
//! follows (assembly, buoyancy) is shared and the two can be compared field by field.

use glam::DVec3;
use serde::Serialize;
use std::ops::{Add, AddAssign, Mul};

/// `∫ f dV` over the solid for f = 1, x, y, z, x², y², z², xy, yz, zx (in that order).
///
/// Double precision: the GPU sums are fp32 per pixel, but the accumulation over peels and
/// the change of origin ([`VolumeIntegrals::translated`]) cancel large terms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct VolumeIntegrals {
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
    /// The first moments as a vector.
    pub fn first(&self) -> DVec3 {
        DVec3::new(self.x, self.y, self.z)
    }

    /// The same solid's integrals in coordinates shifted by `t` (`x' = x + t`):
    /// `∫x' = ∫x + t V`, `∫x'y' = ∫xy + t_y ∫x + t_x ∫y + t_x t_y V`, and so on.
    /// The GPU integrates about the framing centre; this moves the result back to the origin.
    pub fn translated(&self, t: DVec3) -> Self {
        let v = self.v;
        let m = self.first();
        let second =
            |a: f64, ma: f64, ta: f64, mb: f64, tb: f64| a + ta * mb + tb * ma + ta * tb * v;
        Self {
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

    /// The ten values in the order of the struct (for comparisons and JSON).
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

impl Add for VolumeIntegrals {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
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
