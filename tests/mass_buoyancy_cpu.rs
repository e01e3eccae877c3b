//! Section 5 on the CPU reference solver (clip + Mirtich): the physical checks of the
//! buoyancy simulation, independent of the GPU.

use classic_gpgpu::mass::buoyancy::forces::Water;
use classic_gpgpu::mass::buoyancy::simulation::{AnalyticSolver, Shape, Simulation};
use classic_gpgpu::mesh::Mesh;
use glam::{DQuat, DVec3, Vec3};

fn cuboid(size: Vec3) -> Mesh {
    let h = size / 2.0;
    let positions = (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            )
        })
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    Mesh::new(
        positions,
        quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect(),
    )
}

fn sphere(r: f32, stacks: u32, slices: u32) -> Mesh {
    let mut positions = vec![Vec3::Z * r];
    for i in 1..stacks {
        let t = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let f = std::f32::consts::TAU * j as f32 / slices as f32;
            positions.push(r * Vec3::new(t.sin() * f.cos(), t.sin() * f.sin(), t.cos()));
        }
    }
    positions.push(-Vec3::Z * r);
    let s = positions.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * slices + j % slices;
    let mut tris = Vec::new();
    for j in 0..slices {
        tris.push([0, ring(1, j), ring(1, j + 1)]);
        tris.push([s, ring(stacks - 1, j + 1), ring(stacks - 1, j)]);
        for i in 1..stacks - 1 {
            tris.push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
            tris.push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
        }
    }
    Mesh::new(positions, tris)
}

fn run(sim: &mut Simulation, steps: usize) {
    for _ in 0..steps {
        sim.step(&mut AnalyticSolver).unwrap();
    }
}

#[test]
fn flat_box_of_density_03_floats_level_at_draft_03() {
    let (w, h) = (1.0, 0.25);
    let shape = Shape::new("box", &cuboid(Vec3::new(w, w, h))).unwrap();
    let mut sim = Simulation::new(
        vec![shape],
        Water {
            drag: 4.0,
            ..Water::default()
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
    let shape = Shape::new("box", &cuboid(Vec3::new(1.0, 1.0, 0.25))).unwrap();
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
    let shape = Shape::new("sphere", &sphere(0.5, 24, 48)).unwrap();
    let mut sim = Simulation::new(
        vec![shape],
        Water {
            drag: 4.0,
            ..Water::default()
        },
        0.01,
    );
    sim.add(0, 500.0, DVec3::new(0.0, 0.0, 0.2), DQuat::IDENTITY);
    run(&mut sim, 800);
    let z = sim.bodies[0].rigid.position.z;
    assert!(z.abs() < 0.005, "centre at z = {z}");
}

fn energy_run(drag: f64) -> (f64, f64, f64) {
    let shape = Shape::new("box", &cuboid(Vec3::new(1.0, 0.6, 0.4))).unwrap();
    let water = Water {
        drag,
        linear_drag: drag,
        angular_damping: if drag > 0.0 { 1.0 } else { 0.0 },
        ..Water::default()
    };
    let mut sim = Simulation::new(vec![shape], water, 0.002);
    sim.add(
        0,
        600.0,
        DVec3::new(0.0, 0.0, 0.15),
        DQuat::from_rotation_y(0.3),
    );
    let e0 = sim.energy();
    let mut max_e = e0;
    for _ in 0..1000 {
        sim.step(&mut AnalyticSolver).unwrap();
        max_e = max_e.max(sim.energy());
    }
    (e0, max_e, sim.energy())
}

#[test]
fn energy_is_conserved_without_drag_and_decays_with_it() {
    let (e0, max_e, _) = energy_run(0.0);
    // Energy relative to a mass m: m g * 1 cm is the scale of the bobbing motion.
    let scale = 240.0 * 9.81 * 0.1;
    assert!(
        (max_e - e0) / scale < 0.02,
        "energy grew by {} of {scale}",
        max_e - e0
    );
    let (d0, _, d_end) = energy_run(4.0);
    let (_, _, free_end) = energy_run(0.0);
    assert!(d_end < d0 - 0.3 * scale, "drag removed only {}", d0 - d_end);
    assert!(d_end < free_end);
}

#[test]
fn cube_of_density_05_rolls_off_face_up() {
    // Metacentric height of a face-up cube at half draft: -s/12 < 0, so face-up is unstable.
    let shape = Shape::new("cube", &cuboid(Vec3::ONE)).unwrap();
    let mut sim = Simulation::new(vec![shape], Water::default(), 0.01);
    sim.add(0, 500.0, DVec3::ZERO, DQuat::from_rotation_x(0.02));
    run(&mut sim, 400);
    let up = sim.bodies[0].rigid.orientation * DVec3::Z;
    let tilt = up.z.clamp(-1.0, 1.0).acos();
    assert!(tilt > 0.3, "tilt stayed at {tilt} rad");
}
