//! Step 3a, the views: "a cube map around the origin", six 90° perspective views. The six
//! faces lie side by side in one R32F target of `6N x N` texels (face f in columns
//! `fN .. fN + N`), so that one reduction covers them all. Pixel (i, j) of face f looks along
//! `forward + s right + t up`, with `s = (2i + 1) / N - 1`, `t = (2j + 1) / N - 1`: the ray
//! through the pixel's centre, which the GPU rebuilds from `gl_FragCoord` and the CPU
//! reference and the compute path use alike.

use glam::{DVec3, Mat3, Mat4, Vec3, Vec4};

/// Near plane of the views, in the unit frame (coordinates within [-1, 1]): a back face nearer
/// to the origin than this is clipped, so an exit closer than 1e-6 of the scene's size is not
/// seen (the fp32 coordinates resolve about 1e-7 of it).
pub const NEAR: f32 = 1e-6;
/// Far plane: beyond every vertex of the unit frame (|x| <= sqrt 3).
pub const FAR: f32 = 4.0;

/// One face's (right, up, forward), with right x up = -forward (a right-handed camera, so a
/// triangle counter-clockwise seen from the origin stays counter-clockwise on screen).
#[derive(Clone, Copy, Debug)]
pub struct Face {
    pub right: DVec3,
    pub up: DVec3,
    pub forward: DVec3,
}

/// The six faces: +x, -x, +y, -y, +z, -z.
pub fn faces() -> [Face; 6] {
    let make = |forward: DVec3, up: DVec3| Face {
        right: forward.cross(up),
        up,
        forward,
    };
    [
        make(DVec3::X, DVec3::Y),
        make(DVec3::NEG_X, DVec3::Y),
        make(DVec3::Y, DVec3::Z),
        make(DVec3::NEG_Y, DVec3::Z),
        make(DVec3::Z, DVec3::Y),
        make(DVec3::NEG_Z, DVec3::Y),
    ]
}

impl Face {
    /// The (unnormalised) ray of pixel (i, j) at `resolution` N.
    pub fn ray(&self, i: usize, j: usize, resolution: usize) -> DVec3 {
        let n = resolution as f64;
        let s = (2 * i + 1) as f64 / n - 1.0;
        let t = (2 * j + 1) as f64 / n - 1.0;
        self.forward + s * self.right + t * self.up
    }

    /// Columns right, up, forward (the fragment shader's `u_face`).
    pub fn basis(&self) -> Mat3 {
        Mat3::from_cols(
            self.right.as_vec3(),
            self.up.as_vec3(),
            self.forward.as_vec3(),
        )
    }

    /// World (unit frame) to clip space: x = right · p, y = up · p, w = forward · p (so that
    /// x / w is the `s` of [`Face::ray`]), z mapping [NEAR, FAR] to [-1, 1].
    pub fn view_projection(&self) -> Mat4 {
        let (n, f) = (NEAR, FAR);
        let a = (f + n) / (f - n);
        let b = -2.0 * f * n / (f - n);
        let (r, u, w) = (
            self.right.as_vec3(),
            self.up.as_vec3(),
            self.forward.as_vec3(),
        );
        // Rows of the matrix; glam builds from columns, so transpose.
        Mat4::from_cols(
            r.extend(0.0),
            u.extend(0.0),
            (w * a).extend(b),
            w.extend(0.0),
        )
        .transpose()
    }
}

/// The pixel of the `6N x N` layout with index `k` (row-major from the bottom row): its face,
/// and (i, j) within the face.
pub fn pixel_of(k: usize, resolution: usize) -> (usize, usize, usize) {
    let (x, j) = (k % (6 * resolution), k / (6 * resolution));
    (x / resolution, x % resolution, j)
}

/// The unit direction of pixel `k` of the layout.
pub fn direction_of(k: usize, resolution: usize) -> DVec3 {
    let (face, i, j) = pixel_of(k, resolution);
    faces()[face].ray(i, j, resolution).normalize()
}

/// A point's clip coordinates under a face's matrix (used by the tests of the layout).
pub fn project(face: &Face, p: Vec3) -> Vec4 {
    face.view_projection() * p.extend(1.0)
}
