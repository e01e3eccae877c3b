//! Frames of the buoyancy scene as PNG [Fig. 9, 10]: bodies flat-shaded, the water as a
//! translucent plane, and at each body the gravity (blue, down, at the centre of mass) and
//! buoyancy (yellow, up, at the centre of buoyancy) arrows, scaled by force.

use super::simulation::{Shape, Simulation};
use crate::gl::{
    dump, Blend, Buffer, BufferUsage, Compare, Context, DepthTest, DrawState, Framebuffer, GlError,
    Primitive, Program, Rect, Texture, TextureFormat, VertexArray,
};
use crate::shader;
use glam::camera::rh::{proj::opengl, view::look_at_mat4};
use glam::{Mat4, Vec3, Vec4};
use std::path::Path;

/// Body colours by shape index.
const COLORS: [Vec3; 5] = [
    Vec3::new(0.85, 0.3, 0.25),
    Vec3::new(0.8, 0.65, 0.3),
    Vec3::new(0.35, 0.7, 0.35),
    Vec3::new(0.75, 0.75, 0.8),
    Vec3::new(0.85, 0.75, 0.6),
];

/// A turn of the camera (the viewer's mouse): yaw about the vertical and pitch in radians, and
/// a zoom factor (2 brings the camera twice as close).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turn {
    pub yaw: f32,
    pub pitch: f32,
    pub zoom: f32,
}

impl Default for Turn {
    fn default() -> Self {
        Turn {
            yaw: 0.0,
            pitch: 0.0,
            zoom: 1.0,
        }
    }
}

/// An off-screen renderer of the scene.
pub struct FrameRenderer {
    ctx: Context,
    target: Framebuffer,
    meshes: FlatMeshes,
    bodies: Program,
    water: Program,
    lines: Program,
    width: u32,
    height: u32,
}

impl FrameRenderer {
    pub fn new(
        ctx: &Context,
        shapes: &[Shape],
        width: u32,
        height: u32,
    ) -> Result<FrameRenderer, GlError> {
        let color = Texture::new_2d(ctx, width, height, TextureFormat::Rgba8)?;
        let depth = Texture::new_2d(ctx, width, height, TextureFormat::Depth32F)?;
        let meshes: Vec<_> = shapes.iter().map(|s| &s.mesh).collect();
        Ok(FrameRenderer {
            ctx: ctx.clone(),
            target: Framebuffer::new(ctx, "buoyancy frame", &[&color], Some(&depth))?,
            meshes: FlatMeshes::new(ctx, &meshes)?,
            bodies: Program::new(
                ctx,
                &[shader!("glsl/mass/render_body.vert")],
                &[shader!("glsl/mass/render_body.frag")],
            )?,
            water: Program::new(
                ctx,
                &[shader!("glsl/mass/render_water.vert")],
                &[shader!("glsl/mass/render_flat.frag")],
            )?,
            lines: Program::new(
                ctx,
                &[shader!("glsl/mass/render_lines.vert")],
                &[shader!("glsl/mass/render_flat.frag")],
            )?,
            width,
            height,
        })
    }

    /// A camera looking down at the whole scene from the south, turned by `turn`, for a
    /// target of `aspect` (width over height).
    fn view_projection(&self, sim: &Simulation, turn: Turn, aspect: f32) -> Mat4 {
        let extent = sim
            .bodies
            .iter()
            .map(|b| b.rigid.position.truncate().length() as f32)
            .fold(1.0, f32::max)
            + 2.0;
        let target = Vec3::new(0.0, 0.0, -0.5);
        let eye = Vec3::new(0.0, -1.1 * extent, 0.7 * extent) - target;
        let eye = Mat4::from_rotation_z(turn.yaw)
            * Mat4::from_axis_angle(Vec3::X, -turn.pitch)
            * eye.extend(0.0);
        let eye = target + eye.truncate() / turn.zoom.max(1e-3);
        let view = look_at_mat4(eye, target, Vec3::Z);
        opengl::perspective(0.8, aspect, 0.1, 10.0 * extent) * view
    }

    /// Draws the current state into the renderer's own target and waits until it is drawn:
    /// one frame of an interactive run (the bodies with their force arrows, and the water).
    pub fn draw_frame(&self, sim: &Simulation) -> Result<(), GlError> {
        self.draw(sim, &self.target, Turn::default())?;
        self.ctx.finish_all();
        Ok(())
    }

    /// The size of the renderer's own target.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Draws the current state and writes it to `path`.
    pub fn write_png(&self, sim: &Simulation, path: &Path) -> Result<(), GlError> {
        self.draw(sim, &self.target, Turn::default())?;
        let pixels = self
            .target
            .read_u8(0, Rect::sized(self.width, self.height))?;
        dump::rgba_png(&pixels, (self.width, self.height), path)
    }

    /// Draw the current state into `target` (colour and depth; cleared here), the camera
    /// turned by `turn`.
    pub fn draw(&self, sim: &Simulation, target: &Framebuffer, turn: Turn) -> Result<(), GlError> {
        let aspect = target.width() as f32 / target.height().max(1) as f32;
        let vp = self.view_projection(sim, turn, aspect);
        target.clear_colors([0.62, 0.75, 0.88, 1.0])?;
        target.clear_depth_stencil(1.0, 0)?;
        let opaque = DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            ..DrawState::default()
        };
        {
            let mut pass = target.pass(&self.bodies, "buoyancy frame: bodies")?;
            pass.state(opaque)
                .uniform("u_view_projection", vp)
                .uniform("u_water_level", sim.water.level as f32);
            for body in &sim.bodies {
                let (first, count) = self.meshes.ranges[body.shape];
                let model = Mat4::from_rotation_translation(
                    body.rigid.orientation.as_quat(),
                    body.rigid.position.as_vec3(),
                );
                pass.uniform("u_model", model)
                    .uniform("u_colour", COLORS[body.shape % COLORS.len()]);
                pass.draw_arrays(&self.meshes.vertices, Primitive::Triangles, first, count)?;
            }
        }
        self.draw_arrows(sim, vp, target)?;
        {
            let mut pass = target.pass(&self.water, "buoyancy frame: water")?;
            pass.state(DrawState {
                depth: Some(DepthTest {
                    func: Compare::Less,
                    write: false,
                }),
                blend: Some(Blend::Alpha),
                ..DrawState::default()
            })
            .uniform("u_view_projection", vp)
            .uniform("u_water_level", sim.water.level as f32)
            .uniform("u_extent", 1000.0f32)
            .uniform("u_colour", Vec4::new(0.05, 0.22, 0.42, 0.55));
            pass.draw_attributeless(Primitive::TriangleStrip, 4, 1)?;
        }
        Ok(())
    }

    /// Gravity and buoyancy arrows, drawn over everything (depth test off).
    fn draw_arrows(&self, sim: &Simulation, vp: Mat4, target: &Framebuffer) -> Result<(), GlError> {
        let g = sim.water.gravity;
        let scale = |force: f64, mass: f64| (0.8 * force / (mass * g)) as f32;
        let mut gravity = Vec::new();
        let mut buoyancy = Vec::new();
        for body in &sim.bodies {
            let c = body.rigid.position.as_vec3();
            gravity.extend(arrow(c, -Vec3::Z * 0.8));
            let sub = body.submerged;
            if sub.volume > 0.0 {
                let f = sim.water.density * g * sub.volume;
                buoyancy.extend(arrow(
                    sub.center.as_vec3(),
                    Vec3::Z * scale(f, body.rigid.mass),
                ));
            }
        }
        for (segments, color) in [
            (gravity, Vec4::new(0.1, 0.2, 1.0, 1.0)),
            (buoyancy, Vec4::new(1.0, 0.9, 0.1, 1.0)),
        ] {
            if segments.is_empty() {
                continue;
            }
            let buffer = Buffer::from_slice(&self.ctx, &segments, BufferUsage::Dynamic)?;
            let mut vertices = VertexArray::new(&self.ctx)?;
            vertices.float_attribute(0, &buffer, 3, 12, 0, 0)?;
            let mut pass = target.pass(&self.lines, "buoyancy frame: force arrows")?;
            pass.uniform("u_view_projection", vp)
                .uniform("u_colour", color);
            pass.draw_arrays(&vertices, Primitive::Lines, 0, segments.len())?;
        }
        Ok(())
    }
}

/// The shapes for flat shading: every triangle corner with its face normal.
struct FlatMeshes {
    vertices: VertexArray,
    /// (first vertex, vertex count) of each shape.
    ranges: Vec<(usize, usize)>,
}

impl FlatMeshes {
    fn new(ctx: &Context, meshes: &[&crate::mesh::Mesh]) -> Result<FlatMeshes, GlError> {
        let mut data: Vec<[f32; 6]> = Vec::new();
        let mut ranges = Vec::new();
        for mesh in meshes {
            let first = data.len();
            for t in 0..mesh.triangles.len() {
                let [a, b, c] = mesh.triangle(t);
                let n = (b - a).cross(c - a).normalize_or_zero();
                data.extend([a, b, c].map(|v| [v.x, v.y, v.z, n.x, n.y, n.z]));
            }
            ranges.push((first, data.len() - first));
        }
        let buffer = Buffer::from_slice(ctx, &data, BufferUsage::Static)?;
        let mut vertices = VertexArray::new(ctx)?;
        vertices.float_attribute(0, &buffer, 3, 24, 0, 0)?;
        vertices.float_attribute(1, &buffer, 3, 24, 12, 0)?;
        Ok(FlatMeshes { vertices, ranges })
    }
}

/// Line segments of an arrow from `from` along `v`, with a small head.
fn arrow(from: Vec3, v: Vec3) -> Vec<[f32; 3]> {
    let to = from + v;
    let side = v.any_orthonormal_vector() * v.length() * 0.12;
    let back = to - v * 0.2;
    [from, to, to, back + side, to, back - side]
        .iter()
        .map(|p| p.to_array())
        .collect()
}
