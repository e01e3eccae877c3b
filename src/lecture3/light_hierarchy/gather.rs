//! The gathers: for every receiver of the G-buffer, the irradiance from the VPLs, either by
//! the hierarchical search of the light hierarchy (`vpl_gather_tree.frag`) or by the
//! brute-force sum over every VPL (`vpl_gather_brute.frag`). One full-screen pass each.

use super::clusters::GpuClusters;
use super::gbuffer::GBuffer;
use crate::gl::{Context, Framebuffer, GlError, Pass, Program, Rect, Texture, TextureFormat};
use crate::lecture3::error::{check_range, Error};
use crate::shader;
use serde::Serialize;

/// Distances below this are clamped in the irradiance (scene units; the room is 1 wide).
pub const MIN_DISTANCE: f32 = 0.1;

/// How the light is gathered.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Gather {
    /// The hierarchical search: a cluster is one light when radius < theta x distance.
    Tree { theta: f32 },
    /// Every VPL.
    BruteForce,
}

impl Gather {
    /// The tree search, with `theta` checked (finite, 0..=4; `--theta`).
    pub fn tree(theta: f32) -> Result<Gather, Error> {
        check_range("--theta", theta as f64, 0.0, 4.0)?;
        Ok(Gather::Tree { theta })
    }
}

/// The two gather programs and their target.
pub struct GatherPasses {
    tree: Program,
    brute: Program,
    /// Irradiance rgb and nodes visited per pixel.
    pub target: Framebuffer,
}

impl GatherPasses {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<GatherPasses, GlError> {
        let common = shader!("glsl/lecture3/vpl_common.glsl");
        let texture = Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F)?;
        Ok(GatherPasses {
            tree: Program::rect(
                ctx,
                &[common, shader!("glsl/lecture3/vpl_gather_tree.frag")],
            )?,
            brute: Program::rect(
                ctx,
                &[common, shader!("glsl/lecture3/vpl_gather_brute.frag")],
            )?,
            target: Framebuffer::new(ctx, "gathered light", &[&texture], None)?,
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
            Gather::Tree { .. } => &self.tree,
            Gather::BruteForce => &self.brute,
        };
        let mut pass = self.target.pass(program, "gather VPL light")?;
        bind_common(&mut pass, gbuffer, clusters);
        match gather {
            Gather::Tree { theta } => pass
                .uniform("u_top", clusters.top() as i32)
                .uniform("u_theta", theta),
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
        bind_common(&mut pass, gbuffer, clusters);
        pass.uniform("u_size", 1i32);
        pass.draw_full()?;
        let mut pass = self.target.pass(&self.tree, "warm up the tree gather")?;
        bind_common(&mut pass, gbuffer, clusters);
        pass.uniform("u_top", 0i32).uniform("u_theta", 0.0f32);
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
}

fn bind_common(pass: &mut Pass, gbuffer: &GBuffer, clusters: &GpuClusters) {
    let atlas = &clusters.atlases;
    pass.texture("u_receiver_position", gbuffer.position())
        .texture("u_receiver_normal", gbuffer.normal())
        .texture("u_cluster_position", &atlas[0].texture)
        .texture("u_cluster_normal", &atlas[1].texture)
        .texture("u_cluster_flux", &atlas[2].texture)
        .uniform("u_level_x", &atlas[0].offsets_x()[..])
        .uniform("u_level_y", &atlas[0].offsets_y()[..])
        .uniform("u_min_distance", MIN_DISTANCE);
}
