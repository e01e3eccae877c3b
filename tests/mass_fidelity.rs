//! Paper 4 as the paper words it: the stencil bit of section 5.2, the paper's
//! order of peels and sums, the peel limit, principal moments, the scene's closed shapes
//! and the 50-body scene against the CPU reference solver. Each on a real headless GL
//! context (llvmpipe and softpipe), against the CPU.

use classic_gpgpu::mass::buoyancy::batch::GpuSolver;
use classic_gpgpu::mass::buoyancy::scene;
use classic_gpgpu::mass::buoyancy::simulation::{AnalyticSolver, Shape, SubmergedSolver};
use classic_gpgpu::mass::framing::Framing;
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mass::peel::{PeelOrder, PeelSettings};
use classic_gpgpu::mass::{analytic, cpu_reference, MassProperties};
use classic_gpgpu::mesh::{self, Mesh};
use common::context;
use glam::{DMat3, DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed};

mod common;

mod mass_shapes;

mod mass_check;
use mass_check::{assert_integrals_close, largest};

/// A tilted torus: four crossings per pixel in places, so deep peels and a water line
/// through holes.
fn tilted_torus() -> Mesh {
    transformed(
        &torus(1.0, 0.35, 40, 20),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.9, 0.3, 0.1),
        DVec3::new(0.3, -0.2, 0.1),
    )
}

/// Pass 1's stencil bit (two-sided stencil: back faces write 1) is, pixel for pixel, the
/// CPU's "first crossing below the water faces down", and the water patch drawn through it
/// gives the CPU's integrals. Pixels whose line grazes an edge may be decided differently
/// by fp32 rasterization: at most 1% of the covered pixels.
#[test]
fn the_stencil_bit_marks_where_the_first_peel_faces_down() {
    let ctx = context();
    let mesh = tilted_torus();
    let n = 64;
    let gpu = GpuMass::new(&ctx, n).unwrap();
    for level in [-0.2, 0.1, 0.35] {
        let result = gpu.integrate(&mesh, Some(level), None).unwrap();
        let framing = Framing::fit(&mesh, n).unwrap();
        let bits = gpu.first_peel_faces_down().unwrap();
        let want = cpu_reference::first_below_faces_down(&mesh, &framing, level);
        assert_eq!(bits.len(), want.len());
        let marked = want.iter().filter(|&&w| w).count();
        let differ = bits
            .iter()
            .zip(&want)
            .filter(|(&b, &w)| (b == 1) != w)
            .count();
        assert!(marked > 20, "level {level}: only {marked} pixels face down");
        assert!(
            differ * 100 <= marked,
            "level {level}: {differ} of {marked} stencil bits differ from the CPU"
        );
        let cpu = cpu_reference::integrate(&mesh, &framing, Some(level));
        assert_integrals_close(&format!("below {level}"), &result.integrals, &cpu, 1e-3);
    }
}

/// The paper's order (keep the n layers, reduce each) gives each layer's integrals as the
/// CPU sums that layer's crossings, and the same total as the running sums (fp32 sums in
/// another order: 1e-5 of the largest integral).
#[test]
fn keeping_the_layers_gives_each_layer_and_the_same_total() {
    let ctx = context();
    let mesh = tilted_torus();
    let n = 64;
    let keep = PeelSettings {
        order: PeelOrder::KeepLayers,
        ..PeelSettings::default()
    };
    let kept = GpuMass::with_settings(&ctx, n, keep).unwrap();
    let running = GpuMass::new(&ctx, n).unwrap();
    let framing = Framing::fit(&mesh, n).unwrap();
    for water in [None, Some(0.1)] {
        let a = kept.integrate(&mesh, water, None).unwrap();
        let b = running.integrate(&mesh, water, None).unwrap();
        assert!(b.layers.is_empty(), "running sums keep no layers");
        let want = cpu_reference::integrate_layers(&mesh, &framing, water);
        assert_eq!(a.layers.len(), want.len(), "layers (water {water:?})");
        assert_eq!(a.peels, cpu_reference::layers(&mesh, &framing, water));
        let scale = largest(&cpu_reference::integrate(&mesh, &framing, water));
        for (k, (g, w)) in a.layers.iter().zip(&want).enumerate() {
            let g = g.about(w.origin);
            for (x, y) in g.to_array().iter().zip(w.to_array()) {
                assert!(
                    (x - y).abs() <= 1e-3 * scale,
                    "layer {k} (water {water:?}): {x} vs {y}"
                );
            }
        }
        assert_integrals_close("keep vs running", &a.integrals, &b.integrals, 1e-5);
    }
}

/// A stack of flat boxes has two crossings per box: a limit below that stops early, says
/// so, and loses volume; the default limit peels them all and says nothing.
#[test]
fn the_peel_limit_is_settable_and_reported() {
    let ctx = context();
    let boxes: Vec<Mesh> = (0..5)
        .map(|k| {
            cuboid(
                Vec3::new(1.0, 1.0, 0.1),
                Vec3::new(0.0, 0.0, 0.3 * k as f32),
            )
        })
        .collect();
    let stack = Mesh::merged(&boxes);
    let all = GpuMass::new(&ctx, 16)
        .unwrap()
        .integrate(&stack, None, None)
        .unwrap();
    assert_eq!((all.peels, all.truncated), (10, false));
    assert!((all.integrals.v - 0.5).abs() < 0.01, "{}", all.integrals.v);
    for order in [PeelOrder::RunningSums, PeelOrder::KeepLayers] {
        let limited = GpuMass::with_settings(
            &ctx,
            16,
            PeelSettings {
                max_peels: 4,
                order,
            },
        )
        .unwrap()
        .integrate(&stack, None, None)
        .unwrap();
        assert_eq!((limited.peels, limited.truncated), (4, true), "{order:?}");
        // The top two boxes (four crossings) of five: the same pixels, two fifths.
        let share = limited.integrals.v / all.integrals.v;
        assert!((share - 0.4).abs() < 1e-5, "{order:?}: {share}");
    }
    let exact = GpuMass::with_settings(
        &ctx,
        16,
        PeelSettings {
            max_peels: 10,
            order: PeelOrder::RunningSums,
        },
    )
    .unwrap()
    .integrate(&stack, None, None)
    .unwrap();
    assert_eq!((exact.peels, exact.truncated), (10, false));
    assert!(GpuMass::with_settings(
        &ctx,
        16,
        PeelSettings {
            max_peels: 0,
            order: PeelOrder::RunningSums
        }
    )
    .is_err());
}

/// The principal moments of a box turned off the axes are its axis-aligned moments
/// m (b² + c²) / 12 ..., though the tensor's diagonal is not: analytic exactly, the GPU
/// within the paper's 5% at 32x32 (measured: under 1%).
#[test]
fn principal_moments_of_a_rotated_box_are_the_closed_form() {
    let ctx = context();
    let (a, b, c) = (2.0, 1.0, 0.5);
    let q = DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.1);
    let mesh = transformed(
        &cuboid(Vec3::new(a as f32, b as f32, c as f32), Vec3::ZERO),
        q,
        DVec3::new(0.5, 0.2, -0.3),
    );
    let density = 3.0;
    let m = density * a * b * c;
    let mut want = [
        m * (b * b + c * c) / 12.0,
        m * (a * a + c * c) / 12.0,
        m * (a * a + b * b) / 12.0,
    ];
    want.sort_by(f64::total_cmp);
    let exact = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), density);
    let diagonal = [
        exact.inertia.x_axis.x,
        exact.inertia.y_axis.y,
        exact.inertia.z_axis.z,
    ];
    assert!(
        (diagonal[0] - want[0]).abs() > 0.05 * want[0],
        "the diagonal must differ from the principal moments for this test to mean anything"
    );
    let p = exact.principal_moments().to_array();
    for k in 0..3 {
        assert!((p[k] - want[k]).abs() < 1e-4 * want[2], "{p:?} vs {want:?}");
    }
    // The tensor is R diag(want) R^T (the box's axes turned by q).
    let r = DMat3::from_quat(q);
    let local = [
        m * (b * b + c * c) / 12.0,
        m * (a * a + c * c) / 12.0,
        m * (a * a + b * b) / 12.0,
    ];
    let tensor = r * DMat3::from_diagonal(DVec3::from_array(local)) * r.transpose();
    assert!((tensor - exact.inertia)
        .abs()
        .to_cols_array()
        .iter()
        .all(|d| *d < 1e-6 * want[2]));
    let gpu = GpuMass::new(&ctx, 32)
        .unwrap()
        .integrate(&mesh, None, None)
        .unwrap();
    let g = MassProperties::from_integrals(&gpu.integrals, density)
        .principal_moments()
        .to_array();
    for k in 0..3 {
        assert!(
            ((g[k] - want[k]) / want[k]).abs() < 0.05,
            "GPU principal moments {g:?} vs {want:?}"
        );
    }
}

/// The buoyancy scene's shapes are closed, its teapot included (the scene is fixed, so
/// this test, not a run-time warning, is where that is checked), and the GPU's volume of
/// each is the analytic one within 2% at 32x32; the Newell teapot, which the scene no
/// longer uses, is open.
#[test]
fn the_scene_shapes_are_closed_and_newells_teapot_is_not() {
    let ctx = context();
    let shapes = scene::paper_shapes().unwrap();
    for s in &shapes {
        let r = classic_gpgpu::mass::surface::check(&s.mesh);
        assert!(r.is_closed(), "{}: {}", s.name, r.problems());
    }
    let gpu = GpuMass::new(&ctx, 32).unwrap();
    for s in &shapes {
        let v = gpu.integrate(&s.mesh, None, None).unwrap().integrals.v;
        assert!(
            ((v - s.unit.volume) / s.unit.volume).abs() < 0.02,
            "{}: GPU {v} vs analytic {}",
            s.name,
            s.unit.volume
        );
    }
    let newell = Shape::new("newell", &mesh::teapot(5)).unwrap();
    let r = classic_gpgpu::mass::surface::check(&newell.mesh);
    assert!(!r.is_closed() && r.open_edges > 0);
}

/// The 50 bodies of section 5.3 for a few steps, drop and plunge included: at every step
/// the GPU solver's submerged volumes and centres of buoyancy are the CPU reference
/// solver's (clip + Mirtich) on the same poses, within the 32x32 discretisation (3% of a
/// body's volume, 3 cm); and the whole run stays within 3 cm of the same scene driven
/// by the CPU solver.
#[test]
fn the_fifty_body_scene_follows_the_cpu_reference_solver() {
    let ctx = context();
    let dt = 1.0 / 30.0;
    let steps = 16;
    let mut gpu_sim = scene::paper_scene(50, dt).unwrap();
    let mut cpu_sim = scene::paper_scene(50, dt).unwrap();
    let mut solver = GpuSolver::new(&ctx, &gpu_sim.shapes, 50, 32).unwrap();
    let mut wet = 0;
    for step in 0..steps {
        let got = solver
            .submerged(&gpu_sim.shapes, &gpu_sim.bodies, &gpu_sim.water)
            .unwrap();
        let want = AnalyticSolver
            .submerged(&gpu_sim.shapes, &gpu_sim.bodies, &gpu_sim.water)
            .unwrap();
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            let whole = gpu_sim.shapes[gpu_sim.bodies[k].shape].unit.volume;
            assert!(
                (g.volume - w.volume).abs() < 0.03 * whole,
                "step {step}, body {k}: {} vs {}",
                g.volume,
                w.volume
            );
            if w.volume > 0.05 * whole {
                wet += 1;
                assert!(
                    (g.center - w.center).length() < 0.03,
                    "step {step}, body {k}: centre {} vs {}",
                    g.center,
                    w.center
                );
            }
        }
        assert_eq!(solver.truncated_steps, 0);
        gpu_sim.apply(&got);
        cpu_sim.step(&mut AnalyticSolver).unwrap();
    }
    assert!(
        wet > 200,
        "only {wet} wet body-steps: the scene never reached the water"
    );
    for (k, (g, c)) in gpu_sim.bodies.iter().zip(&cpu_sim.bodies).enumerate() {
        let d = (g.rigid.position - c.rigid.position).length();
        assert!(d < 0.03, "body {k}: {d} m from the CPU-driven run");
    }
}
