//! The GL layer's counters of fragment shader runs: the pipeline statistics query counts at
//! least one invocation per pixel of a full-target pass and at most two (helper invocations
//! of the 2x2 quads cut by the rectangle's two triangles may be counted: llvmpipe does), two
//! passes inside one query twice as many; atomic counters bound for draws count exactly the
//! pixels whose shader ran (none where the early depth test, asked for, rejects them). Where
//! the context has no pipeline statistics, creating the query is an error that names what is
//! missing.

use classic_gpgpu::gl::{
    AtomicCounters, Compare, DepthTest, DrawState, FragmentInvocationsQuery, Framebuffer, Program,
    Texture, TextureFormat,
};
use classic_gpgpu::shader;
use common::context;

mod common;

fn target(ctx: &classic_gpgpu::gl::Context, w: u32, h: u32) -> Framebuffer {
    let colour = Texture::new_2d(ctx, w, h, TextureFormat::Rgba8).unwrap();
    let depth = Texture::new_2d(ctx, w, h, TextureFormat::Depth32F).unwrap();
    Framebuffer::new(ctx, "counted target", &[&colour], Some(&depth)).unwrap()
}

fn state(func: Compare) -> DrawState {
    DrawState {
        depth: Some(DepthTest { func, write: false }),
        ..DrawState::default()
    }
}

#[test]
fn the_pipeline_statistics_query_counts_one_run_per_pixel_drawn() {
    let ctx = context();
    if !FragmentInvocationsQuery::supported(&ctx) {
        let err = FragmentInvocationsQuery::new(&ctx)
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("GL_ARB_pipeline_statistics_query"), "{err}");
        eprintln!("no pipeline statistics here: {err}");
        return;
    }
    let (w, h) = (24, 10);
    let fb = target(&ctx, w, h);
    let program = Program::rect(&ctx, &[shader!("glsl/test/constant.frag")]).unwrap();
    let query = FragmentInvocationsQuery::new(&ctx).unwrap();
    let pixels = (w * h) as u64;
    let mut once = 0;
    for passes in [1, 2] {
        fb.clear_depth_stencil(1.0, 0).unwrap();
        query.begin();
        for _ in 0..passes {
            fb.pass(&program, "counted pass")
                .unwrap()
                .state(state(Compare::Always))
                .draw_full()
                .unwrap();
        }
        query.end();
        let counted = query.invocations().unwrap();
        assert!(
            (passes * pixels..=2 * passes * pixels).contains(&counted),
            "{passes} passes over {pixels} pixels: {counted} invocations"
        );
        if passes == 1 {
            once = counted;
        } else {
            assert_eq!(counted, 2 * once, "the same pass twice counts twice");
        }
    }
}

#[test]
fn atomic_counters_bound_for_draws_count_the_shader_runs() {
    let ctx = context();
    if !ctx.has_compute() {
        assert!(AtomicCounters::new(&ctx, 1).is_err());
        return;
    }
    let (w, h) = (16, 12);
    let fb = target(&ctx, w, h);
    let program = Program::rect(&ctx, &[shader!("glsl/test/count_runs.frag")]).unwrap();
    let counters = AtomicCounters::new(&ctx, 1).unwrap();
    for (clear, func, expected) in [(1.0, Compare::Less, w * h), (0.0, Compare::Less, 0)] {
        fb.clear_depth_stencil(clear, 0).unwrap();
        counters.reset().unwrap();
        counters.bind_for_draws(0).unwrap();
        fb.pass(&program, "counting pass")
            .unwrap()
            .state(state(func))
            .draw_full()
            .unwrap();
        assert_eq!(
            counters.read().unwrap(),
            vec![expected],
            "depth cleared to {clear}"
        );
    }
}
