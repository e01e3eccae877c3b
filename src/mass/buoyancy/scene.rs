//! The scene of section 5.3 and Fig. 9: ten spheres, ten rectangular boxes, ten tori, ten
//! teapots and ten Stanford bunnies of various densities on still water, some boxes denser
//! than water (they sink, as the paper observed).
//!
//! Newell's teapot is not a closed surface (the lid floats above the rim, the spout and
//! handle pierce the body), so neither its analytic mass properties nor its peels can be
//! trusted (its GPU volume is 6.4% off the analytic one). The scene's teapot is therefore
//! closed: Newell's lid, rim, body and Crow's bottom as one surface of revolution, the
//! lid's edge joined to the rim, without the handle and spout. The shapes are fixed and
//! closed (a test checks it), so a run has no open shape to warn about.

use super::forces::Water;
use super::simulation::{Shape, Simulation};
use crate::mesh::{self, Mesh};
use glam::{DQuat, DVec2, DVec3, Vec3};

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
        Shape::new("teapot", &fit(closed_teapot(32, 4), 1.0))?,
        Shape::new("bunny", &fit(crate::mass::models::table1_bunny(), 1.0))?,
    ])
}

/// The profile of Newell's teapot as (radius, height) cubic Bezier segments, top to
/// bottom: lid (two), the joint from the lid's edge to the rim (a straight segment),
/// rim, body (two) and Crow's bottom, from the control points of the standard data set.
const TEAPOT_PROFILE: [[[f64; 2]; 4]; 7] = [
    [[0.0, 3.15], [0.8, 3.15], [0.0, 2.85], [0.2, 2.7]],
    [[0.2, 2.7], [0.4, 2.55], [1.3, 2.55], [1.3, 2.4]],
    [[1.3, 2.4], [1.3333, 2.4], [1.3667, 2.4], [1.4, 2.4]],
    [[1.4, 2.4], [1.3375, 2.53125], [1.4375, 2.53125], [1.5, 2.4]],
    [[1.5, 2.4], [1.75, 1.875], [2.0, 1.35], [2.0, 0.9]],
    [[2.0, 0.9], [2.0, 0.45], [1.5, 0.225], [1.5, 0.15]],
    [[1.5, 0.15], [1.5, 0.075], [1.425, 0.0], [0.0, 0.0]],
];

/// A closed teapot: `TEAPOT_PROFILE` sampled `per_segment` times per segment and turned
/// about z in `around` steps; the poles at the knob and the bottom centre are single
/// vertices, so the surface has no hole. Triangles face outward.
pub fn closed_teapot(around: usize, per_segment: usize) -> Mesh {
    let bezier = |c: &[[f64; 2]; 4], t: f64| -> DVec2 {
        let u = 1.0 - t;
        let w = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
        (0..4).map(|k| DVec2::from(c[k]) * w[k]).sum()
    };
    // The profile from the knob (radius 0) down to the bottom centre (radius 0).
    let mut profile = vec![DVec2::from(TEAPOT_PROFILE[0][0])];
    for segment in &TEAPOT_PROFILE {
        for k in 1..=per_segment {
            profile.push(bezier(segment, k as f64 / per_segment as f64));
        }
    }
    let rings = &profile[1..profile.len() - 1];
    let mut positions = vec![Vec3::new(0.0, 0.0, profile[0].y as f32)];
    for p in rings {
        for j in 0..around {
            let a = std::f64::consts::TAU * j as f64 / around as f64;
            positions.push(Vec3::new(
                (p.x * a.cos()) as f32,
                (p.x * a.sin()) as f32,
                p.y as f32,
            ));
        }
    }
    let bottom = positions.len() as u32;
    positions.push(Vec3::new(0.0, 0.0, profile[profile.len() - 1].y as f32));
    let ring = |r: usize, j: usize| (1 + r * around + j % around) as u32;
    let mut triangles = Vec::new();
    for j in 0..around {
        triangles.push([0, ring(0, j), ring(0, j + 1)]);
        for r in 0..rings.len() - 1 {
            let (a, b, c, d) = (
                ring(r, j),
                ring(r + 1, j),
                ring(r + 1, j + 1),
                ring(r, j + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
        let last = rings.len() - 1;
        triangles.push([ring(last, j), bottom, ring(last, j + 1)]);
    }
    Mesh::new(positions, triangles)
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
