//! The sprite level, this project's extension (the paper's section 3 has three LOD meshes
//! and no sprites; the tutorial's lecture 2 mentions sprites for larger crowds): beyond
//! [`super::lod::LodPolicy::sprites_beyond`] a character is a textured quad. The impostor atlas is captured once per model: the coarsest mesh, skinned by the
//! vertex-shader path, seen from `VIEWS` directions around it (columns) at `FRAMES`
//! phases of its clip (rows), under an orthographic camera fitted to its bounding sphere.

use glam::camera::rh::{proj::opengl, view::look_at_mat4};
use glam::{DAffine3, DQuat, DVec3, Vec3};

use crate::gl::{
    Buffer, BufferUsage, Compare, Context, DepthTest, DrawState, Framebuffer, GlError, Primitive,
    Program, Rect, Texture, TextureFormat, VertexArray,
};
use crate::shader;

use super::character::{CharacterModel, Instances};
use super::pass2_draw::Shading;
use super::vertex_shader_skinning::VertexShaderSkinning;

/// Captured view directions (atlas columns) and animation phases (rows).
pub const VIEWS: u32 = 8;
pub const FRAMES: u32 = 8;
/// Pixels per atlas tile side.
pub const TILE: u32 = 64;

/// The atlas and the program that draws sprites from it.
pub struct Sprites {
    atlas: Framebuffer,
    program: Program,
    instances: Buffer,
    vertices: VertexArray,
}

/// Floats per sprite instance: centre xyz, radius, tile column, tile row.
const INSTANCE_FLOATS: usize = 6;

/// Atlas column for a character facing `heading` seen from direction `to_eye` (world xz):
/// the view whose captured facing, relative to the camera, is nearest.
pub fn view_column(heading: f64, to_eye: DVec3) -> u32 {
    let towards_eye = to_eye.x.atan2(to_eye.z);
    let step = std::f64::consts::TAU / VIEWS as f64;
    ((heading - towards_eye) / step)
        .round()
        .rem_euclid(VIEWS as f64) as u32
        % VIEWS
}

/// Atlas row for animation phase `phase` (cycles).
pub fn frame_row(phase: f64) -> u32 {
    ((phase.rem_euclid(1.0) * FRAMES as f64).floor() as u32).min(FRAMES - 1)
}

impl Sprites {
    /// Captures the atlas of `model` with `skinning` (its coarsest mesh).
    pub fn new(
        ctx: &Context,
        model: &CharacterModel,
        skinning: &VertexShaderSkinning,
        colour: Vec3,
        light: Vec3,
    ) -> Result<Self, GlError> {
        let (w, h) = (VIEWS * TILE, FRAMES * TILE);
        let colour_texture = Texture::new_2d(ctx, w, h, TextureFormat::Rgba8)?;
        let depth = Texture::new_2d(ctx, w, h, ctx.z_buffer_format())?;
        let atlas = Framebuffer::new(
            ctx,
            "crowd impostor atlas",
            &[&colour_texture],
            Some(&depth),
        )?;
        atlas.clear_colors([0.0; 4])?;
        atlas.clear_depth_stencil(1.0, 0)?;
        let c = model.bound_centre.as_dvec3();
        let r = model.bound_radius;
        let view = look_at_mat4(
            Vec3::new(0.0, c.y as f32, 3.0 * r),
            Vec3::new(0.0, c.y as f32, 0.0),
            Vec3::Y,
        );
        let projection = opengl::orthographic(-r, r, -r, r, 0.1, 6.0 * r);
        let shading = Shading {
            view_projection: projection * view,
            colour,
            light,
        };
        for column in 0..VIEWS {
            let facing = std::f64::consts::TAU * column as f64 / VIEWS as f64;
            let place = DAffine3::from_quat(DQuat::from_rotation_y(facing))
                * DAffine3::from_translation(DVec3::new(-c.x, 0.0, -c.z));
            for row in 0..FRAMES {
                let phase = (row as f64 + 0.5) / FRAMES as f64;
                let pose = model.clip.sample(&model.skeleton, phase);
                let matrices = model.skeleton.skinning_matrices(&pose, place);
                let tile = Rect::new(column * TILE, row * TILE, TILE, TILE);
                skinning.draw(&atlas, &shading, &matrices, Some(tile))?;
            }
        }
        let program = Program::new(
            ctx,
            &[shader!("glsl/crowd/sprite.vert")],
            &[shader!("glsl/crowd/sprite.frag")],
        )?;
        let instances = Buffer::new(ctx, INSTANCE_FLOATS * 4, BufferUsage::Dynamic)?;
        let mut vertices = VertexArray::new(ctx)?;
        let stride = INSTANCE_FLOATS * 4;
        vertices.float_attribute(0, &instances, 4, stride, 0, 1)?;
        vertices.float_attribute(1, &instances, 2, stride, 16, 1)?;
        Ok(Self {
            atlas,
            program,
            instances,
            vertices,
        })
    }

    /// The atlas colour texture (for figures).
    pub fn atlas(&self) -> &Texture {
        self.atlas.color(0)
    }

    /// Draws characters `ids` as sprites.
    pub fn draw(
        &self,
        scene: &Framebuffer,
        camera: &super::culling::Camera,
        model: &CharacterModel,
        instances: &Instances,
        ids: &[usize],
    ) -> Result<(), GlError> {
        let eye = camera.eye.as_dvec3();
        let centre = model.bound_centre.as_dvec3();
        let mut data: Vec<f32> = Vec::with_capacity(ids.len() * INSTANCE_FLOATS);
        for &i in ids {
            let m = &instances.models[i];
            let world = m.transform_point3(centre);
            let forward = m.transform_vector3(DVec3::Z);
            let heading = forward.x.atan2(forward.z);
            let column = view_column(heading, eye - world);
            let row = frame_row(instances.phases[i]);
            data.extend([
                world.x as f32,
                world.y as f32,
                world.z as f32,
                model.bound_radius,
                column as f32,
                row as f32,
            ]);
        }
        self.instances.replace(&data)?;
        let mut pass = scene.pass(&self.program, "crowd sprites")?;
        pass.state(DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            ..DrawState::default()
        })
        .uniform("u_view_projection", camera.view_projection())
        .uniform("u_eye", camera.eye)
        .uniform("u_tiles", glam::Vec2::new(VIEWS as f32, FRAMES as f32))
        .texture("u_atlas", self.atlas.color(0));
        pass.draw_arrays_instanced(&self.vertices, Primitive::TriangleStrip, 0, 4, ids.len())
    }
}
