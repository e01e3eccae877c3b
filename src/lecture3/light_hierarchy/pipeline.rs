//! The whole technique on one scene: VPLs from the light, the light hierarchy, the receivers,
//! a gather, the picture. Each step is a method, so that callers can time them apart.

use super::clusters::GpuClusters;
use super::gather::{Gather, GatherPasses};
use super::gbuffer::GBuffer;
use super::scene::Scene;
use super::shade::{ShadePass, Terms};
use super::uses::LightUse;
use super::vpl_image::VplPass;
use crate::gl::{Context, VertexArray};
use crate::lecture3::error::Error;

/// The GPU side of technique 3 for one scene, VPL image size and picture size.
pub struct IndirectLighting {
    pub scene: Scene,
    /// What the hierarchy holds and gathers (indirect light for [`IndirectLighting::new`]).
    pub light_use: LightUse,
    vertices: VertexArray,
    vertex_count: usize,
    vpl_pass: VplPass,
    pub clusters: GpuClusters,
    pub gbuffer: GBuffer,
    pub gathers: GatherPasses,
    pub shade: ShadePass,
}

impl IndirectLighting {
    /// `vpl_size` (a power of two, 2 to 128) VPLs a side; a `width x height` picture. The
    /// brute-force gather loops once per VPL, and llvmpipe stops a shader's loops after 65535
    /// iterations in all: 128^2 = 16384 stays well within.
    pub fn new(
        ctx: &Context,
        scene: Scene,
        vpl_size: u32,
        width: u32,
        height: u32,
    ) -> Result<IndirectLighting, Error> {
        IndirectLighting::for_use(ctx, LightUse::Indirect, scene, vpl_size, width, height)
    }

    /// The same steps for another use of the hierarchy: `vpl_size` is then the side of the
    /// irradiance-sample image or of the sky's lat-long grid.
    pub fn for_use(
        ctx: &Context,
        light_use: LightUse,
        scene: Scene,
        vpl_size: u32,
        width: u32,
        height: u32,
    ) -> Result<IndirectLighting, Error> {
        if let LightUse::Subsurface(m) = &light_use {
            m.check()?;
        }
        if !vpl_size.is_power_of_two() || !(2..=128).contains(&vpl_size) {
            return Err(Error::input(
                "--vpls",
                format!("{vpl_size} VPLs a side: a power of two from 2 to 128 is needed"),
            ));
        }
        let (vertices, vertex_count) = scene.vertex_array(ctx)?;
        Ok(IndirectLighting {
            vertices,
            vertex_count,
            vpl_pass: VplPass::new(ctx)?,
            clusters: GpuClusters::new(ctx, vpl_size)?,
            gbuffer: GBuffer::new(ctx, width, height)?,
            gathers: GatherPasses::with_kernel(ctx, width, height, light_use.kernel_shader())?,
            shade: ShadePass::new(ctx, width, height)?,
            scene,
            light_use,
        })
    }

    /// VPLs (or irradiance samples) from the light into level 0, or the sky's lights
    /// uploaded there, then the hierarchy above it.
    pub fn build_lights(&self) -> Result<(), Error> {
        if let LightUse::Environment(sky) = &self.light_use {
            sky.upload(&self.clusters)?;
            self.clusters.build()?;
            return Ok(());
        }
        self.vpl_pass.draw(
            &self.scene,
            &self.vertices,
            self.vertex_count,
            &self.clusters,
        )?;
        self.clusters.build()?;
        Ok(())
    }

    /// The receivers, from the camera.
    pub fn draw_receivers(&self) -> Result<(), Error> {
        self.gbuffer
            .draw(&self.scene, &self.vertices, self.vertex_count)?;
        Ok(())
    }

    /// A gather into [`GatherPasses::target`].
    pub fn gather(&self, gather: Gather) -> Result<(), Error> {
        self.gathers.gather(&self.gbuffer, &self.clusters, gather)?;
        Ok(())
    }

    /// Both gathers' programs run once at a small part of their cost
    /// ([`GatherPasses::warm_up`]), before they are timed.
    pub fn warm_up_gathers(&self) -> Result<(), Error> {
        self.gathers.warm_up(&self.gbuffer, &self.clusters)?;
        Ok(())
    }

    /// The picture of the last gather, into [`ShadePass::target`].
    pub fn shade(&self, terms: Terms, exposure: f32) -> Result<(), Error> {
        self.shade.shade(
            &self.scene,
            &self.gbuffer,
            &self.clusters,
            self.gathers.target.color(0),
            terms,
            exposure,
        )?;
        Ok(())
    }
}
