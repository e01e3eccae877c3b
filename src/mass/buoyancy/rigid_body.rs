//! Rigid-body dynamics on the CPU [section 5.3]: state, wrenches, and a semi-implicit
//! (symplectic) Euler step with a fixed time step.

use glam::{DMat3, DQuat, DVec3};
use serde::Serialize;

/// A rigid body whose body frame has its origin at the centre of mass.
#[derive(Clone, Debug, Serialize)]
pub struct RigidBody {
    pub mass: f64,
    /// Inertia tensor about the centre of mass, in body axes (from [`crate::mass`]).
    pub inertia_body: DMat3,
    /// World position of the centre of mass.
    pub position: DVec3,
    pub orientation: DQuat,
    pub velocity: DVec3,
    /// World-frame angular velocity.
    pub angular_velocity: DVec3,
}

/// A force and a torque about the centre of mass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wrench {
    pub force: DVec3,
    pub torque: DVec3,
}

impl std::ops::Add for Wrench {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            force: self.force + o.force,
            torque: self.torque + o.torque,
        }
    }
}

impl RigidBody {
    /// A body at rest at `position` with `orientation`.
    pub fn at_rest(mass: f64, inertia_body: DMat3, position: DVec3, orientation: DQuat) -> Self {
        Self {
            mass,
            inertia_body,
            position,
            orientation,
            velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
        }
    }

    /// `R I_body Rᵀ`.
    pub fn world_inertia(&self) -> DMat3 {
        let r = DMat3::from_quat(self.orientation);
        r * self.inertia_body * r.transpose()
    }

    /// A body-frame point in world coordinates.
    pub fn to_world(&self, p: DVec3) -> DVec3 {
        self.position + self.orientation * p
    }

    /// Body-frame points (a mesh's vertices) in world coordinates, in f64.
    pub fn posed(&self, points: &[glam::Vec3]) -> Vec<DVec3> {
        points.iter().map(|p| self.to_world(p.as_dvec3())).collect()
    }

    /// Velocity of the material point at world position `p`.
    pub fn point_velocity(&self, p: DVec3) -> DVec3 {
        self.velocity + self.angular_velocity.cross(p - self.position)
    }

    /// The wrench of `force` applied at world point `p`.
    pub fn force_at(&self, force: DVec3, p: DVec3) -> Wrench {
        Wrench {
            force,
            torque: (p - self.position).cross(force),
        }
    }

    /// `½ m v² + ½ ωᵀ I ω`.
    pub fn kinetic_energy(&self) -> f64 {
        let w = self.angular_velocity;
        0.5 * self.mass * self.velocity.length_squared() + 0.5 * w.dot(self.world_inertia() * w)
    }

    /// One semi-implicit Euler step: velocities from the wrench first (Euler's equations
    /// with the gyroscopic term), then the pose from the new velocities. Symplectic for
    /// the translational part, so a conservative force keeps the energy bounded.
    pub fn step(&mut self, w: Wrench, dt: f64) {
        self.velocity += w.force / self.mass * dt;
        let inertia = self.world_inertia();
        let omega = self.angular_velocity;
        let gyro = omega.cross(inertia * omega);
        self.angular_velocity += inertia.inverse() * (w.torque - gyro) * dt;

        self.position += self.velocity * dt;
        let spin = DQuat::from_xyzw(
            self.angular_velocity.x,
            self.angular_velocity.y,
            self.angular_velocity.z,
            0.0,
        ) * self.orientation;
        self.orientation = (self.orientation + spin * (0.5 * dt)).normalize();
    }
}
