//! Whether a fragment shader's `gl_FrontFacing` agrees with the facing the rasterizer gives a
//! triangle for culling and two-sided stencil (the winding in window space against
//! `glFrontFace`). The GL specification says it must (section 14.6.1 of GL 4.6), but nothing
//! is taken on trust: a shader that counts a fragment with the facing it was drawn with asks
//! [`Context::fragment_facing`] first. Shaders read `gl_FrontFacing` through `?:` only: on
//! softpipe (Mesa 22.3) it is right there but compares unequal to `true` with `==`.

use super::{Context, DrawState, Face, Framebuffer, GlError, Pass, Primitive, Program, Rect};
use super::{Texture, TextureFormat};
use crate::shader;

/// What `gl_FrontFacing` says, measured on this context.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FragmentFacing {
    /// True exactly for the triangles the rasterizer treats as front faces.
    FollowsWinding,
    /// True exactly for the triangles the rasterizer treats as back faces.
    Reversed,
    /// The same for both windings (or no answer): it tells nothing.
    Unusable,
}

impl FragmentFacing {
    /// +1 when `gl_FrontFacing` is the rasterizer's facing, -1 when it is the opposite, 0
    /// when it cannot be used: the factor a shader applies to it.
    pub fn sign(self) -> f32 {
        match self {
            FragmentFacing::FollowsWinding => 1.0,
            FragmentFacing::Reversed => -1.0,
            FragmentFacing::Unusable => 0.0,
        }
    }
}

impl Context {
    /// What `gl_FrontFacing` says on this renderer, probed once per context: two triangles of
    /// opposite winding drawn without culling (what the shader sees) and with back faces
    /// culled (what the rasterizer calls front).
    pub fn fragment_facing(&self) -> Result<FragmentFacing, GlError> {
        if let Some(known) = self.inner.facing.get() {
            return Ok(known);
        }
        let facing = probe(self)?;
        self.inner.facing.set(Some(facing));
        Ok(facing)
    }
}

fn probe(ctx: &Context) -> Result<FragmentFacing, GlError> {
    let program = Program::new(
        ctx,
        &[shader!("glsl/gl/facing_probe.vert")],
        &[shader!("glsl/gl/facing_probe.frag")],
    )?;
    let target = Texture::new_2d(ctx, 2, 1, TextureFormat::Rgba8)?;
    let framebuffer = Framebuffer::new(ctx, "facing probe", &[&target], None)?;
    let draw = |cull: Option<Face>| -> Result<[u8; 2], GlError> {
        framebuffer.clear_colors([0.0; 4])?;
        let mut pass: Pass = framebuffer.pass(&program, "facing probe")?;
        pass.state(DrawState {
            cull,
            ..DrawState::default()
        });
        pass.draw_attributeless(Primitive::Triangles, 6, 1)?;
        let texels = framebuffer.read_u8(0, Rect::sized(2, 1))?;
        Ok([texels[0], texels[4]])
    };
    let shader_says = draw(None)?;
    let rasterizer_keeps = draw(Some(Face::Back))?;
    Ok(classify(shader_says, rasterizer_keeps))
}

/// From the red channel of the two pixels (255 front, 128 back, 0 none) drawn without culling
/// (`shader_says`) and with back faces culled (`rasterizer_keeps`).
fn classify(shader_says: [u8; 2], rasterizer_keeps: [u8; 2]) -> FragmentFacing {
    let front = match rasterizer_keeps.map(|v| v != 0) {
        [true, false] => 0,
        [false, true] => 1,
        _ => return FragmentFacing::Unusable,
    };
    let says_front = shader_says.map(|v| v > 192);
    let drawn = shader_says.map(|v| v != 0);
    if drawn != [true, true] || says_front[0] == says_front[1] {
        return FragmentFacing::Unusable;
    }
    if says_front[front] {
        FragmentFacing::FollowsWinding
    } else {
        FragmentFacing::Reversed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shader_agreeing_with_the_culled_pass_follows_the_winding() {
        assert_eq!(
            classify([255, 128], [255, 0]),
            FragmentFacing::FollowsWinding
        );
        assert_eq!(
            classify([128, 255], [0, 255]),
            FragmentFacing::FollowsWinding
        );
        assert_eq!(classify([128, 255], [255, 0]), FragmentFacing::Reversed);
        assert_eq!(classify([255, 255], [255, 0]), FragmentFacing::Unusable);
        assert_eq!(classify([255, 128], [255, 255]), FragmentFacing::Unusable);
        assert_eq!(classify([255, 0], [255, 0]), FragmentFacing::Unusable);
    }
}
