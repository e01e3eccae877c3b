//! The forces of section 5: gravity at the centre of mass, Archimedes' buoyant force
//! `ρ_w g V` at the centre of buoyancy [eq. 7], and a viscous drag at the centre of buoyancy
//! proportional to the submerged volume and the square of the body velocity [5.3] (the
//! velocity of the centre of mass: "the body velocity"). That is all the paper models, and
//! the default.
//!
//! An option adds a linear drag and a rotational damping proportional to the submerged
//! part ([`Water::with_extra_damping`]): the quadratic drag alone lets small oscillations
//! die out only as 1/t; real floating bodies also lose energy to the waves they radiate,
//! which still water does not model, and the linear term stands in for that.

use super::rigid_body::{RigidBody, Wrench};
use glam::DVec3;
use serde::Serialize;

/// The still water the bodies float on.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Water {
    /// Height of the (flat) free surface.
    pub level: f64,
    /// `ρ_w` (kg/m³).
    pub density: f64,
    /// `g` (m/s²), acting along −z.
    pub gravity: f64,
    /// Drag coefficient `c` (1/m): `F = −c ρ_w V_sub |v| v` at the centre of buoyancy, `v`
    /// the velocity of the centre of mass.
    pub drag: f64,
    /// Linear drag rate `k` (1/s): `F = −k ρ_w V_sub v` (not in the paper: 0 unless
    /// [`Water::with_extra_damping`]).
    pub linear_drag: f64,
    /// Rotational damping rate (1/s) when fully submerged: `τ = −k (V_sub / V) I ω` (not
    /// in the paper: 0 unless [`Water::with_extra_damping`]).
    pub angular_damping: f64,
}

/// The extra damping's linear drag rate (1/s).
pub const EXTRA_LINEAR_DRAG: f64 = 2.0;
/// The extra damping's rotational damping rate (1/s).
pub const EXTRA_ANGULAR_DAMPING: f64 = 1.0;

impl Water {
    /// The same water with the linear drag and rotational damping the paper does not
    /// model ([`EXTRA_LINEAR_DRAG`], [`EXTRA_ANGULAR_DAMPING`]): bodies settle in seconds
    /// instead of rocking on.
    pub fn with_extra_damping(self) -> Self {
        Self {
            linear_drag: EXTRA_LINEAR_DRAG,
            angular_damping: EXTRA_ANGULAR_DAMPING,
            ..self
        }
    }

    /// Whether any damping beyond the paper's quadratic drag is on.
    pub fn has_extra_damping(&self) -> bool {
        self.linear_drag != 0.0 || self.angular_damping != 0.0
    }
}

impl Default for Water {
    fn default() -> Self {
        Self {
            level: 0.0,
            density: 1000.0,
            gravity: 9.81,
            drag: 1.0,
            linear_drag: 0.0,
            angular_damping: 0.0,
        }
    }
}

/// What the buoyancy computation delivers per body: the submerged volume and its centroid.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Submerged {
    pub volume: f64,
    /// The centre of buoyancy `B` (world).
    pub center: DVec3,
}

impl Submerged {
    /// From the integrals of the part below the water: nothing when no volume is below
    /// (the centroid of nothing is not a point).
    pub fn of(integrals: &crate::mass::VolumeIntegrals) -> Submerged {
        if integrals.v > 0.0 {
            Submerged {
                volume: integrals.v,
                center: integrals.centroid(),
            }
        } else {
            Submerged::default()
        }
    }
}

/// Gravity + buoyancy + drag (+ the optional damping) on `body` of total volume
/// `body_volume`.
pub fn wrench(body: &RigidBody, body_volume: f64, sub: Submerged, water: &Water) -> Wrench {
    let gravity = Wrench {
        force: DVec3::new(0.0, 0.0, -body.mass * water.gravity),
        torque: DVec3::ZERO,
    };
    if sub.volume <= 0.0 {
        return gravity;
    }
    let buoyant = DVec3::new(0.0, 0.0, water.density * water.gravity * sub.volume);
    // [5.3] "proportional to the submerged volume and the square of the body velocity",
    // acting at the centre of buoyancy: the velocity of the body (its centre of mass).
    let v = body.velocity;
    let drag = -water.density * sub.volume * (water.drag * v.length() + water.linear_drag) * v;
    let fraction = (sub.volume / body_volume).clamp(0.0, 1.0);
    let damping = Wrench {
        force: DVec3::ZERO,
        torque: -water.angular_damping * fraction * (body.world_inertia() * body.angular_velocity),
    };
    gravity + body.force_at(buoyant + drag, sub.center) + damping
}

/// Potential energy of gravity and buoyancy: `m g z_C + ρ_w g V_sub (level − z_B)`.
/// The buoyant part is `ρ_w g ∫_sub (level − z) dV`, the work needed to push the body down
/// against the hydrostatic pressure of eq. 7; with the kinetic energy it is conserved
/// when there is no drag.
pub fn potential_energy(body: &RigidBody, sub: Submerged, water: &Water) -> f64 {
    body.mass * water.gravity * body.position.z
        + water.density * water.gravity * sub.volume * (water.level - sub.center.z)
}
