//! Paper 4's compute formulation (OpenGL 4.3) against its f64 CPU reference (the same
//! signed-tetrahedron sum), Mirtich's analytic method and the classic peeling path. On a
//! context below 4.3 (softpipe) the compute path is a clear error and the classic path runs.
//!
//! Tolerances: the compute path sums exact per-triangle terms in fp32 in a unit frame, so it
//! matches the f64 sums to a few fp32 ulps of the largest integral times the depth of the
//! reduction tree: 1e-5 of the largest value. The classic path is image based: at 256x256
//! its error on this torus is resolution error, bounded at 1e-3 of the largest value.

use classic_gpgpu::mass::compute::{tetrahedron_sum, ComputeMass};
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mass::{analytic, MassProperties};
use classic_gpgpu::mesh::Mesh;
use common::compute_context;
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed, uv_sphere};

mod common;

mod mass_shapes;

mod mass_check;
use mass_check::assert_integrals_close;

fn tilted_torus() -> Mesh {
    transformed(
        &torus(1.0, 0.4, 64, 32),
        DQuat::from_rotation_x(0.6),
        DVec3::new(0.5, 0.0, 1.0),
    )
}

fn bodies() -> Vec<Mesh> {
    vec![
        tilted_torus(),
        cuboid(Vec3::new(2.0, 0.5, 3.0), Vec3::new(1e4, -2.0, 5.0)),
        uv_sphere(24, 48, |_| 1e3),
        // A body of few triangles beside bodies of many: its segment is mostly padding.
        cuboid(Vec3::splat(1e-3), Vec3::ZERO),
    ]
}

#[test]
fn below_4_3_compute_is_a_clear_error_and_the_classic_path_runs() {
    let (ctx, compute) = compute_context();
    if compute {
        assert!(ComputeMass::new(&ctx).is_ok());
        return;
    }
    let err = ComputeMass::new(&ctx).err().unwrap().to_string();
    assert!(
        err.contains("paper 4") && err.contains("needs OpenGL 4.3"),
        "{err}"
    );
    let mesh = tilted_torus();
    let classic = GpuMass::new(&ctx, 64)
        .unwrap()
        .integrate(&mesh, None, None)
        .unwrap();
    let want = analytic::volume_integrals(&mesh);
    assert_integrals_close("classic at 64x64", &classic.integrals, &want, 0.05);
}

#[test]
fn every_body_in_one_pass_matches_the_cpu_sum_and_mirtich() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let meshes = bodies();
    let refs: Vec<&Mesh> = meshes.iter().collect();
    let got = ComputeMass::new(&ctx).unwrap().integrate(&refs).unwrap();
    assert_eq!(got.integrals.len(), meshes.len());
    for (k, (mesh, gpu)) in meshes.iter().zip(&got.integrals).enumerate() {
        let cpu = tetrahedron_sum(mesh, gpu.origin);
        assert_integrals_close(&format!("body {k} vs CPU"), gpu, &cpu, 1e-5);
        let mirtich = analytic::volume_integrals(mesh);
        assert_integrals_close(&format!("body {k} vs Mirtich"), gpu, &mirtich, 1e-5);
        // And the CPU sum is Mirtich's answer to f64 rounding.
        assert_integrals_close(&format!("body {k}: CPU vs Mirtich"), &cpu, &mirtich, 1e-9);
    }
    // One body alone gives what it gave among the others.
    let alone = ComputeMass::new(&ctx)
        .unwrap()
        .integrate(&refs[..1])
        .unwrap();
    assert_integrals_close("alone", &alone.integrals[0], &got.integrals[0], 1e-6);
}

#[test]
fn same_mass_properties_as_the_classic_peeling_path() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let mesh = tilted_torus();
    let now = ComputeMass::new(&ctx).unwrap().integrate(&[&mesh]).unwrap();
    let then = GpuMass::new(&ctx, 256)
        .unwrap()
        .integrate(&mesh, None, None)
        .unwrap();
    assert!(then.peels >= 2, "a tilted torus has several layers");
    assert_integrals_close(
        "compute vs classic",
        &now.integrals[0],
        &then.integrals,
        1e-3,
    );
    let a = MassProperties::from_integrals(&now.integrals[0], 2.0);
    let b = MassProperties::from_integrals(&then.integrals, 2.0);
    let worst = a.relative_errors(&b).iter().cloned().fold(0.0, f64::max);
    eprintln!("compute vs classic 256x256: worst relative error {worst:.2e}");
    // Measured on llvmpipe: 2.9e-5.
    assert!(worst < 2e-3, "{worst}");
}

#[test]
fn inverted_and_non_finite_bodies() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let mass = ComputeMass::new(&ctx).unwrap();
    let mesh = tilted_torus();
    let mut inverted = mesh.clone();
    for t in &mut inverted.triangles {
        t.swap(1, 2);
    }
    let r = mass.integrate(&[&mesh, &inverted]).unwrap();
    assert!(r.integrals[1].v < 0.0);
    assert!((r.integrals[0].v + r.integrals[1].v).abs() < 1e-5 * r.integrals[0].v);
    let mut bad = mesh.clone();
    bad.positions[7] = Vec3::new(f32::NAN, 0.0, 0.0);
    let err = mass.integrate(&[&mesh, &bad]).unwrap_err().to_string();
    assert!(err.contains("body 1: vertex 7 is not finite"), "{err}");
}

#[test]
fn a_mesh_past_the_work_group_limit_is_split_into_several_dispatches() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    ctx.set_checks(true);
    // 4096 triangles are 64 work groups of 64; with at most 10 groups a dispatch, 7 dispatches
    // (the split a 10M-triangle mesh needs against the 65,535 limit). The reduction after it
    // takes 8 groups of 512, within the limit.
    let mesh = tilted_torus();
    assert_eq!(mesh.triangles.len(), 4096);
    let mass = ComputeMass::new(&ctx).unwrap();
    let whole = mass.integrate(&[&mesh]).unwrap();
    ctx.set_work_group_limit(Some(10));
    let split = mass.integrate(&[&mesh]);
    ctx.set_work_group_limit(None);
    let split = split.unwrap();
    let cpu = tetrahedron_sum(&mesh, split.integrals[0].origin);
    assert_integrals_close("split vs CPU", &split.integrals[0], &cpu, 1e-5);
    assert_integrals_close(
        "split vs whole",
        &split.integrals[0],
        &whole.integrals[0],
        1e-6,
    );
    // The limit is real: one dispatch over every triangle is refused under it.
    ctx.set_work_group_limit(Some(10));
    let program = classic_gpgpu::gl::ComputeProgram::new(
        &ctx,
        &[classic_gpgpu::shader!(
            "glsl/mass/compute/triangle_integrals.comp"
        )],
    )
    .unwrap();
    let refused = program
        .dispatch("one dispatch")
        .uniform("u_first", 0u32)
        .run_over(mesh.triangles.len() as u32)
        .unwrap_err()
        .to_string();
    ctx.set_work_group_limit(None);
    assert!(refused.contains("allows 10"), "{refused}");
}

/// Past the work-group limit the reduction is split too, along both of its axes: with at
/// most 3 groups a dispatch, a body of 16384 triangles needs 32 partials in its first pass
/// (11 dispatches along x) and five bodies are 15 segments (5 along y). Past what one
/// storage buffer holds, the triangles go through in chunks: with room for 1000 triangles
/// of each of the five bodies, 17 chunks. Each way the sums equal the unsplit run's (within
/// fp32 rounding of another order of additions) and the CPU's.
#[test]
fn work_past_the_dispatch_and_buffer_limits_is_split() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    ctx.set_checks(true);
    let big = transformed(
        &torus(1.0, 0.4, 128, 64),
        DQuat::from_rotation_y(0.3),
        DVec3::new(-2.0, 1.0, 0.0),
    );
    assert_eq!(big.triangles.len(), 16384);
    let mut meshes = bodies();
    meshes.push(big);
    let refs: Vec<&Mesh> = meshes.iter().collect();
    let mass = ComputeMass::new(&ctx).unwrap();
    let whole = mass.integrate(&refs).unwrap();
    ctx.set_work_group_limit(Some(3));
    let split = mass.integrate(&refs);
    ctx.set_work_group_limit(None);
    let split = split.unwrap();
    ctx.set_storage_buffer_limit(Some(1000 * 3 * 16 * meshes.len()));
    let chunked = mass.integrate(&refs);
    ctx.set_storage_buffer_limit(None);
    let chunked = chunked.unwrap();
    for (k, mesh) in meshes.iter().enumerate() {
        assert_integrals_close(
            &format!("body {k}, chunked vs whole"),
            &chunked.integrals[k],
            &whole.integrals[k],
            1e-6,
        );
        let cpu = tetrahedron_sum(mesh, split.integrals[k].origin);
        assert_integrals_close(
            &format!("body {k}, split vs CPU"),
            &split.integrals[k],
            &cpu,
            1e-5,
        );
        assert_integrals_close(
            &format!("body {k}, split vs whole"),
            &split.integrals[k],
            &whole.integrals[k],
            1e-6,
        );
    }
}
