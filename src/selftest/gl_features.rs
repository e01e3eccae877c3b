//! The GL features the papers are built from, each on a small input against what the CPU says
//! it must produce: 1D float textures, several render targets, the stencil test, occlusion
//! and timer queries, render-to-vertex-buffer through a PBO, depth peeling and ping-pong
//! reduction.

use super::Check;
use crate::gl::reduce::{passes_for, ReduceOp};
use crate::gl::{
    self, peel, query, Buffer, BufferUsage, DrawState, Filter, Framebuffer, MeshBuffers,
    OcclusionQuery, Primitive, Program, Rect, ShaderSource, StencilTest, Texture, TextureFormat,
    VertexArray,
};
use crate::{mesh, shader};
use anyhow::ensure;
use glam::{Vec3, Vec4};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const CONSTANT: ShaderSource<'static> = shader!("glsl/test/constant.frag");

pub fn checks() -> Vec<Check> {
    let check = |name, run| Check {
        name,
        group: "gl",
        run,
    };
    vec![
        check("1d-float-texture", one_d_float_texture),
        check("mrt", mrt),
        check("stencil", stencil),
        check("occlusion-query", occlusion_query),
        check("timer-query", timer_query),
        check("pbo-render-to-vertex-buffer", pbo_to_vbo),
        check("depth-peeling", depth_peeling),
        check("ping-pong-reduction", reduction),
    ]
}

/// A 1D R32F table: uploaded and read back bit for bit, then sampled by a pass with nearest
/// filtering (exact) and linear filtering (within 9/256: filter weights may have 8 bits).
fn one_d_float_texture(ctx: &gl::Context) -> anyhow::Result<String> {
    let data: Vec<f32> = (0..37).map(|i| (i as f32 * 0.37).sin() * 1e5).collect();
    let t = Texture::new_1d(ctx, data.len() as u32, TextureFormat::R32F)?;
    t.upload_f32(&data)?;
    ensure!(
        t.download_f32()? == data,
        "a 1D R32F texture did not read back as written"
    );

    let table = Texture::new_1d(ctx, 4, TextureFormat::R32F)?;
    table.upload_f32(&[0.0, 1.0, 4.0, 9.0])?;
    let target = Texture::new_2d(ctx, 8, 1, TextureFormat::Rgba32F)?;
    let fb = Framebuffer::new(ctx, "1D lookups", &[&target], None)?;
    let program = Program::rect(ctx, &[shader!("glsl/test/sample_1d.frag")])?;
    let x = [0.125f32, 0.25, 0.375, 0.5, 0.625, 0.875, 0.0, 1.0];
    let mut worst = 0.0f32;
    for (filter, expected, tolerance) in [
        (
            Filter::Nearest,
            [0.0f32, 1.0, 1.0, 4.0, 4.0, 9.0, 0.0, 9.0],
            0.0,
        ),
        (
            Filter::Linear,
            [0.0, 0.5, 1.0, 2.5, 4.0, 9.0, 0.0, 9.0],
            9.0 / 256.0,
        ),
    ] {
        table.set_filter(filter);
        fb.pass(&program, "1D lookups")?
            .texture("u_table", &table)
            .uniform("u_x", &x[..])
            .draw_full()?;
        let values = fb.read_f32(0, Rect::sized(8, 1))?;
        for i in 0..8 {
            let err = (values[4 * i] - expected[i]).abs();
            ensure!(
                err <= tolerance,
                "{filter:?} lookup at {}: GPU {} vs CPU {} (tolerance {tolerance})",
                x[i],
                values[4 * i],
                expected[i]
            );
            worst = worst.max(err);
        }
    }
    Ok(format!(
        "37 texels round trip exactly; nearest lookups exact, linear within {worst:.4} (tolerance 9/256)"
    ))
}

/// Three render targets written in one pass, each a different function of the pixel: exact.
fn mrt(ctx: &gl::Context) -> anyhow::Result<String> {
    let (w, h) = (13, 9);
    let targets = (0..3)
        .map(|_| Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F))
        .collect::<Result<Vec<_>, _>>()?;
    let fb = Framebuffer::new(ctx, "mrt", &targets.iter().collect::<Vec<_>>(), None)?;
    let program = Program::rect(ctx, &[shader!("glsl/test/mrt.frag")])?;
    fb.pass(&program, "mrt")?.draw_full()?;
    for (i, f) in [
        (|x: f32, y: f32| [x, y, 1.0, 2.0]) as fn(f32, f32) -> [f32; 4],
        |x, y| [x * y, -x, 0.5, 3.0],
        |x, y| [x + 100.0 * y, 7.0, -1.0, 4.0],
    ]
    .into_iter()
    .enumerate()
    {
        let read = fb.read_f32(i, fb.rect())?;
        for y in 0..h {
            for x in 0..w {
                let at = ((y * w + x) * 4) as usize;
                let want = f(x as f32, y as f32);
                ensure!(
                    read[at..at + 4] == want,
                    "target {i} pixel ({x}, {y}): GPU {:?} vs CPU {want:?}",
                    &read[at..at + 4]
                );
            }
        }
    }
    Ok(format!(
        "3 targets of {w}x{h} written in one pass, all exact"
    ))
}

/// A stencil framebuffer with a `mark` rectangle written into its stencil buffer.
fn marked_stencil(ctx: &gl::Context, mark: Rect) -> anyhow::Result<(Texture, Texture, Program)> {
    let colour = Texture::new_2d(ctx, 16, 12, TextureFormat::R32F)?;
    let depth = Texture::new_2d(ctx, 16, 12, TextureFormat::Depth24Stencil8)?;
    let program = Program::rect(ctx, &[CONSTANT])?;
    {
        let fb = Framebuffer::new(ctx, "stencil", &[&colour], Some(&depth))?;
        fb.clear_colors([0.0; 4])?;
        fb.clear_depth_stencil(1.0, 0)?;
        let mut pass = fb.pass(&program, "stencil mark")?;
        pass.state(DrawState {
            stencil: Some(StencilTest::write(1)),
            color_write: false,
            ..DrawState::default()
        });
        pass.draw_rect(mark)?;
    }
    Ok((colour, depth, program))
}

/// A rectangle marked in the stencil buffer; a full-screen pass masked by it writes exactly
/// the marked pixels.
fn stencil(ctx: &gl::Context) -> anyhow::Result<String> {
    let mark = Rect::new(3, 2, 5, 4);
    let (colour, depth, program) = marked_stencil(ctx, mark)?;
    let fb = Framebuffer::new(ctx, "stencil", &[&colour], Some(&depth))?;
    let marked = fb
        .read_stencil(fb.rect())?
        .iter()
        .filter(|&&s| s == 1)
        .count();
    ensure!(
        marked == mark.area(),
        "{marked} stencil values set, CPU {}",
        mark.area()
    );
    let mut pass = fb.pass(&program, "stencil masked")?;
    pass.state(DrawState {
        stencil: Some(StencilTest::equal(1)),
        ..DrawState::default()
    })
    .uniform("u_colour", Vec4::splat(1.0));
    pass.draw_full()?;
    drop(pass);
    let pixels = fb.read_f32(0, fb.rect())?;
    for y in 0..12u32 {
        for x in 0..16u32 {
            let inside = (3..8).contains(&x) && (2..6).contains(&y);
            let got = pixels[(y * 16 + x) as usize];
            ensure!(
                got == inside as u32 as f32,
                "pixel ({x}, {y}): {got}, CPU says {}",
                inside as u32
            );
        }
    }
    Ok(format!(
        "{} marked pixels written, the other {} kept",
        mark.area(),
        16 * 12 - mark.area()
    ))
}

/// The occlusion query counts the samples a stencil-masked pass writes: exactly the marked
/// area.
fn occlusion_query(ctx: &gl::Context) -> anyhow::Result<String> {
    let mark = Rect::new(1, 4, 9, 5);
    let (colour, depth, program) = marked_stencil(ctx, mark)?;
    let fb = Framebuffer::new(ctx, "occlusion", &[&colour], Some(&depth))?;
    let query = OcclusionQuery::new(ctx)?;
    let mut counts = Vec::new();
    for (test, want) in [
        (StencilTest::equal(1), mark.area()),
        (StencilTest::equal(0), 16 * 12 - mark.area()),
    ] {
        let mut pass = fb.pass(&program, "counted")?;
        pass.state(DrawState {
            stencil: Some(test),
            ..DrawState::default()
        })
        .uniform("u_colour", Vec4::splat(1.0));
        query.begin();
        pass.draw_full()?;
        query.end();
        let got = query.samples()?;
        ensure!(got == want as u64, "samples passed {got}, CPU count {want}");
        counts.push(got);
    }
    Ok(format!(
        "samples passed {} inside and {} outside the mask, as counted",
        counts[0], counts[1]
    ))
}

/// A timer query around a pass gives a time between 0 and the wall clock around it.
fn timer_query(ctx: &gl::Context) -> anyhow::Result<String> {
    let t = Texture::new_2d(ctx, 64, 64, TextureFormat::Rgba32F)?;
    let fb = Framebuffer::new(ctx, "timed", &[&t], None)?;
    let program = Program::rect(ctx, &[CONSTANT])?;
    let mut last = (0.0, 0.0);
    for _ in 0..2 {
        ctx.finish_all();
        let start = std::time::Instant::now();
        let ((), gpu_ms) = query::time_gpu(ctx, || {
            fb.pass(&program, "timed")?
                .uniform("u_colour", Vec4::ONE)
                .draw_full()
        })?;
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        ensure!(
            gpu_ms.is_finite() && gpu_ms >= 0.0 && gpu_ms <= wall_ms + 0.5,
            "GL timer {gpu_ms} ms outside [0, wall clock {wall_ms:.3} ms + 0.5]"
        );
        last = (gpu_ms, wall_ms);
    }
    Ok(format!(
        "GL timer {:.3} ms within the wall clock {:.3} ms",
        last.0, last.1
    ))
}

/// Paper 2's render-to-vertex-buffer: a pass renders positions into a float texture, a PBO
/// read copies them into a buffer, and that buffer is drawn as points; the lit pixels are
/// exactly the ones the CPU computes.
fn pbo_to_vbo(ctx: &gl::Context) -> anyhow::Result<String> {
    let (w, h) = (6u32, 5u32);
    let positions = Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F)?;
    let fb = Framebuffer::new(ctx, "positions", &[&positions], None)?;
    let program = Program::rect(ctx, &[shader!("glsl/test/positions.frag")])?;
    let (tw, th) = (2 * w, 2 * h);
    fb.pass(&program, "write positions")?
        .uniform("u_target", glam::Vec2::new(tw as f32, th as f32))
        .draw_full()?;
    let vbo = Buffer::new(ctx, (w * h * 16) as usize, BufferUsage::GpuCopy)?;
    fb.read_into_buffer(0, fb.rect(), &vbo, 0)?;
    let copied: Vec<f32> = vbo.read()?;
    ensure!(
        copied == positions.download_f32()?,
        "the buffer does not hold what the pass rendered"
    );
    let mut vertices = VertexArray::new(ctx)?;
    vertices.float_attribute(0, &vbo, 4, 16, 0, 0)?;
    let lit = Texture::new_2d(ctx, tw, th, TextureFormat::R32F)?;
    let target = Framebuffer::new(ctx, "points", &[&lit], None)?;
    target.clear_colors([0.0; 4])?;
    let points = Program::new(ctx, &[shader!("glsl/test/points.vert")], &[CONSTANT])?;
    let mut pass = target.pass(&points, "draw points")?;
    pass.uniform("u_colour", Vec4::splat(1.0));
    pass.draw_arrays(&vertices, Primitive::Points, 0, (w * h) as usize)?;
    drop(pass);
    let read = target.read_f32(0, target.rect())?;
    for y in 0..th {
        for x in 0..tw {
            let want = (x % 2 == 1 && y % 2 == 1) as u32 as f32;
            let got = read[(y * tw + x) as usize];
            ensure!(got == want, "pixel ({x}, {y}): {got}, CPU says {want}");
        }
    }
    Ok(format!(
        "{} vertices rendered, copied through a PBO and drawn where the CPU puts them",
        w * h
    ))
}

/// Depth peeling a tilted torus: the layers per pixel equal a CPU ray cast through each
/// pixel centre on the GPU's 8-bit sub-pixel grid (exact).
fn depth_peeling(ctx: &gl::Context) -> anyhow::Result<String> {
    let tilt =
        glam::Affine3A::from_quat(glam::Quat::from_euler(glam::EulerRot::XYZ, 0.9, 0.3, 0.0));
    let torus = mesh::torus_closed(1.0, 0.35, 32, 12).transformed(&tilt);
    let (positions, triangles) = (torus.positions_f32().to_vec(), torus.triangles.clone());
    let buffers = MeshBuffers::new(ctx, &positions, &triangles)?;
    let (min, max) = positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(Vec3::from(*p)), hi.max(Vec3::from(*p))),
    );
    let (min, max) = (min - 0.1, max + 0.1);
    let size = (48, 40);
    let (layers, counts) = peel::layer_counts(
        ctx,
        &buffers,
        peel::ortho_box(min, max),
        size.0,
        size.1,
        peel::PeelOptions::default(),
    )?;
    let expected = ray_cast_counts(&positions, &triangles, min, max, size);
    let mismatches = counts.iter().zip(&expected).filter(|(a, b)| a != b).count();
    ensure!(
        mismatches == 0,
        "{mismatches} of {} pixels have a layer count other than the CPU ray cast's",
        counts.len()
    );
    let deepest = expected.iter().copied().max().unwrap_or(0);
    ensure!(
        layers as u32 == deepest,
        "{layers} layers peeled, the CPU finds {deepest}"
    );
    ensure!(
        deepest >= 4,
        "only {deepest} layers: the view is too easy to show peeling"
    );
    Ok(format!(
        "{layers} layers; {} pixels' counts equal the CPU ray cast",
        counts.len()
    ))
}

/// Layers per pixel by casting a ray down -z through each pixel centre, with the vertices
/// snapped to 8 sub-pixel bits as the rasterizer does.
fn ray_cast_counts(
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    min: Vec3,
    max: Vec3,
    (w, h): (u32, u32),
) -> Vec<u32> {
    let snap = |v: f64| (v * 256.0).round() / 256.0;
    let to_pixels = |p: [f32; 3]| {
        let x = (p[0] - min.x) as f64 / (max.x - min.x) as f64 * w as f64;
        let y = (p[1] - min.y) as f64 / (max.y - min.y) as f64 * h as f64;
        (snap(x), snap(y))
    };
    let mut counts = vec![0u32; (w * h) as usize];
    for tri in triangles {
        let v = tri.map(|i| to_pixels(positions[i as usize]));
        let area = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[2].0 - v[0].0) * (v[1].1 - v[0].1);
        if area == 0.0 {
            continue;
        }
        let lo = |f: fn(&(f64, f64)) -> f64| v.iter().map(f).fold(f64::MAX, f64::min);
        let hi = |f: fn(&(f64, f64)) -> f64| v.iter().map(f).fold(f64::MIN, f64::max);
        let (x0, x1) = (
            lo(|p| p.0).floor().max(0.0) as u32,
            hi(|p| p.0).ceil().min(w as f64) as u32,
        );
        let (y0, y1) = (
            lo(|p| p.1).floor().max(0.0) as u32,
            hi(|p| p.1).ceil().min(h as f64) as u32,
        );
        for py in y0..y1 {
            for px in x0..x1 {
                let (cx, cy) = (px as f64 + 0.5, py as f64 + 0.5);
                let edge = |a: (f64, f64), b: (f64, f64)| {
                    (b.0 - a.0) * (cy - a.1) - (b.1 - a.1) * (cx - a.0)
                };
                let inside = [edge(v[0], v[1]), edge(v[1], v[2]), edge(v[2], v[0])]
                    .iter()
                    .all(|&e| e * area.signum() > 0.0);
                if inside {
                    counts[(py * w + px) as usize] += 1;
                }
            }
        }
    }
    counts
}

/// Ping-pong sum, min and max of random RGBA32F textures. Min and max are exact; the sum is
/// compared with an f64 sum within levels * 3 * 2^-24 of the sum of magnitudes (each level
/// of the 4-ary tree adds three rounded additions).
fn reduction(ctx: &gl::Context) -> anyhow::Result<String> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut worst: f64 = 0.0;
    let sizes = [(1, 1), (17, 33), (100, 37), (256, 256)];
    for (w, h) in sizes {
        let data: Vec<f32> = (0..w * h * 4)
            .map(|_| rng.gen_range(-10.0..100.0))
            .collect();
        let t = Texture::from_f32(ctx, w, h, TextureFormat::Rgba32F, &data)?;
        let sum = gl::reduce::reduce(ctx, &t, ReduceOp::Sum)?;
        let min = gl::reduce::reduce(ctx, &t, ReduceOp::Min)?;
        let max = gl::reduce::reduce(ctx, &t, ReduceOp::Max)?;
        let levels = passes_for(w, h) as f64;
        for c in 0..4 {
            let channel = || data.iter().skip(c).step_by(4).copied();
            let exact: f64 = channel().map(f64::from).sum();
            let magnitude: f64 = channel().map(|v| f64::from(v).abs()).sum();
            let tolerance = levels * 3.0 * f32::EPSILON as f64 * 0.5 * magnitude + 1e-6;
            let err = (sum[c] as f64 - exact).abs();
            ensure!(
                err <= tolerance,
                "{w}x{h} channel {c}: GPU sum {} vs CPU {exact} (tolerance {tolerance:e})",
                sum[c]
            );
            worst = worst.max(err / tolerance);
            let (lo, hi) = (
                channel().fold(f32::INFINITY, f32::min),
                channel().fold(f32::NEG_INFINITY, f32::max),
            );
            ensure!(
                min[c] == lo && max[c] == hi,
                "{w}x{h} channel {c}: min/max {}/{} vs CPU {lo}/{hi}",
                min[c],
                max[c]
            );
        }
    }
    Ok(format!(
        "sum, min, max of {} textures up to 256x256: min/max exact, sums within {:.2} of the tolerance",
        sizes.len(),
        worst
    ))
}
