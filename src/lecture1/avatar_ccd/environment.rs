//! Step 3a, the environment: a triangle soup (an OBJ, or a built-in room) with a bounding
//! volume hierarchy over its triangles (parry3d's BVH), queried with each link's swept
//! capsule bound to cull the links far from everything ("a dynamic BVH culls distant
//! links" in the source; here the environment's tree is static and the link bounds are
//! queried against it each sub-interval).

use super::body::Capsule;
use super::sweep_bound::capsule_box;
use crate::mesh::generate::torus_closed;
use crate::mesh::{cuboid, Mesh};
use glam::{DVec3, Vec3};
use parry3d::bounding_volume::Aabb;
use parry3d::math::Vector;
use parry3d::partitioning::{Bvh, BvhBuildStrategy};

/// The environment's triangles (f64 copies of the mesh's f32 corners) and their BVH.
pub struct Environment {
    pub triangles: Vec<[DVec3; 3]>,
    bvh: Bvh,
}

impl Environment {
    /// The environment of a mesh; a mesh without triangles, or with a non-finite corner, is
    /// refused.
    pub fn new(mesh: &Mesh) -> anyhow::Result<Environment> {
        anyhow::ensure!(
            !mesh.triangles.is_empty(),
            "the environment has no triangles"
        );
        let mut triangles = Vec::with_capacity(mesh.triangles.len());
        for (k, t) in mesh.triangles.iter().enumerate() {
            let corners = t.map(|v| mesh.positions[v as usize].as_dvec3());
            anyhow::ensure!(
                corners.iter().all(|c| c.is_finite()),
                "environment triangle {k} has a non-finite corner"
            );
            triangles.push(corners);
        }
        let leaves: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
                outward(lo, hi)
            })
            .collect();
        Ok(Environment {
            triangles,
            bvh: Bvh::from_leaves(BvhBuildStrategy::Binned, &leaves),
        })
    }

    /// The triangles whose boxes overlap the capsule's box (the BVH's leaves), sorted.
    pub fn near(&self, capsule: &Capsule) -> Vec<u32> {
        let (lo, hi) = capsule_box(capsule);
        let query = outward(lo, hi);
        let mut out: Vec<u32> = self.bvh.intersect_aabb(&query).collect();
        out.sort_unstable();
        out
    }

    /// The box of every triangle.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.triangles
            .iter()
            .flatten()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            })
    }
}

/// An f32 box holding the f64 box `[lo, hi]` (rounded outward by a relative 1e-6).
fn outward(lo: DVec3, hi: DVec3) -> Aabb {
    let pad = 1e-6 * (lo.abs().max(hi.abs()).max_element() + 1e-30);
    let v = |p: DVec3| Vector::new(p.x as f32, p.y as f32, p.z as f32);
    Aabb::new(v(lo - DVec3::splat(pad)), v(hi + DVec3::splat(pad)))
}

/// The built-in room: a floor 10 units square at y = 0, a wall across the path at z = 2.6
/// (1.4 high, 3 wide, 0.2 thick), a low bench beside the path and a pillar (neither across
/// it).
pub fn room() -> Mesh {
    let floor = Mesh::new(
        vec![
            Vec3::new(-5.0, 0.0, -5.0),
            Vec3::new(5.0, 0.0, -5.0),
            Vec3::new(5.0, 0.0, 5.0),
            Vec3::new(-5.0, 0.0, 5.0),
        ],
        vec![[0, 2, 1], [0, 3, 2]],
    );
    let wall = cuboid(Vec3::new(1.5, 0.7, 0.1)).translated(Vec3::new(0.0, 0.7, 2.6));
    let bench = cuboid(Vec3::new(0.3, 0.2, 0.8)).translated(Vec3::new(1.2, 0.2, 1.0));
    let pillar = cuboid(Vec3::new(0.15, 1.2, 0.15)).translated(Vec3::new(-1.0, 1.2, 0.8));
    let mut mesh = floor;
    for part in [wall, bench, pillar] {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(part.positions);
        mesh.triangles
            .extend(part.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    mesh
}

/// The published scale's environment (Presence 2007: "hundreds of thousands of polygons";
/// generated here, not the paper's): the built-in room and, around it, eight finely
/// tessellated tori standing on the floor (2 x 160 x 40 triangles each, 102,400 in all,
/// the room's 38 beside them). The nearest stands 1.2 units beside the walk, so the BVH and
/// the culling see them while the first contact stays the room's wall.
pub fn published_room() -> Mesh {
    let mut mesh = room();
    for k in 0..8 {
        let side = if k % 2 == 0 { 1.0 } else { -1.0 };
        let z = -1.5 + 1.2 * (k / 2) as f32;
        // Upright (the ring in the x-y plane, facing the walk), its lowest point on the floor.
        let upright = torus_closed(0.45, 0.12, 160, 40).translated(Vec3::new(side * 1.9, 0.57, z));
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(upright.positions);
        mesh.triangles
            .extend(upright.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    mesh
}
