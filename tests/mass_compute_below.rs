//! The compute formulation below a plane (`mass --formulation compute --below Z`): the kernel
//! clips every triangle to `z <= Z`, with the integration origin on the plane so the cap adds
//! nothing. Checked against its f64 CPU mirror (the same clip, no cap), against the mesh
//! clipped and capped on the CPU (`clip::below_plane`) and integrated by Mirtich's method, and
//! against the classic peeling path with the fluid-surface passes. On a context below 4.3
//! (softpipe) the compute path is a clear error and the classic `--below` runs.
//!
//! Tolerances: the kernel's terms are exact per triangle and summed in fp32 in a unit frame,
//! so it matches the f64 sums within a few fp32 ulps times the reduction depth: 1e-5 of the
//! largest integral of the whole body about the same origin (a thin slice's own integrals are
//! far smaller than the body's, whose fp32 coordinates carry the rounding). The CPU mirror
//! and the clipped-and-capped mesh differ only by the latter's cut points stored as f32:
//! 1e-6. The classic path at 256x256 carries resolution error: 1e-3 of the largest value.

use classic_gpgpu::mass::clip::below_plane;
use classic_gpgpu::mass::compute::{tetrahedron_sum, tetrahedron_sum_below, ComputeMass};
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mass::{analytic, MassProperties, VolumeIntegrals};
use classic_gpgpu::mesh::Mesh;
use common::compute_context;
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed, uv_sphere};

mod common;

mod mass_shapes;

mod mass_check;
use mass_check::{assert_integrals_close, largest};

fn tilted_torus() -> Mesh {
    transformed(
        &torus(1.0, 0.4, 64, 32),
        DQuat::from_rotation_x(0.6),
        DVec3::new(0.5, 0.0, 1.0),
    )
}

/// A box turned 45 degrees about x: two of its edges are horizontal, at z = +-h sqrt(2).
fn box_on_its_edge() -> Mesh {
    transformed(
        &cuboid(Vec3::new(2.0, 1.0, 1.0), Vec3::ZERO),
        DQuat::from_rotation_x(std::f64::consts::FRAC_PI_4),
        DVec3::new(0.0, 0.0, 0.0),
    )
}

/// A box tilted about two axes: its eight corners at eight heights.
fn tilted_box() -> Mesh {
    transformed(
        &cuboid(Vec3::new(1.0, 0.7, 0.4), Vec3::ZERO),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 0.5, 0.2),
        DVec3::new(3.0, -1.0, 2.0),
    )
}

/// Meshes and the planes that cut them: through vertices, through a horizontal edge, through
/// the middle, near the top and bottom, above everything and below everything.
fn cases() -> Vec<(String, Mesh, Vec<f64>)> {
    let mut out = Vec::new();
    let b = tilted_box();
    let mut zs: Vec<f64> = b.positions.iter().map(|p| p.z as f64).collect();
    zs.sort_by(f64::total_cmp);
    // Through each corner that is neither the lowest nor the highest.
    let mut planes: Vec<f64> = zs[1..7].to_vec();
    planes.extend([zs[0] - 1.0, zs[7] + 1.0, (zs[0] + zs[7]) / 2.0]);
    out.push(("tilted box".to_string(), b, planes));
    let edge = box_on_its_edge();
    let top = edge.positions.iter().map(|p| p.z).fold(f32::MIN, f32::max) as f64;
    // Through the upper horizontal edge, the two middle edges (at z = 0) and just below the top.
    out.push((
        "box on its edge".into(),
        edge,
        vec![top, 0.0, top - 1e-3, -0.3],
    ));
    // The torus's rings at z = 1 (its centre) are vertices; the plane through them.
    out.push((
        "tilted torus".into(),
        tilted_torus(),
        vec![1.0, 0.7, 1.3, 0.5, -5.0, 5.0],
    ));
    out.push((
        "flat torus".into(),
        torus(1.0, 0.4, 48, 24),
        vec![0.0, 0.2, -0.39],
    ));
    out.push((
        "bumpy sphere".into(),
        uv_sphere(24, 48, |d| 1.0 + 0.2 * (3.0 * d.x).sin() * d.y),
        vec![0.0, 0.5, -0.8],
    ));
    // Extreme scales: a cube of side 1e30 far from the origin, one of side 1e-20.
    out.push((
        "huge box".into(),
        cuboid(Vec3::splat(1e30), Vec3::new(3e30, 0.0, 5e29)),
        vec![5e29, 7e29, 1e29],
    ));
    out.push((
        "tiny box".into(),
        tilted_box_scaled(1e-20),
        vec![2e-20, 2.1e-20],
    ));
    out
}

fn tilted_box_scaled(s: f64) -> Mesh {
    let b = tilted_box();
    Mesh::new(
        b.positions
            .iter()
            .map(|p| (p.as_dvec3() * s).as_vec3())
            .collect(),
        b.triangles,
    )
}

/// The clipped and capped mesh's integrals by Mirtich, about `origin`.
fn capped(mesh: &Mesh, level: f64) -> VolumeIntegrals {
    analytic::volume_integrals(&below_plane(mesh, level as f32))
}

/// Within `rel` of the largest integral of the whole body about `want`'s origin.
fn assert_close_for_body(
    what: &str,
    got: &VolumeIntegrals,
    want: &VolumeIntegrals,
    body: &Mesh,
    rel: f64,
) {
    let scale = largest(&analytic::volume_integrals(body).about(want.origin));
    let got = got.about(want.origin);
    for (k, (g, w)) in got.to_array().iter().zip(want.to_array()).enumerate() {
        assert!(
            (g - w).abs() <= rel * scale,
            "{what}: integral {k}: got {g}, want {w} (body scale {scale})\n{got:?}\n{want:?}"
        );
    }
}

#[test]
fn the_cap_adds_nothing_with_the_origin_on_the_plane_cpu() {
    for (name, mesh, planes) in cases() {
        let bounds = mesh.bounds();
        let c = ((bounds.min + bounds.max) / 2.0).as_dvec3();
        for level in planes {
            // The origin anywhere on the plane: the bounding-box centre's x, y, or elsewhere.
            for (ox, oy) in [
                (c.x, c.y),
                (c.x + 0.3 * (bounds.max.x - bounds.min.x) as f64, c.y),
            ] {
                let open = tetrahedron_sum_below(&mesh, level, ox, oy);
                let want = capped(&mesh, level);
                assert_close_for_body(
                    &format!("{name} below {level}: clipped, no cap vs clipped and capped"),
                    &open,
                    &want,
                    &mesh,
                    1e-6,
                );
            }
        }
    }
    // Off the plane the cap does count: the clipped surface without its cap, summed about a
    // point on the plane, is the solid; about a point above the plane it is not.
    let mesh = tilted_torus();
    let level = 1.0;
    let solid = capped(&mesh, level);
    let closed = below_plane(&mesh, level as f32);
    let on_plane = |t: &[u32; 3]| {
        t.iter()
            .all(|&v| closed.positions[v as usize].z == level as f32)
    };
    let open = Mesh::new(
        closed.positions.clone(),
        closed
            .triangles
            .iter()
            .filter(|t| !on_plane(t))
            .copied()
            .collect(),
    );
    assert!(open.triangles.len() < closed.triangles.len());
    let from_plane = tetrahedron_sum(&open, DVec3::new(0.2, 0.1, level));
    assert_integrals_close("open surface from the plane", &from_plane, &solid, 1e-6);
    let from_above = tetrahedron_sum(&open, DVec3::new(0.2, 0.1, level + 0.5));
    assert!(
        (from_above.v - solid.v).abs() > 0.01 * solid.v,
        "an origin off the plane needs the cap: {} vs {}",
        from_above.v,
        solid.v
    );
}

#[test]
fn below_a_plane_matches_the_cpu_mirror_and_the_capped_mesh() {
    let (ctx, compute) = compute_context();
    if !compute {
        eprintln!("skipped: the compute formulation needs OpenGL 4.3 (checked in below_4_3_...)");
        return;
    }
    ctx.set_checks(true);
    let mass = ComputeMass::new(&ctx).unwrap();
    for (name, mesh, planes) in cases() {
        let whole = mass.integrate(&[&mesh]).unwrap().integrals[0];
        for level in planes {
            let got = mass.integrate_below(&[&mesh], level).unwrap().integrals[0];
            let what = format!("{name} below {level}");
            let mirror = tetrahedron_sum_below(&mesh, level, got.origin.x, got.origin.y);
            let b = mesh.bounds();
            if level as f32 >= b.max.z {
                // Nothing clipped: the whole body, about its own centre.
                assert_eq!(got, whole, "{what}");
            } else if level as f32 <= b.min.z {
                assert_eq!(got.to_array(), [0.0; 10], "{what}");
            } else {
                assert_eq!(got.origin.z, level, "{what}: the origin is on the plane");
                assert_close_for_body(&format!("{what} vs CPU mirror"), &got, &mirror, &mesh, 1e-5);
            }
            assert_close_for_body(
                &format!("{what} vs capped"),
                &got,
                &capped(&mesh, level),
                &mesh,
                1e-5,
            );
        }
    }
}

#[test]
fn below_a_plane_every_body_in_one_pass() {
    let (ctx, compute) = compute_context();
    if !compute {
        eprintln!("skipped: the compute formulation needs OpenGL 4.3");
        return;
    }
    let cases = cases();
    let meshes: Vec<&Mesh> = cases.iter().map(|(_, m, _)| m).collect();
    // One plane for all: some bodies cut, some wholly below, some wholly above.
    let level = 1.0;
    let mass = ComputeMass::new(&ctx).unwrap();
    let all = mass.integrate_below(&meshes, level).unwrap();
    for (k, mesh) in meshes.iter().enumerate() {
        let alone = mass.integrate_below(&[mesh], level).unwrap().integrals[0];
        assert_close_for_body(
            &format!("body {k} among others vs alone"),
            &all.integrals[k],
            &alone,
            mesh,
            1e-6,
        );
        assert_close_for_body(
            &format!("body {k} vs capped"),
            &all.integrals[k],
            &capped(mesh, level),
            mesh,
            1e-5,
        );
    }
}

#[test]
fn below_a_plane_same_mass_properties_as_the_classic_path() {
    let (ctx, compute) = compute_context();
    if !compute {
        eprintln!("skipped: the compute formulation needs OpenGL 4.3");
        return;
    }
    let mesh = tilted_torus();
    let mass = ComputeMass::new(&ctx).unwrap();
    let classic = GpuMass::new(&ctx, 256).unwrap();
    for level in [1.0, 0.6, 1.5] {
        let now = mass.integrate_below(&[&mesh], level).unwrap().integrals[0];
        let then = classic.integrate(&mesh, Some(level), None).unwrap();
        assert!(then.peels >= 2);
        assert_close_for_body(
            &format!("compute vs classic below {level}"),
            &now,
            &then.integrals,
            &mesh,
            1e-3,
        );
        let a = MassProperties::from_integrals(&now, 1.0);
        let b = MassProperties::from_integrals(&then.integrals, 1.0);
        assert!(
            (a.volume - b.volume).abs() < 2e-3 * a.volume,
            "{} vs {}",
            a.volume,
            b.volume
        );
        assert!(
            (a.center_of_mass - b.center_of_mass).length() < 2e-3,
            "{a:?} vs {b:?}"
        );
    }
}

/// The chunking of the whole-body path (past the work-group limit, past what one storage
/// buffer holds) works the same with the plane: split and chunked runs equal the unsplit one
/// and the CPU.
#[test]
fn below_a_plane_past_the_dispatch_and_buffer_limits() {
    let (ctx, compute) = compute_context();
    if !compute {
        eprintln!("skipped: the compute formulation needs OpenGL 4.3");
        return;
    }
    ctx.set_checks(true);
    let big = transformed(
        &torus(1.0, 0.4, 128, 64),
        DQuat::from_rotation_y(0.3),
        DVec3::new(-2.0, 1.0, 0.9),
    );
    let meshes = [tilted_torus(), tilted_box(), big];
    let refs: Vec<&Mesh> = meshes.iter().collect();
    let level = 1.1;
    let mass = ComputeMass::new(&ctx).unwrap();
    let whole = mass.integrate_below(&refs, level).unwrap();
    ctx.set_work_group_limit(Some(3));
    let split = mass.integrate_below(&refs, level);
    ctx.set_work_group_limit(None);
    ctx.set_storage_buffer_limit(Some(1000 * 3 * 16 * meshes.len()));
    let chunked = mass.integrate_below(&refs, level);
    ctx.set_storage_buffer_limit(None);
    let (split, chunked) = (split.unwrap(), chunked.unwrap());
    for (k, mesh) in meshes.iter().enumerate() {
        let w = &whole.integrals[k];
        assert_close_for_body(
            &format!("body {k}: split vs whole"),
            &split.integrals[k],
            w,
            mesh,
            1e-6,
        );
        assert_close_for_body(
            &format!("body {k}: chunked vs whole"),
            &chunked.integrals[k],
            w,
            mesh,
            1e-6,
        );
        let cpu = tetrahedron_sum_below(mesh, level, w.origin.x, w.origin.y);
        assert_close_for_body(
            &format!("body {k}: chunked vs CPU"),
            &chunked.integrals[k],
            &cpu,
            mesh,
            1e-5,
        );
    }
}

#[test]
fn below_4_3_compute_below_is_a_clear_error_and_the_classic_below_runs() {
    let (ctx, compute) = compute_context();
    if compute {
        eprintln!("this renderer has OpenGL 4.3: the error path is checked on softpipe");
        return;
    }
    let err = ComputeMass::new(&ctx).err().unwrap().to_string();
    assert!(err.contains("needs OpenGL 4.3"), "{err}");
    let mesh = tilted_torus();
    let classic = GpuMass::new(&ctx, 64)
        .unwrap()
        .integrate(&mesh, Some(1.0), None)
        .unwrap();
    let want = capped(&mesh, 1.0);
    assert_close_for_body(
        "classic below at 64x64",
        &classic.integrals,
        &want,
        &mesh,
        0.05,
    );
}
