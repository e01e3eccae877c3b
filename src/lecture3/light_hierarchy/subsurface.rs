//! Subsurface scattering on the light hierarchy, the lecture's demo after Ki & Oh's
//! hierarchical translucent rendering (a reconstruction: that text is not available; the
//! light-hierarchy abstract names subsurface scattering among its uses).
//!
//! Irradiance samples: the translucent object seen from the spot light, one sample per texel
//! of the light's image ([`super::vpl_image`], the object's albedo 1 so that a texel holds
//! the power entering the surface there, Φ = I dω; Fresnel transmission is left out, F_t = 1).
//! Their hierarchy is the same cluster pyramid as the VPLs'. Each receiver x (a pixel of the
//! G-buffer on the object) sums the diffusion profile over the samples,
//! M(x) = Σ_i R_d(|x - x_i|) Φ_i, taking a cluster as one sample at its centre when
//! radius < theta x distance, as for indirect light; the picture shows L = M / π.
//!
//! R_d is the dipole of Jensen, Marschner, Levoy and Hanrahan, "A practical model for
//! subsurface light transport" (SIGGRAPH 2001), per colour channel:
//!
//! R_d(r) = α'/(4π) [ z_r (σ_tr d_r + 1) e^(-σ_tr d_r) / d_r^3 + z_v (σ_tr d_v + 1) e^(-σ_tr d_v) / d_v^3 ]
//!
//! with σ_t' = σ_a + σ_s', α' = σ_s'/σ_t', σ_tr = sqrt(3 σ_a σ_t'), z_r = 1/σ_t',
//! z_v = z_r (1 + 4A/3), A = (1 + F_dr)/(1 - F_dr), F_dr = -1.440/η² + 0.710/η + 0.668 +
//! 0.0636 η, d_r = sqrt(r² + z_r²), d_v = sqrt(r² + z_v²). The GPU's copy is
//! `glsl/lecture3/subsurface_dipole.glsl`.

use super::clusters::Cluster;
use super::gather::KernelShader;
use super::light::{Kernel, Receiver};
use crate::lecture3::error::{check_range, Error};
use glam::{DVec3, Vec3};
use serde::Serialize;

/// A translucent material: absorption σ_a and reduced scattering σ_s' per scene unit (per
/// colour channel), relative index of refraction η.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Material {
    pub sigma_a: Vec3,
    pub sigma_s_prime: Vec3,
    pub eta: f32,
}

/// Scene units per millimetre for the measured materials: the scene unit is taken as 20 mm.
pub const MM_PER_UNIT: f32 = 20.0;

impl Material {
    /// Jensen et al.'s "skin 1" (σ_s' = 0.74, 0.88, 1.01 /mm; σ_a = 0.032, 0.17, 0.48 /mm;
    /// η = 1.3), the scene unit taken as [`MM_PER_UNIT`] mm.
    pub fn skin() -> Material {
        Material {
            sigma_a: Vec3::new(0.032, 0.17, 0.48) * MM_PER_UNIT,
            sigma_s_prime: Vec3::new(0.74, 0.88, 1.01) * MM_PER_UNIT,
            eta: 1.3,
        }
    }

    /// Every coefficient finite and positive, η in 1..=3.
    pub fn check(&self) -> Result<(), Error> {
        for (name, v) in [("sigma_a", self.sigma_a), ("sigma_s'", self.sigma_s_prime)] {
            for c in v.to_array() {
                if !c.is_finite() || c <= 0.0 {
                    return Err(Error::input(
                        name,
                        format!("{c}: a coefficient must be finite and positive"),
                    ));
                }
            }
        }
        check_range("eta", self.eta as f64, 1.0, 3.0)
    }

    /// The dipole's constants (f64).
    pub fn dipole(&self) -> Dipole {
        let sigma_a = self.sigma_a.as_dvec3();
        let sigma_t = sigma_a + self.sigma_s_prime.as_dvec3();
        let eta = self.eta as f64;
        let f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
        let a = (1.0 + f_dr) / (1.0 - f_dr);
        let z_r = DVec3::ONE / sigma_t;
        Dipole {
            sigma_tr: (3.0 * sigma_a * sigma_t).powf(0.5),
            alpha_prime: self.sigma_s_prime.as_dvec3() / sigma_t,
            z_r,
            z_v: z_r * (1.0 + 4.0 * a / 3.0),
        }
    }
}

/// The dipole's constants per colour channel.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Dipole {
    pub sigma_tr: DVec3,
    pub alpha_prime: DVec3,
    pub z_r: DVec3,
    pub z_v: DVec3,
}

impl Dipole {
    /// R_d(r), the diffuse reflectance profile at distance `r` (per scene unit squared).
    pub fn rd(&self, r: f64) -> DVec3 {
        let pole = |z: DVec3| {
            let d = (DVec3::splat(r * r) + z * z).powf(0.5);
            let s = self.sigma_tr * d;
            z * (s + 1.0) * (-s).exp() / (d * d * d)
        };
        self.alpha_prime / (4.0 * std::f64::consts::PI) * (pole(self.z_r) + pole(self.z_v))
    }

    /// The GPU's kernel (`subsurface_dipole.glsl`) and its uniforms.
    pub fn kernel_shader(&self) -> KernelShader {
        KernelShader {
            define: "#define KERNEL 1\n",
            floats: Vec::new(),
            vectors: vec![
                ("u_sigma_tr", self.sigma_tr.as_vec3()),
                ("u_alpha_prime", self.alpha_prime.as_vec3()),
                ("u_z_r", self.z_r.as_vec3()),
                ("u_z_v", self.z_v.as_vec3()),
            ],
        }
    }
}

impl Kernel for Dipole {
    /// Φ R_d(|x - x_i|): the exitance one sample (or a cluster at its centre) gives x.
    fn light(&self, r: &Receiver, light: &Cluster) -> DVec3 {
        light.flux.as_dvec3() * self.rd(light.position.as_dvec3().distance(r.position))
    }
    fn distance(&self, r: &Receiver, light: &Cluster) -> f64 {
        light.position.as_dvec3().distance(r.position)
    }
}
