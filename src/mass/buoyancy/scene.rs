//! The scene of section 5.3 and Fig. 9: ten spheres, ten rectangular boxes, ten tori, ten
//! teapots and ten Stanford bunnies of various densities on still water, some boxes denser
//! than water (they sink, as the paper observed).

use super::forces::Water;
use super::simulation::{Shape, Simulation};
use crate::mesh::{self, Mesh};
use glam::{DQuat, DVec3, Vec3};

/// Densities (kg/m³, water 1000) of the ten bodies of each kind, in placement order.
const DENSITIES: [[f64; 10]; 5] = [
    // spheres
    [
        200.0, 300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 900.0, 350.0, 650.0,
    ],
    // boxes: the last three sink
    [
        250.0, 350.0, 450.0, 550.0, 650.0, 750.0, 850.0, 1300.0, 1600.0, 2000.0,
    ],
    // tori
    [
        300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 450.0, 550.0, 650.0, 750.0,
    ],
    // teapots
    [
        300.0, 400.0, 500.0, 600.0, 700.0, 350.0, 450.0, 550.0, 650.0, 750.0,
    ],
    // bunnies
    [
        300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 350.0, 450.0, 550.0, 650.0,
    ],
];

/// The five shapes, each about a metre across.
pub fn paper_shapes() -> Result<Vec<Shape>, String> {
    let fit = |m: Mesh, size: f32| -> Mesh {
        let (lo, hi) =
            crate::mass::framing::bounds(m.positions.iter().copied()).expect("non-empty");
        let scale = size / (hi - lo).max_element();
        let c = (lo + hi) / 2.0;
        Mesh::new(
            m.positions.iter().map(|p| (*p - c) * scale).collect(),
            m.triangles,
        )
    };
    Ok(vec![
        Shape::new("sphere", &mesh::uv_sphere(0.5, 30, 15))?,
        Shape::new("box", &mesh::cuboid(Vec3::new(0.6, 0.4, 0.25)))?,
        Shape::new("torus", &mesh::torus(0.4, 0.15, 31, 31))?,
        Shape::new("teapot", &fit(mesh::teapot(5), 1.0))?,
        Shape::new("bunny", &fit(mesh::load_bunny(), 1.0))?,
    ])
}

/// `bodies` bodies (kinds in turn, ten rows of five per fifty) on a grid 3 m apart, dropped
/// from just above the water in assorted orientations. Deterministic.
pub fn paper_scene(bodies: usize, dt: f64) -> Result<Simulation, String> {
    let mut sim = Simulation::new(paper_shapes()?, Water::default(), dt);
    let columns = (bodies as f64).sqrt().ceil() as usize;
    for k in 0..bodies {
        let kind = k % 5;
        let nth = (k / 5) % 10;
        let (col, row) = (k % columns, k / columns);
        let position = DVec3::new(
            3.0 * (col as f64 - (columns as f64 - 1.0) / 2.0),
            3.0 * (row as f64 - (bodies.div_ceil(columns) as f64 - 1.0) / 2.0),
            0.3 + 0.1 * (nth % 3) as f64,
        );
        // Orientations from a fixed low-discrepancy sequence, so runs are reproducible.
        let a = k as f64 * 2.399_963;
        let orientation =
            DQuat::from_euler(glam::EulerRot::ZXY, a, 0.4 * a.sin(), 0.3 * (1.7 * a).cos());
        sim.add(kind, DENSITIES[kind][nth], position, orientation);
    }
    Ok(sim)
}
