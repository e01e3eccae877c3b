//! Section 5 as the paper states it: the buoyancy step evaluates eq. 4's four integrands
//! (one render target) and gets the same submerged volumes and centres as the ten-integral
//! path and the CPU; the CPU's pixel-centre cull drops only triangles GL makes no fragment
//! of; the default drag is the paper's alone, at the body's velocity; the race of the two
//! solvers gives finite ratios and refuses an empty race.

use classic_gpgpu::gl::{OcclusionQuery, Primitive, Program, Rect, Texture, TextureFormat};
use classic_gpgpu::mass::buoyancy::batch::GpuSolver;
use classic_gpgpu::mass::buoyancy::forces::{self, Submerged, Water};
use classic_gpgpu::mass::buoyancy::race::{self, RaceSetup};
use classic_gpgpu::mass::buoyancy::rigid_body::RigidBody;
use classic_gpgpu::mass::buoyancy::scene;
use classic_gpgpu::mass::buoyancy::simulation::{AnalyticSolver, SubmergedSolver};
use classic_gpgpu::mass::framing::Framing;
use classic_gpgpu::mass::integrands::{self, Integrands, Placement, Soup};
use classic_gpgpu::mass::peel::PeelSettings;
use classic_gpgpu::shader;
use common::context;
use glam::{DMat3, DQuat, DVec3};
use rand::{Rng, SeedableRng};

mod common;

/// Ten bodies of the paper scene, stepped by the CPU solver into assorted poses (in the
/// air, plunging, floating): at each of a few steps the one-target solver (eq. 4) and the
/// three-target one (eq. 4 and 6) agree to fp32 rounding of the same fragments (a
/// millionth of the body's volume and size), and both are the CPU's clip + Mirtich within
/// the 32x32 discretisation (3% of the body's volume, 3% of its size for the centre).
#[test]
fn eq4_alone_gives_the_ten_integral_paths_submerged_parts() {
    let ctx = context();
    let mut sim = scene::paper_scene(10, 1.0 / 60.0).unwrap();
    let mut eq4 = GpuSolver::new(&ctx, &sim.shapes, 10, 32).unwrap();
    let mut all = GpuSolver::with_integrands(&ctx, &sim.shapes, 10, 32, Integrands::All).unwrap();
    let mut compared = 0;
    for step in 0..60 {
        if step % 15 == 14 {
            let a = eq4.submerged(&sim.shapes, &sim.bodies, &sim.water).unwrap();
            let b = all.submerged(&sim.shapes, &sim.bodies, &sim.water).unwrap();
            let c = AnalyticSolver
                .submerged(&sim.shapes, &sim.bodies, &sim.water)
                .unwrap();
            for (k, body) in sim.bodies.iter().enumerate() {
                let v = sim.shapes[body.shape].unit.volume;
                let size = v.cbrt();
                let near = |x: Submerged, y: Submerged, tol: f64| {
                    (x.volume - y.volume).abs() <= tol * v
                        && (x.volume < 1e-3 * v || (x.center - y.center).length() <= tol * size)
                };
                assert!(
                    near(a[k], b[k], 1e-6),
                    "step {step} body {k}: {:?} vs {:?}",
                    a[k],
                    b[k]
                );
                assert!(
                    near(a[k], c[k], 0.03),
                    "step {step} body {k}: {:?} vs CPU {:?}",
                    a[k],
                    c[k]
                );
                compared += (a[k].volume > 0.0) as usize;
            }
        }
        sim.step(&mut AnalyticSolver).unwrap();
    }
    assert!(compared > 10, "only {compared} submerged bodies compared");
}

/// Random small triangles at 32x32, each drawn alone under its own occlusion query: every
/// triangle the cull drops makes no sample, and the cull drops many that their bounding
/// box alone would keep (it is exact up to a 1/64 pixel margin, not a box test).
#[test]
fn the_pixel_centre_cull_drops_only_triangles_that_make_no_fragment() {
    let ctx = context();
    let framing = Framing::fit_box(DVec3::splat(-1.0), DVec3::splat(1.0), 32).unwrap();
    let place = Placement {
        framing,
        tile: Rect::new(0, 0, 32, 32),
        target: (32, 32),
    };
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let count = 1500;
    let triangles: Vec<[DVec3; 3]> = (0..count)
        .map(|_| {
            let c = DVec3::new(rng.gen_range(-0.9..0.9), rng.gen_range(-0.9..0.9), 0.0);
            let size = rng.gen_range(0.005..0.1);
            std::array::from_fn(|_| {
                c + DVec3::new(
                    rng.gen_range(-size..size),
                    rng.gen_range(-size..size),
                    rng.gen_range(-0.9..0.9),
                )
            })
        })
        .collect();
    let soup = Soup::new(&ctx).unwrap();
    soup.clear();
    for t in &triangles {
        soup.begin_group();
        soup.push_body(&[[0, 1, 2]], t, &place, |_| true);
    }
    soup.upload().unwrap();
    let colour = Texture::new_2d(&ctx, 32, 32, TextureFormat::Rgba8).unwrap();
    let target = classic_gpgpu::gl::Framebuffer::new(&ctx, "cull test", &[&colour], None).unwrap();
    let program = Program::new(
        &ctx,
        &[integrands::VERTEX],
        &[shader!("glsl/test/constant.frag")],
    )
    .unwrap();
    let queries: Vec<OcclusionQuery> = (0..count)
        .map(|_| OcclusionQuery::new(&ctx).unwrap())
        .collect();
    {
        let mut pass = target.pass(&program, "one triangle per query").unwrap();
        pass.uniform("u_colour", glam::Vec4::ONE);
        pass.draw_elements_counted(
            &soup.vertices,
            Primitive::Triangles,
            &soup.groups(),
            &queries,
        )
        .unwrap();
    }
    let samples = OcclusionQuery::samples_of(&queries).unwrap();
    let (mut dropped, mut box_would_keep) = (0, 0);
    for (t, &n) in triangles.iter().zip(&samples) {
        let keep = framing.may_cover_pixel_centre(*t);
        assert!(
            keep || n == 0,
            "dropped a triangle that made {n} samples: {t:?}"
        );
        if !keep {
            dropped += 1;
            box_would_keep += box_holds_centre(&framing, t) as usize;
        }
    }
    assert!(dropped > 200, "dropped {dropped}");
    assert!(
        box_would_keep > 50,
        "the box test would keep only {box_would_keep} of them"
    );
}

/// Whether the triangle's bounding box holds a pixel centre (the looser test).
fn box_holds_centre(f: &Framing, t: &[DVec3; 3]) -> bool {
    let s = f.pixel_size();
    (0..2).all(|axis| {
        let px: Vec<f64> = t
            .iter()
            .map(|p| (p[axis] - f.center[axis] + f.half_width) / s - 0.5)
            .collect();
        let lo = px.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = px.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        lo.ceil() <= hi.floor()
    })
}

/// The default water has the paper's drag alone: a body that only spins (its centre of
/// mass at rest) feels no drag however fast its centre of buoyancy moves, and no damping
/// torque; a translating one feels -c rho V |v| v. The extra damping is an option.
#[test]
fn the_default_drag_is_the_papers_at_the_body_velocity() {
    let water = Water::default();
    assert!(!water.has_extra_damping());
    let mut body = RigidBody::at_rest(500.0, DMat3::IDENTITY * 50.0, DVec3::ZERO, DQuat::IDENTITY);
    body.angular_velocity = DVec3::new(0.0, 3.0, 0.0);
    let sub = Submerged {
        volume: 0.4,
        center: DVec3::new(0.2, 0.0, -0.1),
    };
    let w = forces::wrench(&body, 1.0, sub, &water);
    let buoyant = water.density * water.gravity * sub.volume;
    let expected = DVec3::new(0.0, 0.0, buoyant - body.mass * water.gravity);
    assert!(
        (w.force - expected).length() < 1e-9 * buoyant,
        "{:?}",
        w.force
    );
    body.angular_velocity = DVec3::ZERO;
    body.velocity = DVec3::new(1.5, 0.0, 0.0);
    let w = forces::wrench(&body, 1.0, sub, &water);
    let drag = -water.drag * water.density * sub.volume * 1.5 * 1.5;
    assert!(
        (w.force.x - drag).abs() < 1e-9 * drag.abs(),
        "{:?}",
        w.force
    );
    let damped = water.with_extra_damping();
    assert!(damped.has_extra_damping());
    body.angular_velocity = DVec3::new(0.0, 3.0, 0.0);
    body.velocity = DVec3::ZERO;
    let w = forces::wrench(&body, 1.0, sub, &damped);
    let without = forces::wrench(&body, 1.0, sub, &water);
    assert!((w.torque - without.torque).length() > 1.0);
}

/// A race of two bodies over a few steps: finite, positive ratios and rates, the rounds
/// counted; no rounds is an error.
#[test]
fn the_race_gives_a_ratio_per_round() {
    let ctx = context();
    let setup = RaceSetup {
        bodies: 2,
        resolution: 16,
        steps: 3,
        rounds: 2,
        dt: 1.0 / 60.0,
        extra_damping: false,
    };
    let r = race::run(&ctx, setup, PeelSettings::default()).unwrap();
    assert_eq!(r.gpu_over_cpu.runs, 2);
    for v in [
        r.gpu_over_cpu.median,
        r.gpu_steps_per_second,
        r.cpu_steps_per_second,
    ] {
        assert!(v.is_finite() && v > 0.0, "{v}");
    }
    assert!(
        r.in_words().contains("median of 2 rounds"),
        "{}",
        r.in_words()
    );
    let empty = RaceSetup { rounds: 0, ..setup };
    assert!(race::run(&ctx, empty, PeelSettings::default()).is_err());
}

/// A round taken beside another run of the GPU solver (the report's scene): the CPU solver
/// steps only while the round lasts and is timed on its own copy of the scene; the race then
/// runs only the rounds left, and its rates count the round given with its own.
#[test]
fn a_round_run_beside_the_scene_counts_as_the_race_s_first() {
    let ctx = context();
    let setup = RaceSetup {
        bodies: 2,
        resolution: 16,
        steps: 3,
        rounds: 2,
        dt: 1.0 / 60.0,
        extra_damping: false,
    };
    let mut beside = race::Beside::new(&setup).unwrap();
    for k in 0..5 {
        assert_eq!(beside.round().is_some(), k >= 3, "after {k} steps");
        beside.step(10.0).unwrap();
    }
    let round = beside.round().unwrap();
    assert_eq!(round.gpu_ms, 30.0, "only the round's three steps count");
    assert!(round.cpu_ms.is_finite() && round.cpu_ms > 0.0);
    let r = race::run_after(&ctx, setup, PeelSettings::default(), vec![round], None).unwrap();
    assert_eq!(r.gpu_over_cpu.runs, 2);
    let own = |rate: f64| rate.is_finite() && rate > 0.0;
    assert!(own(r.gpu_steps_per_second) && own(r.cpu_steps_per_second));
    // Every round given: nothing is run, the rates are the given rounds' (3 steps in 30 ms).
    let all_given = race::run_after(
        &ctx,
        setup,
        PeelSettings::default(),
        vec![round, round],
        None,
    )
    .unwrap();
    assert_eq!(all_given.gpu_over_cpu.runs, 2);
    assert!((all_given.gpu_steps_per_second - 100.0).abs() < 1e-9);
    assert_eq!(all_given.gpu_over_cpu.median, round.cpu_ms / round.gpu_ms);
}

/// `buoyancy --race`: a bad round count and a race asked to draw are clear errors; a tiny
/// race prints its ratio and the load.
#[test]
fn the_race_command_prints_the_ratio_and_refuses_bad_input() {
    let out = common::classic_gpgpu(&["buoyancy", "--race", "0"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--race 0"), "{err}");
    let out = common::classic_gpgpu(&["buoyancy", "--race", "1", "--cpu"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--cpu"));
    let json = common::json_of(&[
        "buoyancy",
        "--race",
        "1",
        "--bodies",
        "2",
        "--steps",
        "2",
        "--resolution",
        "16",
        "--json",
    ]);
    let ratio = json["gpu_over_cpu"]["median"].as_f64().unwrap();
    assert!(ratio.is_finite() && ratio > 0.0, "{json}");
    assert_eq!(json["setup"]["steps"], 2);
}
