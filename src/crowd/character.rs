//! Characters: a skeleton, a looping clip and three skinned LOD meshes built from body
//! parts, with a bounding sphere that holds every frame of the animation; and the crowd's
//! instances of one, where each stands and how far its animation is ([`Instances`]).

use glam::{DAffine3, DVec3, Vec3};
use thiserror::Error;

use super::animation::Clip;
use super::blueprint::Blueprint;
use super::cpu_skinning;
use super::lod::{tessellate_to_budget, LodError, LOD_TRIANGLES};
use super::skeleton::Skeleton;
use super::validate::{SkinError, SkinnedMesh};
use super::{horse, soldier};
use crate::mesh::Mesh;

/// The two models of the paper's Table 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    Soldier,
    Horse,
}

impl ModelKind {
    pub const ALL: [ModelKind; 2] = [ModelKind::Soldier, ModelKind::Horse];

    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Soldier => "soldier",
            ModelKind::Horse => "horse",
        }
    }
}

impl std::fmt::Display for ModelKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ModelKind {
    type Err = String;

    /// `soldier` or `horse`.
    fn from_str(text: &str) -> Result<Self, String> {
        ModelKind::ALL
            .into_iter()
            .find(|k| k.name() == text)
            .ok_or_else(|| format!("unknown model '{text}' (expected soldier or horse)"))
    }
}

/// A model could not be built.
#[derive(Debug, Error)]
pub enum BuildError {
    #[error(transparent)]
    Lod(#[from] LodError),
    #[error(transparent)]
    Skin(#[from] SkinError),
}

/// A ready-to-draw character model.
#[derive(Clone, Debug)]
pub struct CharacterModel {
    pub kind: ModelKind,
    pub skeleton: Skeleton,
    pub clip: Clip,
    /// The LOD meshes, finest first, with the triangle counts of [`LOD_TRIANGLES`].
    pub lods: Vec<SkinnedMesh>,
    /// Bounding sphere (model space) of every animation frame of LOD 0.
    pub bound_centre: Vec3,
    pub bound_radius: f32,
}

impl CharacterModel {
    /// Builds the soldier or the horse with the paper's three LODs.
    pub fn build(kind: ModelKind) -> Result<Self, BuildError> {
        let blueprint = match kind {
            ModelKind::Soldier => soldier::blueprint(),
            ModelKind::Horse => horse::blueprint(),
        };
        Self::from_blueprint(kind, blueprint, &LOD_TRIANGLES)
    }

    /// Builds a model with LOD meshes of exactly `lod_triangles` triangles each.
    pub fn from_blueprint(
        kind: ModelKind,
        blueprint: Blueprint,
        lod_triangles: &[usize],
    ) -> Result<Self, BuildError> {
        let lods = lod_triangles
            .iter()
            .map(|&target| skinned_mesh(&blueprint, target))
            .collect::<Result<Vec<_>, _>>()?;
        let (bound_centre, bound_radius) = animated_bound(&blueprint, &lods[0]);
        Ok(Self {
            kind,
            skeleton: blueprint.skeleton,
            clip: blueprint.clip,
            lods,
            bound_centre,
            bound_radius,
        })
    }

    pub fn bone_count(&self) -> usize {
        self.skeleton.len()
    }
}

/// Where each character stands and how far its animation is.
#[derive(Clone, Copy, Debug)]
pub struct Instances<'a> {
    pub models: &'a [DAffine3],
    pub phases: &'a [f64],
}

impl Instances<'_> {
    /// Skinning matrices of the characters `ids` of `model`, its bones per character, in
    /// order: what pass 1 (and the compute formulation) skins with.
    pub fn bone_matrices(&self, model: &CharacterModel, ids: &[usize]) -> Vec<DAffine3> {
        let skeleton = &model.skeleton;
        let mut out = Vec::with_capacity(ids.len() * skeleton.len());
        for &i in ids {
            let pose = model.clip.sample(skeleton, self.phases[i]);
            out.extend(skeleton.skinning_matrices(&pose, self.models[i]));
        }
        out
    }
}

/// Tessellates every body part to hit `target` triangles and skins the result.
fn skinned_mesh(blueprint: &Blueprint, target: usize) -> Result<SkinnedMesh, BuildError> {
    let tessellations = tessellate_to_budget(&blueprint.parts, target)?;
    let mut positions: Vec<Vec3> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut bone_indices = Vec::new();
    let mut bone_weights = Vec::new();
    for (part, tess) in blueprint.parts.iter().zip(tessellations) {
        let geometry = part.build(tess, &blueprint.skeleton);
        let base = positions.len() as u32;
        positions.extend(geometry.positions.iter().map(|p| p.as_vec3()));
        triangles.extend(geometry.triangles.iter().map(|t| t.map(|i| i + base)));
        for influence in geometry.influences {
            bone_indices.push(influence.map(|(bone, _)| bone));
            bone_weights.push(influence.map(|(_, w)| w as f32));
        }
    }
    let mesh = Mesh::new(positions, triangles);
    let normals = vertex_normals(&mesh);
    Ok(SkinnedMesh::new(
        mesh,
        normals,
        bone_indices,
        bone_weights,
        blueprint.skeleton.len(),
    )?)
}

/// Area-weighted average of the face normals around each vertex.
pub fn vertex_normals(mesh: &Mesh) -> Vec<Vec3> {
    let mut sums = vec![DVec3::ZERO; mesh.positions.len()];
    for tri in &mesh.triangles {
        let [a, b, c] = tri.map(|i| mesh.positions[i as usize].as_dvec3());
        let area_normal = (b - a).cross(c - a);
        for &i in tri {
            sums[i as usize] += area_normal;
        }
    }
    sums.iter()
        .map(|n| n.normalize_or_zero().as_vec3())
        .collect()
}

/// Phases at which the animation is sampled for the bounding sphere.
const BOUND_SAMPLES: usize = 32;

/// Centre of the bind-pose box and the largest distance any skinned vertex reaches from
/// it over one animation cycle, with 5 % margin for poses between the samples.
fn animated_bound(blueprint: &Blueprint, mesh: &SkinnedMesh) -> (Vec3, f32) {
    let (lo, hi) = mesh.mesh.positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let centre = ((lo + hi) * 0.5).as_dvec3();
    let mut radius: f64 = 0.0;
    for k in 0..BOUND_SAMPLES {
        let pose = blueprint
            .clip
            .sample(&blueprint.skeleton, k as f64 / BOUND_SAMPLES as f64);
        let bones = blueprint
            .skeleton
            .skinning_matrices(&pose, glam::DAffine3::IDENTITY);
        let skinned = cpu_skinning::skin(mesh, &bones);
        for p in skinned.positions {
            radius = radius.max(p.distance(centre));
        }
    }
    (centre.as_vec3(), (radius * 1.05) as f32)
}
