//! The gathers: for every receiver of the G-buffer, the irradiance from the VPLs, either by
//! the hierarchical search of the light hierarchy (`vpl_gather_tree.frag`) or by the
//! brute-force sum over every VPL (`vpl_gather_brute.frag`). One full-screen pass each.
//! What a light gives a receiver is a kernel compiled between the common part and the gather
//! ([`KernelShader`]): VPL irradiance, the subsurface dipole or directional sky light.

use super::clusters::GpuClusters;
use super::gbuffer::GBuffer;
use crate::gl::{
    Context, Framebuffer, GlError, Pass, Program, Rect, ShaderSource, Texture, TextureFormat,
};
use crate::lecture3::error::{check_range, Error};
use crate::shader;
use glam::Vec3;
use serde::Serialize;

/// Distances below this are clamped in the irradiance (scene units; the room is 1 wide).
pub const MIN_DISTANCE: f32 = 0.1;

/// How the light is gathered.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Gather {
    /// The hierarchical search: a cluster is one light when radius < theta x distance.
    Tree { theta: f32 },
    /// The tree search with normal-aware clustering ([`super::normal_cone`]): a cluster is one
    /// light when radius < theta x distance and its mean normal is at least `min_coherence` long.
    NormalAware { theta: f32, min_coherence: f32 },
    /// Every VPL.
    BruteForce,
}

impl Gather {
    /// The tree search, with `theta` checked (finite, 0..=4; `--theta`).
    pub fn tree(theta: f32) -> Result<Gather, Error> {
        check_range("--theta", theta as f64, 0.0, 4.0)?;
        Ok(Gather::Tree { theta })
    }

    /// The normal-aware tree search, `theta` as [`Gather::tree`], `min_coherence` finite in
    /// 0..=1 (`--min-coherence`; 0 is the fixed merge).
    pub fn normal_aware(theta: f32, min_coherence: f32) -> Result<Gather, Error> {
        check_range("--theta", theta as f64, 0.0, 4.0)?;
        check_range("--min-coherence", min_coherence as f64, 0.0, 1.0)?;
        Ok(Gather::NormalAware {
            theta,
            min_coherence,
        })
    }

    /// The tree criterion on the CPU (`None` for the brute force).
    pub fn criterion(self) -> Option<super::light::Criterion> {
        match self {
            Gather::Tree { theta } => Some(super::light::Criterion::theta(theta as f64)),
            Gather::NormalAware {
                theta,
                min_coherence,
            } => Some(super::light::Criterion {
                theta: theta as f64,
                min_coherence: min_coherence as f64,
            }),
            Gather::BruteForce => None,
        }
    }
}

/// A kernel (what one light gives a receiver, and the criterion's distance) and the uniforms
/// it declares. The three kernel files are compiled into every gather, each inside
/// `#if KERNEL == k`; `define` picks one.
#[derive(Clone, Debug)]
pub struct KernelShader {
    /// `#define KERNEL k` (0: VPL irradiance, 1: the subsurface dipole, 2: directional sky light).
    pub define: &'static str,
    pub floats: Vec<(&'static str, f32)>,
    pub vectors: Vec<(&'static str, Vec3)>,
}

impl KernelShader {
    /// The VPLs' irradiance (`vpl_kernel.glsl`).
    pub fn vpl() -> KernelShader {
        KernelShader {
            define: "#define KERNEL 0\n",
            floats: vec![("u_min_distance", MIN_DISTANCE)],
            vectors: Vec::new(),
        }
    }
}

/// The two gather programs and their target.
pub struct GatherPasses {
    tree: Program,
    brute: Program,
    kernel: KernelShader,
    /// Irradiance rgb and nodes visited per pixel.
    pub target: Framebuffer,
}

impl GatherPasses {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<GatherPasses, GlError> {
        GatherPasses::with_kernel(ctx, width, height, KernelShader::vpl())
    }

    /// The gathers with another kernel.
    pub fn with_kernel(
        ctx: &Context,
        width: u32,
        height: u32,
        kernel: KernelShader,
    ) -> Result<GatherPasses, GlError> {
        let common = shader!("glsl/lecture3/vpl_common.glsl");
        let k = [
            ShaderSource {
                name: "(generated: the kernel's number)",
                source: kernel.define,
            },
            shader!("glsl/lecture3/vpl_kernel.glsl"),
            shader!("glsl/lecture3/subsurface_dipole.glsl"),
            shader!("glsl/lecture3/environment_kernel.glsl"),
        ];
        let texture = Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F)?;
        Ok(GatherPasses {
            tree: Program::rect(
                ctx,
                &[
                    &[common][..],
                    &k,
                    &[shader!("glsl/lecture3/vpl_gather_tree.frag")],
                ]
                .concat(),
            )?,
            brute: Program::rect(
                ctx,
                &[
                    &[common][..],
                    &k,
                    &[shader!("glsl/lecture3/vpl_gather_brute.frag")],
                ]
                .concat(),
            )?,
            target: Framebuffer::new(ctx, "gathered light", &[&texture], None)?,
            kernel,
        })
    }

    /// Gathers into [`GatherPasses::target`].
    pub fn gather(
        &self,
        gbuffer: &GBuffer,
        clusters: &GpuClusters,
        gather: Gather,
    ) -> Result<(), GlError> {
        self.target.clear_colors([0.0; 4])?;
        let program = match gather {
            Gather::Tree { .. } | Gather::NormalAware { .. } => &self.tree,
            Gather::BruteForce => &self.brute,
        };
        let mut pass = self.target.pass(program, "gather VPL light")?;
        self.bind_common(&mut pass, gbuffer, clusters);
        match gather {
            Gather::Tree { theta } => pass
                .uniform("u_top", clusters.top() as i32)
                .uniform("u_theta", theta)
                .uniform("u_min_coherence", 0.0f32),
            Gather::NormalAware {
                theta,
                min_coherence,
            } => pass
                .uniform("u_top", clusters.top() as i32)
                .uniform("u_theta", theta)
                .uniform("u_min_coherence", min_coherence),
            Gather::BruteForce => pass.uniform("u_size", clusters.size() as i32),
        };
        pass.draw_full()
    }

    /// Both gather programs drawn once with one node per receiver (the brute force over one
    /// VPL, the tree from a level-0 root): their shader variants compiled and their textures
    /// bound, at a small part of a gather's cost. The target is left with that partial sum.
    pub fn warm_up(&self, gbuffer: &GBuffer, clusters: &GpuClusters) -> Result<(), GlError> {
        self.target.clear_colors([0.0; 4])?;
        let mut pass = self
            .target
            .pass(&self.brute, "warm up the brute-force gather")?;
        self.bind_common(&mut pass, gbuffer, clusters);
        pass.uniform("u_size", 1i32);
        pass.draw_full()?;
        let mut pass = self.target.pass(&self.tree, "warm up the tree gather")?;
        self.bind_common(&mut pass, gbuffer, clusters);
        pass.uniform("u_top", 0i32)
            .uniform("u_theta", 0.0f32)
            .uniform("u_min_coherence", 0.0f32);
        pass.draw_full()
    }

    /// The gathered irradiance (rgb) and nodes visited, per pixel, row by row from the bottom.
    pub fn read(&self) -> Result<Vec<[f32; 4]>, GlError> {
        let rect = Rect::sized(self.target.width(), self.target.height());
        Ok(self
            .target
            .read_f32(0, rect)?
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect())
    }

    fn bind_common(&self, pass: &mut Pass, gbuffer: &GBuffer, clusters: &GpuClusters) {
        let atlas = &clusters.atlases;
        pass.texture("u_receiver_position", gbuffer.position())
            .texture("u_receiver_normal", gbuffer.normal())
            .texture("u_cluster_position", &atlas[0].texture)
            .texture("u_cluster_normal", &atlas[1].texture)
            .texture("u_cluster_flux", &atlas[2].texture)
            .uniform("u_level_x", &atlas[0].offsets_x()[..])
            .uniform("u_level_y", &atlas[0].offsets_y()[..]);
        for &(name, value) in &self.kernel.floats {
            pass.uniform(name, value);
        }
        for &(name, value) in &self.kernel.vectors {
            pass.uniform(name, value);
        }
    }
}
