//! The GL layer's image-pyramid, integer and filtering features on a real headless context:
//! mipmap levels as render targets, a level rendered from the level below, RGBA32UI textures
//! and targets, and linear filtering of a 1D texture. Each against what the CPU says.

use classic_gpgpu::gl::{Filter, Framebuffer, Program, Rect, Texture, TextureFormat};
use classic_gpgpu::shader;
use common::context;

mod common;

#[test]
fn mipmap_levels_have_halved_sizes_and_are_render_targets() {
    let ctx = context();
    let t = Texture::new_2d_mipmapped(&ctx, 12, 5, TextureFormat::R32F, 4).unwrap();
    assert_eq!(t.levels(), 4);
    let sizes: Vec<_> = (0..4).map(|l| t.level_size(l)).collect();
    assert_eq!(sizes, [(12, 5), (6, 2), (3, 1), (1, 1)]);
    for level in 0..4 {
        let fb = Framebuffer::new_at_level(&ctx, "level", &[&t], None, level).unwrap();
        assert_eq!((fb.width(), fb.height()), t.level_size(level));
        fb.clear_color(0, [level as f32 + 0.5; 4]).unwrap();
    }
    for level in 0..4 {
        let (w, h) = t.level_size(level);
        let values = t.download_level_f32(level).unwrap();
        assert_eq!(values.len(), (w * h) as usize);
        assert!(
            values.iter().all(|&v| v == level as f32 + 0.5),
            "{values:?}"
        );
    }
    let err = Texture::new_2d_mipmapped(&ctx, 12, 5, TextureFormat::R32F, 5)
        .unwrap_err()
        .to_string();
    assert!(err.contains("1 to 4 mipmap levels"), "{err}");
    let err = Framebuffer::new_at_level(&ctx, "too deep", &[&t], None, 4)
        .unwrap_err()
        .to_string();
    assert!(err.contains("level 4 of a texture with 4 levels"), "{err}");
}

#[test]
fn each_level_is_rendered_from_the_level_below() {
    let ctx = context();
    let program = Program::rect(&ctx, &[shader!("glsl/test/level_from_below.frag")]).unwrap();
    let size = 8;
    let levels = 4;
    let t = Texture::new_2d_mipmapped(&ctx, size, size, TextureFormat::R32F, levels).unwrap();
    let base: Vec<f32> = (0..size * size).map(|i| i as f32).collect();
    t.upload_f32(&base).unwrap();
    let mut expected = vec![base];
    for level in 1..levels {
        t.set_level_range(level - 1, level - 1).unwrap();
        let fb = Framebuffer::new_at_level(&ctx, "pyramid level", &[&t], None, level).unwrap();
        fb.pass(&program, "level from below")
            .unwrap()
            .texture("u_below", &t)
            .draw_full()
            .unwrap();
        let below = expected.last().unwrap();
        let (w, below_w) = ((size >> level) as usize, (size >> (level - 1)) as usize);
        let level_values = (0..w * w)
            .map(|i| {
                let (x, y) = (i % w * 2, i / w * 2);
                let at = |dx: usize, dy: usize| below[(y + dy) * below_w + x + dx];
                at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1) + 1000.0
            })
            .collect();
        expected.push(level_values);
    }
    t.set_level_range(0, levels - 1).unwrap();
    for (level, values) in expected.iter().enumerate() {
        assert_eq!(&t.download_level_f32(level as u32).unwrap(), values);
    }
}

#[test]
fn rgba32ui_textures_round_trip_and_are_integer_render_targets() {
    let ctx = context();
    let (w, h) = (5u32, 3u32);
    let state: Vec<u32> = (0..w * h * 4)
        .map(|i| i.wrapping_mul(2_654_435_761))
        .collect();
    let input = Texture::new_2d(&ctx, w, h, TextureFormat::Rgba32Ui).unwrap();
    input.upload_u32(&state).unwrap();
    assert_eq!(input.download_u32().unwrap(), state);
    let output = Texture::new_2d(&ctx, w, h, TextureFormat::Rgba32Ui).unwrap();
    let fb = Framebuffer::new(&ctx, "uint target", &[&output], None).unwrap();
    let program = Program::rect(&ctx, &[shader!("glsl/test/uint_state.frag")]).unwrap();
    fb.pass(&program, "uint pass")
        .unwrap()
        .texture("u_state", &input)
        .draw_full()
        .unwrap();
    let expected: Vec<u32> = state
        .chunks_exact(4)
        .enumerate()
        .flat_map(|(i, s)| {
            let (x, y) = (i as u32 % w, i as u32 / w);
            [s[1] ^ x, s[2] ^ y, s[3] ^ 0xdead_beef, s[0] ^ (s[0] << 3)]
        })
        .collect();
    assert_eq!(fb.read_u32(0, Rect::sized(w, h)).unwrap(), expected);
    assert!(fb.read_u8(0, Rect::sized(w, h)).is_err());
    assert!(fb.read_f32(0, Rect::sized(w, h)).is_err());
}

#[test]
fn linear_filtering_interpolates_a_1d_table() {
    let ctx = context();
    let table = Texture::new_1d(&ctx, 4, TextureFormat::R32F).unwrap();
    table.upload_f32(&[0.0, 1.0, 4.0, 9.0]).unwrap();
    table.set_filter(Filter::Linear);
    let target = Texture::new_2d(&ctx, 8, 1, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "samples", &[&target], None).unwrap();
    let program = Program::rect(&ctx, &[shader!("glsl/test/sample_1d.frag")]).unwrap();
    // Texel centres at (i + 0.5) / 4; between them the value is interpolated, beyond the
    // outer centres it is clamped.
    let x = [0.125f32, 0.25, 0.375, 0.5, 0.625, 0.875, 0.0, 1.0];
    let expected = [0.0f32, 0.5, 1.0, 2.5, 4.0, 9.0, 0.0, 9.0];
    fb.pass(&program, "1D lookups")
        .unwrap()
        .texture("u_table", &table)
        .uniform("u_x", &x[..])
        .draw_full()
        .unwrap();
    let values = fb.read_f32(0, Rect::sized(8, 1)).unwrap();
    for i in 0..8 {
        // Filtering hardware may round the weights to 8 fractional bits: 9/256 at most here.
        assert!(
            (values[4 * i] - expected[i]).abs() <= 9.0 / 256.0,
            "x = {}: {} vs {}",
            x[i],
            values[4 * i],
            expected[i]
        );
    }
    table.set_filter(Filter::Nearest);
    fb.pass(&program, "1D lookups")
        .unwrap()
        .texture("u_table", &table)
        .draw_full()
        .unwrap();
    let values = fb.read_f32(0, Rect::sized(8, 1)).unwrap();
    // Nearest: texel floor(4 x); x = 0.25 is the left edge of texel 1.
    assert_eq!(values[4], 1.0);
    assert_eq!(values[4 * 3], 4.0);
}

#[test]
fn texel_fetch_reads_any_mipmap_level() {
    let ctx = context();
    let t = Texture::new_2d_mipmapped(&ctx, 8, 4, TextureFormat::R32F, 4).unwrap();
    let program = Program::rect(&ctx, &[shader!("glsl/test/fetch_level.frag")]).unwrap();
    let values = |level: u32| -> Vec<f32> {
        let (w, h) = t.level_size(level);
        (0..w * h).map(|i| (level * 100 + i) as f32).collect()
    };
    for level in 0..4 {
        t.upload_level_f32(level, &values(level)).unwrap();
    }
    for level in 0..4 {
        let (w, h) = t.level_size(level);
        let out = Texture::new_2d(&ctx, w, h, TextureFormat::Rgba32F).unwrap();
        let fb = Framebuffer::new(&ctx, "fetched", &[&out], None).unwrap();
        fb.pass(&program, "fetch a level")
            .unwrap()
            .texture("u_texture", &t)
            .uniform("u_level", level as i32)
            .draw_full()
            .unwrap();
        let fetched: Vec<f32> = fb
            .read_f32(0, Rect::sized(w, h))
            .unwrap()
            .chunks_exact(4)
            .map(|c| c[0])
            .collect();
        assert_eq!(fetched, values(level), "level {level}");
    }
}
