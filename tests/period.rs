//! The period GPUs' limits as a checked budget (`gl::period`): each limit of the GeForce 7800
//! GTX and the RADEON 9700 PRO refused with the limit named, what fits still drawn right, and
//! the fp16 storage the G70 allowed for blending and filtering against a CPU model of it.

use classic_gpgpu::gl::period::{self, round_to_f16, round_to_f16_toward_zero};
use classic_gpgpu::gl::{
    Blend, DrawState, Filter, Framebuffer, GlError, Primitive, Program, Rect, ShaderSource,
    Texture, TextureFormat,
};
use classic_gpgpu::shader;
use common::context;

mod common;

const CONSTANT: ShaderSource<'static> = shader!("glsl/test/constant.frag");

fn g70() -> &'static classic_gpgpu::gl::PeriodGpu {
    period::for_paper(1)
}

fn r300() -> &'static classic_gpgpu::gl::PeriodGpu {
    period::for_paper(3)
}

/// The error's text, which must name the GPU and the limit.
fn refused<T>(result: Result<T, GlError>, gpu: &str, limit: &str) -> String {
    let Err(e) = result else {
        panic!("expected {gpu} to refuse ({limit})")
    };
    let text = e.to_string();
    assert!(text.contains(gpu), "{text}");
    assert!(text.contains(limit), "{text}");
    text
}

#[test]
fn table_loads_every_value_has_a_source() {
    assert_eq!(g70().name, "GeForce 7800 GTX");
    assert_eq!(period::for_paper(2).key, "g70");
    assert_eq!(period::for_paper(4).key, "g70");
    assert_eq!(r300().name, "ATI RADEON 9700 PRO");
    assert!(period::try_for_paper(5).is_none());
    assert_eq!(g70().max_texture_size.value, 4096);
    assert_eq!(r300().max_texture_size.value, 2048);
    assert_eq!(g70().fragment_float_bits.value, 32);
    assert_eq!(r300().fragment_float_bits.value, 24);
    for gpu in period::all() {
        let rows = gpu.limits();
        assert_eq!(rows.len(), 10, "{}", gpu.name);
        for row in rows {
            assert!(
                row.source.len() > 20,
                "{} {}: no source",
                gpu.name,
                row.limit
            );
            // An unconfirmed value says so in its source line.
            if !row.sourced {
                let s = row.source.to_lowercase();
                assert!(
                    s.contains("not found in the sources searched"),
                    "{} {}: {}",
                    gpu.name,
                    row.limit,
                    row.source
                );
            }
        }
    }
    // The values the papers state are quoted from them.
    assert!(g70().max_texture_size.source.contains("4096x4096"));
    assert!(r300().max_texture_size.source.contains("is 2048"));
}

#[test]
fn texture_over_the_period_size_is_refused() {
    let ctx = context();
    ctx.set_period(Some(g70()));
    Texture::new_2d(&ctx, 4096, 1, TextureFormat::R32F).unwrap();
    let text = refused(
        Texture::new_2d(&ctx, 4097, 1, TextureFormat::R32F),
        "GeForce 7800 GTX",
        "max_texture_size",
    );
    assert!(text.contains("4097x1"), "{text}");
    ctx.set_period(Some(r300()));
    Texture::new_1d(&ctx, 2048, TextureFormat::Rgba32F).unwrap();
    refused(
        Texture::new_1d(&ctx, 2049, TextureFormat::Rgba32F),
        "ATI RADEON 9700 PRO",
        "max_texture_size",
    );
    // Today's limits alone again.
    ctx.set_period(None);
    Texture::new_1d(&ctx, 2049, TextureFormat::Rgba32F).unwrap();
}

#[test]
fn formats_the_chip_did_not_have_are_refused() {
    let ctx = context();
    ctx.set_period(Some(g70()));
    let text = refused(
        Texture::new_2d(&ctx, 8, 8, TextureFormat::Depth32F),
        "GeForce 7800 GTX",
        "texture_formats",
    );
    assert!(text.contains("DEPTH_COMPONENT32F"), "{text}");
    refused(
        Texture::new_2d(&ctx, 8, 8, TextureFormat::Rgba32Ui),
        "GeForce 7800 GTX",
        "texture_formats",
    );
    Texture::new_2d(&ctx, 8, 8, TextureFormat::Depth24Stencil8).unwrap();
    Texture::new_2d(&ctx, 8, 8, TextureFormat::Rgba16F).unwrap();
    // The G70's texture unit had no two-component fp32 and no one-component fp16 format
    // (nouveau's NV40 format table); the R300's had both.
    for format in [TextureFormat::Rg32F, TextureFormat::R16F] {
        ctx.set_period(Some(g70()));
        let text = refused(
            Texture::new_2d(&ctx, 8, 8, format),
            "GeForce 7800 GTX",
            "texture_formats",
        );
        assert!(text.contains(format.name()), "{text}");
        ctx.set_period(Some(r300()));
        Texture::new_2d(&ctx, 8, 8, format).unwrap();
    }
}

#[test]
fn a_fifth_render_target_is_refused() {
    let ctx = context();
    let targets: Vec<Texture> = (0..5)
        .map(|_| Texture::new_2d(&ctx, 4, 4, TextureFormat::R32F).unwrap())
        .collect();
    let all: Vec<&Texture> = targets.iter().collect();
    ctx.set_period(Some(g70()));
    Framebuffer::new(&ctx, "four", &all[..4], None).unwrap();
    let text = refused(
        Framebuffer::new(&ctx, "five", &all, None),
        "GeForce 7800 GTX",
        "max_draw_buffers",
    );
    assert!(text.contains("5 render targets"), "{text}");
    // The R300 also wrote four at most.
    ctx.set_period(Some(r300()));
    Framebuffer::new(&ctx, "four", &all[..4], None).unwrap();
    refused(
        Framebuffer::new(&ctx, "five", &all, None),
        "ATI RADEON 9700 PRO",
        "max_draw_buffers",
    );
}

/// Adds `values` one after another into a 1x1 target of `format` by blending.
fn blend_sum(
    ctx: &classic_gpgpu::gl::Context,
    format: TextureFormat,
    values: &[f32],
) -> Result<f32, GlError> {
    let target = Texture::new_2d(ctx, 1, 1, format)?;
    let fb = Framebuffer::new(ctx, "sum", &[&target], None)?;
    let program = Program::rect(ctx, &[CONSTANT])?;
    for &v in values {
        let mut pass = fb.pass(&program, "blend a value")?;
        pass.state(DrawState {
            blend: Some(Blend::Add),
            ..DrawState::default()
        })
        .uniform("u_colour", glam::Vec4::splat(v));
        pass.draw_full()?;
    }
    Ok(fb.read_f32(0, Rect::sized(1, 1))?[0])
}

#[test]
fn fp32_blending_is_refused_and_fp16_blending_rounds_each_sum() {
    let ctx = context();
    ctx.set_period(Some(g70()));
    let text = refused(
        blend_sum(&ctx, TextureFormat::Rgba32F, &[1.0]),
        "GeForce 7800 GTX",
        "float_blending",
    );
    assert!(
        text.contains("32-bit float render target (RGBA32F)"),
        "{text}"
    );
    // fp16 blending fits: each addition is rounded to half precision. GL leaves the rounding
    // to the implementation, so the CPU models both (to nearest, toward zero): the GPU's sum
    // lies between them, give or take one fp16 step of the sum (2^-10 relative) for a
    // blender that adds in more precision before it stores.
    let values: Vec<f32> = (0..40).map(|i| 0.1 + 0.37 * i as f32).collect();
    let gpu = blend_sum(&ctx, TextureFormat::Rgba16F, &values).unwrap();
    let model = |round: fn(f32) -> f32| values.iter().fold(0.0f32, |sum, &v| round(sum + round(v)));
    let (nearest, toward_zero) = (model(round_to_f16), model(round_to_f16_toward_zero));
    let step = 2f32.powi(-10) * nearest.abs();
    assert!(
        gpu >= toward_zero - step && gpu <= nearest + step,
        "gpu {gpu}, CPU models {toward_zero} (toward zero) .. {nearest} (nearest)"
    );
    // And fp16 loses what fp32 keeps: the exact sum is 328.6, not a multiple of 0.25.
    let exact: f32 = values.iter().sum();
    assert!((gpu - exact).abs() > 0.01, "gpu {gpu} exact {exact}");
    // Each of the 40 additions is off by at most one step of the running sum (0.25 above 256).
    assert!(
        (gpu - exact).abs() <= 40.0 * 0.25,
        "gpu {gpu} exact {exact}"
    );
    // The R300 blended no float target at all.
    ctx.set_period(Some(r300()));
    refused(
        blend_sum(&ctx, TextureFormat::Rgba16F, &[1.0]),
        "ATI RADEON 9700 PRO",
        "float_blending",
    );
}

/// Samples `texture` at `uvs` (up to 8) with its filter.
fn sample(
    ctx: &classic_gpgpu::gl::Context,
    texture: &Texture,
    uvs: &[glam::Vec2],
) -> Result<Vec<f32>, GlError> {
    let out = Texture::new_2d(ctx, uvs.len() as u32, 1, TextureFormat::Rgba32F)?;
    let fb = Framebuffer::new(ctx, "samples", &[&out], None)?;
    let program = Program::rect(ctx, &[shader!("glsl/test/sample_2d.frag")])?;
    let mut pass = fb.pass(&program, "sample a float texture")?;
    pass.texture("u_source", texture);
    for (i, &uv) in uvs.iter().enumerate() {
        pass.uniform(&format!("u_uv[{i}]"), uv);
    }
    pass.draw_full()?;
    fb.read_f32(0, Rect::sized(uvs.len() as u32, 1))
}

#[test]
fn fp32_linear_filtering_is_refused_and_fp16_filtering_matches_the_cpu() {
    let ctx = context();
    let (w, h) = (4u32, 4u32);
    let data: Vec<f32> = (0..w * h * 4)
        .map(|i| (i as f32 * 0.731).sin() * 3.0)
        .collect();
    let fp32 = Texture::from_f32(&ctx, w, h, TextureFormat::Rgba32F, &data).unwrap();
    let fp16 = Texture::from_f32(&ctx, w, h, TextureFormat::Rgba16F, &data).unwrap();
    fp32.set_filter(Filter::Linear);
    fp16.set_filter(Filter::Linear);
    ctx.set_period(Some(g70()));
    let uvs = [
        glam::Vec2::new(0.3, 0.45),
        glam::Vec2::new(0.5, 0.5),
        glam::Vec2::new(0.71, 0.2),
    ];
    let text = refused(
        sample(&ctx, &fp32, &uvs),
        "GeForce 7800 GTX",
        "float_filtering",
    );
    assert!(text.contains("32-bit float texture (RGBA32F"), "{text}");
    // Nearest reads of fp32 fit.
    fp32.set_filter(Filter::Nearest);
    sample(&ctx, &fp32, &uvs).unwrap();
    let gpu = sample(&ctx, &fp16, &uvs).unwrap();
    // CPU: bilinear interpolation of the texels as stored (rounded to fp16).
    let texel = |x: i32, y: i32, c: usize| {
        let (x, y) = (x.clamp(0, w as i32 - 1), y.clamp(0, h as i32 - 1));
        round_to_f16(data[((y as u32 * w + x as u32) * 4) as usize + c])
    };
    for (k, uv) in uvs.iter().enumerate() {
        let (fx, fy) = (uv.x * w as f32 - 0.5, uv.y * h as f32 - 0.5);
        let (x0, y0) = (fx.floor() as i32, fy.floor() as i32);
        let (ax, ay) = (fx - x0 as f32, fy - y0 as f32);
        for c in 0..4 {
            let cpu = (1.0 - ay) * ((1.0 - ax) * texel(x0, y0, c) + ax * texel(x0 + 1, y0, c))
                + ay * ((1.0 - ax) * texel(x0, y0 + 1, c) + ax * texel(x0 + 1, y0 + 1, c));
            // The texels are exact fp16 values; the filter weights have at least 8 bits of
            // sub-texel precision (GL 4.5 section 8.14: implementations may quantise them),
            // so each weight is off by at most 2^-9 of the largest texel (3).
            let tol = 3.0 * 2f32.powi(-8);
            let got = gpu[k * 4 + c];
            assert!(
                (got - cpu).abs() <= tol,
                "uv {uv} channel {c}: gpu {got} cpu {cpu}"
            );
        }
    }
    // The R300 filtered no float texture, 16-bit ones included; nearest reads fit.
    ctx.set_period(Some(r300()));
    refused(
        sample(&ctx, &fp16, &uvs),
        "ATI RADEON 9700 PRO",
        "float_filtering",
    );
    fp16.set_filter(Filter::Nearest);
    sample(&ctx, &fp16, &uvs).unwrap();
}

#[test]
fn vertex_texture_formats_and_filtering_are_checked() {
    let ctx = context();
    let n = 4u32;
    let program = Program::new(
        &ctx,
        &[shader!("glsl/test/vertex_fetch.vert")],
        &[shader!("glsl/test/vertex_value.frag")],
    )
    .unwrap();
    let out = Texture::new_2d(&ctx, n, 1, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "fetched", &[&out], None).unwrap();
    let draw = |values: &Texture| -> Result<Vec<f32>, GlError> {
        let mut pass = fb.pass(&program, "vertex texture fetch")?;
        pass.texture("u_values", values)
            .uniform("u_width", n as f32);
        pass.draw_attributeless(Primitive::Points, n as usize, 1)?;
        fb.read_f32(0, Rect::sized(n, 1))
    };
    let rgba: Vec<f32> = (0..n * 4).map(|i| i as f32 * 1.5 - 3.0).collect();
    let rg: Vec<f32> = (0..n * 2).map(|i| i as f32).collect();
    let four = Texture::from_f32(&ctx, n, 1, TextureFormat::Rgba32F, &rgba).unwrap();
    let two = Texture::from_f32(&ctx, n, 1, TextureFormat::Rg32F, &rg).unwrap();
    ctx.set_period(Some(g70()));
    // A 4-component fp32 vertex texture read nearest fits, and reads every texel exactly.
    assert_eq!(draw(&four).unwrap(), rgba);
    let text = refused(draw(&two), "GeForce 7800 GTX", "vertex_texture_formats");
    assert!(text.contains("RG32F"), "{text}");
    four.set_filter(Filter::Linear);
    refused(draw(&four), "GeForce 7800 GTX", "vertex_texture_filtering");
    four.set_filter(Filter::Nearest);
    // The R300 had no vertex texture fetch at all.
    ctx.set_period(Some(r300()));
    refused(draw(&four), "ATI RADEON 9700 PRO", "vertex_texture_formats");
}

#[test]
fn compute_shaders_are_refused() {
    let ctx = context();
    ctx.set_period(Some(g70()));
    let text = refused(
        ctx.require_compute("the compute formulation"),
        "GeForce 7800 GTX",
        "compute_shaders",
    );
    assert!(text.contains("the compute formulation"), "{text}");
    ctx.set_period(Some(r300()));
    refused(
        ctx.require_compute("x"),
        "ATI RADEON 9700 PRO",
        "compute_shaders",
    );
}

#[test]
fn occlusion_counts_are_checked_against_the_counter_width() {
    // The ARB_occlusion_query floor for a 4096 x 4096 viewport, ceil(log2(4096^2 x 2)) = 25
    // bits: a count of 2^25 could not have been held; 2^25 - 1 could.
    assert_eq!(g70().occlusion_query_counter_bits.value, 25);
    g70().check_occlusion_count((1 << 25) - 1).unwrap();
    refused(
        g70().check_occlusion_count(1 << 25),
        "GeForce 7800 GTX",
        "occlusion_query_counter_bits",
    );
}

#[test]
fn fp16_rounding_model() {
    assert_eq!(round_to_f16(1.0), 1.0);
    // 1 + 2^-11 is halfway between 1 and 1 + 2^-10: ties to even (1).
    assert_eq!(round_to_f16(1.0 + 2f32.powi(-11)), 1.0);
    assert_eq!(
        round_to_f16(1.0 + 3.0 * 2f32.powi(-11)),
        1.0 + 2.0 * 2f32.powi(-10)
    );
    assert_eq!(round_to_f16(65504.0), 65504.0);
    assert_eq!(round_to_f16(65519.0), 65504.0);
    assert_eq!(round_to_f16(65520.0), f32::INFINITY);
    assert_eq!(round_to_f16(-0.1), -0.099975586);
    // Subnormals: steps of 2^-24.
    assert_eq!(round_to_f16(2f32.powi(-24) * 1.4), 2f32.powi(-24));
    assert_eq!(round_to_f16(2f32.powi(-26)), 0.0);
    // Toward zero: 1 + 3 * 2^-11 is 1 + 2^-10 and a bit, kept as 1 + 2^-10.
    assert_eq!(
        round_to_f16_toward_zero(1.0 + 3.0 * 2f32.powi(-11)),
        1.0 + 2f32.powi(-10)
    );
    assert_eq!(round_to_f16_toward_zero(-0.1), -0.099975586);
    assert_eq!(round_to_f16_toward_zero(1e6), 65504.0);
}

#[test]
fn the_gpu_stores_fp16_as_the_model_rounds() {
    let ctx = context();
    let data: Vec<f32> = (0..64)
        .map(|i| (i as f32 * 1.37).sin() * 10f32.powi(i % 9 - 4))
        .collect();
    let t = Texture::from_f32(&ctx, 16, 1, TextureFormat::Rgba16F, &data).unwrap();
    let back = t.download_f32().unwrap();
    // Either rounding GL allows, value by value.
    for (x, y) in data.iter().zip(&back) {
        assert!(
            round_to_f16(*x) == *y || round_to_f16_toward_zero(*x) == *y,
            "{x} stored as {y}"
        );
    }
}

#[test]
fn cli_period_collide_fits_and_finds_every_pair() {
    use classic_gpgpu::collide::brute_force::all_pairs;
    use classic_gpgpu::collide::Predicate;
    use classic_gpgpu::mesh;
    use glam::{Affine3A, Quat, Vec3};
    let dir = common::temp_dir("period-cli", "collide");
    let a = mesh::torus_with_triangles(1.0, 0.33, 300);
    let b = a.transformed(&Affine3A::from_rotation_translation(
        Quat::from_rotation_x(1.4),
        Vec3::new(1.5, 0.1, 0.0),
    ));
    let (pa, pb) = (dir.join("a.obj"), dir.join("b.obj"));
    mesh::write_obj(&a, &pa).unwrap();
    mesh::write_obj(&b, &pb).unwrap();
    let (la, lb) = (mesh::load_obj(&pa).unwrap(), mesh::load_obj(&pb).unwrap());
    let expected = all_pairs(&la, &la.positions, &lb, &lb.positions, Predicate::Exact);
    assert!(!expected.is_empty());
    let out = common::classic_gpgpu(&[
        "collide",
        pa.to_str().unwrap(),
        pb.to_str().unwrap(),
        "--readback",
        "paper-switch",
        "--period",
        "--json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("GeForce 7800 GTX"), "{stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let pairs: Vec<(u32, u32)> = v["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p[0].as_u64().unwrap() as u32, p[1].as_u64().unwrap() as u32))
        .collect();
    assert_eq!(pairs, expected);
    // The compute formulation did not exist on the chip.
    let out = common::classic_gpgpu(&[
        "collide",
        pa.to_str().unwrap(),
        pb.to_str().unwrap(),
        "--formulation",
        "compute",
        "--period",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("GeForce 7800 GTX") && stderr.contains("compute_shaders"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_period_mass_and_buoyancy_peel_at_24_bits() {
    let out = common::classic_gpgpu(&["mass", "cube", "--resolution", "16", "--period"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("GeForce 7800 GTX"), "{stderr}");
    let out = common::classic_gpgpu(&[
        "buoyancy", "--period", "--steps", "2", "--bodies", "4", "--json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // Too many tiles for the chip's 4096 x 4096 target: the error names that limit first.
    let out = common::classic_gpgpu(&[
        "buoyancy",
        "--period",
        "--steps",
        "1",
        "--bodies",
        "5000",
        "--resolution",
        "64",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    let error = stderr
        .lines()
        .find(|l| l.starts_with("error:"))
        .unwrap_or("");
    assert!(
        error.contains("--bodies 5000 at --resolution 64")
            && error.contains("4096x4096")
            && error.contains("max_texture_size"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn mass_sums_fp32_blending_refused_kept_layers_fit_fp16_sums_close_to_fp32() {
    use classic_gpgpu::mass::assemble::MassProperties;
    use classic_gpgpu::mass::gpu::GpuMass;
    use classic_gpgpu::mass::peel::{PeelOrder, PeelSettings};
    use classic_gpgpu::mass::peel_depth::PeelDepth;
    let ctx = context();
    let mesh = classic_gpgpu::mesh::uv_sphere(1.0, 24, 12);
    let resolution = 32;
    let run = |order, sums| -> Result<MassProperties, GlError> {
        let mut gpu = GpuMass::with_sum_format(&ctx, resolution, sums)?;
        gpu.set_settings(PeelSettings {
            order,
            ..PeelSettings::default()
        })?;
        let r = gpu.integrate(&mesh, None, None)?;
        Ok(MassProperties::from_integrals(&r.integrals, 1.0))
    };
    let today = run(PeelOrder::RunningSums, TextureFormat::Rgba32F).unwrap();
    ctx.set_period(Some(g70()));
    // The chip itself: no float depth for the peels; they take 24-bit depth instead.
    refused(
        GpuMass::with_depth(&ctx, resolution, TextureFormat::Rgba32F, PeelDepth::Float32),
        "GeForce 7800 GTX",
        "texture_formats",
    );
    let gpu = GpuMass::with_sum_format(&ctx, resolution, TextureFormat::Rgba16F).unwrap();
    assert_eq!(gpu.peeler().depth(), PeelDepth::Fixed24);
    refused(
        run(PeelOrder::RunningSums, TextureFormat::Rgba32F),
        "GeForce 7800 GTX",
        "float_blending",
    );
    let kept = run(PeelOrder::KeepLayers, TextureFormat::Rgba32F).unwrap();
    let fp16 = run(PeelOrder::RunningSums, TextureFormat::Rgba16F).unwrap();
    ctx.set_period(None);
    // Kept layers: the same sums in another order, fp32 rounding (2^-24 relative per
    // addition over a few thousand pixels).
    let close = |a: f64, b: f64, rel: f64| (a - b).abs() <= rel * b.abs();
    assert!(
        close(kept.mass, today.mass, 1e-4),
        "{} {}",
        kept.mass,
        today.mass
    );
    // fp16 sums: a sphere has two peels, so each pixel's sum is two roundings to 11
    // significant bits (2^-10 relative each toward zero); the peels' values have opposite
    // signs, so a pixel's error is relative to the larger of them, at most about 3 times
    // its net value at the rim: 2 * 2^-10 * 3 = 0.6 %.
    let tol = 2.0 * 2f64.powi(-10) * 3.0;
    assert!(
        close(fp16.mass, today.mass, tol),
        "{} {}",
        fp16.mass,
        today.mass
    );
    for axis in 0..3 {
        let (a, b) = (fp16.inertia.col(axis)[axis], today.inertia.col(axis)[axis]);
        assert!(close(a, b, tol), "axis {axis}: fp16 {a} fp32 {b}");
    }
}

fn bench_options(ctx: &classic_gpgpu::gl::Context) -> classic_gpgpu::report::BenchOptions<'_> {
    classic_gpgpu::report::BenchOptions {
        gl: ctx,
        quick: true,
        out_dir: std::env::temp_dir(),
        progress: indicatif::MultiProgress::with_draw_target(
            indicatif::ProgressDrawTarget::hidden(),
        ),
        runs: None,
    }
}

#[test]
fn report_period_blocks_of_papers_1_2_and_4() {
    use classic_gpgpu::report::period::Verdict;
    use classic_gpgpu::report::{paper1, paper2, paper4};
    let ctx = context();
    let opts = bench_options(&ctx);

    // Paper 1: the pipeline fits, finds every pair the CPU finds; compute is refused.
    let p1 = paper1::period::measure(&opts).unwrap();
    assert_eq!(p1.steps[0].verdict, Verdict::Fits, "{:?}", p1.steps[0]);
    let compute = p1
        .steps
        .iter()
        .find(|s| s.step.contains("compute"))
        .unwrap();
    assert_eq!(compute.verdict, Verdict::Refused);
    assert!(compute.detail.contains("compute_shaders"), "{compute:?}");
    assert!(
        p1.comparisons[0].period.ends_with(", 0 missed"),
        "{:?}",
        p1.comparisons
    );
    assert_eq!(p1.comparisons[0].today, p1.comparisons[0].period);

    // Paper 2: both methods ran the period's way (24-bit z-buffer).
    let p2 = paper2::period::measure(&opts).unwrap();
    assert_eq!(
        p2.steps[0].verdict,
        Verdict::PeriodsWay,
        "{:?}",
        p2.steps[0]
    );
    assert_eq!(
        p2.steps[1].verdict,
        Verdict::PeriodsWay,
        "{:?}",
        p2.steps[1]
    );
    assert_eq!(p2.comparisons.len(), 2);

    // Paper 4: float-depth peeling refused and 24-bit peeling the period's way, fp32 blended
    // sums refused, the paper's order and fp16 sums the period's way.
    let p4 = paper4::period::measure(&opts).unwrap();
    let verdict = |needle: &str| {
        p4.steps
            .iter()
            .find(|s| s.step.contains(needle))
            .unwrap_or_else(|| panic!("{needle}: {:?}", p4.steps))
            .clone()
    };
    let peel = verdict("32-bit float depth");
    assert_eq!(peel.verdict, Verdict::Refused);
    assert!(peel.detail.contains("texture_formats"), "{peel:?}");
    assert_eq!(verdict("24-bit depth").verdict, Verdict::PeriodsWay);
    let blended = verdict("fp32 additive blending");
    assert_eq!(blended.verdict, Verdict::Refused);
    assert!(blended.detail.contains("float_blending"), "{blended:?}");
    assert_eq!(verdict("the paper's order").verdict, Verdict::PeriodsWay);
    assert_eq!(verdict("fp16").verdict, Verdict::PeriodsWay);
    assert_eq!(p4.comparisons.len(), 6);
    for c in &p4.comparisons {
        assert!(c.period.ends_with('%'), "{c:?}");
    }
    for block in [&p1, &p2, &p4] {
        assert_eq!(block.tables().len(), 2);
    }
}

#[test]
fn report_period_block_of_paper_3_has_the_shape_of_the_others() {
    use classic_gpgpu::report::period::Verdict;
    use classic_gpgpu::report::{paper2, paper3};
    let ctx = context();
    let dir = common::temp_dir("period", "paper3-block");
    let opts = classic_gpgpu::report::BenchOptions {
        out_dir: dir.clone(),
        ..bench_options(&ctx)
    };
    // The first rows of text.png are enough for the shape (the report's --quick takes 24).
    let photo = image::open(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/mlp/text.png"))
        .unwrap()
        .to_luma8();
    let photo = image::imageops::crop_imm(&photo, 0, 0, photo.width(), 4).to_image();
    let p3 = paper3::period::measure(&opts, &photo).unwrap();
    assert_eq!(p3.block.gpu, "ATI RADEON 9700 PRO");
    // Every step ran under the R300's limits; the split products and the 24-bit arithmetic
    // are the period's way.
    let verdicts: Vec<Verdict> = p3.block.steps.iter().map(|s| s.verdict).collect();
    assert!(
        !verdicts.contains(&Verdict::Refused),
        "{:?}",
        p3.block.steps
    );
    for needle in ["Matrix product", "Arithmetic"] {
        let step = p3.block.steps.iter().find(|s| s.step.contains(needle));
        assert_eq!(
            step.map(|s| s.verdict),
            Some(Verdict::PeriodsWay),
            "{needle}"
        );
    }
    assert_eq!(p3.block.comparisons.len(), 5);
    let class = &p3.block.comparisons[1];
    assert!(
        class.change.contains(&p3.photo.changed_pixels.to_string())
            || (p3.photo.changed_pixels == 0 && class.change.starts_with("none")),
        "{class:?}"
    );
    // The same two tables, with the same columns, as papers 1, 2 and 4.
    let p2 = paper2::period::measure(&opts).unwrap();
    let (t3, t2) = (paper3::period::tables(&p3), p2.tables());
    assert_eq!(t3.len(), 2);
    for (a, b) in t3.iter().zip(&t2) {
        assert_eq!(a.header, b.header);
        assert!(a.caption.starts_with("Period: ") && a.caption.contains("RADEON 9700"));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_report_carries_the_period_block_unless_no_period() {
    let section = |extra: &[&str]| -> serde_json::Value {
        let dir = common::temp_dir("period-cli", &format!("crowd-bench{}", extra.len()));
        let out_dir = dir.to_str().unwrap().to_string();
        let args = [
            &["crowd-bench", "--quick", "--json", "--out", &out_dir][..],
            extra,
        ]
        .concat();
        let v = common::json_of(&args);
        std::fs::remove_dir_all(&dir).ok();
        v
    };
    let period_tables = |v: &serde_json::Value| {
        v["tables"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|t| t["caption"].as_str().unwrap().starts_with("Period: "))
            .count()
    };
    let with = section(&[]);
    assert_eq!(with["results"]["period"]["gpu"], "GeForce 7800 GTX");
    assert_eq!(period_tables(&with), 2);
    let without = section(&["--no-period"]);
    assert!(without["results"].get("period").is_none(), "{without}");
    assert_eq!(period_tables(&without), 0);
    // A section with no period GPU says so rather than ignoring the flag.
    let out = common::classic_gpgpu(&["lecture3-bench", "--quick", "--no-period"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("has no period block"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// The table agrees with itself: every format a limit names (vertex texture fetch, float
/// blending, float filtering) is one of the chip's texture formats, and every format is
/// one the GL layer knows by that name. The G70 once listed R16F for blending and filtering
/// but not among its textures (Mesa's nv30_format.c has no R16F).
#[test]
fn every_format_a_limit_names_is_a_format_the_chip_has() {
    let known: Vec<&str> = [
        TextureFormat::Rgba32F,
        TextureFormat::Rg32F,
        TextureFormat::R32F,
        TextureFormat::R16F,
        TextureFormat::Rgba16F,
        TextureFormat::R8,
        TextureFormat::Rgba8,
        TextureFormat::Depth32F,
        TextureFormat::Depth24Stencil8,
        TextureFormat::Depth32FStencil8,
        TextureFormat::Rgba32Ui,
    ]
    .map(TextureFormat::name)
    .to_vec();
    for gpu in period::all() {
        let has = &gpu.texture_formats.value;
        for format in has {
            assert!(
                known.contains(&format.as_str()),
                "{}: texture format {format} is not a format the GL layer makes",
                gpu.name
            );
        }
        for (limit, formats) in [
            ("vertex_texture_formats", &gpu.vertex_texture_formats.value),
            ("float_blending", &gpu.float_blending.value),
            ("float_filtering", &gpu.float_filtering.value),
        ] {
            for format in formats {
                assert!(
                    has.contains(format),
                    "{}: {limit} names {format}, which is not in its texture_formats {has:?}",
                    gpu.name
                );
            }
        }
    }
    // The G70's fp16 blending and filtering is of its one fp16 texture format.
    assert_eq!(g70().float_blending.value, ["RGBA16F"]);
    assert_eq!(g70().float_filtering.value, ["RGBA16F"]);
}
