//! The facing probe (`Context::fragment_facing`): on Mesa's software renderers the shader's
//! `gl_FrontFacing` follows the winding the rasterizer culls by, and paper 4's peel counts
//! each fragment with it (`glsl/mass/peel_main.frag`).

use classic_gpgpu::gl::FragmentFacing;
use common::context;

mod common;

#[test]
fn gl_front_facing_follows_the_winding_on_mesa() {
    let ctx = context();
    let facing = ctx.fragment_facing().unwrap();
    let renderer = ctx.info().renderer.clone();
    if renderer.contains("llvmpipe") || renderer.contains("softpipe") {
        assert_eq!(facing, FragmentFacing::FollowsWinding, "{renderer}");
    }
    // Probed once: the same answer again, without drawing.
    assert_eq!(ctx.fragment_facing().unwrap(), facing);
}
