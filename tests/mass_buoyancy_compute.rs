//! Section 5's buoyancy with the submerged integrals from the compute formulation (one pass
//! that clips every body against the water plane) beside the classic n + 2 passes and the CPU
//! solver (clip + Mirtich): the same submerged volumes, centres of buoyancy, forces and
//! trajectories. On a context below 4.3 (softpipe) the compute solver is a clear error and
//! the classic solver runs.
//!
//! Tolerances: the compute solver's integrals are exact per triangle, summed in fp32 in each
//! body's unit frame (about 1 m across here): 1e-5 of the body's volume for the submerged
//! volume, 1e-5 m for the centre of buoyancy, against the CPU solver, which itself rounds the
//! posed vertices to f32 (1e-7 m at these 10 m). The classic solver views each body at
//! 32x32: its water-line section is a few percent off (3% of the body's volume, 3 cm).
//! Trajectories: the solvers' per-step differences grow through the dynamics; after 30 steps
//! (half a second, the bodies plunging and rising) the compute run stays within 1e-4 m of
//! the CPU run and the classic run within 5 cm.

use classic_gpgpu::mass::buoyancy::batch::GpuSolver;
use classic_gpgpu::mass::buoyancy::compute::ComputeSolver;
use classic_gpgpu::mass::buoyancy::forces;
use classic_gpgpu::mass::buoyancy::scene;
use classic_gpgpu::mass::buoyancy::simulation::{AnalyticSolver, Simulation, SubmergedSolver};
use common::compute_context;

mod common;

const STEPS: usize = 30;
const BODIES: usize = 5;

/// The paper's scene, one body of each kind, after `settle` steps of the CPU solver.
fn scene_after(settle: usize) -> Simulation {
    let mut sim = scene::paper_scene(BODIES, 1.0 / 60.0).unwrap();
    for _ in 0..settle {
        sim.step(&mut AnalyticSolver).unwrap();
    }
    sim
}

#[test]
fn same_submerged_parts_and_forces_as_the_cpu_and_classic_solvers() {
    let (ctx, compute) = compute_context();
    if !compute {
        eprintln!(
            "skipped: the compute formulation needs OpenGL 4.3 (softpipe: see below_4_3_...)"
        );
        return;
    }
    ctx.set_checks(true);
    let mut now = ComputeSolver::new(&ctx).unwrap();
    // Poses from the drop (some bodies above the water, wholly or partly) to deep in it.
    for settle in [0, 10, 25] {
        let sim = scene_after(settle);
        let mut then = GpuSolver::new(&ctx, &sim.shapes, sim.bodies.len(), 32).unwrap();
        let c = now.submerged(&sim.shapes, &sim.bodies, &sim.water).unwrap();
        let g = then
            .submerged(&sim.shapes, &sim.bodies, &sim.water)
            .unwrap();
        let e = AnalyticSolver
            .submerged(&sim.shapes, &sim.bodies, &sim.water)
            .unwrap();
        let mut cut = 0;
        for (k, body) in sim.bodies.iter().enumerate() {
            let shape = &sim.shapes[body.shape];
            let whole = shape.unit.volume;
            let what = format!("after {settle} steps, body {k} ({})", shape.name);
            assert!(
                (c[k].volume - e[k].volume).abs() <= 1e-5 * whole,
                "{what}: compute {} vs CPU {}",
                c[k].volume,
                e[k].volume
            );
            assert!(
                (g[k].volume - c[k].volume).abs() <= 0.03 * whole,
                "{what}: classic {} vs compute {}",
                g[k].volume,
                c[k].volume
            );
            if e[k].volume > 1e-3 * whole {
                assert!(
                    (c[k].center - e[k].center).length() <= 1e-5,
                    "{what}: centre {} vs {}",
                    c[k].center,
                    e[k].center
                );
            }
            if e[k].volume > 0.05 * whole {
                assert!((g[k].center - c[k].center).length() <= 0.03, "{what}");
            }
            if e[k].volume > 0.0 && e[k].volume < 0.999 * whole {
                cut += 1;
            }
            // The forces the step applies from them.
            let (fc, fe) = (
                forces::wrench(&body.rigid, whole, c[k], &sim.water),
                forces::wrench(&body.rigid, whole, e[k], &sim.water),
            );
            // Against the buoyant force of the whole body (and its torque at 1 m): the
            // volume's 1e-5 and the centre's 1e-5 m, with room.
            let full = sim.water.density * sim.water.gravity * whole;
            assert!(
                (fc.force - fe.force).length() <= 1e-4 * full,
                "{what}: force {} vs {}",
                fc.force,
                fe.force
            );
            assert!(
                (fc.torque - fe.torque).length() <= 1e-4 * full,
                "{what}: torque {} vs {}",
                fc.torque,
                fe.torque
            );
        }
        if settle > 0 {
            assert!(
                cut >= 2,
                "after {settle} steps the water plane cuts some bodies"
            );
        }
    }
}

#[test]
fn trajectories_of_the_three_solvers_agree() {
    let (ctx, compute) = compute_context();
    if !compute {
        eprintln!("skipped: the compute formulation needs OpenGL 4.3");
        return;
    }
    let (mut on_compute, mut on_classic, mut on_cpu) =
        (scene_after(0), scene_after(0), scene_after(0));
    let mut now = ComputeSolver::new(&ctx).unwrap();
    let mut then = GpuSolver::new(&ctx, &on_classic.shapes, BODIES, 32).unwrap();
    let mut worst_volume = 0.0f64;
    for _ in 0..STEPS {
        on_compute.step(&mut now).unwrap();
        on_classic.step(&mut then).unwrap();
        on_cpu.step(&mut AnalyticSolver).unwrap();
        for (a, b) in on_compute.bodies.iter().zip(&on_cpu.bodies) {
            let whole = on_cpu.shapes[b.shape].unit.volume;
            worst_volume =
                worst_volume.max((a.submerged.volume - b.submerged.volume).abs() / whole);
        }
    }
    eprintln!("compute vs CPU: worst submerged volume difference {worst_volume:.2e} of the body");
    assert!(worst_volume <= 1e-4, "{worst_volume}");
    let mut entered = 0;
    for k in 0..BODIES {
        let (c, g, e) = (
            &on_compute.bodies[k].rigid,
            &on_classic.bodies[k].rigid,
            &on_cpu.bodies[k].rigid,
        );
        assert!(
            (c.position - e.position).length() <= 1e-4,
            "body {k}: {} vs {}",
            c.position,
            e.position
        );
        assert!(
            c.orientation.angle_between(e.orientation) <= 1e-3,
            "body {k}"
        );
        assert!(
            (g.position - e.position).length() <= 0.05,
            "body {k}: classic {} vs {}",
            g.position,
            e.position
        );
        entered += (on_cpu.bodies[k].submerged.volume > 0.0) as usize;
    }
    assert!(
        entered >= 3,
        "the bodies reach the water within {STEPS} steps"
    );
}

#[test]
fn below_4_3_the_compute_solver_is_a_clear_error_and_the_classic_one_runs() {
    let (ctx, compute) = compute_context();
    if compute {
        eprintln!("this renderer has OpenGL 4.3: the error path is checked on softpipe");
        return;
    }
    let err = ComputeSolver::new(&ctx).err().unwrap().to_string();
    assert!(err.contains("needs OpenGL 4.3"), "{err}");
    let sim = scene_after(15);
    let mut then = GpuSolver::new(&ctx, &sim.shapes, BODIES, 32).unwrap();
    let g = then
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .unwrap();
    let e = AnalyticSolver
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .unwrap();
    for (k, b) in sim.bodies.iter().enumerate() {
        let whole = sim.shapes[b.shape].unit.volume;
        assert!(
            (g[k].volume - e[k].volume).abs() <= 0.03 * whole,
            "body {k}"
        );
    }
}

/// The buoyancy then-and-now table states which formulation is faster only as the runs and
/// the load allow ([`classic_gpgpu::timing::judge_ends`]), never from the medians alone.
#[test]
fn the_then_and_now_timing_is_judged_with_the_load() {
    use classic_gpgpu::report::then_and_now::{StageRow, ThenAndNow};
    use classic_gpgpu::timing::{Load, Spread};
    let table = ThenAndNow {
        workload: "a step".into(),
        unavailable: None,
        stages: vec![StageRow::new("step", Some(10.0), Some(2.0), Some(5.0))],
        same_answer: Some(true),
        verdict: "What each needs.".into(),
    };
    let classic = Spread::of(&[9.0, 10.0, 11.0]);
    let compute = Spread::of(&[1.5, 2.0, 2.5]);
    let load = |one_minute| {
        Some(Load {
            one_minute,
            cores: 2,
        })
    };
    let loaded = table
        .table_judged("llvmpipe", &classic, &compute, load(9.0))
        .caption;
    assert!(loaded.contains("not judged: machine loaded"), "{loaded}");
    assert!(loaded.contains("load average 9.00 on 2 cores"), "{loaded}");
    assert!(!loaded.contains("Measured here"), "{loaded}");
    let quiet = table
        .table_judged("llvmpipe", &classic, &compute, load(0.5))
        .caption;
    assert!(quiet.contains("compute is faster than classic"), "{quiet}");
    assert!(quiet.contains("classic 3 runs: 9.000-11.000 ms"), "{quiet}");
    let slow = Spread::of(&[12.0, 13.0, 14.0]);
    let quiet = table
        .table_judged("llvmpipe", &classic, &slow, load(0.5))
        .caption;
    assert!(
        quiet.contains("compute is not faster than classic"),
        "{quiet}"
    );
    let overlapping = Spread::of(&[1.0, 12.0]);
    let quiet = table
        .table_judged("llvmpipe", &classic, &overlapping, load(0.5))
        .caption;
    assert!(
        quiet.contains("not judged: the two formulations' runs overlap"),
        "{quiet}"
    );
    // The unjudged table keeps its ratio of medians.
    assert!(table.table("llvmpipe").caption.contains("Measured here"));
}
