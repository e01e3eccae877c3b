//! CPU side of paper 4: Mirtich's analytic algorithm against closed forms and an
//! independent tetrahedron sum, mesh clipping below a plane, rigid-body integration.

use classic_gpgpu::mass::buoyancy::forces::{self, Submerged, Water};
use classic_gpgpu::mass::buoyancy::rigid_body::{RigidBody, Wrench};
use classic_gpgpu::mass::{analytic, clip, closed_form, surface, MassProperties, VolumeIntegrals};
use classic_gpgpu::mesh::Mesh;
use glam::{DMat3, DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed, uv_sphere};
use rand::{Rng, SeedableRng};

mod mass_shapes;
use std::f64::consts::PI;

fn rng() -> rand_chacha::ChaCha8Rng {
    rand_chacha::ChaCha8Rng::seed_from_u64(4)
}

/// Independent reference: signed tetrahedra from the origin, with the exact moments of a
/// tetrahedron `∫ x_i x_j = V/20 (Σ_k a_ki a_kj + (Σ_k a_ki)(Σ_k a_kj))` (k over 4 corners).
fn tetrahedron_sum(mesh: &Mesh) -> VolumeIntegrals {
    let mut out = VolumeIntegrals::default();
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t).map(|p| p.as_dvec3());
        let v = a.dot(b.cross(c)) / 6.0;
        let s = a + b + c; // the fourth corner is the origin
        let m =
            |i: usize, j: usize| v / 20.0 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
        out += VolumeIntegrals {
            origin: DVec3::ZERO,
            v,
            x: v * s.x / 4.0,
            y: v * s.y / 4.0,
            z: v * s.z / 4.0,
            xx: m(0, 0),
            yy: m(1, 1),
            zz: m(2, 2),
            xy: m(0, 1),
            yz: m(1, 2),
            zx: m(2, 0),
        };
    }
    out
}

fn assert_close(what: &str, got: f64, want: f64, rel: f64, scale: f64) {
    let err = (got - want).abs() / scale.max(want.abs());
    assert!(
        err <= rel,
        "{what}: got {got}, want {want} (relative error {err:e} > {rel:e})"
    );
}

fn assert_mat_close(what: &str, got: DMat3, want: DMat3, rel: f64) {
    let scale = want
        .to_cols_array()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (g, w) in got.to_cols_array().iter().zip(want.to_cols_array()) {
        assert_close(what, *g, w, rel, scale);
    }
}

/// f32 vertex coordinates carry ~1e-7 relative error into every moment; 1e-5 leaves room.
const MESH_ROUNDING: f64 = 1e-5;

#[test]
fn analytic_box_equals_closed_form() {
    let size = DVec3::new(2.0, 3.0, 0.5);
    let center = DVec3::new(1.5, -2.0, 0.25);
    let mp = MassProperties::from_integrals(
        &analytic::volume_integrals(&cuboid(size.as_vec3(), center.as_vec3())),
        2.5,
    );
    let want = closed_form::cuboid(size, center, 2.5);
    assert_close("volume", mp.volume, want.volume, MESH_ROUNDING, 0.0);
    assert_close("mass", mp.mass, want.mass, MESH_ROUNDING, 0.0);
    assert!(
        (mp.center_of_mass - center).length() < 1e-5,
        "{:?}",
        mp.center_of_mass
    );
    assert_mat_close("inertia", mp.inertia, want.inertia, MESH_ROUNDING);
}

#[test]
fn analytic_fine_sphere_approaches_closed_form() {
    // The inscribed 128x256 polyhedron falls short of the sphere by ~ (pi/128)^2 / 2... of
    // order 3e-4 relative in volume and 6e-4 in inertia; 1e-3 states that bound.
    let r = 1.5;
    let mesh = uv_sphere(128, 256, |_| r as f32);
    let mp = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
    let want = closed_form::sphere(r, DVec3::ZERO, 1.0);
    assert_close("volume", mp.volume, 4.0 / 3.0 * PI * r * r * r, 1e-3, 0.0);
    assert!(mp.center_of_mass.length() < 1e-5);
    assert_mat_close("inertia", mp.inertia, want.inertia, 1e-3);
}

#[test]
fn analytic_matches_tetrahedron_sum_on_irregular_meshes() {
    let mut rng = rng();
    for _ in 0..5 {
        let c: [f32; 6] = std::array::from_fn(|_| rng.gen_range(-0.4..0.4));
        let mesh = uv_sphere(9, 13, |d| {
            1.0 + c[0] * d.x + c[1] * d.y * d.z + c[2] * (3.0 * d.x).sin() + c[3] * d.z * d.z
        });
        let moved = transformed(
            &mesh,
            DQuat::from_euler(glam::EulerRot::XYZ, c[4] as f64, 1.0, c[5] as f64),
            DVec3::new(0.3, -1.0, 2.0),
        );
        let got = analytic::volume_integrals(&moved).world().to_array();
        let want = tetrahedron_sum(&moved).to_array();
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (g, w) in got.iter().zip(want) {
            assert_close("integral", *g, w, 1e-10, scale);
        }
    }
}

#[test]
fn analytic_is_invariant_under_rigid_motion() {
    let mesh = torus(1.0, 0.3, 48, 24);
    let base = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 3.0);
    let mut rng = rng();
    for _ in 0..4 {
        let q = DQuat::from_scaled_axis(DVec3::new(
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
        ));
        let t = DVec3::new(rng.gen_range(-5.0..5.0), rng.gen_range(-5.0..5.0), 3.0);
        let moved = MassProperties::from_integrals(
            &analytic::volume_integrals(&transformed(&mesh, q, t)),
            3.0,
        );
        let r = DMat3::from_quat(q);
        assert_close("volume", moved.volume, base.volume, MESH_ROUNDING, 0.0);
        assert!((moved.center_of_mass - (q * base.center_of_mass + t)).length() < 1e-5);
        // The translation by up to ~6 units costs a few digits in the parallel-axis shift.
        assert_mat_close(
            "inertia",
            moved.inertia,
            r * base.inertia * r.transpose(),
            1e-4,
        );
    }
}

#[test]
fn analytic_torus_approaches_closed_form() {
    let mp = MassProperties::from_integrals(
        &analytic::volume_integrals(&torus(2.0, 0.5, 256, 128)),
        1.0,
    );
    let want = closed_form::torus(2.0, 0.5, DVec3::ZERO, 1.0);
    assert_close("volume", mp.volume, want.volume, 1e-3, 0.0);
    assert_mat_close("inertia", mp.inertia, want.inertia, 1e-3);
}

#[test]
fn inverted_mesh_gives_negative_volume() {
    let mut mesh = cuboid(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO);
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    let mp = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
    assert_close("volume", mp.volume, -6.0, MESH_ROUNDING, 0.0);
    assert!(surface::check(&mesh).is_closed());
}

#[test]
fn open_mesh_is_reported_as_open() {
    let mut mesh = uv_sphere(8, 12, |_| 1.0);
    assert!(surface::check(&mesh).is_closed());
    mesh.triangles.truncate(mesh.triangles.len() - 3);
    let report = surface::check(&mesh);
    assert!(!report.is_closed());
    assert!(report.open_edges >= 3, "{report:?}");
}

#[test]
fn flipped_triangle_is_reported_as_inconsistent() {
    let mut mesh = cuboid(Vec3::ONE, Vec3::ZERO);
    mesh.triangles[0].swap(1, 2);
    let report = surface::check(&mesh);
    assert!(!report.is_closed());
    assert!(report.inconsistent_edges > 0, "{report:?}");
}

fn submerged(mesh: &Mesh, level: f32) -> (f64, DVec3, Mesh) {
    let below = clip::below_plane(mesh, level);
    let i = analytic::volume_integrals(&below);
    let c = if i.v > 0.0 { i.centroid() } else { DVec3::ZERO };
    (i.v, c, below)
}

#[test]
fn box_below_plane_matches_closed_form() {
    let size = DVec3::new(2.0, 1.5, 1.0);
    let center = DVec3::new(0.5, 0.25, 0.0);
    let mesh = transformed(&cuboid(size.as_vec3(), Vec3::ZERO), DQuat::IDENTITY, center);
    for level in [-0.7, -0.5, -0.3, 0.0, 0.123, 0.49, 0.5, 0.8] {
        let (v, c, below) = submerged(&mesh, level as f32);
        let (want_v, want_c) = closed_form::submerged_cuboid(size, center, level);
        assert_close("volume", v, want_v, MESH_ROUNDING, size.x * size.y * size.z);
        if want_v > 0.0 {
            assert!(
                (c - want_c).length() < 1e-5,
                "level {level}: {c} vs {want_c}"
            );
        }
        // A body just touching the plane leaves a zero-volume sliver, closed only as a chain.
        if want_v > 0.0 {
            assert!(surface::check(&below).is_closed(), "level {level}");
        }
    }
}

#[test]
fn tilted_box_below_plane_matches_tetrahedron_sum_and_is_closed() {
    let mesh = transformed(
        &cuboid(Vec3::new(2.0, 1.0, 0.5), Vec3::ZERO),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.4, -0.3, 0.9),
        DVec3::ZERO,
    );
    for level in [-0.5f32, -0.1, 0.0, 0.3] {
        let below = clip::below_plane(&mesh, level);
        assert!(surface::check(&below).is_closed(), "level {level}");
        let got = analytic::volume_integrals(&below).world().to_array();
        let want = tetrahedron_sum(&below).to_array();
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-9, "{g} vs {w}");
        }
        assert!(got[0] > 0.0 && got[0] < 1.0);
    }
}

#[test]
fn sphere_below_plane_matches_cap_closed_form() {
    let r = 1.0;
    let mesh = uv_sphere(128, 256, |_| r as f32);
    for level in [-0.9, -0.5, 0.0, 0.3, 0.75] {
        let (v, c, below) = submerged(&mesh, level as f32);
        let (want_v, want_c) = closed_form::submerged_sphere(r, DVec3::ZERO, level);
        // The polyhedron is inscribed: ~1e-3 relative, as for the whole sphere.
        assert_close("cap volume", v, want_v, 2e-3, 0.0);
        assert!(
            (c.z - want_c.z).abs() < 2e-3,
            "level {level}: {} vs {}",
            c.z,
            want_c.z
        );
        assert!(surface::check(&below).is_closed());
    }
}

#[test]
fn torus_cut_through_its_hole_keeps_half_its_volume() {
    // The cap of a torus cut at its equator is an annulus: the fan over the cut segments
    // must cancel over the hole.
    let mesh = torus(1.0, 0.4, 64, 32);
    let whole = analytic::volume_integrals(&mesh).v;
    let (v, c, below) = submerged(&mesh, 0.0);
    assert_close("half torus", v, whole / 2.0, 1e-6, 0.0);
    assert!(c.x.abs() < 1e-6 && c.y.abs() < 1e-6);
    // Centroid of a half torus: 4r / (3 pi) below the cut for the tube section.
    assert_close("centroid", -c.z, 4.0 * 0.4 / (3.0 * PI), 1e-2, 0.0);
    assert!(surface::check(&below).is_closed());
}

#[test]
fn rigid_body_falls_with_gravity_exactly() {
    // Semi-implicit Euler: z_n = -g dt^2 n(n+1)/2, exactly.
    let mut body = RigidBody::at_rest(2.0, DMat3::IDENTITY, DVec3::ZERO, DQuat::IDENTITY);
    let water = Water::default();
    let dt = 0.01;
    for _ in 0..100 {
        let w = forces::wrench(&body, 1.0, Submerged::default(), &water);
        body.step(w, dt);
    }
    let want = -water.gravity * dt * dt * 100.0 * 101.0 / 2.0;
    assert!(
        (body.position.z - want).abs() < 1e-9,
        "{} vs {want}",
        body.position.z
    );
}

#[test]
fn torque_free_spin_conserves_energy_and_momentum() {
    let inertia = DMat3::from_diagonal(DVec3::new(1.0, 2.0, 3.0));
    let mut body = RigidBody::at_rest(1.0, inertia, DVec3::ZERO, DQuat::IDENTITY);
    body.angular_velocity = DVec3::new(0.1, 2.0, 0.1);
    let e0 = body.kinetic_energy();
    let l0 = body.world_inertia() * body.angular_velocity;
    for _ in 0..1000 {
        body.step(Wrench::default(), 1e-3);
    }
    let l1 = body.world_inertia() * body.angular_velocity;
    // First-order method over 1 s of an (intermediate-axis-near) spin: a few per cent.
    assert!((body.kinetic_energy() - e0).abs() / e0 < 0.05);
    assert!((l1 - l0).length() / l0.length() < 0.05);
    assert!((body.orientation.length() - 1.0).abs() < 1e-12);
}

#[test]
fn off_centre_force_makes_torque() {
    let body = RigidBody::at_rest(
        1.0,
        DMat3::IDENTITY,
        DVec3::new(1.0, 0.0, 0.0),
        DQuat::IDENTITY,
    );
    let w = body.force_at(DVec3::Z, DVec3::new(2.0, 0.0, 0.0));
    assert_eq!(w.torque, DVec3::new(0.0, -1.0, 0.0));
}

mod pixel_sums {
    use super::*;
    use classic_gpgpu::mass::{cpu_reference, framing::Framing};

    fn relative_errors(mesh: &Mesh, n: u32) -> [f64; 4] {
        let f = Framing::fit(mesh, n).unwrap();
        let got = MassProperties::from_integrals(&cpu_reference::integrate(mesh, &f, None), 1.0);
        let want = MassProperties::from_integrals(&analytic::volume_integrals(mesh), 1.0);
        got.relative_errors(&want)
    }

    #[test]
    fn pixel_sums_converge_to_the_analytic_result() {
        let shapes = [
            (
                "torus",
                transformed(
                    &torus(1.0, 0.35, 48, 24),
                    DQuat::from_rotation_x(0.5),
                    DVec3::new(3.0, 1.0, -2.0),
                ),
            ),
            ("sphere", uv_sphere(24, 48, |_| 1.0)),
        ];
        for (name, mesh) in &shapes {
            let coarse = relative_errors(mesh, 32);
            let fine = relative_errors(mesh, 256);
            eprintln!("{name}: 32 -> {coarse:?}, 256 -> {fine:?}");
            assert!(coarse.iter().all(|e| *e < 0.05), "{name} at 32: {coarse:?}");
            assert!(fine.iter().all(|e| *e < 0.005), "{name} at 256: {fine:?}");
        }
    }

    #[test]
    fn pixel_sums_below_water_match_the_clipped_mesh() {
        let mesh = transformed(
            &torus(1.0, 0.35, 48, 24),
            DQuat::from_rotation_x(0.7),
            DVec3::ZERO,
        );
        for level in [-0.5f32, -0.1, 0.2] {
            let f = Framing::fit(&mesh, 256).unwrap();
            let got = cpu_reference::integrate(&mesh, &f, Some(level as f64));
            let want = analytic::volume_integrals(&clip::below_plane(&mesh, level));
            let (gc, wc) = (got.centroid(), want.centroid());
            eprintln!("level {level}: V {} vs {}, c {gc} vs {wc}", got.v, want.v);
            assert!((got.v - want.v).abs() / want.v < 0.005);
            assert!((gc - wc).length() < 0.005);
        }
    }
}

/// The pixel-centre cull never drops a triangle that holds a pixel centre.
#[test]
fn pixel_centre_cull_keeps_every_triangle_that_makes_a_fragment() {
    use classic_gpgpu::mass::framing::Framing;
    let framing = Framing::fit_box(DVec3::splat(-1.0), DVec3::splat(1.0), 32).unwrap();
    let mut rng = rng();
    let (mut kept, mut dropped) = (0, 0);
    for _ in 0..20_000 {
        let c = DVec3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 0.0);
        let size = rng.gen_range(0.001..0.12);
        let corners: [DVec3; 3] = std::array::from_fn(|_| {
            c + DVec3::new(
                rng.gen_range(-size..size),
                rng.gen_range(-size..size),
                rng.gen_range(-1.0..1.0),
            )
        });
        let holds_centre = (0..32).any(|j| {
            (0..32).any(|i| {
                let (x, y) = framing.pixel_center(i, j);
                let p = glam::DVec2::new(x, y) + framing.center.truncate();
                let [a, b, c] = corners.map(|v| v.truncate());
                let d = |u: glam::DVec2, v: glam::DVec2| (v - u).perp_dot(p - u);
                let (d0, d1, d2) = (d(a, b), d(b, c), d(c, a));
                (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
            })
        });
        let keep = framing.may_cover_pixel_centre(corners);
        assert!(
            keep || !holds_centre,
            "dropped a triangle holding a pixel centre: {corners:?}"
        );
        if keep {
            kept += 1
        } else {
            dropped += 1
        }
    }
    assert!(
        dropped > 1000 && kept > 1000,
        "kept {kept}, dropped {dropped}"
    );
}

/// A cuboid whose corners are exact in f32 however far it lies (sides and offsets with few
/// significant bits), so the mesh itself is the same solid at every offset.
fn far_cuboid(size: Vec3, offset: DVec3) -> Mesh {
    let mesh = cuboid(size, Vec3::ZERO);
    let moved = transformed(&mesh, DQuat::IDENTITY, offset);
    for (p, q) in moved.positions.iter().zip(&mesh.positions) {
        assert_eq!(p.as_dvec3() - offset, q.as_dvec3(), "not exact in f32");
    }
    moved
}

/// Far from the world origin the analytic reference keeps the body's own moments: before
/// it integrated about its bounding-box centre, a unit cube 10^6 away got Ixx = 0 and
/// Ixy = 32 (the projection integrals' products of coordinates, ~10^24, cancelled in f64),
/// and the parallel-axis shift back to the centre of mass cancelled 10^12 against 10^12.
#[test]
fn analytic_is_exact_far_from_the_origin() {
    for (size, offset) in [
        (DVec3::new(1.0, 2.0, 0.5), DVec3::new(1e6, 0.0, 0.0)),
        (DVec3::new(1.0, 2.0, 0.5), DVec3::new(1e6, -3e6, 2e6)),
        (DVec3::new(256.0, 512.0, 128.0), DVec3::new(1e8, 2e8, -3e8)),
    ] {
        let want = closed_form::cuboid(size, offset, 1.0);
        let far = MassProperties::from_integrals(
            &analytic::volume_integrals(&far_cuboid(size.as_vec3(), offset)),
            1.0,
        );
        let what = format!("{size} at {offset}");
        assert_close(&what, far.volume, want.volume, 1e-12, 0.0);
        assert!((far.center_of_mass - offset).length() < 1e-12 * offset.length());
        // Every entry within 1e-12 of the largest (the products are exactly zero).
        let err = (far.inertia - want.inertia).to_cols_array();
        let worst = err.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        assert!(
            worst <= 1e-12 * want.inertia.x_axis.x,
            "{what}: inertia {:?} vs {:?}",
            far.inertia,
            want.inertia
        );
    }
}

/// A vertex of a cube pulled out to 10^38 makes a needle of volume ~3.3e37 whose faces
/// are slivers 10^38 long and 1 wide. The analytic reference keeps them (it once dropped
/// every face whose area was small next to the square of its distance from the origin,
/// and answered 0.5) and agrees with the signed tetrahedra.
#[test]
fn analytic_keeps_needle_faces_at_extreme_coordinates() {
    for far in [1e20f32, 1e30, 1e38] {
        let mut mesh = cuboid(Vec3::ONE, Vec3::ZERO);
        let corner = mesh
            .positions
            .iter()
            .position(|p| *p == Vec3::splat(0.5))
            .unwrap();
        mesh.positions[corner] = Vec3::new(far, 0.5, 0.5);
        let got = analytic::volume_integrals(&mesh);
        let want = tetrahedron_sum(&mesh);
        assert!(want.v > 0.3 * far as f64, "{}", want.v);
        assert_close(&format!("volume at {far}"), got.v, want.v, 1e-12, 0.0);
        let (gc, wc) = (got.centroid(), want.centroid());
        assert!(
            (gc - wc).length() <= 1e-12 * far as f64,
            "centroid at {far}: {gc} vs {wc}"
        );
    }
}
