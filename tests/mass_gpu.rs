//! Paper 4 on a real headless GL context: the integrand shaders, depth peeling, reduction
//! and the fluid-surface passes, each compared with the CPU.

use classic_gpgpu::gl::Program;
use classic_gpgpu::mass::framing::Framing;
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mass::{
    analytic, clip, closed_form, cpu_reference, integrands, MassProperties, VolumeIntegrals,
};
use classic_gpgpu::mesh::Mesh;
use common::context;
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed, uv_sphere};

mod common;

mod mass_shapes;

mod mass_check;
use mass_check::assert_integrals_close;

#[test]
fn every_mass_shader_compiles() {
    let ctx = context();
    // The section 3.1 listing alone, as printed (a complete fragment shader).
    Program::new(&ctx, &[integrands::VERTEX], &[integrands::LISTING]).unwrap();
    integrands::peel_program(&ctx, integrands::Integrands::All).unwrap();
    integrands::peel_program(&ctx, integrands::Integrands::Eq4).unwrap();
    integrands::water_depth_program(&ctx).unwrap();
    integrands::water_patch_program(&ctx, integrands::Integrands::All).unwrap();
    integrands::water_patch_program(&ctx, integrands::Integrands::Eq4).unwrap();
    classic_gpgpu::mass::reduce::Accumulator::new(&ctx, 8, 8).unwrap();
    classic_gpgpu::mass::peel_end::PeelEnd::new(&ctx).unwrap();
    // The frame renderer's body, water and arrow programs.
    let shape = classic_gpgpu::mass::buoyancy::simulation::Shape::new(
        "box",
        &cuboid(Vec3::ONE, Vec3::ZERO),
    )
    .unwrap();
    classic_gpgpu::mass::buoyancy::render::FrameRenderer::new(&ctx, &[shape], 16, 16).unwrap();
}

/// The GPU's pixel sums equal the CPU's at the same pixel centres. fp32 per fragment
/// (p interpolated, ~1e-7 relative) and fp32 tree sums over <= 64^2 pixels: 1e-4 of the
/// largest integral leaves room for a few silhouette pixels decided differently. 45 is not a
/// power of two: the reduction's last blocks reach past the target's edge.
#[test]
fn gpu_pixel_sums_equal_the_cpu_reference() {
    let ctx = context();
    let mesh = transformed(
        &torus(1.0, 0.35, 40, 20),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.5, 0.2, 0.1),
        DVec3::new(2.0, -1.0, 0.5),
    );
    for (n, tilt) in [(32, 0.5), (45, 0.9), (64, 1.3)] {
        let mesh = transformed(&mesh, DQuat::from_rotation_y(tilt), DVec3::ZERO);
        let gpu = GpuMass::new(&ctx, n)
            .unwrap()
            .integrate(&mesh, None, None)
            .unwrap();
        let framing = Framing::fit(&mesh, n).unwrap();
        assert_eq!(gpu.framing, framing);
        let cpu = cpu_reference::integrate(&mesh, &framing, None);
        assert_integrals_close(&format!("{n}x{n}"), &gpu.integrals, &cpu, 1e-3);
        assert_eq!(gpu.peels, cpu_reference::layers(&mesh, &framing, None));
    }
}

/// Measured on llvmpipe for this tilted torus (relative error of mass / worst of Ixx, Iyy,
/// Izz): 32x32 1.4e-3 / 1.1e-3, 128x128 3.4e-4 / 4.8e-4, 512x512 1.9e-6 / 4.2e-6. The
/// asserted bounds are the paper's 5% at 32x32, a decrease, and 0.2% at 512x512.
#[test]
fn gpu_converges_to_the_analytic_result() {
    let ctx = context();
    let mesh = transformed(
        &torus(1.0, 0.4, 64, 32),
        DQuat::from_rotation_x(0.6),
        DVec3::new(0.5, 0.0, 1.0),
    );
    let want = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 2.0);
    let mut worst = Vec::new();
    for n in [32, 128, 512] {
        let gpu = GpuMass::new(&ctx, n)
            .unwrap()
            .integrate(&mesh, None, None)
            .unwrap();
        let got = MassProperties::from_integrals(&gpu.integrals, 2.0);
        let e = got.relative_errors(&want);
        eprintln!("{n}x{n}: relative errors (mass, Ixx, Iyy, Izz) = {e:?}");
        worst.push(e.iter().cloned().fold(0.0, f64::max));
    }
    assert!(
        worst[0] < 0.05,
        "the paper's 5% bound at 32x32: {}",
        worst[0]
    );
    assert!(worst[1] < worst[0] && worst[2] < 0.002, "{worst:?}");
}

#[test]
fn inverted_mesh_gives_negative_volume_on_the_gpu() {
    let ctx = context();
    let mut mesh = cuboid(Vec3::new(1.0, 2.0, 0.5), Vec3::ZERO);
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    let gpu = GpuMass::new(&ctx, 32)
        .unwrap()
        .integrate(&mesh, None, None)
        .unwrap();
    assert!((gpu.integrals.v + 1.0).abs() < 0.02, "{}", gpu.integrals.v);
}

#[test]
fn below_a_plane_matches_closed_forms() {
    let ctx = context();
    let gpu = GpuMass::new(&ctx, 128).unwrap();
    let size = DVec3::new(1.5, 1.0, 0.8);
    let box_mesh = cuboid(size.as_vec3(), Vec3::ZERO);
    let sphere = uv_sphere(32, 64, |_| 1.0);
    for level in [-0.3, 0.0, 0.25, 0.6] {
        let got = gpu
            .integrate(&box_mesh, Some(level), None)
            .unwrap()
            .integrals;
        let (v, c) = closed_form::submerged_cuboid(size, DVec3::ZERO, level);
        eprintln!("box below {level}: V {} vs {v}", got.v);
        assert!(
            (got.v - v).abs() < 0.01 * size.x * size.y * size.z,
            "box at {level}: {} vs {v}",
            got.v
        );
        assert!((got.centroid() - c).length() < 0.01, "box at {level}");

        let got = gpu.integrate(&sphere, Some(level), None).unwrap().integrals;
        let (v, c) = closed_form::submerged_sphere(1.0, DVec3::ZERO, level);
        let exact = analytic::volume_integrals(&clip::below_plane(&sphere, level as f32));
        eprintln!(
            "sphere below {level}: V {} vs {v} (polyhedron {})",
            got.v, exact.v
        );
        assert!(
            (got.v - v).abs() / v < 0.01,
            "sphere at {level}: {} vs {v}",
            got.v
        );
        assert!((got.centroid().z - c.z).abs() < 0.01, "sphere at {level}");
    }
}

#[test]
fn below_a_plane_equals_the_cpu_reference_of_section_5_2() {
    let ctx = context();
    let mesh = transformed(
        &torus(1.0, 0.35, 40, 20),
        DQuat::from_rotation_y(0.8),
        DVec3::ZERO,
    );
    let gpu = GpuMass::new(&ctx, 64).unwrap();
    for level in [-0.6, -0.2, 0.1, 0.5, 2.0, -3.0] {
        let got = gpu.integrate(&mesh, Some(level), None).unwrap();
        let cpu = cpu_reference::integrate(&mesh, &got.framing, Some(level));
        if level < -2.0 {
            assert_eq!(got.integrals.v, 0.0);
            assert_eq!(got.peels, 0);
            continue;
        }
        assert_integrals_close(&format!("below {level}"), &got.integrals, &cpu, 1e-3);
        assert_eq!(
            got.peels,
            cpu_reference::layers(&mesh, &got.framing, Some(level))
        );
    }
}

/// The same body integrated again and again, on fresh targets and on reused ones, gives the
/// same finite sums each time. On softpipe the accumulation once read peel texels it had
/// not drawn (new textures held whatever memory a freed one left, NaN included) and every
/// GPU value came out NaN in most runs; repeating makes such an intermittent read show.
#[test]
fn repeated_runs_give_the_same_finite_sums() {
    let ctx = context();
    let mesh = transformed(
        &torus(1.0, 0.35, 40, 20),
        DQuat::from_rotation_x(0.7),
        DVec3::new(0.3, -0.2, 0.1),
    );
    let reused = GpuMass::new(&ctx, 32).unwrap();
    let mut first: Option<VolumeIntegrals> = None;
    for round in 0..6 {
        let fresh = GpuMass::new(&ctx, 32).unwrap();
        for (which, gpu) in [("fresh", &fresh), ("reused", &reused)] {
            let got = gpu.integrate(&mesh, None, None).unwrap();
            let values = got.integrals.to_array();
            assert!(
                values.iter().all(|v| v.is_finite()),
                "round {round}, {which} targets: {:?}",
                got.integrals
            );
            let want = first.get_or_insert(got.integrals);
            assert_eq!(
                values,
                want.to_array(),
                "round {round}, {which} targets differ from the first run"
            );
        }
        let cpu = cpu_reference::integrate(&mesh, &Framing::fit(&mesh, 32).unwrap(), None);
        assert_integrals_close(&format!("round {round}"), &first.unwrap(), &cpu, 1e-3);
    }
}

/// The GPU draws every body in a unit frame (coordinates relative to the framing centre,
/// scaled per axis by powers of two), so its sums equal the f64 pixel sums of the CPU
/// reference whatever the body's size and place: a unit cube 10^6 from the origin (whose
/// fp32 integrands about the world origin lost the 1/12 of its inertia), tiny ones, and
/// ones whose integrands x²z, about 10^114, overflowed fp32 (NaN and inf with exit 0).
#[test]
fn gpu_frames_bodies_of_any_size_and_place() {
    let ctx = context();
    let gpu = GpuMass::new(&ctx, 32).unwrap();
    let body = transformed(
        &torus(1.0, 0.35, 40, 20),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.5, 0.2, 0.1),
        DVec3::ZERO,
    );
    // (At 10^6 the f32 vertices lie on a grid of 1/16 to 1/8: the torus is 16 across there
    // so that the grid does not fold its triangles over each other.)
    for (scale, offset) in [
        (16.0, DVec3::new(1e6, -2e6, 5e5)),
        (1e-20, DVec3::ZERO),
        (1e20, DVec3::new(3e20, 0.0, -1e20)),
        (5e37, DVec3::ZERO),
        (1e38, DVec3::new(0.0, 1e37, 0.0)),
    ] {
        let mesh = Mesh::new(
            body.positions
                .iter()
                .map(|p| (p.as_dvec3() * scale + offset).as_vec3())
                .collect(),
            body.triangles.clone(),
        );
        let what = format!("scale {scale:e}, offset {offset}");
        let got = gpu.integrate(&mesh, None, None).unwrap();
        assert!(got.integrals.is_finite(), "{what}: {:?}", got.integrals);
        let cpu = cpu_reference::integrate(&mesh, &got.framing, None);
        assert_integrals_close(&what, &got.integrals, &cpu, 1e-3);
        // And the mass properties agree with the analytic reference of the same (f32)
        // mesh within 1% (this torus's 32x32 error is 1.4e-3 at the origin).
        let mp = MassProperties::from_integrals(&got.integrals, 1.0);
        let want = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
        assert!(
            (mp.volume - want.volume).abs() < 1e-2 * want.volume,
            "{what}: volume {} vs {}",
            mp.volume,
            want.volume
        );
        assert!(
            (mp.center_of_mass - want.center_of_mass).length() < 1e-2 * scale,
            "{what}: centre {} vs {}",
            mp.center_of_mass,
            want.center_of_mass
        );
        let inertia = want.inertia.to_cols_array();
        let largest = inertia.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, (g, w)) in mp.inertia.to_cols_array().iter().zip(inertia).enumerate() {
            assert!(
                (g - w).abs() < 1e-2 * largest,
                "{what}: inertia entry {k}: {g} vs {w}"
            );
        }
    }
}

/// A cube with one vertex pulled out to 10^20 or 10^38 is a needle one unit thick, far
/// thinner than a pixel of a frame 10^38 wide: the GPU sees none of it (it answered volume
/// 0 with exit 0), and now says so.
#[test]
fn gpu_refuses_a_body_thinner_than_a_pixel() {
    let ctx = context();
    let gpu = GpuMass::new(&ctx, 32).unwrap();
    for far in [1e20f32, 1e38] {
        let mut mesh = cuboid(Vec3::ONE, Vec3::ZERO);
        let corner = mesh
            .positions
            .iter()
            .position(|p| *p == Vec3::splat(0.5))
            .unwrap();
        mesh.positions[corner] = Vec3::new(far, 0.5, 0.5);
        let err = gpu.integrate(&mesh, None, None).unwrap_err().to_string();
        assert!(
            err.contains("covers no pixel centre") && err.contains("thinner than a pixel"),
            "{far}: {err}"
        );
    }
    // A body that does cover pixels is not refused however thin.
    let slab = cuboid(Vec3::new(1.0, 0.2, 1e-6), Vec3::ZERO);
    assert!(gpu.integrate(&slab, None, None).is_ok());
}

/// A body whose integrands overflow fp32 (here: a cube scaled by 10^30, posed behind the
/// unit frame's back) is an error naming the body and the pass, not a NaN.
#[test]
fn peeler_names_a_body_with_non_finite_integrals() {
    use classic_gpgpu::gl::{GlError, Rect};
    use classic_gpgpu::mass::integrands::{Placement, Soup};
    use classic_gpgpu::mass::peel::{Job, Peeler};
    let ctx = context();
    let cube = cuboid(Vec3::ONE, Vec3::ZERO);
    let soup = Soup::new(&ctx).unwrap();
    let peeler = Peeler::new(&ctx, 64, 32, Some(32)).unwrap();
    let job = |body, group, x, scale: f64| Job {
        body,
        group,
        framing: Framing {
            center: DVec3::ZERO,
            half_width: 0.6 * scale,
            half_depth: 0.6 * scale,
            resolution: 32,
        },
        tile: Rect::new(x, 0, 32, 32),
    };
    let pose = |jobs: &[Job]| {
        soup.clear();
        for (job, scale) in jobs.iter().zip([1.0, 1e30]) {
            let world: Vec<DVec3> = cube
                .positions
                .iter()
                .map(|p| p.as_dvec3() * scale)
                .collect();
            let at = Placement {
                framing: job.framing,
                tile: job.tile,
                target: (64, 32),
            };
            soup.begin_group();
            soup.push_body(&cube.triangles, &world, &at, |_| true);
        }
        soup.upload().unwrap();
    };
    let one = [job("body 0 (box)", 0, 0, 1.0)];
    pose(&one);
    let fine = peeler.run(&soup, &one, None, None).unwrap();
    assert!((fine.integrals[0].v - 1.0).abs() < 0.05);
    // A job in a group the soup does not have is an error naming it, not a panic.
    let stray = [job("body 5 (box)", 1, 0, 1.0)];
    let err = peeler
        .run(&soup, &stray, None, None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("body 5 (box) is in group 1 of a soup of 1 groups"),
        "{err}"
    );
    let jobs = [
        job("body 0 (box)", 0, 0, 1.0),
        job("body 1 (box)", 1, 32, 1e30),
    ];
    pose(&jobs);
    let err = peeler.run(&soup, &jobs, None, None).unwrap_err();
    assert!(matches!(err, GlError::NonFinite { .. }), "{err}");
    let message = err.to_string();
    assert!(
        message.contains("body 1 (box)") && message.contains("pass 'mass: sum reduction'"),
        "{message}"
    );
}

/// Peeling ends with the last layer that drew, not with an empty peel after it (pass 2 on
/// counts fragments per pixel in the stencil, `mass::peel_end`): as many peel passes as
/// layers, and exactly the layers the CPU reference counts, so no layer is lost by
/// stopping early. A sphere (2 layers), a tilted torus (4 at some pixels) and a torus seen
/// edge-on, below a plane through it (odd layer counts where the water cuts the body).
#[test]
fn peeling_ends_with_the_last_layer_without_an_empty_peel() {
    let ctx = context();
    let sphere = uv_sphere(24, 48, |_| 1.0);
    let torus_mesh = torus(1.0, 0.35, 40, 20);
    let tilted = transformed(&torus_mesh, DQuat::from_rotation_x(0.4), DVec3::ZERO);
    let edge_on = transformed(&torus_mesh, DQuat::from_rotation_x(1.5), DVec3::ZERO);
    for (name, mesh, below) in [
        ("sphere", &sphere, None),
        ("tilted torus", &tilted, None),
        ("edge-on torus below z = 0.2", &edge_on, Some(0.2)),
    ] {
        let gpu = GpuMass::new(&ctx, 32).unwrap();
        classic_gpgpu::gl::profile::start(&ctx);
        let got = gpu.integrate(mesh, below, None).unwrap();
        let table = classic_gpgpu::gl::profile::finish(&ctx).unwrap();
        let framing = Framing::fit(mesh, 32).unwrap();
        assert_eq!(
            got.peels,
            cpu_reference::layers(mesh, &framing, below),
            "{name}"
        );
        let peel_passes = table
            .row("mass: passes 1..n, depth peel")
            .unwrap_or_else(|| panic!("{name}: no peel row in\n{table}"))
            .calls;
        assert_eq!(
            peel_passes, got.peels as u64,
            "{name}: peel passes\n{table}"
        );
        let cpu = cpu_reference::integrate(mesh, &framing, below);
        assert_integrals_close(name, &got.integrals, &cpu, 1e-3);
    }
}

/// The passes with the layer count given in advance (what `mass` times to show what the
/// stopping test's waits cost) draw the same peels and give the same integrals as the
/// paper's stopping test, read no occlusion query between peels, and draw no stencil-count
/// quad; the test
/// is back once the count is taken away. A wrong count gives a different result (so the
/// count is really used). A tilted torus (4 layers at some pixels) and the same below a plane.
#[test]
fn peeling_with_a_known_layer_count_equals_the_stopping_test() {
    let ctx = context();
    let torus_mesh = torus(1.0, 0.35, 40, 20);
    let tilted = transformed(&torus_mesh, DQuat::from_rotation_x(0.4), DVec3::ZERO);
    for (name, below) in [
        ("tilted torus", None),
        ("tilted torus below z = 0.1", Some(0.1)),
    ] {
        let gpu = GpuMass::new(&ctx, 32).unwrap();
        let tested = gpu.integrate(&tilted, below, None).unwrap();
        gpu.set_known_layers(Some(tested.peels));
        classic_gpgpu::gl::profile::start(&ctx);
        let known = gpu.integrate(&tilted, below, None).unwrap();
        let table = classic_gpgpu::gl::profile::finish(&ctx).unwrap();
        assert_eq!(known.peels, tested.peels, "{name}");
        assert_integrals_close(name, &known.integrals, &tested.integrals, 1e-6);
        let calls = |row: &str| table.row(row).map_or(0, |r| r.calls);
        assert_eq!(
            calls("mass: passes 1..n, depth peel"),
            tested.peels as u64,
            "{name}\n{table}"
        );
        assert_eq!(calls("mass: occlusion queries"), 0, "{name}\n{table}");
        assert_eq!(
            calls("mass: another layer? (stencil count)"),
            0,
            "{name}\n{table}"
        );
        // One layer short misses the deepest layer's integrals.
        gpu.set_known_layers(Some(tested.peels - 1));
        let short = gpu.integrate(&tilted, below, None).unwrap();
        assert_eq!(short.peels, tested.peels - 1, "{name}");
        assert_ne!(short.integrals, tested.integrals, "{name}");
        gpu.set_known_layers(None);
        let again = gpu.integrate(&tilted, below, None).unwrap();
        assert_eq!(again.peels, tested.peels, "{name}");
        assert_integrals_close(name, &again.integrals, &tested.integrals, 1e-6);
    }
}
