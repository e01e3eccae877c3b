//! Section 5 on the GPU: the batched n + 2 passes drive the rigid bodies.

use classic_gpgpu::mass::buoyancy::batch::GpuSolver;
use classic_gpgpu::mass::buoyancy::forces::Water;
use classic_gpgpu::mass::buoyancy::simulation::{
    AnalyticSolver, Shape, Simulation, SubmergedSolver,
};
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mesh::Mesh;
use common::context;
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, energy_run, torus, uv_sphere};
use rand::{Rng, SeedableRng};

mod common;

mod mass_shapes;

const RESOLUTION: u32 = 32;

fn settle(sim: &mut Simulation, solver: &mut dyn SubmergedSolver, steps: usize) {
    for _ in 0..steps {
        sim.step(solver).unwrap();
    }
}

#[test]
fn flat_box_of_density_03_floats_level_at_draft_03_on_the_gpu() {
    let ctx = context();
    let h = 0.25;
    let shape = Shape::new("box", &cuboid(Vec3::new(1.0, 1.0, h as f32), Vec3::ZERO)).unwrap();
    let mut solver = GpuSolver::new(&ctx, std::slice::from_ref(&shape), 1, RESOLUTION).unwrap();
    let mut sim = Simulation::new(vec![shape], Water::default().with_extra_damping(), 0.01);
    sim.add(
        0,
        300.0,
        DVec3::new(0.0, 0.0, 0.05),
        DQuat::from_rotation_x(0.05),
    );
    settle(&mut sim, &mut solver, 600);
    let body = &sim.bodies[0].rigid;
    let draft = h / 2.0 - body.position.z;
    let up = body.orientation * DVec3::Z;
    assert!(
        (draft / h - 0.3).abs() < 0.01 * 0.3,
        "draft {} of the height",
        draft / h
    );
    assert!(up.z > 0.9999, "not level: up = {up}");
}

#[test]
fn dense_box_sinks_and_light_sphere_floats_at_its_centre_on_the_gpu() {
    let ctx = context();
    let shapes = vec![
        Shape::new("box", &cuboid(Vec3::new(1.0, 1.0, 0.25), Vec3::ZERO)).unwrap(),
        Shape::new("sphere", &uv_sphere(16, 32, |_| 0.5)).unwrap(),
    ];
    let mut solver = GpuSolver::new(&ctx, &shapes, 2, RESOLUTION).unwrap();
    let mut sim = Simulation::new(shapes, Water::default().with_extra_damping(), 0.01);
    sim.add(0, 1500.0, DVec3::new(-2.0, 0.0, 0.0), DQuat::IDENTITY);
    sim.add(1, 500.0, DVec3::new(2.0, 0.0, 0.1), DQuat::IDENTITY);
    settle(&mut sim, &mut solver, 600);
    assert!(
        sim.bodies[0].rigid.position.z < -2.0,
        "box at {}",
        sim.bodies[0].rigid.position.z
    );
    let z = sim.bodies[1].rigid.position.z;
    // A 32x32 view of the sphere's water-line disc is ~1% off in area; the centre follows
    // within a few millimetres of its 0.5 m radius.
    assert!(z.abs() < 0.01 * 0.5, "sphere centre at z = {z}");
}

/// The submerged volume the simulation uses is what `mass --below` computes for the same
/// pose (same framing: the world bounding box): equal up to fp32 (vertices transformed in the
/// shader versus on the CPU), and within the discretisation of the exact clipped volume.
#[test]
fn batched_submerged_volumes_equal_the_mass_module_below_answer() {
    let ctx = context();
    let shapes = vec![
        Shape::new("torus", &torus(1.0, 0.35, 40, 20)).unwrap(),
        Shape::new("box", &cuboid(Vec3::new(1.0, 0.6, 0.4), Vec3::ZERO)).unwrap(),
    ];
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
    let mut sim = Simulation::new(shapes.clone(), Water::default(), 0.01);
    for k in 0..12 {
        let q = DQuat::from_scaled_axis(DVec3::new(
            rng.gen_range(-1.5..1.5),
            rng.gen_range(-1.5..1.5),
            rng.gen_range(-1.5..1.5),
        ));
        sim.add(
            k % 2,
            500.0,
            DVec3::new(k as f64 * 3.0, 0.0, rng.gen_range(-0.5..0.5)),
            q,
        );
    }
    let mut solver = GpuSolver::new(&ctx, &shapes, sim.bodies.len(), RESOLUTION).unwrap();
    let batched = solver
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .unwrap();
    let exact = AnalyticSolver
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .unwrap();
    let mass = GpuMass::new(&ctx, RESOLUTION).unwrap();
    for (k, body) in sim.bodies.iter().enumerate() {
        let world = Mesh::new(
            sim.shapes[body.shape]
                .mesh
                .positions
                .iter()
                .map(|p| body.rigid.to_world(p.as_dvec3()).as_vec3())
                .collect(),
            sim.shapes[body.shape].mesh.triangles.clone(),
        );
        let alone = mass.integrate(&world, Some(0.0), None).unwrap().integrals;
        let whole = sim.shapes[body.shape].unit.volume;
        assert!(
            (batched[k].volume - alone.v).abs() < 1e-3 * whole,
            "body {k}: {} vs {}",
            batched[k].volume,
            alone.v
        );
        assert!(
            (batched[k].volume - exact[k].volume).abs() < 0.03 * whole,
            "body {k}: {} vs exact {}",
            batched[k].volume,
            exact[k].volume
        );
        if exact[k].volume > 0.05 * whole {
            assert!(
                (batched[k].center - exact[k].center).length() < 0.03,
                "body {k}"
            );
        }
    }
    assert!(solver.last_peels >= 2);
}

/// Energy with the GPU's discretised buoyancy: the force is a pixel sum, not exactly the
/// gradient of the potential, so energy wanders by the discretisation (~0.1% of V per
/// pixel row): allowed 3% of m g (10 cm) without drag; with drag it must fall clearly.
#[test]
fn energy_on_the_gpu_stays_bounded_without_drag_and_decays_with_it() {
    let ctx = context();
    let box_shape = Shape::new("box", &cuboid(Vec3::new(1.0, 0.6, 0.4), Vec3::ZERO)).unwrap();
    let mut solver = GpuSolver::new(&ctx, std::slice::from_ref(&box_shape), 1, RESOLUTION).unwrap();
    let mut run = |drag: f64| energy_run(&mut solver, drag, 0.004, 300);
    let scale = 240.0 * 9.81 * 0.1;
    let (e0, max_e, _) = run(0.0);
    assert!(
        (max_e - e0) / scale < 0.03,
        "energy grew by {} of {scale}",
        max_e - e0
    );
    let (d0, _, d_end) = run(4.0);
    assert!(d_end < d0 - 0.3 * scale, "drag removed only {}", d0 - d_end);
}

#[test]
fn cube_of_density_05_rolls_off_face_up_on_the_gpu() {
    let ctx = context();
    let shape = Shape::new("cube", &cuboid(Vec3::ONE, Vec3::ZERO)).unwrap();
    let mut solver = GpuSolver::new(&ctx, std::slice::from_ref(&shape), 1, RESOLUTION).unwrap();
    let mut sim = Simulation::new(vec![shape], Water::default(), 0.01);
    sim.add(0, 500.0, DVec3::ZERO, DQuat::from_rotation_x(0.02));
    settle(&mut sim, &mut solver, 400);
    let up = sim.bodies[0].rigid.orientation * DVec3::Z;
    assert!(up.z.clamp(-1.0, 1.0).acos() > 0.3, "still face up: {up}");
}
