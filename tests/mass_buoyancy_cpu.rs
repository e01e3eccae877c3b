//! Section 5 on the CPU reference solver (clip + Mirtich): the physical checks of the
//! buoyancy simulation, independent of the GPU.

use classic_gpgpu::mass::buoyancy::forces::Water;
use classic_gpgpu::mass::buoyancy::simulation::{AnalyticSolver, Shape, Simulation};
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, energy_run, uv_sphere};

mod mass_shapes;

fn run(sim: &mut Simulation, steps: usize) {
    for _ in 0..steps {
        sim.step(&mut AnalyticSolver).unwrap();
    }
}

#[test]
fn flat_box_of_density_03_floats_level_at_draft_03() {
    let (w, h) = (1.0, 0.25);
    let shape = Shape::new("box", &cuboid(Vec3::new(w, w, h), Vec3::ZERO)).unwrap();
    let mut sim = Simulation::new(
        vec![shape],
        Water {
            drag: 4.0,
            // The option's damping settles the body within the run (the paper's
            // quadratic drag alone lets it rock on for long).
            ..Water::default().with_extra_damping()
        },
        0.01,
    );
    let tilt = DQuat::from_rotation_x(0.05);
    sim.add(0, 300.0, DVec3::new(0.0, 0.0, 0.1), tilt);
    run(&mut sim, 800);
    let body = &sim.bodies[0].rigid;
    let draft = (h as f64) / 2.0 - body.position.z;
    let up = body.orientation * DVec3::Z;
    assert!(
        (draft / h as f64 - 0.3).abs() < 0.01 * 0.3,
        "draft {} of the height",
        draft / h as f64
    );
    assert!(up.z > 0.9999, "not level: up = {up}");
}

#[test]
fn box_of_density_15_sinks() {
    let shape = Shape::new("box", &cuboid(Vec3::new(1.0, 1.0, 0.25), Vec3::ZERO)).unwrap();
    let mut sim = Simulation::new(vec![shape], Water::default(), 0.01);
    sim.add(0, 1500.0, DVec3::ZERO, DQuat::IDENTITY);
    run(&mut sim, 200);
    let body = &sim.bodies[0];
    assert!(
        body.rigid.position.z < -1.0,
        "z = {}",
        body.rigid.position.z
    );
    assert!(body.rigid.velocity.z < 0.0);
    assert!((body.submerged.volume - 0.25).abs() < 1e-6);
}

#[test]
fn sphere_of_density_05_floats_with_its_centre_at_the_water_line() {
    let shape = Shape::new("sphere", &uv_sphere(24, 48, |_| 0.5)).unwrap();
    let mut sim = Simulation::new(
        vec![shape],
        Water {
            drag: 4.0,
            // The option's damping settles the body within the run (the paper's
            // quadratic drag alone lets it rock on for long).
            ..Water::default().with_extra_damping()
        },
        0.01,
    );
    sim.add(0, 500.0, DVec3::new(0.0, 0.0, 0.2), DQuat::IDENTITY);
    run(&mut sim, 800);
    let z = sim.bodies[0].rigid.position.z;
    assert!(z.abs() < 0.005, "centre at z = {z}");
}

#[test]
fn energy_is_conserved_without_drag_and_decays_with_it() {
    let (e0, max_e, _) = energy_run(&mut AnalyticSolver, 0.0, 0.002, 1000);
    // Energy relative to a mass m: m g * 1 cm is the scale of the bobbing motion.
    let scale = 240.0 * 9.81 * 0.1;
    assert!(
        (max_e - e0) / scale < 0.02,
        "energy grew by {} of {scale}",
        max_e - e0
    );
    let (d0, _, d_end) = energy_run(&mut AnalyticSolver, 4.0, 0.002, 1000);
    let (_, _, free_end) = energy_run(&mut AnalyticSolver, 0.0, 0.002, 1000);
    assert!(d_end < d0 - 0.3 * scale, "drag removed only {}", d0 - d_end);
    assert!(d_end < free_end);
}

#[test]
fn cube_of_density_05_rolls_off_face_up() {
    // Metacentric height of a face-up cube at half draft: -s/12 < 0, so face-up is unstable.
    let shape = Shape::new("cube", &cuboid(Vec3::ONE, Vec3::ZERO)).unwrap();
    let mut sim = Simulation::new(vec![shape], Water::default(), 0.01);
    sim.add(0, 500.0, DVec3::ZERO, DQuat::from_rotation_x(0.02));
    run(&mut sim, 400);
    let up = sim.bodies[0].rigid.orientation * DVec3::Z;
    let tilt = up.z.clamp(-1.0, 1.0).acos();
    assert!(tilt > 0.3, "tilt stayed at {tilt} rad");
}
