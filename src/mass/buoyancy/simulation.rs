//! The simulation loop of section 5.3: every step, the submerged volume and centre of
//! buoyancy of every body from a [`SubmergedSolver`] (the GPU's n + 2 passes, or the CPU
//! reference), then one rigid-body step per body.

use super::forces::{self, Submerged, Water};
use super::rigid_body::RigidBody;
use crate::mass::{analytic, MassProperties};
use crate::mesh::Mesh;
use glam::{DQuat, DVec3, Vec3};
use serde::Serialize;

/// A shape bodies can take: its mesh in the body frame (centre of mass at the origin) and
/// its unit-density mass properties.
#[derive(Clone, Debug)]
pub struct Shape {
    pub name: String,
    pub mesh: Mesh,
    /// Mass properties at density 1 (the body frame's origin is the centre of mass).
    pub unit: MassProperties,
}

impl Shape {
    /// Re-centres `mesh` at its centre of mass (Mirtich's algorithm: exact, and done once).
    /// Errors when the mesh does not enclose a positive volume.
    pub fn new(name: &str, mesh: &Mesh) -> Result<Self, String> {
        let whole = MassProperties::from_integrals(&analytic::volume_integrals(mesh), 1.0);
        if whole.volume.is_nan() || whole.volume <= 0.0 {
            return Err(format!(
                "shape {name}: the mesh encloses volume {} (inside out or open?)",
                whole.volume
            ));
        }
        let c = whole.center_of_mass.as_vec3();
        let mesh = Mesh::new(
            mesh.positions.iter().map(|p| *p - c).collect::<Vec<Vec3>>(),
            mesh.triangles.clone(),
        );
        let unit = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
        Ok(Self {
            name: name.to_string(),
            mesh,
            unit,
        })
    }
}

/// One floating body.
#[derive(Clone, Debug, Serialize)]
pub struct Body {
    /// Index into [`Simulation::shapes`].
    pub shape: usize,
    pub density: f64,
    pub rigid: RigidBody,
    /// What the last step's solver reported.
    pub submerged: Submerged,
}

/// Computes the submerged part of every body for one step.
pub trait SubmergedSolver {
    fn submerged(
        &mut self,
        shapes: &[Shape],
        bodies: &[Body],
        water: &Water,
    ) -> Result<Vec<Submerged>, String>;
}

/// The CPU reference solver: clip + Mirtich per body.
pub struct AnalyticSolver;

impl SubmergedSolver for AnalyticSolver {
    fn submerged(
        &mut self,
        shapes: &[Shape],
        bodies: &[Body],
        water: &Water,
    ) -> Result<Vec<Submerged>, String> {
        Ok(bodies
            .iter()
            .map(|b| super::analytic::submerged(&shapes[b.shape].mesh, &b.rigid, water.level))
            .collect())
    }
}

/// Bodies, their shapes and the water.
#[derive(Clone, Debug)]
pub struct Simulation {
    pub shapes: Vec<Shape>,
    pub bodies: Vec<Body>,
    pub water: Water,
    /// Fixed time step (s).
    pub dt: f64,
    pub time: f64,
}

impl Simulation {
    pub fn new(shapes: Vec<Shape>, water: Water, dt: f64) -> Self {
        Self {
            shapes,
            bodies: Vec::new(),
            water,
            dt,
            time: 0.0,
        }
    }

    /// Adds a body of `shape` and `density` at rest.
    pub fn add(&mut self, shape: usize, density: f64, position: DVec3, orientation: DQuat) {
        let unit = &self.shapes[shape].unit;
        let rigid = RigidBody::at_rest(
            unit.volume * density,
            unit.inertia * density,
            position,
            orientation,
        );
        self.bodies.push(Body {
            shape,
            density,
            rigid,
            submerged: Submerged::default(),
        });
    }

    /// One step: buoyancy of every body from `solver`, then the rigid-body step.
    pub fn step(&mut self, solver: &mut dyn SubmergedSolver) -> Result<(), String> {
        let subs = solver.submerged(&self.shapes, &self.bodies, &self.water)?;
        self.apply(&subs);
        Ok(())
    }

    /// The rigid-body half of a step, given every body's submerged part.
    pub fn apply(&mut self, subs: &[Submerged]) {
        for (body, &sub) in self.bodies.iter_mut().zip(subs) {
            let volume = self.shapes[body.shape].unit.volume;
            let w = forces::wrench(&body.rigid, volume, sub, &self.water);
            body.rigid.step(w, self.dt);
            body.submerged = sub;
        }
        self.time += self.dt;
    }

    /// Kinetic + gravitational + buoyant potential energy of every body, with the
    /// submerged parts computed exactly (CPU) for the current poses.
    pub fn energy(&self) -> f64 {
        self.bodies
            .iter()
            .map(|b| {
                let sub = super::analytic::submerged(
                    &self.shapes[b.shape].mesh,
                    &b.rigid,
                    self.water.level,
                );
                b.rigid.kinetic_energy() + forces::potential_energy(&b.rigid, sub, &self.water)
            })
            .sum()
    }
}
