//! The simple scene lit indirectly: a Cornell-style room (white floor, ceiling and back
//! wall, red left wall, green right wall, open at the front) with one tall white block, lit
//! by a spot light; and the two cameras that see it (the light's and the viewer's).
//!
//! Units: the room is the unit cube, y up.

use crate::gl::{Buffer, BufferUsage, Context, GlError, VertexArray};
use glam::camera::rh::{proj::opengl, view::look_at_mat4};
use glam::{Mat4, Vec3};

/// One flat, diffuse quad: `corner`, `corner + u`, `corner + u + v`, `corner + v`, its normal
/// `u x v` (normalised).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    pub corner: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    pub albedo: Vec3,
}

impl Quad {
    pub fn normal(&self) -> Vec3 {
        self.u.cross(self.v).normalize()
    }
}

/// One triangle with a normal per corner (a model's, [`super::model`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub positions: [Vec3; 3],
    pub normals: [Vec3; 3],
    pub albedo: Vec3,
}

/// A perspective view: the spot light's (its frustum is its cone) or the camera's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub eye: Vec3,
    pub target: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
}

impl View {
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        opengl::perspective(self.fov_y, aspect, 0.02, 10.0) * self.view_matrix()
    }

    /// World to the view's eye space (looking down -z).
    pub fn view_matrix(&self) -> Mat4 {
        let up = if (self.target - self.eye).normalize().y.abs() > 0.99 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        look_at_mat4(self.eye, self.target, up)
    }
}

/// The room, its light and its camera.
#[derive(Clone, Debug)]
pub struct Scene {
    pub quads: Vec<Quad>,
    /// Triangles besides the quads (a model from an OBJ file).
    pub triangles: Vec<Triangle>,
    /// The spot light: a point light emitting `intensity` (per steradian, RGB) inside the
    /// square frustum of this view, nothing outside it.
    pub light: View,
    pub intensity: Vec3,
    pub camera: View,
}

const WHITE: Vec3 = Vec3::new(0.75, 0.75, 0.75);
const RED: Vec3 = Vec3::new(0.75, 0.15, 0.12);
const GREEN: Vec3 = Vec3::new(0.15, 0.6, 0.15);

impl Scene {
    pub fn room() -> Scene {
        let q = |corner: [f32; 3], u: [f32; 3], v: [f32; 3], albedo| Quad {
            corner: corner.into(),
            u: u.into(),
            v: v.into(),
            albedo,
        };
        let mut quads = vec![
            q([0., 0., 0.], [0., 0., 1.], [1., 0., 0.], WHITE), // floor, +y
            q([0., 1., 0.], [1., 0., 0.], [0., 0., 1.], WHITE), // ceiling, -y
            q([0., 0., 0.], [1., 0., 0.], [0., 1., 0.], WHITE), // back wall, +z
            q([0., 0., 0.], [0., 1., 0.], [0., 0., 1.], RED),   // left wall, +x
            q([1., 0., 0.], [0., 0., 1.], [0., 1., 0.], GREEN), // right wall, -x
        ];
        // The tall block, outward normals.
        let (x0, x1, z0, z1, h) = (0.55, 0.8, 0.25, 0.5, 0.55);
        let (dx, dz) = (x1 - x0, z1 - z0);
        quads.extend([
            q([x0, h, z0], [0., 0., dz], [dx, 0., 0.], WHITE), // top
            q([x0, 0., z1], [dx, 0., 0.], [0., h, 0.], WHITE), // front
            q([x0, 0., z0], [0., h, 0.], [dx, 0., 0.], WHITE), // back
            q([x0, 0., z0], [0., 0., dz], [0., h, 0.], WHITE), // left
            q([x1, 0., z0], [0., h, 0.], [0., 0., dz], WHITE), // right
        ]);
        Scene {
            quads,
            triangles: Vec::new(),
            light: View {
                eye: Vec3::new(0.25, 0.92, 0.85),
                target: Vec3::new(0.7, 0.25, 0.3),
                fov_y: 80f32.to_radians(),
            },
            intensity: Vec3::splat(1.2),
            camera: View {
                eye: Vec3::new(0.5, 0.5, 2.1),
                target: Vec3::new(0.5, 0.45, 0.4),
                fov_y: 40f32.to_radians(),
            },
        }
    }

    /// Two triangles per quad, then the triangles, each vertex `[position, normal, albedo]`.
    pub fn vertices(&self) -> Vec<[[f32; 3]; 3]> {
        let triangles = self.triangles.iter().flat_map(|t| {
            (0..3).map(|k| {
                [
                    t.positions[k].to_array(),
                    t.normals[k].to_array(),
                    t.albedo.to_array(),
                ]
            })
        });
        self.quads
            .iter()
            .flat_map(|q| {
                let n = q.normal();
                let c = [
                    q.corner,
                    q.corner + q.u,
                    q.corner + q.u + q.v,
                    q.corner + q.v,
                ];
                [c[0], c[1], c[2], c[0], c[2], c[3]]
                    .map(|p| [p.to_array(), n.to_array(), q.albedo.to_array()])
            })
            .chain(triangles)
            .collect()
    }

    /// The scene's triangles on the GPU: position at location 0, normal at 1, albedo at 2.
    pub fn vertex_array(&self, ctx: &Context) -> Result<(VertexArray, usize), GlError> {
        let vertices = self.vertices();
        let buffer = Buffer::from_slice(ctx, &vertices, BufferUsage::Static)?;
        let mut array = VertexArray::new(ctx)?;
        for location in 0..3 {
            array.float_attribute(location, &buffer, 3, 36, 12 * location as usize, 0)?;
        }
        Ok((array, vertices.len()))
    }
}
