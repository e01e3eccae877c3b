//! Closed forms for the shapes the tests and the benchmark check against: whole boxes,
//! spheres and tori, and the submerged part of an axis-aligned box and of a sphere.

use super::assemble::MassProperties;
use glam::{DMat3, DVec3};
use std::f64::consts::PI;

/// A solid box of side lengths `size` centred at `center`, axes aligned.
pub fn cuboid(size: DVec3, center: DVec3, density: f64) -> MassProperties {
    let volume = size.x * size.y * size.z;
    let m = density * volume;
    let s2 = size * size;
    MassProperties {
        density,
        volume,
        mass: m,
        center_of_mass: center,
        inertia: DMat3::from_diagonal(
            DVec3::new(s2.y + s2.z, s2.z + s2.x, s2.x + s2.y) * (m / 12.0),
        ),
    }
}

/// A solid sphere of radius `r`.
pub fn sphere(r: f64, center: DVec3, density: f64) -> MassProperties {
    let volume = 4.0 / 3.0 * PI * r.powi(3);
    let m = density * volume;
    MassProperties {
        density,
        volume,
        mass: m,
        center_of_mass: center,
        inertia: DMat3::from_diagonal(DVec3::splat(0.4 * m * r * r)),
    }
}

/// A solid torus about the z axis: tube radius `r`, distance `big_r` from the axis to the
/// tube centre. `I_zz = m (R² + 3r²/4)`, `I_xx = I_yy = m (R²/2 + 5r²/8)`.
pub fn torus(big_r: f64, r: f64, center: DVec3, density: f64) -> MassProperties {
    let volume = 2.0 * PI * PI * big_r * r * r;
    let m = density * volume;
    let ixx = m * (big_r * big_r / 2.0 + 5.0 * r * r / 8.0);
    let izz = m * (big_r * big_r + 0.75 * r * r);
    MassProperties {
        density,
        volume,
        mass: m,
        center_of_mass: center,
        inertia: DMat3::from_diagonal(DVec3::new(ixx, ixx, izz)),
    }
}

/// Volume and centre of buoyancy of an axis-aligned box below the plane `z = level`:
/// `V = A · depth`, centroid half the depth above the bottom.
pub fn submerged_cuboid(size: DVec3, center: DVec3, level: f64) -> (f64, DVec3) {
    let bottom = center.z - size.z / 2.0;
    let depth = (level - bottom).clamp(0.0, size.z);
    let volume = size.x * size.y * depth;
    (volume, DVec3::new(center.x, center.y, bottom + depth / 2.0))
}

/// Volume and centre of buoyancy of a sphere below the plane `z = level`: a cap of height
/// `h` has `V = π h² (3r − h) / 3`, its centroid `3 (2r − h)² / (4 (3r − h))` below the
/// sphere's centre.
pub fn submerged_sphere(r: f64, center: DVec3, level: f64) -> (f64, DVec3) {
    let h = (level - (center.z - r)).clamp(0.0, 2.0 * r);
    if h == 0.0 {
        return (0.0, DVec3::new(center.x, center.y, center.z - r));
    }
    let volume = PI * h * h * (3.0 * r - h) / 3.0;
    let below = 3.0 * (2.0 * r - h).powi(2) / (4.0 * (3.0 * r - h));
    (volume, DVec3::new(center.x, center.y, center.z - below))
}
