//! The per-pass profiler (`gl::profile`): it names every pass drawn while it runs, counts
//! the calls, nests scopes, and adds up the waits; when off it records nothing.

use classic_gpgpu::gl::{
    profile, Framebuffer, Program, Rect, ShaderSource, Texture, TextureFormat,
};
use classic_gpgpu::shader;
use common::context;

mod common;

const CONSTANT: ShaderSource<'static> = shader!("glsl/test/constant.frag");

#[test]
fn profile_names_passes_counts_calls_and_adds_waits() {
    let ctx = context();
    let t = Texture::new_2d(&ctx, 32, 32, TextureFormat::Rgba32F).unwrap();
    let fb = Framebuffer::new(&ctx, "profiled", &[&t], None).unwrap();
    let program = Program::rect(&ctx, &[CONSTANT]).unwrap();
    let draw = |name: &str| {
        let mut pass = fb.pass(&program, name).unwrap();
        pass.uniform("u_colour", glam::Vec4::ONE);
        pass.draw_full().unwrap();
    };
    // Off: nothing is recorded.
    draw("before");
    assert!(!profile::is_on(&ctx));
    assert!(profile::finish(&ctx).is_none());

    profile::start(&ctx);
    {
        let _frame = profile::scope(&ctx, "frame");
        for _ in 0..3 {
            draw("first");
        }
        draw("second");
        let values = {
            let _decode = profile::cpu_scope(&ctx, "decode (CPU)");
            fb.read_f32(0, Rect::sized(32, 32)).unwrap()
        };
        assert!(values.iter().all(|&v| v == 1.0));
        ctx.finish_all();
    }
    let table = profile::finish(&ctx).expect("a profile was running");
    assert!(!profile::is_on(&ctx));
    let row = |name: &str| {
        table
            .row(name)
            .unwrap_or_else(|| panic!("no row {name} in\n{table}"))
    };
    assert!(table.row("before").is_none(), "{table}");
    assert_eq!(row("frame").calls, 1);
    assert_eq!(row("frame").depth, 0);
    assert_eq!(row("first").calls, 3);
    assert_eq!(row("first").depth, 1);
    assert_eq!(row("second").calls, 1);
    assert_eq!(row("wait: glReadPixels").calls, 1);
    // A CPU scope has no GPU time, and holds the wait inside it.
    assert_eq!(row("decode (CPU)").gpu_ms, None);
    assert_eq!(
        row("decode (CPU)").wait_ms,
        row("wait: glReadPixels").wall_ms
    );
    assert_eq!(row("wait: glFinish").calls, 1);
    // The frame contains its passes and its waits.
    let inner = row("first").wall_ms + row("second").wall_ms;
    assert!(row("frame").wall_ms >= inner, "{table}");
    let waits = row("wait: glReadPixels").wall_ms + row("wait: glFinish").wall_ms;
    assert!((row("frame").wait_ms - waits).abs() < 1e-9, "{table}");
    assert!(table.wall_ms >= row("frame").wall_ms, "{table}");
    // GPU times, where the renderer has timestamps, are read after the run and never negative.
    for r in &table.rows {
        if let Some(gpu) = r.gpu_ms {
            assert!(gpu >= 0.0, "{table}");
        }
    }
    let text = table.to_string();
    assert!(text.contains("first") && text.contains("wait ms"), "{text}");
}
