//! Paper 4's depth peeling at the period's 24-bit depth (`mass::peel_depth`), against the
//! CPU model of what a 24-bit peel keeps, beside the 32-bit float peels.
//!
//! Tolerances: a 24-bit peel keeps exactly the fragments a float peel keeps at every pixel
//! whose surface crossings lie two or more depth steps (2 x 2^-24 of the depth range) apart;
//! there the two paths draw the same fragments in the same order and their sums are equal.
//! Only pixels with two crossings closer than that can differ, and the CPU model counts them.

use classic_gpgpu::gl::{Rect, TextureFormat};
use classic_gpgpu::mass::framing::Framing;
use classic_gpgpu::mass::gpu::GpuMass;
use classic_gpgpu::mass::integrands::{Placement, Soup};
use classic_gpgpu::mass::peel::{Job, Peeler, PeelerOptions};
use classic_gpgpu::mass::peel_depth::{self, PeelDepth};
use classic_gpgpu::mass::{cpu_reference, VolumeIntegrals};
use classic_gpgpu::mesh::Mesh;
use common::context;
use glam::{DQuat, DVec3, Vec3};
use mass_shapes::{cuboid, torus, transformed, uv_sphere};

mod common;

mod mass_shapes;

mod mass_check;
use mass_check::assert_integrals_close;

fn shapes() -> Vec<(&'static str, Mesh)> {
    vec![
        (
            "tilted torus",
            transformed(
                &torus(1.0, 0.4, 48, 24),
                DQuat::from_rotation_x(0.6),
                DVec3::new(0.5, 0.0, 1.0),
            ),
        ),
        ("bumpy sphere", uv_sphere(16, 24, |p| 1.0 + 0.2 * p.x * p.y)),
        (
            // Turned, so that no edge runs along a row of pixel centres (where the CPU's
            // edge rule and the rasterizer's fp32 snapping may disagree by a whole row).
            "turned box",
            transformed(
                &cuboid(Vec3::new(1.0, 0.7, 0.4), Vec3::new(0.1, -0.2, 0.3)),
                DQuat::from_rotation_z(0.3) * DQuat::from_rotation_x(0.2),
                DVec3::ZERO,
            ),
        ),
    ]
}

/// The whole body and its part below two water levels: at 24 bits against the CPU model
/// (the GPU tolerance of the other mass tests, 1e-3 of the largest integral, which covers
/// the rasterizer's edge rule), and against the float peels, equal where no two crossings
/// are within two steps.
#[test]
fn depth24_peels_agree_with_the_cpu_model_and_the_float_peels() {
    let ctx = context();
    ctx.set_checks(true);
    let n = 32;
    let fixed = GpuMass::with_depth(&ctx, n, TextureFormat::Rgba32F, PeelDepth::Fixed24).unwrap();
    let float = GpuMass::with_depth(&ctx, n, TextureFormat::Rgba32F, PeelDepth::Float32).unwrap();
    assert_eq!(fixed.peeler().depth(), PeelDepth::Fixed24);
    for (name, mesh) in shapes() {
        for below in [None, Some(0.9), Some(0.2)] {
            let what = format!("{name}, below {below:?}");
            let got = fixed.integrate(&mesh, below, None).unwrap();
            let today = float.integrate(&mesh, below, None).unwrap();
            let model = cpu_reference::integrate_at(&mesh, &got.framing, below, PeelDepth::Fixed24);
            assert_integrals_close(&what, &got.integrals, &model, 1e-3);
            let close = cpu_reference::close_crossings(&mesh, &got.framing, below, 2.0);
            eprintln!(
                "{what}: {} peels at 24 bits, {} in float; {close} pixels with crossings \
                 within two steps",
                got.peels, today.peels
            );
            if close == 0 {
                assert_eq!(got.peels, today.peels, "{what}");
                assert_integrals_close(&what, &got.integrals, &today.integrals, 1e-9);
            }
        }
    }
}

/// The framing of the hand-placed test: the window [-1, 1]^2, heights [-1, 1], so the
/// window depth of height z is (1 - z) / 2 exactly.
fn unit_framing(n: u32) -> Framing {
    Framing {
        center: DVec3::ZERO,
        half_width: 1.0,
        half_depth: 1.0,
        resolution: n,
    }
}

/// A horizontal rectangle over `x` and `y` at height `z`, facing up (`up`) or down.
fn quad(mesh: &mut Mesh, x: (f32, f32), y: (f32, f32), z: f32, up: bool) {
    let base = mesh.positions.len() as u32;
    mesh.positions.extend([
        Vec3::new(x.0, y.0, z),
        Vec3::new(x.1, y.0, z),
        Vec3::new(x.1, y.1, z),
        Vec3::new(x.0, y.1, z),
    ]);
    let (a, b) = if up { (1, 2) } else { (2, 1) };
    mesh.triangles.push([base, base + a, base + b]);
    let (c, d) = if up { (2, 3) } else { (3, 2) };
    mesh.triangles.push([base, base + c, base + d]);
}

/// The height whose window depth is `depth` in [`unit_framing`].
fn height_at(depth: f64) -> f32 {
    let z = 1.0 - 2.0 * depth;
    assert_eq!(z as f32 as f64, z, "height {z} not exact in fp32");
    z as f32
}

/// Peels `mesh` in one tile of [`unit_framing`] with peel depths `depth`.
fn peel(
    ctx: &classic_gpgpu::gl::Context,
    mesh: &Mesh,
    depth: PeelDepth,
) -> (VolumeIntegrals, usize) {
    let n = 16;
    let framing = unit_framing(n);
    let options = PeelerOptions {
        depth: Some(depth),
        ..PeelerOptions::default()
    };
    let peeler = Peeler::with_options(ctx, n, n, None, options).unwrap();
    let soup = Soup::new(ctx).unwrap();
    let tile = Rect::sized(n, n);
    let world: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let place = Placement {
        framing,
        tile,
        target: (n, n),
    };
    soup.push_body(&mesh.triangles, &world, &place, |_| true);
    soup.upload().unwrap();
    let job = Job {
        body: "plates",
        group: 0,
        framing,
        tile,
    };
    let batch = peeler.run(&soup, &[job], None, None).unwrap();
    (batch.integrals[0], batch.peels)
}

/// Two thin plates, each a face up over a face down (the upper face drawn first). Plate A's
/// faces are half a 24-bit step apart: fp32 holds both depths ((2m - 1) 2^-25 and
/// 2m 2^-25, near depth 0.375, where fp32 depths are 2^-25 apart), the 24-bit buffer
/// cannot (both fall in step m - 1). Plate B's are three steps apart.
///
/// Float depth peels all four faces: each plate adds its thickness. At 24 bits plate A is
/// one layer: its upper face is peeled and the lower one lost with it, so plate A adds its
/// upper face's `sgn(n_z) z` alone, which the CPU model predicts; plate B is unchanged.
#[test]
fn two_surfaces_within_one_depth_step_are_one_layer() {
    let ctx = context();
    ctx.set_checks(true);
    let m = (0.375 * 2f64.powi(24)) as u64;
    let step = 2f64.powi(-24);
    let (a_top, a_bottom) = ((2 * m - 1) as f64 * step / 2.0, (2 * m) as f64 * step / 2.0);
    let b_top = (0.3 / step).round() * step;
    let b_bottom = b_top + 3.0 * step;
    let mut mesh = Mesh {
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    quad(&mut mesh, (0.1, 0.9), (-0.8, 0.8), height_at(a_top), true);
    quad(
        &mut mesh,
        (0.1, 0.9),
        (-0.8, 0.8),
        height_at(a_bottom),
        false,
    );
    quad(&mut mesh, (-0.9, -0.1), (-0.8, 0.8), height_at(b_top), true);
    quad(
        &mut mesh,
        (-0.9, -0.1),
        (-0.8, 0.8),
        height_at(b_bottom),
        false,
    );
    let framing = unit_framing(16);
    assert_eq!(
        peel_depth::step_24(a_top),
        peel_depth::step_24(a_bottom),
        "plate A must lie in one step"
    );

    let (float, float_peels) = peel(&ctx, &mesh, PeelDepth::Float32);
    let (fixed, fixed_peels) = peel(&ctx, &mesh, PeelDepth::Fixed24);
    let model_float = cpu_reference::integrate_at(&mesh, &framing, None, PeelDepth::Float32);
    let model_fixed = cpu_reference::integrate_at(&mesh, &framing, None, PeelDepth::Fixed24);
    eprintln!(
        "volume: float peels {} ({float_peels} peels), 24-bit {} ({fixed_peels} peels); \
         models {} and {}",
        float.v, fixed.v, model_float.v, model_fixed.v
    );
    // The sums hold a few hundred fp32 terms below 0.3 in magnitude: 1e-5 absolute.
    assert_abs_close("float peels", &float, &model_float, 1e-5);
    assert_abs_close("24-bit peels", &fixed, &model_fixed, 1e-5);
    // Plate A's lost lower face: z = 0.25 exactly, over 6 x 12 pixel centres of 1/64.
    let lost = 0.25 * (6.0 * 12.0) / 64.0;
    assert!(
        (model_fixed.v - model_float.v - lost).abs() < 1e-9,
        "{} {}",
        model_fixed.v,
        model_float.v
    );
    assert!(
        (fixed.v - float.v - lost).abs() < 1e-5,
        "{} {}",
        fixed.v,
        float.v
    );
    assert_eq!(float_peels, 2);
    assert_eq!(fixed_peels, 2, "plate B still needs two peels");
}

/// Every one of the ten integrals within `tol` of the reference's.
fn assert_abs_close(what: &str, got: &VolumeIntegrals, want: &VolumeIntegrals, tol: f64) {
    for (k, (g, w)) in got.to_array().iter().zip(want.to_array()).enumerate() {
        assert!(
            (g - w).abs() <= tol,
            "{what}: integral {k}: got {g}, want {w}"
        );
    }
}
