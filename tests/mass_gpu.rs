//! Paper 4 on a real headless GL context: the integrand shaders, depth peeling, reduction
//! and the fluid-surface passes, each compared with the CPU.

use classic_gpgpu::gl::Program;
use classic_gpgpu::mass::framing::Framing;
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mass::{
    analytic, clip, closed_form, cpu_reference, integrands, MassProperties, VolumeIntegrals,
};
use common::context;
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed, uv_sphere};

mod common;

mod mass_shapes;

fn largest(i: &VolumeIntegrals) -> f64 {
    i.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Every value within `rel` of the largest (the integrals differ in scale by orders).
fn assert_integrals_close(what: &str, got: &VolumeIntegrals, want: &VolumeIntegrals, rel: f64) {
    let scale = largest(want);
    for (k, (g, w)) in got.to_array().iter().zip(want.to_array()).enumerate() {
        assert!(
            (g - w).abs() <= rel * scale,
            "{what}: integral {k}: GPU {g} vs CPU {w} (scale {scale})\n{got:?}\n{want:?}"
        );
    }
}

#[test]
fn every_mass_shader_compiles() {
    let ctx = context();
    // The section 3.1 listing alone, as printed (a complete fragment shader).
    Program::new(&ctx, &[integrands::VERTEX], &[integrands::LISTING]).unwrap();
    integrands::peel_program(&ctx).unwrap();
    integrands::water_depth_program(&ctx).unwrap();
    integrands::water_patch_program(&ctx).unwrap();
    classic_gpgpu::mass::reduce::Accumulator::new(&ctx, 8, 8).unwrap();
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
/// largest integral leaves room for a few silhouette pixels decided differently.
#[test]
fn gpu_pixel_sums_equal_the_cpu_reference() {
    let ctx = context();
    let mesh = transformed(
        &torus(1.0, 0.35, 40, 20),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.5, 0.2, 0.1),
        DVec3::new(2.0, -1.0, 0.5),
    );
    for (n, tilt) in [(32, 0.5), (64, 1.3)] {
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
        assert!((got.first() / got.v - c).length() < 0.01, "box at {level}");

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
        assert!(
            (got.first().z / got.v - c.z).abs() < 0.01,
            "sphere at {level}"
        );
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
