//! A small fixed workload of every paper, each against the paper module's CPU reference.

use super::Check;
use crate::collide::brute_force::all_pairs;
use crate::collide::pipeline::{Options, StreamingCollider};
use crate::collide::reduction_gpu::ReadbackMode;
use crate::collide::Predicate;
use crate::crowd::character::Instances;
use crate::crowd::cpu_skinning;
use crate::crowd::{CharacterModel, CrowdRenderer, ModelKind};
use crate::gl::Context;
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, PyramidBuilder};
use crate::mass::buoyancy::batch::GpuSolver;
use crate::mass::buoyancy::forces::Water;
use crate::mass::buoyancy::simulation::{Shape, Simulation, SubmergedSolver};
use crate::mass::framing::Framing;
use crate::mass::gpu::GpuMass;
use crate::mass::{cpu_reference, VolumeIntegrals};
use crate::mesh::{self, Mesh};
use crate::mlp::cpu::{error_bound, forward, CpuProduct};
use crate::mlp::{Activation, Formulation, GpuMlp, Layer, Network};
use anyhow::{anyhow, ensure};
use glam::{DAffine3, DQuat, DVec3, Vec3};
use ndarray::{Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn checks() -> Vec<Check> {
    vec![
        Check {
            name: "collide-pairs",
            group: "paper1",
            run: collide_pairs,
        },
        Check {
            name: "crowd-skinning",
            group: "paper2",
            run: crowd_skinning,
        },
        Check {
            name: "mlp-forward",
            group: "paper3",
            run: mlp_forward,
        },
        Check {
            name: "mass-integrals",
            group: "paper4",
            run: mass_integrals,
        },
        Check {
            name: "buoyancy-submerged",
            group: "paper4",
            run: buoyancy_submerged,
        },
        Check {
            name: "pyramid",
            group: "lecture3",
            run: pyramid,
        },
    ]
}

/// `n` random triangles of size about `size` in the unit cube, no shared vertices.
fn soup(n: usize, size: f32, seed: u64) -> Mesh {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut positions = Vec::new();
    for _ in 0..n {
        let c = Vec3::new(rng.gen(), rng.gen(), rng.gen());
        for _ in 0..3 {
            positions.push(c + (Vec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5) * size);
        }
    }
    let triangles = (0..n as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Mesh::new(positions, triangles)
}

/// Paper 1: the streaming-AABB pipeline's pairs equal the brute-force pairs exactly (same
/// exact predicate), with every readback scheme.
fn collide_pairs(ctx: &Context) -> anyhow::Result<String> {
    let (x, y) = (soup(300, 0.2, 1), soup(200, 0.2, 51));
    let expected = all_pairs(&x, &x.positions, &y, &y.positions, Predicate::Exact);
    ensure!(
        !expected.is_empty(),
        "the soups do not touch: the check would prove nothing"
    );
    for readback in [
        ReadbackMode::Hierarchical,
        ReadbackMode::Reduced,
        ReadbackMode::Full,
    ] {
        let options = Options {
            leaf_size: 4,
            readback,
            predicate: Predicate::Exact,
            max_tile: None,
        };
        let mut collider = StreamingCollider::new(ctx, &x, &y, options)?;
        let got = collider.frame(&x.positions, &y.positions)?.pairs;
        if got != expected {
            let missed = expected.iter().filter(|p| !got.contains(p)).count();
            let extra = got.iter().filter(|p| !expected.contains(p)).count();
            return Err(anyhow!(
                "{readback:?} readback: {missed} pairs missed, {extra} false of {}",
                expected.len()
            ));
        }
    }
    Ok(format!(
        "300 x 200 triangles: {} pairs, equal to brute force with all three readbacks",
        expected.len()
    ))
}

/// Paper 2: pass 1 + render-to-VBO skins characters as f64 CPU linear blend skinning does,
/// within 16 ulp of the coordinate's magnitude.
fn crowd_skinning(ctx: &Context) -> anyhow::Result<String> {
    let model = CharacterModel::build(ModelKind::Soldier)?;
    let mut renderer = CrowdRenderer::new(ctx, model.clone())?;
    let (models, phases): (Vec<DAffine3>, Vec<f64>) = (0..6)
        .map(|i| {
            let t = i as f64;
            let place = DAffine3::from_rotation_translation(
                DQuat::from_rotation_y(0.9 * t - 1.0),
                DVec3::new(13.0 * (t * 1.7).sin(), 0.0, -11.0 * (t * 0.6).cos()),
            );
            (place, 0.137 * t + 0.05 * t * t)
        })
        .unzip();
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    let ids = [5, 0, 3, 1];
    let mut worst: f64 = 0.0;
    let mut vertices = 0;
    for lod in [0, model.lods.len() - 1] {
        let gpu = renderer.skin_to_vbo(lod, &instances, &ids)?;
        let mesh = &model.lods[lod];
        for (slot, &id) in ids.iter().enumerate() {
            let pose = model.clip.sample(&model.skeleton, phases[id]);
            let bones = model.skeleton.skinning_matrices(&pose, models[id]);
            let cpu = cpu_skinning::skin(mesh, &bones);
            let positions = &gpu[slot].0;
            ensure!(
                positions.len() == mesh.vertex_count(),
                "LOD {lod}: vertex count"
            );
            for (v, (p, q)) in positions.iter().zip(&cpu.positions).enumerate() {
                let err = (DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - *q)
                    .abs()
                    .max_element();
                let tolerance = 16.0 * f32::EPSILON as f64 * (1.0 + q.abs().max_element());
                ensure!(
                    err <= tolerance,
                    "LOD {lod} character {id} vertex {v}: GPU {p:?} vs CPU {q} (error {err:e} > {tolerance:e})"
                );
                worst = worst.max(err / tolerance);
            }
            vertices += positions.len();
        }
    }
    Ok(format!(
        "{vertices} skinned vertices at two LODs within {worst:.2} of the 16-ulp tolerance"
    ))
}

/// Paper 3: a three-layer network as render passes, both formulations, against the CPU
/// forward pass within twice the fp32 error bound of each output.
fn mlp_forward(ctx: &Context) -> anyhow::Result<String> {
    let mut rng = ChaCha8Rng::seed_from_u64(2004);
    let sizes = [121, 30, 7, 1];
    let layers = sizes
        .windows(2)
        .enumerate()
        .map(|(i, s)| {
            let r = 2.0 / (s[0] as f32).sqrt();
            Layer {
                weights: Array2::from_shape_simple_fn((s[1], s[0]), || rng.gen_range(-r..r)),
                bias: Array1::from_shape_simple_fn(s[1], || rng.gen_range(-1.0..1.0)),
                activation: if i == 1 {
                    Activation::Identity
                } else {
                    Activation::Sigmoid
                },
            }
        })
        .collect();
    let net = Network::new(layers)?;
    let x = Array2::from_shape_simple_fn((77, sizes[0]), || rng.gen_range(-1.0f32..1.0));
    let cpu = forward(CpuProduct::Plain, &net, x.view()).outputs;
    let bound = error_bound(&net, x.view());
    let gpu = GpuMlp::new(ctx)?;
    let mut worst = 0.0f32;
    for formulation in [Formulation::Faithful, Formulation::Packed] {
        let out = gpu
            .load(&net, formulation)?
            .forward(x.view(), None)?
            .outputs;
        ensure!(
            out.dim() == cpu.dim(),
            "{formulation:?}: output shape {:?}",
            out.dim()
        );
        for ((j, g), (c, e)) in out.iter().enumerate().zip(cpu.iter().zip(bound.iter())) {
            ensure!(
                (g - c).abs() <= 2.0 * e,
                "{formulation:?} output {j}: GPU {g} vs CPU {c} (allowed {})",
                2.0 * e
            );
            if *e > 0.0 {
                worst = worst.max((g - c).abs() / (2.0 * e));
            }
        }
    }
    Ok(format!(
        "121-30-7-1 network on 77 vectors, faithful and packed passes within {worst:.1e} of the fp32 bound"
    ))
}

/// Every integral within `rel` of the largest (they differ in scale by orders).
fn integrals_close(got: &VolumeIntegrals, want: &VolumeIntegrals, rel: f64) -> anyhow::Result<f64> {
    let scale = want.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst: f64 = 0.0;
    for (k, (g, w)) in got.to_array().iter().zip(want.to_array()).enumerate() {
        ensure!(g.is_finite(), "integral {k}: the GPU gave {g}");
        ensure!(
            (g - w).abs() <= rel * scale,
            "integral {k}: GPU {g} vs CPU {w} (allowed {:e})",
            rel * scale
        );
        worst = worst.max((g - w).abs() / (rel * scale));
    }
    Ok(worst)
}

/// Paper 4: depth peeling + integrands + reduction against the CPU's sums over the same
/// pixel centres, whole and below a plane. fp32 per fragment and fp32 tree sums: 1e-3 of the
/// largest integral.
fn mass_integrals(ctx: &Context) -> anyhow::Result<String> {
    let tilt = glam::Affine3A::from_rotation_translation(
        glam::Quat::from_euler(glam::EulerRot::XYZ, 0.5, 0.2, 0.1),
        Vec3::new(2.0, -1.0, 0.5),
    );
    let torus = mesh::torus_closed(1.0, 0.35, 40, 20).transformed(&tilt);
    let gpu = GpuMass::new(ctx, 32)?;
    let mut worst: f64 = 0.0;
    for below in [None, Some(0.4)] {
        let got = gpu.integrate(&torus, below, None)?;
        let framing = Framing::fit(&torus, 32).map_err(anyhow::Error::msg)?;
        let cpu = cpu_reference::integrate(&torus, &framing, below);
        worst = worst.max(
            integrals_close(&got.integrals, &cpu, 1e-3)
                .map_err(|e| e.context(format!("below {below:?}")))?,
        );
        let layers = cpu_reference::layers(&torus, &framing, below);
        ensure!(
            got.peels == layers,
            "below {below:?}: {} peels, CPU counts {layers} layers",
            got.peels
        );
    }
    Ok(format!(
        "tilted torus at 32x32, whole and below z = 0.4: ten integrals within {worst:.1e} of the 1e-3 tolerance"
    ))
}

/// Paper 4, section 5: the batched GPU solver's submerged volumes of several bodies against
/// the CPU's clip + Mirtich, within 3% of each body's volume (32x32 per body).
fn buoyancy_submerged(ctx: &Context) -> anyhow::Result<String> {
    let torus = mesh::torus_closed(1.0, 0.35, 40, 20);
    let cube = mesh::cube(1.0);
    let shapes = vec![
        Shape::new("torus", &torus).map_err(anyhow::Error::msg)?,
        Shape::new("cube", &cube).map_err(anyhow::Error::msg)?,
    ];
    let mut sim = Simulation::new(shapes.clone(), Water::default(), 0.01);
    for k in 0..6 {
        let q = DQuat::from_scaled_axis(DVec3::new(0.3 * k as f64, -0.7, 0.2 * k as f64));
        sim.add(
            k % 2,
            500.0,
            DVec3::new(k as f64 * 3.0, 0.0, 0.1 * k as f64 - 0.25),
            q,
        );
    }
    let mut solver = GpuSolver::new(ctx, &shapes, sim.bodies.len(), 32)?;
    let gpu = solver
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .map_err(anyhow::Error::msg)?;
    let cpu = crate::mass::buoyancy::simulation::AnalyticSolver
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .map_err(anyhow::Error::msg)?;
    let mut worst: f64 = 0.0;
    for (k, body) in sim.bodies.iter().enumerate() {
        let whole = sim.shapes[body.shape].unit.volume;
        let err = (gpu[k].volume - cpu[k].volume).abs();
        ensure!(
            gpu[k].volume.is_finite() && err <= 0.03 * whole,
            "body {k}: GPU submerged volume {} vs CPU {} (allowed {:e})",
            gpu[k].volume,
            cpu[k].volume,
            0.03 * whole
        );
        worst = worst.max(err / (0.03 * whole));
    }
    ensure!(
        cpu.iter().any(|s| s.volume > 0.0),
        "no body is in the water: the check would prove nothing"
    );
    Ok(format!(
        "{} bodies: submerged volumes within {worst:.2} of the 3% tolerance",
        sim.bodies.len()
    ))
}

/// Lecture 3: the max and min image pyramids drawn by render passes equal the CPU's bit for
/// bit (max and min are exact in fp32).
fn pyramid(ctx: &Context) -> anyhow::Result<String> {
    let mut rng = ChaCha8Rng::seed_from_u64(2006);
    let builder = PyramidBuilder::new(ctx)?;
    let mut levels = 0;
    for (w, h) in [(37, 64), (100, 7)] {
        let image: Vec<f32> = (0..w * h).map(|_| rng.gen_range(-100.0..100.0)).collect();
        for extreme in [Extreme::Max, Extreme::Min] {
            let cpu = cpu_pyramid(w, h, &image, extreme);
            let gpu = builder.from_image(w, h, &image, extreme)?.read_levels()?;
            ensure!(
                gpu.len() == cpu.len(),
                "{w}x{h} {extreme:?}: {} levels, CPU {}",
                gpu.len(),
                cpu.len()
            );
            for (level, (g, c)) in gpu.iter().zip(&cpu).enumerate() {
                let same = g.values.len() == c.values.len()
                    && g.values
                        .iter()
                        .zip(&c.values)
                        .all(|(a, b)| a.to_bits() == b.to_bits());
                ensure!(
                    same,
                    "{w}x{h} {extreme:?} level {level} differs from the CPU's"
                );
            }
            levels += cpu.len();
        }
    }
    Ok(format!(
        "{levels} max/min pyramid levels equal the CPU's bit for bit"
    ))
}
