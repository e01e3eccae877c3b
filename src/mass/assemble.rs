//! Assembly of the mass properties from the volume integrals [eq. 1, 2, 4-6].
//!
//! Equation 5 as printed puts the second moments `I_xx = ∫x² dV` of eq. 6 on the diagonal;
//! the inertia tensor of eq. 2 needs `∫(y² + z²) dV` there. We follow eq. 2:
//! `I = ρ (tr(S) 1 − S)` with `S` the second-moment matrix about the centre of mass.

use super::integrals::VolumeIntegrals;
use glam::{DMat3, DVec3};
use serde::Serialize;

/// Mass, volume, centre of mass and inertia tensor of a body of uniform density.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MassProperties {
    pub density: f64,
    /// `V` of eq. 4 (negative for an inside-out mesh: we never hide that).
    pub volume: f64,
    /// `m = ρ V` (eq. 1 with constant ρ).
    pub mass: f64,
    /// `r` of eq. 4.
    pub center_of_mass: DVec3,
    /// Eq. 2, about the centre of mass, in world axes, scaled by the density.
    pub inertia: DMat3,
}

impl MassProperties {
    /// Equations 4-6 for density `density`. A zero volume puts the centre of mass at the
    /// integrals' origin.
    pub fn from_integrals(i: &VolumeIntegrals, density: f64) -> Self {
        let center = i.centroid();
        let s = central_second_moments(i, center);
        let inertia = (DMat3::IDENTITY * (s.x_axis.x + s.y_axis.y + s.z_axis.z) - s) * density;
        Self {
            density,
            volume: i.v,
            mass: density * i.v,
            center_of_mass: center,
            inertia,
        }
    }

    /// Relative errors of mass, Ixx, Iyy and Izz against `reference`: the measure of paper 4's
    /// Fig. 4.
    pub fn relative_errors(&self, reference: &MassProperties) -> [f64; 4] {
        let rel = |got: f64, want: f64| ((got - want) / want).abs();
        [
            rel(self.mass, reference.mass),
            rel(self.inertia.x_axis.x, reference.inertia.x_axis.x),
            rel(self.inertia.y_axis.y, reference.inertia.y_axis.y),
            rel(self.inertia.z_axis.z, reference.inertia.z_axis.z),
        ]
    }

    /// The principal moments (eigenvalues of the inertia tensor), ascending.
    pub fn principal_moments(&self) -> DVec3 {
        symmetric_eigenvalues(self.inertia)
    }

    /// The inertia tensor as rows, for JSON.
    pub fn inertia_rows(&self) -> [[f64; 3]; 3] {
        let m = self.inertia.transpose().to_cols_array_2d();
        [m[0], m[1], m[2]]
    }
}

/// `S_ij = ∫ (x_i − r_i)(x_j − r_j) dV`, by the parallel-axis shift of the moments from
/// their origin (near the solid, so the shift cancels little).
fn central_second_moments(i: &VolumeIntegrals, r: DVec3) -> DMat3 {
    let c = i.about(r);
    DMat3::from_cols(
        DVec3::new(c.xx, c.xy, c.zx),
        DVec3::new(c.xy, c.yy, c.yz),
        DVec3::new(c.zx, c.yz, c.zz),
    )
}

/// Eigenvalues of a symmetric 3x3 matrix, ascending (closed form by the trigonometric
/// method; accurate to a few ulps of the largest eigenvalue, plenty for mass properties).
pub fn symmetric_eigenvalues(a: DMat3) -> DVec3 {
    let (a00, a11, a22) = (a.x_axis.x, a.y_axis.y, a.z_axis.z);
    let (a01, a02, a12) = (a.y_axis.x, a.z_axis.x, a.z_axis.y);
    let p1 = a01 * a01 + a02 * a02 + a12 * a12;
    if p1 <= 1e-30 * (a00 * a00 + a11 * a11 + a22 * a22).max(1e-300) {
        let mut e = [a00, a11, a22];
        e.sort_by(f64::total_cmp);
        return DVec3::from_array(e);
    }
    let q = (a00 + a11 + a22) / 3.0;
    let p2 = (a00 - q).powi(2) + (a11 - q).powi(2) + (a22 - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b = (a - DMat3::IDENTITY * q) * (1.0 / p);
    let r = (b.determinant() / 2.0).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let e_max = q + 2.0 * p * phi.cos();
    let e_min = q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    let e_mid = 3.0 * q - e_max - e_min;
    DVec3::new(e_min, e_mid, e_max)
}
