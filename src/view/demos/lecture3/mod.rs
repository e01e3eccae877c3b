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

use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

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

/// A `side x side` panel of `values`.
fn square(title: &str, values: &[f32], side: u32, scale: Scale) -> Panel {
    Panel {
        title: title.into(),
        values: values.to_vec(),
        width: side,
        height: side,
        scale,
    }
}

/// `panel` (a GPU buffer) probed against `reference`, the CPU's values of the same buffer.
fn against(panel: Panel, reference: &[f32]) -> Shown {
    Shown {
        panel,
        probe_values: None,
        reference: Some(reference.to_vec()),
    }
}

/// A `side x side` GPU buffer probed against the CPU's, and the CPU's beside it, on one scale.
fn gpu_beside_cpu(side: u32, gpu: (&str, &[f32]), cpu: (&str, &[f32])) -> Vec<Shown> {
    let scale = Scale::of([gpu.1, cpu.1]);
    vec![
        against(square(gpu.0, gpu.1, side, scale), cpu.1),
        square(cpu.0, cpu.1, side, scale).into(),
    ]
}

/// Clears the canvas; whether there is a frame to draw (an orbiting demo has none before its
/// first step).
fn cleared(canvas: &Canvas, frames: usize) -> anyhow::Result<bool> {
    canvas.clear([0.0, 0.0, 0.0, 1.0])?;
    Ok(frames > 0)
}

/// Clears the canvas and draws one of two buffers (the first on even `view.shown`), filling
/// the space below the text.
fn draw_one_of(canvas: &Canvas, view: &ViewState, [even, odd]: [Shown; 2]) -> anyhow::Result<()> {
    canvas.clear([0.0, 0.0, 0.0, 1.0])?;
    let shown = if view.shown.is_multiple_of(2) {
        even
    } else {
        odd
    };
    inset::draw_picture(canvas, vec![shown], canvas.below_text())?;
    Ok(())
}
