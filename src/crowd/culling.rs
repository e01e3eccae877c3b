//! View-frustum culling and LOD choice per character [paper section 3, Fig. 4-5]: before
//! pass 1, characters whose bounding sphere lies outside the frustum are dropped, and the
//! rest are sorted into the three LOD meshes (and, when the policy has it, this project's
//! sprite level) by distance to the eye. The paper does not say how it culls: here each
//! character's animated bounding sphere is tested against the six frustum planes on the CPU.

use glam::camera::rh::{proj::opengl, view::look_at_mat4};
use glam::{DAffine3, Mat4, Vec3, Vec4, Vec4Swizzles};

use super::lod::{Level, LodPolicy};

/// A perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub fov_y: f32,
    pub aspect: f32,
    pub near: f32,
    pub far: f32,
}

impl Camera {
    pub fn view(&self) -> Mat4 {
        look_at_mat4(self.eye, self.target, Vec3::Y)
    }

    /// OpenGL clip space (z in [-w, w]).
    pub fn projection(&self) -> Mat4 {
        opengl::perspective(self.fov_y, self.aspect, self.near, self.far)
    }

    pub fn view_projection(&self) -> Mat4 {
        self.projection() * self.view()
    }
}

/// The six planes of a view frustum, normals pointing inside, normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    planes: [Vec4; 6],
}

impl Frustum {
    /// Planes from the rows of a view-projection matrix (Gribb & Hartmann): a point is
    /// inside when `-w <= x, y, z <= w` in clip space.
    pub fn from_view_projection(m: Mat4) -> Self {
        let row = |i: usize| m.row(i);
        let (r0, r1, r2, r3) = (row(0), row(1), row(2), row(3));
        let planes =
            [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2].map(|p| p / p.xyz().length());
        Self { planes }
    }

    /// Whether a sphere touches the frustum (conservative: a sphere near a corner outside
    /// all planes' reach may be kept, never a visible one dropped).
    pub fn intersects_sphere(&self, centre: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .all(|p| p.xyz().dot(centre) + p.w >= -radius)
    }
}

/// Which characters are drawn how in one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FramePlan {
    /// Character indices per LOD mesh, finest first.
    pub lods: [Vec<usize>; 3],
    pub sprites: Vec<usize>,
    pub culled: usize,
}

impl FramePlan {
    /// Characters drawn with a skinned mesh (that go through pass 1).
    pub fn skinned(&self) -> usize {
        self.lods.iter().map(Vec::len).sum()
    }

    /// The same plan with at most `per_level` characters in each LOD mesh and in the sprite
    /// level (the first ones): every level the plan uses, on a few characters.
    pub fn truncated(&self, per_level: usize) -> FramePlan {
        let first = |ids: &Vec<usize>| ids[..ids.len().min(per_level)].to_vec();
        FramePlan {
            lods: [0, 1, 2].map(|l| first(&self.lods[l])),
            sprites: first(&self.sprites),
            culled: self.culled,
        }
    }
}

/// Culls (when `cull`) and assigns levels (when `policy` is given; otherwise everything is
/// LOD 0) for characters placed by `models`, whose model-space bounding sphere is
/// (`bound_centre`, `bound_radius`).
pub fn plan_frame(
    models: &[DAffine3],
    bound_centre: Vec3,
    bound_radius: f32,
    camera: &Camera,
    policy: Option<&LodPolicy>,
    cull: bool,
) -> FramePlan {
    let frustum = Frustum::from_view_projection(camera.view_projection());
    let mut plan = FramePlan::default();
    for (i, model) in models.iter().enumerate() {
        let centre = model.transform_point3(bound_centre.as_dvec3()).as_vec3();
        if cull && !frustum.intersects_sphere(centre, bound_radius) {
            plan.culled += 1;
            continue;
        }
        let level = policy.map_or(Level::Mesh(0), |p| p.select(centre.distance(camera.eye)));
        match level {
            Level::Mesh(lod) => plan.lods[lod].push(i),
            Level::Sprite => plan.sprites.push(i),
        }
    }
    plan
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn truncated_keeps_the_first_characters_of_every_level() {
        let plan = FramePlan {
            lods: [(0..40).collect(), vec![], (50..53).collect()],
            sprites: (60..100).collect(),
            culled: 7,
        };
        let small = plan.truncated(16);
        assert_eq!(small.lods[0], (0..16).collect::<Vec<_>>());
        assert!(small.lods[1].is_empty());
        assert_eq!(small.lods[2], vec![50, 51, 52]);
        assert_eq!(small.sprites, (60..76).collect::<Vec<_>>());
        assert_eq!(small.culled, 7);
    }
}
