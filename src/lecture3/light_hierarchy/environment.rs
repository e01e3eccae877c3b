//! Environment light on the light hierarchy (a reconstruction: the light-hierarchy abstract
//! names environment light among its uses, without saying how).
//!
//! The environment map is a procedural sky the code makes ([`Sky::radiance`]): a blue gradient
//! above the horizon, a darker ground below it, and a sun lobe. It is sampled on a lat-long
//! grid of N x N texels (polar angle from +y by row, azimuth by column, at texel centres),
//! each texel one directional light: direction ω, "flux" L(ω) dω with dω = (2π/N)(π/N) sin θ.
//! The grid is level 0 of the same cluster pyramid, with the direction stored as the position:
//! a cluster's centre is then the flux-weighted mean direction c (shorter than 1), and its
//! radius bounds |ω_i - c| over its lights, so clustering is on direction.
//!
//! A receiver with normal n gathers E = Σ_i L_i dω_i max(n·ω_i, 0), visibility ignored (the
//! object does not shadow itself; the abstract ignores occlusion too). A cluster is one light,
//! E += Φ max(n·c, 0), when radius < theta |n·c|: with theta <= 1 no light of the cluster is
//! then on the other side of the receiver's horizon (n·ω_i >= n·c - radius), where the clamped
//! cosine is linear and the cluster's sum is exact for a grey sky; the sky's colour varying
//! within the cluster is the remaining error. The GPU's kernel is
//! `glsl/lecture3/environment_kernel.glsl`.

use super::clusters::{Cluster, ClusterLevel, GpuClusters};
use super::gather::KernelShader;
use super::light::{Kernel, Receiver};
use crate::gl::GlError;
use glam::{DVec3, Vec3};
use serde::Serialize;
use std::f64::consts::PI;

/// The procedural sky.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sky {
    /// Towards the sun (unit).
    pub sun: Vec3,
}

impl Default for Sky {
    fn default() -> Sky {
        Sky {
            sun: Vec3::new(0.5, 0.6, 0.62).normalize(),
        }
    }
}

impl Sky {
    /// Radiance from direction `w` (unit): above the horizon blue at the zenith to pale at
    /// the horizon, mixed by sqrt(y); below it a brown ground, 0.2; plus the sun lobe
    /// 30 (1, 0.9, 0.75) max(w·sun, 0)^64.
    pub fn radiance(&self, w: DVec3) -> DVec3 {
        let base = if w.y > 0.0 {
            let t = w.y.sqrt();
            DVec3::new(0.8, 0.85, 0.95).lerp(DVec3::new(0.25, 0.45, 0.95), t)
        } else {
            DVec3::new(0.3, 0.25, 0.2) * 0.2
        };
        let sun = w.dot(self.sun.as_dvec3()).max(0.0).powi(64);
        base + DVec3::new(1.0, 0.9, 0.75) * 30.0 * sun
    }

    /// The directional lights of the `side x side` lat-long grid, as level 0 of the light
    /// hierarchy (rows from the bottom: row j has polar angle π (j + 0.5) / side from +y).
    pub fn lights(&self, side: u32) -> ClusterLevel {
        let n = side as f64;
        let nodes = (0..side * side)
            .map(|k| {
                let (i, j) = ((k % side) as f64, (k / side) as f64);
                let theta = PI * (j + 0.5) / n;
                let phi = 2.0 * PI * (i + 0.5) / n;
                let w = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                let solid_angle = (2.0 * PI / n) * (PI / n) * theta.sin();
                let flux = (self.radiance(w) * solid_angle).as_vec3();
                Cluster {
                    position: w.as_vec3(),
                    radius: 0.0,
                    normal: w.as_vec3(),
                    weight: flux.x + flux.y + flux.z,
                    flux,
                    count: 1.0,
                }
            })
            .collect();
        ClusterLevel { size: side, nodes }
    }

    /// The lights uploaded into level 0 of `clusters` (its side), ready for
    /// [`GpuClusters::build`].
    pub fn upload(&self, clusters: &GpuClusters) -> Result<ClusterLevel, GlError> {
        let level = self.lights(clusters.size());
        let texels = |f: &dyn Fn(&Cluster) -> [f32; 4]| -> Vec<f32> {
            level.nodes.iter().flat_map(f).collect()
        };
        let p = texels(&|c| [c.position.x, c.position.y, c.position.z, c.radius]);
        let nw = texels(&|c| [c.normal.x, c.normal.y, c.normal.z, c.weight]);
        let fc = texels(&|c| [c.flux.x, c.flux.y, c.flux.z, c.count]);
        for (texture, data) in clusters.textures.iter().zip([p, nw, fc]) {
            texture.upload_level_f32(0, &data)?;
        }
        Ok(level)
    }

    /// The GPU's kernel (`environment_kernel.glsl`); it has no uniforms.
    pub fn kernel_shader(&self) -> KernelShader {
        KernelShader {
            define: "#define KERNEL 2\n",
            floats: Vec::new(),
            vectors: Vec::new(),
        }
    }
}

/// Directional lights: Φ max(n·c, 0), and |n·c| as the criterion's distance.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DirectionalKernel;

impl Kernel for DirectionalKernel {
    fn light(&self, r: &Receiver, light: &Cluster) -> DVec3 {
        light.flux.as_dvec3() * r.normal.dot(light.position.as_dvec3()).max(0.0)
    }
    fn distance(&self, r: &Receiver, light: &Cluster) -> f64 {
        r.normal.dot(light.position.as_dvec3()).abs()
    }
}
