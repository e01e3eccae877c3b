//! The tutorial's lecture 3 live, one demo per technique of [`crate::lecture3`] (one file
//! each), every intermediate buffer one Tab away, drawn as `gl::dump` says and probed against
//! the module's CPU reference.

mod depth_mask;
mod displace;
mod function;
mod histogram;
mod light;
mod octree;
mod pyramid;
mod random;

use crate::gl::Context;
use crate::view::Demo;

/// The seven techniques, named as `classic-gpgpu lecture3` names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Technique {
    /// 1. The max and min image pyramids of the height map, level by level.
    Pyramid,
    /// 2. Pyramidal displacement mapping, the camera orbiting the box.
    Displace,
    /// 3. Indirect light gathered by a quadtree search of the VPL hierarchy.
    Light,
    /// 4. A function in a 1D texture, looked up per pixel.
    Function,
    /// 5. Random numbers generated into a texture, one step per frame.
    Random,
    /// 6. An if removed with the depth buffer.
    DepthMask,
    /// 7. A histogram by additive blending of points.
    Histogram,
    /// 8. Rays cast through the octree of a point set, against the flat walk.
    Octree,
}

impl Technique {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Technique::Pyramid => "pyramid",
            Technique::Displace => "displace",
            Technique::Light => "light",
            Technique::Function => "function",
            Technique::Random => "random",
            Technique::DepthMask => "depth-mask",
            Technique::Histogram => "histogram",
            Technique::Octree => "octree",
        }
    }

    /// Build the technique's demo on `ctx`.
    pub fn build(self, ctx: &Context) -> anyhow::Result<Box<dyn Demo>> {
        Ok(match self {
            Technique::Pyramid => Box::new(pyramid::PyramidDemo::new(ctx)?),
            Technique::Displace => Box::new(displace::DisplaceDemo::new(ctx)?),
            Technique::Light => Box::new(light::LightDemo::new(ctx)?),
            Technique::Function => Box::new(function::FunctionDemo::new(ctx)?),
            Technique::Random => Box::new(random::RandomDemo::new(ctx)?),
            Technique::DepthMask => Box::new(depth_mask::DepthMaskDemo::new(ctx)?),
            Technique::Histogram => Box::new(histogram::HistogramDemo::new(ctx)?),
            Technique::Octree => Box::new(octree::OctreeDemo::new(ctx)?),
        })
    }
}

/// Values in f64 as the f32 the probe compares with.
fn to_f32(values: &[f64]) -> Vec<f32> {
    values.iter().map(|&v| v as f32).collect()
}
