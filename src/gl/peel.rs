//! Depth peeling (Everitt 2001; paper 4 section 3.2): render a mesh layer by layer, front to
//! back, each layer keeping only the fragments strictly behind the previous layer's depth,
//! until an occlusion query reports that a layer drew nothing.
//!
//! A fragment shader that takes part starts with the snippet [`PEEL_SNIPPET`] and calls
//! `peel_discard()` first. [`PEEL_VERTEX`] is a matching vertex shader with a clip plane.

use super::{
    Compare, Context, DepthTest, DrawState, Framebuffer, GlError, MeshBuffers, OcclusionQuery,
    Pass, Program, Rect, ShaderSource, Texture, TextureFormat,
};
use crate::shader;
use glam::camera::rh::proj::opengl;
use glam::{Mat4, Vec3, Vec4};

/// Fragment-shader snippet: `u_peel_depth`, `u_peel_layer` and `peel_discard()`.
pub const PEEL_SNIPPET: ShaderSource<'static> = shader!("glsl/gl/peel.glsl");
/// Vertex shader: `a_position` at location 0, `u_mvp`, `u_clip_plane`, out `v_position`.
pub const PEEL_VERTEX: ShaderSource<'static> = shader!("glsl/gl/peel_mesh.vert");

/// An orthographic projection of the box `min..max`, looking down -z: x and y fill the
/// viewport, the top (`max.z`) is nearest (depth 0) and the bottom (`min.z`) farthest (1).
pub fn ortho_box(min: Vec3, max: Vec3) -> Mat4 {
    opengl::orthographic(min.x, max.x, min.y, max.y, -max.z, -min.z)
}

/// Options of a peel.
#[derive(Clone, Copy, Debug)]
pub struct PeelOptions {
    /// Stop after this many layers even if fragments remain.
    pub max_layers: usize,
    /// Peel only the part where `dot(plane, (p, 1)) >= 0` (needs a vertex shader writing
    /// `gl_ClipDistance[0]`, as [`PEEL_VERTEX`] does).
    pub clip_plane: Option<Vec4>,
    /// Colour targets are cleared to this before each layer.
    pub clear: [f32; 4],
}

impl Default for PeelOptions {
    fn default() -> Self {
        PeelOptions {
            max_layers: 64,
            clip_plane: None,
            clear: [0.0; 4],
        }
    }
}

/// The two depth textures a peel alternates between, and its occlusion query.
pub struct DepthPeeler {
    ctx: Context,
    depth: [Texture; 2],
    query: OcclusionQuery,
}

impl DepthPeeler {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<DepthPeeler, GlError> {
        let depth = || Texture::new_2d(ctx, width, height, TextureFormat::Depth32F);
        Ok(DepthPeeler {
            ctx: ctx.clone(),
            depth: [depth()?, depth()?],
            query: OcclusionQuery::new(ctx)?,
        })
    }

    pub fn width(&self) -> u32 {
        self.depth[0].width()
    }
    pub fn height(&self) -> u32 {
        self.depth[0].height()
    }

    /// Peel into `colors` (MRT allowed) with `program`. For each layer, `draw` issues the draw
    /// calls (the pass comes with the peeling textures, uniforms and state set); then, if the
    /// layer drew anything, `on_layer(k, framebuffer)` consumes it (reduce, read, dump).
    /// Returns the number of non-empty layers.
    pub fn peel(
        &self,
        colors: &[&Texture],
        program: &Program,
        options: PeelOptions,
        mut draw: impl FnMut(&mut Pass) -> Result<(), GlError>,
        mut on_layer: impl FnMut(usize, &Framebuffer) -> Result<(), GlError>,
    ) -> Result<usize, GlError> {
        let targets = [
            Framebuffer::new(
                &self.ctx,
                "depth peel (even layers)",
                colors,
                Some(&self.depth[0]),
            )?,
            Framebuffer::new(
                &self.ctx,
                "depth peel (odd layers)",
                colors,
                Some(&self.depth[1]),
            )?,
        ];
        let state = DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            clip_distances: options.clip_plane.is_some() as u32,
            ..DrawState::default()
        };
        for layer in 0..options.max_layers {
            let target = &targets[layer % 2];
            target.clear_colors(options.clear)?;
            target.clear_depth_stencil(1.0, 0)?;
            let mut pass = target.pass(program, "depth peel")?;
            pass.state(state)
                .texture("u_peel_depth", &self.depth[(layer + 1) % 2])
                .uniform("u_peel_layer", layer as i32)
                .uniform("u_clip_plane", options.clip_plane.unwrap_or(Vec4::W));
            self.query.begin();
            let drawn = draw(&mut pass);
            self.query.end();
            drawn?;
            if self.query.samples()? == 0 {
                return Ok(layer);
            }
            on_layer(layer, target)?;
        }
        Ok(options.max_layers)
    }
}

/// How many layers cover each pixel of a `width x height` view of a mesh under `mvp`
/// (row by row from the bottom), and the number of layers peeled. A reference for tests
/// and a debugging view.
pub fn layer_counts(
    ctx: &Context,
    mesh: &MeshBuffers,
    mvp: Mat4,
    width: u32,
    height: u32,
    options: PeelOptions,
) -> Result<(usize, Vec<u32>), GlError> {
    let program = Program::new(
        ctx,
        &[PEEL_VERTEX],
        &[PEEL_SNIPPET, shader!("glsl/gl/peel_count.frag")],
    )?;
    // The snippet carries no #version: the count shader's comes first when assembled.
    let covered = Texture::new_2d(ctx, width, height, TextureFormat::R32F)?;
    let peeler = DepthPeeler::new(ctx, width, height)?;
    let mut counts = vec![0u32; (width * height) as usize];
    let layers = peeler.peel(
        &[&covered],
        &program,
        options,
        |pass| {
            pass.uniform("u_mvp", mvp);
            pass.draw_mesh(mesh)
        },
        |_, target| {
            let layer = target.read_f32(0, Rect::sized(width, height))?;
            for (count, value) in counts.iter_mut().zip(layer) {
                *count += (value > 0.5) as u32;
            }
            Ok(())
        },
    )?;
    Ok((layers, counts))
}
