//! The moving camera: a perspective camera orbiting the displaced box, and the ray of each
//! pixel, computed the same way on the GPU (fp32, from the uniforms) and the CPU (f64, from
//! the same fp32 uniforms).

use crate::gl::{Framebuffer, GlError, Pass};
use glam::camera::rh::{proj::opengl, view::look_at_mat4};
use glam::{DVec3, Mat4, Vec2, Vec3};
use serde::Serialize;

/// A perspective camera and the image it renders.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    pub width: u32,
    pub height: u32,
}

/// The camera's frame as the shader gets it: the direction through the image centre, and
/// the steps to the right and top image edges (so a pixel's ray is `forward + x right +
/// y up` for x, y in [-1, 1]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayFrame {
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
}

/// Near and far planes of the depth written per pixel.
pub const NEAR: f32 = 0.05;
pub const FAR: f32 = 50.0;

impl Camera {
    /// Looking at `target` from `distance`, from the direction given by `azimuth` (degrees,
    /// about +z) and `elevation` (degrees above the xy plane: small = grazing).
    pub fn orbit(
        target: Vec3,
        distance: f32,
        azimuth_deg: f32,
        elevation_deg: f32,
        width: u32,
        height: u32,
    ) -> Camera {
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        let dir = Vec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        Camera {
            eye: target + distance * dir,
            target,
            fov_y: 40f32.to_radians(),
            width,
            height,
        }
    }

    /// The same view with `samples` times as many pixels along each side (each pixel of this
    /// camera covers `samples x samples` of its pixels).
    pub fn enlarged(&self, samples: u32) -> Camera {
        Camera {
            width: self.width * samples,
            height: self.height * samples,
            ..*self
        }
    }

    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }

    /// The frame of the pixel rays (z is up in the world).
    pub fn ray_frame(&self) -> RayFrame {
        let forward = (self.target - self.eye).normalize();
        let right = forward.cross(Vec3::Z).normalize();
        let up = right.cross(forward);
        let half = (0.5 * self.fov_y).tan();
        RayFrame {
            forward,
            right: right * half * self.aspect(),
            up: up * half,
        }
    }

    /// The unit direction through the centre of pixel (px, py) (row 0 at the bottom), in
    /// f64 from the fp32 frame the shader gets.
    pub fn pixel_direction(&self, px: u32, py: u32) -> DVec3 {
        let f = self.ray_frame();
        let x = (px as f64 + 0.5) / self.width as f64 * 2.0 - 1.0;
        let y = (py as f64 + 0.5) / self.height as f64 * 2.0 - 1.0;
        (f.forward.as_dvec3() + x * f.right.as_dvec3() + y * f.up.as_dvec3()).normalize()
    }

    /// Sets the uniforms of `glsl/lecture3/pixel_ray.glsl` (the viewport and the ray frame)
    /// on a pass drawing into `fb`, after checking that `fb` is this camera's size.
    pub fn set_ray_uniforms(&self, pass: &mut Pass, fb: &Framebuffer) -> Result<(), GlError> {
        if (fb.width(), fb.height()) != (self.width, self.height) {
            return Err(GlError::Invalid(format!(
                "a {}x{} camera drawing into a {}x{} target",
                self.width,
                self.height,
                fb.width(),
                fb.height()
            )));
        }
        let frame = self.ray_frame();
        pass.uniform(
            "u_viewport",
            Vec2::new(self.width as f32, self.height as f32),
        )
        .uniform("u_eye", self.eye)
        .uniform("u_forward", frame.forward)
        .uniform("u_right", frame.right)
        .uniform("u_up", frame.up);
        Ok(())
    }

    pub fn view_projection(&self) -> Mat4 {
        let view = look_at_mat4(self.eye, self.target, Vec3::Z);
        opengl::perspective(self.fov_y, self.aspect(), NEAR, FAR) * view
    }

    /// The window depth (0..1) of a world point, as gl_FragDepth gets it.
    pub fn depth_of(&self, world: DVec3) -> f64 {
        let clip = self.view_projection().as_dmat4() * world.extend(1.0);
        clip.z / clip.w * 0.5 + 0.5
    }
}
