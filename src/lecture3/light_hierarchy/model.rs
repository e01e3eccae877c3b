//! A scene from a model (an OBJ file, or the shipped bunny): the mesh scaled so that its
//! largest side is half the room, standing on the floor near the room's middle, with smooth
//! normals (area-weighted vertex normals; a triangle's own normal where a vertex has none),
//! turned outward if the file winds it inward. For indirect light it replaces the room's block;
//! for subsurface scattering and environment light it stands alone, seen by a camera and a
//! spot light placed for it.

use super::scene::{Scene, Triangle, View};
use crate::lecture3::error::Error;
use crate::mesh::{self, Mesh};
use glam::Vec3;
use std::path::Path;

/// The model's largest side, scene units.
pub const MODEL_SIZE: f32 = 0.5;

/// Where the model stands: the middle of its footprint, on the floor.
const FOOT: Vec3 = Vec3::new(0.6, 0.0, 0.4);

/// The OBJ file at `path`, as [`model_triangles`] places it; errors name the file.
pub fn load_model(path: &Path, albedo: Vec3) -> Result<Vec<Triangle>, Error> {
    let mesh = mesh::obj::load_obj(path).map_err(|e| Error::input("--scene", e.to_string()))?;
    model_triangles(&mesh, &path.display().to_string(), albedo)
}

/// The mesh scaled and placed (see the module documentation), every triangle `albedo`.
pub fn model_triangles(mesh: &Mesh, source: &str, albedo: Vec3) -> Result<Vec<Triangle>, Error> {
    if mesh.triangle_count() == 0 {
        return Err(Error::input(
            "--scene",
            format!("{source}: the model has no triangles"),
        ));
    }
    let bounds = mesh.bounds();
    let side = bounds.size().max_element();
    if !side.is_finite() || side <= 0.0 {
        return Err(Error::input(
            "--scene",
            format!("{source}: the model has no extent (every vertex at one point)"),
        ));
    }
    // Placed first, normals after: at the scene's size no product of coordinates overflows
    // or underflows (a model 1e30 or 1e-30 across has the same normals as at 0.5).
    let scale = MODEL_SIZE / side;
    let centre = bounds.center();
    let offset = FOOT - Vec3::new(centre.x, bounds.min.y, centre.z) * scale;
    let placed = mesh.positions.iter().map(|&p| p * scale + offset).collect();
    let mesh = Mesh::new(placed, mesh.triangles.clone());
    let mesh = if mesh.is_outward() {
        mesh
    } else {
        mesh.flipped()
    };
    let vertex_normals = mesh.vertex_normals();
    let face_normals = mesh.face_normals();
    let triangles: Vec<Triangle> = mesh
        .triangles
        .iter()
        .zip(&face_normals)
        .filter(|(_, face)| face.length_squared() > 0.0)
        .map(|(tri, &face)| {
            let corner = |k: usize| tri[k] as usize;
            let normal = |k: usize| {
                let n = vertex_normals[corner(k)];
                if n.length_squared() > 0.0 {
                    n
                } else {
                    face
                }
            };
            Triangle {
                positions: [0, 1, 2].map(|k| mesh.positions[corner(k)]),
                normals: [0, 1, 2].map(normal),
                albedo,
            }
        })
        .collect();
    if triangles.is_empty() {
        return Err(Error::input(
            "--scene",
            format!("{source}: every triangle of the model has zero area"),
        ));
    }
    Ok(triangles)
}

/// The room with `model` in place of its block.
pub fn room_with(model: Vec<Triangle>) -> Scene {
    let mut scene = Scene::room();
    scene.quads.truncate(5); // floor, ceiling, back, left, right: the block goes
    scene.triangles = model;
    scene
}

/// `model` alone, lit by a spot light from the upper right front and seen from the front. The
/// light's square frustum is fitted to the model ([`fitted_light`]), so that its image (the
/// irradiance samples of subsurface scattering, the VPLs of indirect light) is spent on the
/// model rather than on the space around it.
pub fn model_alone(model: Vec<Triangle>) -> Scene {
    let centre = FOOT + Vec3::Y * (0.5 * MODEL_SIZE);
    let mut scene = Scene::room();
    scene.quads.clear();
    scene.light = fitted_light(centre + Vec3::new(0.7, 0.6, 0.35), centre, &model);
    scene.triangles = model;
    scene.intensity = Vec3::splat(1.0);
    scene.camera = View {
        eye: centre + Vec3::new(0.0, 0.1, 1.2),
        target: centre,
        fov_y: 35f32.to_radians(),
    };
    scene
}

/// Border left around the model in a fitted light's image (a fraction of its half-extent), so
/// that no part of the silhouette is cut by rounding.
const FIT_MARGIN: f32 = 1.02;

/// A spot light at `eye` aimed at `target` whose square frustum just holds every vertex of
/// `model` (the widest angle of a vertex from the axis, horizontally or vertically, plus
/// a 2% margin); `target` should lie inside the model's bounds.
pub fn fitted_light(eye: Vec3, target: Vec3, model: &[Triangle]) -> View {
    let mut light = View {
        eye,
        target,
        fov_y: 0.0,
    };
    let view = light.view_matrix();
    let half_extent = model
        .iter()
        .flat_map(|t| t.positions)
        .map(|p| view.transform_point3(p))
        .filter(|p| p.z < 0.0)
        .map(|p| (p.x / -p.z).abs().max((p.y / -p.z).abs()))
        .fold(0.0f32, f32::max);
    light.fov_y = 2.0 * (FIT_MARGIN * half_extent).atan();
    light
}
