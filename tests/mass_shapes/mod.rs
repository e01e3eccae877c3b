//! Small meshes the mass tests build themselves (box, UV sphere, torus), so the tests do
//! not depend on the mesh generators they are checked against.
#![allow(dead_code)]

use classic_gpgpu::mesh::Mesh;
use glam::Vec3;
use std::f64::consts::PI;

/// Axis-aligned box, two triangles a face, outward.
pub fn cuboid(size: Vec3, center: Vec3) -> Mesh {
    let h = size / 2.0;
    let positions = (0..8)
        .map(|i| {
            center
                + Vec3::new(
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
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    Mesh::new(positions, triangles)
}

/// UV sphere (stacks x slices), poles shared, outward; `radius_at` perturbs the radius.
pub fn uv_sphere(stacks: u32, slices: u32, radius_at: impl Fn(Vec3) -> f32) -> Mesh {
    let mut positions = vec![Vec3::Z * radius_at(Vec3::Z)];
    for i in 1..stacks {
        let theta = PI as f32 * i as f32 / stacks as f32;
        for j in 0..slices {
            let phi = 2.0 * PI as f32 * j as f32 / slices as f32;
            let d = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            positions.push(d * radius_at(d));
        }
    }
    positions.push(-Vec3::Z * radius_at(-Vec3::Z));
    let south = positions.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * slices + j % slices;
    let mut triangles = Vec::new();
    for j in 0..slices {
        triangles.push([0, ring(1, j), ring(1, j + 1)]);
        triangles.push([south, ring(stacks - 1, j + 1), ring(stacks - 1, j)]);
        for i in 1..stacks - 1 {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i + 1, j),
                ring(i + 1, j + 1),
                ring(i, j + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles)
}

/// Torus about z, outward.
pub fn torus(big_r: f32, r: f32, n: u32, m: u32) -> Mesh {
    let mut positions = Vec::new();
    for i in 0..n {
        let u = 2.0 * PI as f32 * i as f32 / n as f32;
        for j in 0..m {
            let v = 2.0 * PI as f32 * j as f32 / m as f32;
            let rho = big_r + r * v.cos();
            positions.push(Vec3::new(rho * u.cos(), rho * u.sin(), r * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + j % m;
    let mut triangles = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles)
}

/// The energy test's run: a 1 x 0.6 x 0.4 box of mass 600 dropped tilted into the water with
/// `drag` (quadratic and linear; angular damping with it), `steps` steps of `dt` under
/// `solver`. Returns (initial, largest, final) total energy.
pub fn energy_run(
    solver: &mut dyn classic_gpgpu::mass::buoyancy::simulation::SubmergedSolver,
    drag: f64,
    dt: f64,
    steps: usize,
) -> (f64, f64, f64) {
    use classic_gpgpu::mass::buoyancy::forces::Water;
    use classic_gpgpu::mass::buoyancy::simulation::{Shape, Simulation};
    use glam::{DQuat, DVec3};
    let shape = Shape::new("box", &cuboid(Vec3::new(1.0, 0.6, 0.4), Vec3::ZERO)).unwrap();
    let water = Water {
        drag,
        linear_drag: drag,
        angular_damping: if drag > 0.0 { 1.0 } else { 0.0 },
        ..Water::default()
    };
    let mut sim = Simulation::new(vec![shape], water, dt);
    sim.add(
        0,
        600.0,
        DVec3::new(0.0, 0.0, 0.15),
        DQuat::from_rotation_y(0.3),
    );
    let e0 = sim.energy();
    let mut max_e = e0;
    for _ in 0..steps {
        sim.step(solver).unwrap();
        max_e = max_e.max(sim.energy());
    }
    (e0, max_e, sim.energy())
}

/// `mesh` rotated by `q` then moved by `t`, in f64.
pub fn transformed(mesh: &Mesh, q: glam::DQuat, t: glam::DVec3) -> Mesh {
    Mesh::new(
        mesh.positions
            .iter()
            .map(|p| (q * p.as_dvec3() + t).as_vec3())
            .collect(),
        mesh.triangles.clone(),
    )
}
