//! VPLs into images: the scene drawn from the spot light into level 0 of the light
//! hierarchy (a reflective shadow map: position, normal and reflected flux per texel).
//!
//! Reconstruction: the abstract stores VPLs "in images"; making them by rendering the scene
//! from the light is the standard way (reflective shadow maps) and ours.

use super::clusters::GpuClusters;
use super::scene::Scene;
use crate::gl::{Compare, Context, DepthTest, DrawState, GlError, Primitive, Program, VertexArray};
use crate::shader;

/// The VPL pass.
pub struct VplPass {
    program: Program,
}

impl VplPass {
    pub fn new(ctx: &Context) -> Result<VplPass, GlError> {
        Ok(VplPass {
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture3/scene.vert")],
                &[shader!("glsl/lecture3/vpl_image.frag")],
            )?,
        })
    }

    /// Draws `scene` (its `vertices`, `count` of them) from the light into level 0 of
    /// `clusters`.
    pub fn draw(
        &self,
        scene: &Scene,
        vertices: &VertexArray,
        count: usize,
        clusters: &GpuClusters,
    ) -> Result<(), GlError> {
        let target = &clusters.level0;
        target.clear_colors([0.0; 4])?;
        target.clear_depth_stencil(1.0, 0)?;
        target
            .pass(&self.program, "VPLs from the light")?
            .uniform("u_view_projection", scene.light.view_projection(1.0))
            .uniform("u_intensity", scene.intensity)
            .uniform("u_half_extent", (0.5 * scene.light.fov_y).tan())
            .uniform("u_size", clusters.size() as f32)
            .state(DrawState {
                depth: Some(DepthTest {
                    func: Compare::Less,
                    write: true,
                }),
                ..DrawState::default()
            })
            .draw_arrays(vertices, Primitive::Triangles, 0, count)
    }
}
