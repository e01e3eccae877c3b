//! The GL layer on a real headless context (llvmpipe in CI): every feature the papers use,
//! each checked against what the CPU says it must produce.

use classic_gpgpu::gl::reduce::{passes_for, ReduceOp, Reducer};
use classic_gpgpu::gl::{
    self, dump, peel, query, Blend, Buffer, BufferUsage, Compare, DepthTest, DrawState,
    Framebuffer, GlError, MeshBuffers, OcclusionQuery, Primitive, Program, Rect, ShaderSource,
    StencilOp, StencilTest, Texture, TextureFormat, VertexArray,
};
use classic_gpgpu::mesh;
use classic_gpgpu::shader;
use common::context;
use glam::{Vec3, Vec4};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

const CONSTANT: ShaderSource<'static> = shader!("glsl/test/constant.frag");

#[test]
fn context_reports_renderer_and_limits() {
    let ctx = context();
    let info = ctx.info();
    assert!(info.gl_version >= (3, 3), "{:?}", info.gl_version);
    assert!(!info.renderer.is_empty());
    assert!(info.limits.max_texture_size >= 1024);
    assert!(
        info.limits.max_draw_buffers >= 4,
        "MRT needs several draw buffers"
    );
    assert_eq!(info.limits.stencil_bits, 8);
    assert!(info.limits.samples_passed_counter_bits > 0);
    assert!(info.renderer_line().contains(&info.renderer));
}

#[test]
fn unknown_renderer_name_is_a_clear_error() {
    let err = "vulkan".parse::<gl::Renderer>().unwrap_err().to_string();
    assert!(err.contains("unknown renderer 'vulkan'"), "{err}");
}

#[test]
fn every_texture_format_round_trips() {
    let ctx = context();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for (w, h) in [(1, 1), (7, 1), (5, 3), (33, 17)] {
        for one_d in [true, false] {
            if one_d && h != 1 {
                continue;
            }
            let make = |format| {
                if one_d {
                    Texture::new_1d(&ctx, w, format)
                } else {
                    Texture::new_2d(&ctx, w, h, format)
                }
                .unwrap()
            };
            let n = (w * h) as usize;
            for format in [
                TextureFormat::Rgba32F,
                TextureFormat::R32F,
                TextureFormat::Depth32F,
            ] {
                let t = make(format);
                let data: Vec<f32> = (0..n * format.components())
                    .map(|_| {
                        if format.is_depth() {
                            rng.gen_range(0.0..1.0)
                        } else {
                            rng.gen_range(-1e6..1e6)
                        }
                    })
                    .collect();
                t.upload_f32(&data).unwrap();
                assert_eq!(
                    t.download_f32().unwrap(),
                    data,
                    "{format:?} {w}x{h} 1d={one_d}"
                );
            }
            for format in [TextureFormat::R8, TextureFormat::Rgba8] {
                let t = make(format);
                let data: Vec<u8> = (0..n * format.components()).map(|_| rng.gen()).collect();
                t.upload_u8(&data).unwrap();
                assert_eq!(
                    t.download_u8().unwrap(),
                    data,
                    "{format:?} {w}x{h} 1d={one_d}"
                );
            }
            if !one_d {
                let t = make(TextureFormat::Depth24Stencil8);
                let data: Vec<u32> = (0..n).map(|_| rng.gen()).collect();
                t.upload_u32(&data).unwrap();
                assert_eq!(t.download_u32().unwrap(), data, "depth-stencil {w}x{h}");
            }
        }
    }
}

/// A new texture reads as zeros (depth: 0) on every renderer, even where the driver hands
/// it memory a freed texture filled with NaN: softpipe does not clear what it allocates,
/// and a pass that reads texels it has not drawn (mass's accumulation, `0 * NaN`) would
/// otherwise see whatever was there. Repeated so that reused memory shows up.
#[test]
fn new_textures_read_as_zero_after_freed_ones_held_nan() {
    let ctx = context();
    for round in 0..8 {
        for (w, h) in [(32, 32), (64, 64), (200, 100)] {
            let n = (w * h) as usize;
            for format in [
                TextureFormat::Rgba32F,
                TextureFormat::R32F,
                TextureFormat::Depth32F,
            ] {
                let dirty = Texture::new_2d(&ctx, w, h, format).unwrap();
                dirty
                    .upload_f32(&vec![f32::NAN; n * format.components()])
                    .unwrap();
                drop(dirty);
                let fresh = Texture::new_2d(&ctx, w, h, format).unwrap();
                let texels = fresh.download_f32().unwrap();
                assert!(
                    texels.iter().all(|&v| v == 0.0),
                    "round {round}: a new {w}x{h} {format:?} holds {:?}",
                    texels.iter().find(|v| **v != 0.0)
                );
            }
            let dirty = Texture::new_1d(&ctx, w, TextureFormat::Rgba32F).unwrap();
            dirty.upload_f32(&vec![f32::NAN; 4 * w as usize]).unwrap();
            drop(dirty);
            let fresh = Texture::new_1d(&ctx, w, TextureFormat::Rgba32F).unwrap();
            assert!(fresh.download_f32().unwrap().iter().all(|&v| v == 0.0));
            for format in [TextureFormat::R8, TextureFormat::Rgba8] {
                let dirty = Texture::new_2d(&ctx, w, h, format).unwrap();
                dirty
                    .upload_u8(&vec![0xff; n * format.components()])
                    .unwrap();
                drop(dirty);
                let fresh = Texture::new_2d(&ctx, w, h, format).unwrap();
                assert!(fresh.download_u8().unwrap().iter().all(|&v| v == 0));
            }
            let dirty = Texture::new_2d(&ctx, w, h, TextureFormat::Depth24Stencil8).unwrap();
            dirty.upload_u32(&vec![u32::MAX; n]).unwrap();
            drop(dirty);
            let fresh = Texture::new_2d(&ctx, w, h, TextureFormat::Depth24Stencil8).unwrap();
            assert!(fresh.download_u32().unwrap().iter().all(|&v| v == 0));
        }
    }
}
#[test]
fn region_upload_and_size_errors() {
    let ctx = context();
    let t = Texture::from_f32(&ctx, 4, 2, TextureFormat::R32F, &[0.0; 8]).unwrap();
    t.upload_region_f32(1, 1, 2, 1, &[5.0, 6.0]).unwrap();
    assert_eq!(t.download_f32().unwrap(), [0., 0., 0., 0., 0., 5., 6., 0.]);
    let err = t.upload_f32(&[1.0; 3]).unwrap_err().to_string();
    assert!(
        err.contains("12 bytes given for a 4x2 R32F region"),
        "{err}"
    );
    let max = ctx.info().limits.max_texture_size;
    let err = Texture::new_2d(&ctx, max + 1, 1, TextureFormat::Rgba32F).unwrap_err();
    assert!(matches!(err, GlError::Limit(_)), "{err}");
    assert!(err.to_string().contains("GL_MAX_TEXTURE_SIZE"), "{err}");
}

#[test]
fn framebuffer_errors_name_the_framebuffer() {
    let ctx = context();
    let a = Texture::new_2d(&ctx, 4, 4, TextureFormat::Rgba32F).unwrap();
    let b = Texture::new_2d(&ctx, 8, 4, TextureFormat::Rgba32F).unwrap();
    let err = Framebuffer::new(&ctx, "mixed", &[&a, &b], None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("framebuffer mixed") && err.contains("differ in size"),
        "{err}"
    );
    let d = Texture::new_2d(&ctx, 4, 4, TextureFormat::Depth32F).unwrap();
    let err = Framebuffer::new(&ctx, "depth as colour", &[&d], None)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("depth as colour"), "{err}");
}

#[test]
fn mrt_writes_three_attachments_in_one_pass() {
    let ctx = context();
    let (w, h) = (13, 9);
    let targets: Vec<Texture> = (0..3)
        .map(|_| Texture::new_2d(&ctx, w, h, TextureFormat::Rgba32F).unwrap())
        .collect();
    let fb = Framebuffer::new(&ctx, "mrt", &targets.iter().collect::<Vec<_>>(), None).unwrap();
    let program = Program::rect(&ctx, &[shader!("glsl/test/mrt.frag")]).unwrap();
    fb.pass(&program, "mrt").unwrap().draw_full().unwrap();
    let read: Vec<Vec<f32>> = (0..3).map(|i| fb.read_f32(i, fb.rect()).unwrap()).collect();
    for y in 0..h {
        for x in 0..w {
            let (fx, fy) = (x as f32, y as f32);
            let i = ((y * w + x) * 4) as usize;
            assert_eq!(read[0][i..i + 4], [fx, fy, 1.0, 2.0]);
            assert_eq!(read[1][i..i + 4], [fx * fy, -fx, 0.5, 3.0]);
            assert_eq!(read[2][i..i + 4], [fx + 100.0 * fy, 7.0, -1.0, 4.0]);
        }
    }
}

#[test]
fn stencil_masks_a_pass_and_occlusion_query_counts_samples() {
    let ctx = context();
    let (w, h) = (16, 12);
    let colour = Texture::new_2d(&ctx, w, h, TextureFormat::R32F).unwrap();
    let depth = Texture::new_2d(&ctx, w, h, TextureFormat::Depth24Stencil8).unwrap();
    let fb = Framebuffer::new(&ctx, "stencil", &[&colour], Some(&depth)).unwrap();
    fb.clear_colors([0.0; 4]).unwrap();
    fb.clear_depth_stencil(1.0, 0).unwrap();
    let program = Program::rect(&ctx, &[CONSTANT]).unwrap();

    // Mark a 5x4 rectangle in the stencil buffer without touching the colour.
    let mark = Rect::new(3, 2, 5, 4);
    let mut pass = fb.pass(&program, "stencil mark").unwrap();
    pass.state(DrawState {
        stencil: Some(StencilTest::write(1)),
        color_write: false,
        ..DrawState::default()
    });
    pass.draw_rect(mark).unwrap();
    let stencil = fb.read_stencil(fb.rect()).unwrap();
    assert_eq!(stencil.iter().filter(|&&s| s == 1).count(), mark.area());

    // A full-screen pass masked by the stencil writes only the marked pixels; the occlusion
    // query counts exactly those.
    let query = OcclusionQuery::new(&ctx).unwrap();
    let mut pass = fb.pass(&program, "stencil masked").unwrap();
    pass.state(DrawState {
        stencil: Some(StencilTest::equal(1)),
        ..DrawState::default()
    })
    .uniform("u_colour", Vec4::splat(1.0));
    query.begin();
    pass.draw_full().unwrap();
    query.end();
    assert_eq!(query.samples().unwrap(), mark.area() as u64);
    let pixels = fb.read_f32(0, fb.rect()).unwrap();
    for y in 0..h {
        for x in 0..w {
            let inside = (3..8).contains(&x) && (2..6).contains(&y);
            assert_eq!(
                pixels[(y * w + x) as usize],
                inside as u32 as f32,
                "({x}, {y})"
            );
        }
    }

    // The depth test also gates the count. The rectangle lies at depth 0.5; the stored depth
    // is cleared a little nearer, then a little farther (not to 0.5 itself: a 24-bit depth
    // buffer need not round the clear value and the fragment's depth alike, and softpipe
    // does not).
    for (cleared, want) in [(0.25, 0), (0.75, (w * h) as u64)] {
        fb.clear_depth_stencil(cleared, 0).unwrap();
        let mut pass = fb.pass(&program, "depth test").unwrap();
        pass.state(DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: false,
            }),
            ..DrawState::default()
        });
        query.begin();
        pass.draw_full().unwrap();
        query.end();
        assert_eq!(query.samples().unwrap(), want, "depth cleared to {cleared}");
    }
    assert_eq!(
        StencilOp::Keep,
        StencilTest::equal(3).pass,
        "masking must not change the stencil"
    );
}

#[test]
fn min_max_and_additive_blending() {
    let ctx = context();
    let t = Texture::new_2d(&ctx, 2, 2, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "blend", &[&t], None).unwrap();
    let program = Program::rect(&ctx, &[CONSTANT]).unwrap();
    for (blend, values, expected) in [
        (Blend::Min, [3.0, -1.0, 2.0], -1.0),
        (Blend::Max, [3.0, -1.0, 2.0], 3.0),
        (Blend::Add, [3.0, -1.0, 2.0], 4.0),
    ] {
        let start = if blend == Blend::Add { 0.0 } else { values[0] };
        fb.clear_colors([start; 4]).unwrap();
        for v in &values[usize::from(blend != Blend::Add)..] {
            let mut pass = fb.pass(&program, "blend").unwrap();
            pass.state(DrawState {
                blend: Some(blend),
                ..DrawState::default()
            })
            .uniform("u_colour", Vec4::splat(*v));
            pass.draw_full().unwrap();
        }
        let read = fb.read_f32(0, fb.rect()).unwrap();
        assert!(read.iter().all(|&r| r == expected), "{blend:?}: {read:?}");
    }
}

#[test]
fn pbo_to_vbo_copy_feeds_a_draw() {
    let ctx = context();
    let (w, h) = (6u32, 5u32);
    // Pass 1: positions rendered into a float texture.
    let positions = Texture::new_2d(&ctx, w, h, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "positions", &[&positions], None).unwrap();
    let program = Program::rect(&ctx, &[shader!("glsl/test/positions.frag")]).unwrap();
    let (tw, th) = (2 * w, 2 * h);
    fb.pass(&program, "write positions")
        .unwrap()
        .uniform("u_target", glam::Vec2::new(tw as f32, th as f32))
        .draw_full()
        .unwrap();
    // Read them into a buffer object (pixel pack), which then serves as a vertex buffer.
    let vbo = Buffer::new(&ctx, (w * h * 16) as usize, BufferUsage::GpuCopy).unwrap();
    fb.read_into_buffer(0, fb.rect(), &vbo, 0).unwrap();
    let mut vertices = VertexArray::new(&ctx).unwrap();
    vertices.float_attribute(0, &vbo, 4, 16, 0, 0).unwrap();
    // Pass 2: one point per vertex.
    let lit = Texture::new_2d(&ctx, tw, th, TextureFormat::R32F).unwrap();
    let target = Framebuffer::new(&ctx, "points", &[&lit], None).unwrap();
    target.clear_colors([0.0; 4]).unwrap();
    let points = Program::new(&ctx, &[shader!("glsl/test/points.vert")], &[CONSTANT]).unwrap();
    let mut pass = target.pass(&points, "draw points").unwrap();
    pass.uniform("u_colour", Vec4::splat(1.0));
    pass.draw_arrays(&vertices, Primitive::Points, 0, (w * h) as usize)
        .unwrap();
    let read = target.read_f32(0, target.rect()).unwrap();
    for y in 0..th {
        for x in 0..tw {
            let expected = (x % 2 == 1 && y % 2 == 1) as u32 as f32;
            assert_eq!(read[(y * tw + x) as usize], expected, "pixel ({x}, {y})");
        }
    }
    // The buffer's contents are the positions the first pass wrote.
    let copied: Vec<f32> = vbo.read().unwrap();
    assert_eq!(copied, positions.download_f32().unwrap());
}

#[test]
fn timer_query_measures_a_pass_within_its_wall_clock() {
    // A fresh context: llvmpipe once answered the first TIME_ELAPSED query with its uptime.
    let ctx = context();
    let t = Texture::new_2d(&ctx, 64, 64, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "timed", &[&t], None).unwrap();
    let program = Program::rect(&ctx, &[CONSTANT]).unwrap();
    for _ in 0..2 {
        ctx.finish_all();
        let start = std::time::Instant::now();
        let ((), gpu_ms) =
            query::time_gpu(&ctx, || fb.pass(&program, "timed")?.draw_full()).unwrap();
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        // Not a speed check: GPU time of work cannot exceed the wall clock that contains it.
        assert!(
            gpu_ms >= 0.0 && gpu_ms <= wall_ms + 0.5,
            "gpu {gpu_ms} ms, wall {wall_ms} ms"
        );
    }
}

/// Sum in f64 of random data: the GPU's fp32 4-ary tree may differ by at most
/// levels * 3 * 2^-24 * sum(|x|) (each tree level adds three rounded additions).
#[test]
fn sum_reduction_matches_cpu_for_many_sizes() {
    let ctx = context();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let sizes = [
        (1, 1),
        (2, 1),
        (1, 5),
        (3, 3),
        (17, 33),
        (64, 64),
        (100, 37),
        (255, 257),
        (1024, 1024),
    ];
    for (w, h) in sizes {
        let data: Vec<f32> = (0..w * h * 4)
            .map(|_| rng.gen_range(-10.0..100.0))
            .collect();
        let t = Texture::from_f32(&ctx, w, h, TextureFormat::Rgba32F, &data).unwrap();
        let got = gl::reduce::reduce(&ctx, &t, ReduceOp::Sum).unwrap();
        let levels = passes_for(w, h) as f64;
        for (c, &gpu) in got.iter().enumerate() {
            let channel = data.iter().skip(c).step_by(4);
            let exact: f64 = channel.clone().map(|&v| v as f64).sum();
            let magnitude: f64 = channel.map(|&v| (v as f64).abs()).sum();
            let tolerance = levels * 3.0 * f32::EPSILON as f64 * 0.5 * magnitude + 1e-6;
            assert!(
                (gpu as f64 - exact).abs() <= tolerance,
                "{w}x{h} channel {c}: gpu {gpu} cpu {exact} (tolerance {tolerance})"
            );
        }
    }
}

#[test]
fn min_max_count_and_or_reductions() {
    let ctx = context();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (w, h) in [(1, 1), (9, 4), (31, 64), (200, 3)] {
        let n = (w * h) as usize;
        let data: Vec<f32> = (0..n)
            .map(|_| {
                if rng.gen_bool(0.1) {
                    rng.gen_range(-5.0..5.0)
                } else {
                    0.0
                }
            })
            .collect();
        let t = Texture::from_f32(&ctx, w, h, TextureFormat::R32F, &data).unwrap();
        let reducer = Reducer::new(&ctx, w, h).unwrap();
        let min = data.iter().cloned().fold(f32::INFINITY, f32::min);
        let max = data.iter().cloned().fold(f32::NEG_INFINITY, f32::max);
        let count = data.iter().filter(|&&v| v != 0.0).count();
        assert_eq!(reducer.reduce(&t, ReduceOp::Min).unwrap()[0], min);
        assert_eq!(reducer.reduce(&t, ReduceOp::Max).unwrap()[0], max);
        assert_eq!(
            reducer.reduce(&t, ReduceOp::CountNonZero).unwrap()[0],
            count as f32
        );
        assert_eq!(
            reducer.reduce(&t, ReduceOp::Or).unwrap()[0],
            (count > 0) as u32 as f32
        );
    }
    // Every texel zero: OR is 0 and the count is 0.
    let zeros = Texture::from_f32(&ctx, 5, 7, TextureFormat::R32F, &[0.0; 35]).unwrap();
    assert_eq!(
        gl::reduce::reduce(&ctx, &zeros, ReduceOp::Or).unwrap()[0],
        0.0
    );
}

#[test]
fn block_reduction_sums_each_tile() {
    let ctx = context();
    let (block, tiles_x, tiles_y) = (8u32, 5u32, 3u32);
    let (w, h) = (block * tiles_x, block * tiles_y);
    let data: Vec<f32> = (0..w * h)
        .flat_map(|i| {
            let (x, y) = (i % w, i / w);
            [(x / block + 10 * (y / block)) as f32, 1.0, 0.0, 0.0]
        })
        .collect();
    let t = Texture::from_f32(&ctx, w, h, TextureFormat::Rgba32F, &data).unwrap();
    let sums = Reducer::new(&ctx, w, h)
        .unwrap()
        .reduce_blocks(&t, ReduceOp::Sum, block)
        .unwrap();
    assert_eq!(sums.len(), (tiles_x * tiles_y) as usize);
    for (i, s) in sums.iter().enumerate() {
        let (tx, ty) = (i as u32 % tiles_x, i as u32 / tiles_x);
        assert_eq!(
            s[0],
            ((tx + 10 * ty) * block * block) as f32,
            "tile ({tx}, {ty})"
        );
        assert_eq!(s[1], (block * block) as f32);
    }
}

/// Layers per pixel by casting a ray down -z through each pixel centre, on the GPU's own
/// sub-pixel grid (8 bits) so that pixels near an edge are decided the same way.
fn ray_cast_counts(
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    min: Vec3,
    max: Vec3,
    (w, h): (u32, u32),
    below_z: Option<f32>,
) -> Vec<u32> {
    let snap = |v: f64| (v * 256.0).round() / 256.0;
    let to_pixels = |p: [f32; 3]| {
        let x = (p[0] - min.x) as f64 / (max.x - min.x) as f64 * w as f64;
        let y = (p[1] - min.y) as f64 / (max.y - min.y) as f64 * h as f64;
        (snap(x), snap(y), p[2] as f64)
    };
    let mut counts = vec![0u32; (w * h) as usize];
    for tri in triangles {
        let v = tri.map(|i| to_pixels(positions[i as usize]));
        let area = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[2].0 - v[0].0) * (v[1].1 - v[0].1);
        if area == 0.0 {
            continue;
        }
        let x_range = v
            .iter()
            .map(|p| p.0)
            .fold((f64::MAX, f64::MIN), |a, x| (a.0.min(x), a.1.max(x)));
        let y_range = v
            .iter()
            .map(|p| p.1)
            .fold((f64::MAX, f64::MIN), |a, y| (a.0.min(y), a.1.max(y)));
        for py in (y_range.0.floor().max(0.0) as u32)..(y_range.1.ceil().min(h as f64) as u32) {
            for px in (x_range.0.floor().max(0.0) as u32)..(x_range.1.ceil().min(w as f64) as u32) {
                let (cx, cy) = (px as f64 + 0.5, py as f64 + 0.5);
                let edge = |a: (f64, f64, f64), b: (f64, f64, f64)| {
                    (b.0 - a.0) * (cy - a.1) - (b.1 - a.1) * (cx - a.0)
                };
                let e = [edge(v[0], v[1]), edge(v[1], v[2]), edge(v[2], v[0])];
                let inside = e.iter().all(|&e| e * area.signum() > 0.0);
                if !inside {
                    continue;
                }
                let z = (e[1] * v[0].2 + e[2] * v[1].2 + e[0] * v[2].2) / (e[0] + e[1] + e[2]);
                if below_z.is_none_or(|limit| z <= limit as f64) {
                    counts[(py * w + px) as usize] += 1;
                }
            }
        }
    }
    counts
}

fn check_peeling(
    name: &str,
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    below_z: Option<f32>,
    min_layers: usize,
) {
    let ctx = context();
    let mesh = MeshBuffers::new(&ctx, &positions, &triangles).unwrap();
    let (min, max) = positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(Vec3::from(*p)), hi.max(Vec3::from(*p))),
    );
    // A margin keeps every silhouette inside the view.
    let (min, max) = (min - 0.1, max + 0.1);
    let size = (72, 64);
    let options = peel::PeelOptions {
        clip_plane: below_z.map(|z| Vec4::new(0.0, 0.0, -1.0, z)),
        ..Default::default()
    };
    let (layers, counts) = peel::layer_counts(
        &ctx,
        &mesh,
        peel::ortho_box(min, max),
        size.0,
        size.1,
        options,
    )
    .unwrap();
    let expected = ray_cast_counts(&positions, &triangles, min, max, size, below_z);
    let mismatches: Vec<_> = counts
        .iter()
        .zip(&expected)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(i, (a, b))| (i as u32 % size.0, i as u32 / size.0, *a, *b))
        .collect();
    assert!(
        mismatches.is_empty(),
        "{name}: (x, y, gpu, cpu) {mismatches:?}"
    );
    assert_eq!(
        layers as u32,
        *expected.iter().max().unwrap(),
        "{name}: layer count"
    );
    assert!(
        layers >= min_layers,
        "{name}: only {layers} layers; the view is too easy"
    );
}

/// A torus tilted so that its hole and its sides give up to 4 layers.
fn tilted_torus() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let tilt =
        glam::Affine3A::from_quat(glam::Quat::from_euler(glam::EulerRot::XYZ, 0.9, 0.3, 0.0));
    let torus = mesh::torus_closed(1.0, 0.35, 48, 16).transformed(&tilt);
    (torus.positions_f32().to_vec(), torus.triangles)
}

/// A (2, 3) torus knot: up to 4 layers where its strands cross.
fn trefoil() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let knot = mesh::torus_knot(&mesh::TorusKnot::default());
    (knot.positions_f32().to_vec(), knot.triangles)
}

#[test]
fn depth_peeling_counts_torus_layers() {
    let (p, t) = tilted_torus();
    check_peeling("torus", p, t, None, 4);
}

#[test]
fn depth_peeling_counts_knot_layers() {
    let (p, t) = trefoil();
    check_peeling("knot", p, t, None, 4);
}

#[test]
fn depth_peeling_below_a_clip_plane() {
    let (p, t) = trefoil();
    check_peeling("knot below z = 0.2", p, t, Some(0.2), 2);
}

#[test]
fn shader_syntax_error_names_file_and_line() {
    let ctx = context();
    let broken = ShaderSource {
        name: "tests/data/broken.frag",
        source: include_str!("data/broken.frag"),
    };
    let err = Program::rect(&ctx, &[broken])
        .err()
        .expect("must not compile");
    let GlError::Shader(shader_error) = &err else {
        panic!("expected a shader error, got {err}");
    };
    assert_eq!(shader_error.file, "tests/data/broken.frag");
    assert_eq!(shader_error.line, Some(6), "{err}");
    let text = err.to_string();
    assert!(text.contains("tests/data/broken.frag:6"), "{text}");
    assert!(
        text.contains(">    6 |     o_color = vec4(1.0) +;"),
        "{text}"
    );
    // A file that comes second in a stage is still named correctly.
    let snippet = ShaderSource {
        name: "snippet.glsl",
        source: "// nothing wrong here\n",
    };
    let err = Program::rect(&ctx, &[snippet, broken])
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("tests/data/broken.frag:6"), "{err}");
}

#[test]
fn misspelt_uniform_is_an_error_naming_it_and_the_files() {
    let ctx = context();
    let target = Texture::new_2d(&ctx, 4, 4, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "uniforms", &[&target], None).unwrap();
    let program = Program::rect(&ctx, &[shader!("glsl/test/unused_uniform.frag")]).unwrap();

    let err = fb
        .pass(&program, "misspelt")
        .unwrap()
        .uniform("u_color", Vec4::ONE)
        .draw_full()
        .expect_err("u_color is not declared");
    assert!(matches!(err, GlError::Uniform { .. }), "{err}");
    let text = err.to_string();
    for part in [
        "uniform u_color ",
        "glsl/gl/rect.vert",
        "glsl/test/unused_uniform.frag",
    ] {
        assert!(text.contains(part), "{part} missing from: {text}");
    }
    // The message lists what the files do declare.
    assert!(text.contains("u_colour, u_never_read"), "{text}");
    assert!(program.set("u_colr", 1.0f32).is_err());

    // Declared but removed by the compiler: setting it is allowed, on every driver alike.
    // Optional uniforms are set with uniform_if_used, which skips undeclared names.
    fb.clear_colors([0.0; 4]).unwrap();
    fb.pass(&program, "declared")
        .unwrap()
        .uniform("u_colour", Vec4::new(0.25, 0.5, 0.75, 1.0))
        .uniform("u_never_read", 2.0f32)
        .uniform_if_used("u_not_in_this_program", 3.0f32)
        .draw_full()
        .unwrap();
    assert!(program.declares_uniform("u_never_read"));
    assert!(!program.declares_uniform("u_not_in_this_program"));
    let pixels = target.download_f32().unwrap();
    assert!(pixels.chunks(4).all(|p| p == [0.25, 0.5, 0.75, 1.0]));
}

#[test]
fn every_gl_layer_shader_compiles() {
    let ctx = context();
    Program::rect(&ctx, &[shader!("glsl/gl/reduce.frag")]).unwrap();
    Program::new(
        &ctx,
        &[peel::PEEL_VERTEX],
        &[peel::PEEL_SNIPPET, shader!("glsl/gl/peel_count.frag")],
    )
    .unwrap();
    for fragment in [
        shader!("glsl/test/mrt.frag"),
        shader!("glsl/test/constant.frag"),
        shader!("glsl/test/positions.frag"),
        shader!("glsl/test/unused_uniform.frag"),
    ] {
        Program::rect(&ctx, &[fragment]).unwrap();
    }
    Program::new(&ctx, &[shader!("glsl/test/points.vert")], &[CONSTANT]).unwrap();
}

#[test]
fn dump_writes_a_png_of_the_texture() {
    let ctx = context();
    let data: Vec<f32> = (0..6 * 4)
        .flat_map(|i| [i as f32, 0.0, -(i as f32), 1.0])
        .collect();
    let t = Texture::from_f32(&ctx, 6, 4, TextureFormat::Rgba32F, &data).unwrap();
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-dump-{}", std::process::id()));
    let path = dir.join("t.png");
    dump::texture_png(&t, &path, dump::DumpRange::Auto).unwrap();
    let image = image::open(&path).unwrap().to_rgba8();
    assert_eq!(image.dimensions(), (6, 4));
    // Texel 0 (bottom left in GL) is the image's bottom-left pixel: red 0, blue 255.
    assert_eq!(image.get_pixel(0, 3).0, [0, 128, 255, 255]);
    assert_eq!(image.get_pixel(5, 0).0, [255, 128, 0, 255]);
    std::fs::remove_dir_all(dir).ok();
}
