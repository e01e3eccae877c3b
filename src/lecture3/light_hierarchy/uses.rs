//! The hierarchy's three uses side by side: what level 0 holds and what a light gives a
//! receiver. Indirect light: VPLs from the spot light and their irradiance. Subsurface
//! scattering: irradiance samples from the spot light and the dipole ([`super::subsurface`]).
//! Environment light: a sky's lat-long texels as directional lights ([`super::environment`]).
//! The pyramid, the traversal and the brute force are the same for all three.

use super::clusters::Cluster;
use super::environment::{DirectionalKernel, Sky};
use super::gather::{KernelShader, MIN_DISTANCE};
use super::light::{Kernel, Receiver, VplKernel};
use super::model::{model_alone, model_triangles};
use super::scene::Scene;
use super::subsurface::Material;
use crate::mesh::obj::load_bunny;
use glam::{DVec3, Vec3};
use serde::Serialize;

/// What the light hierarchy is used for.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LightUse {
    Indirect,
    Subsurface(Material),
    Environment(Sky),
}

impl LightUse {
    /// Subsurface scattering in [`Material::skin`].
    pub fn subsurface() -> LightUse {
        LightUse::Subsurface(Material::skin())
    }

    /// Environment light from the default [`Sky`].
    pub fn environment() -> LightUse {
        LightUse::Environment(Sky::default())
    }

    pub fn name(&self) -> &'static str {
        match self {
            LightUse::Indirect => "indirect",
            LightUse::Subsurface(_) => "sss",
            LightUse::Environment(_) => "environment",
        }
    }

    /// What a level-0 texel is, for messages.
    pub fn lights_name(&self) -> &'static str {
        match self {
            LightUse::Indirect => "VPLs",
            LightUse::Subsurface(_) => "irradiance samples",
            LightUse::Environment(_) => "sky directions",
        }
    }

    /// The GPU kernel.
    pub fn kernel_shader(&self) -> KernelShader {
        match self {
            LightUse::Indirect => KernelShader::vpl(),
            LightUse::Subsurface(m) => m.dipole().kernel_shader(),
            LightUse::Environment(sky) => sky.kernel_shader(),
        }
    }

    /// The CPU kernel.
    pub fn kernel(&self) -> UseKernel {
        match self {
            LightUse::Indirect => UseKernel::Vpl(VplKernel {
                min_distance: MIN_DISTANCE as f64,
            }),
            LightUse::Subsurface(m) => UseKernel::Dipole(m.dipole()),
            LightUse::Environment(_) => UseKernel::Directional(DirectionalKernel),
        }
    }
}

/// The CPU kernel of a use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UseKernel {
    Vpl(VplKernel),
    Dipole(super::subsurface::Dipole),
    Directional(DirectionalKernel),
}

impl Kernel for UseKernel {
    fn light(&self, r: &Receiver, light: &Cluster) -> DVec3 {
        match self {
            UseKernel::Vpl(k) => k.light(r, light),
            UseKernel::Dipole(k) => k.light(r, light),
            UseKernel::Directional(k) => k.light(r, light),
        }
    }
    fn distance(&self, r: &Receiver, light: &Cluster) -> f64 {
        match self {
            UseKernel::Vpl(k) => k.distance(r, light),
            UseKernel::Dipole(k) => k.distance(r, light),
            UseKernel::Directional(k) => k.distance(r, light),
        }
    }
}

/// The picture's base exposure (multiplier before `--exposure`'s stops) per use: indirect
/// light as before; subsurface light is dimmer and the sky brighter.
pub fn base_exposure(light_use: &LightUse) -> f32 {
    match light_use {
        LightUse::Indirect => 1.5,
        LightUse::Subsurface(_) => 4.0,
        LightUse::Environment(_) => 0.6,
    }
}

/// The default scene of a use: the room for indirect light, the shipped bunny alone for the
/// others (white for subsurface scattering: its samples carry the power that enters).
pub fn default_scene(light_use: &LightUse) -> Scene {
    match light_use {
        LightUse::Indirect => Scene::room(),
        _ => model_alone(
            model_triangles(&load_bunny(), "the shipped bunny", model_albedo(light_use))
                .expect("the shipped bunny has triangles"),
        ),
    }
}

/// The albedo a model gets in a use.
pub fn model_albedo(light_use: &LightUse) -> Vec3 {
    match light_use {
        LightUse::Subsurface(_) => Vec3::ONE,
        _ => Vec3::splat(0.75),
    }
}
