//! Everything the lecture-3 section measures, typed (written as the section's `results`).

use crate::lecture3::depth_mask::{MaskShape, RunCounter};
use crate::lecture3::displacement::compare::Comparison;
use crate::timing::{Load, Spread};
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct Lecture3Results {
    /// The renderer every figure was measured on.
    pub renderer: String,
    /// Its name alone (plot titles).
    pub renderer_name: String,
    /// A software rasterizer (its "GPU" passes run on the CPU cores the CPU references use).
    pub software: bool,
    /// How GPU times were taken ([`super::timed::gpu_ms`]).
    pub gpu_timing: String,
    pub quick: bool,
    /// How often each repeated timing ran (the median is kept; each `*_spread` beside a
    /// time gives its runs, median, min and max).
    pub runs: String,
    /// The busiest the machine was while the techniques were timed (1-minute load average,
    /// read after each timed technique): timing claims are not judged above one per core.
    pub load: Option<Load>,
    pub pyramid: Vec<PyramidRow>,
    pub displacement: DisplacementRun,
    /// Technique 2's minification prefilter against the camera's distance.
    pub prefilter: Vec<super::prefilter::PrefilterRow>,
    /// Octrees on the GPU: the octree cast against the flat walk, per grid resolution.
    pub octree: Vec<super::octree::OctreeRow>,
    pub light: LightRun,
    /// The light hierarchy's other uses (normal-aware clustering, subsurface, environment).
    pub light_uses: super::light_uses::LightUsesRun,
    pub function: FunctionRun,
    pub random: RandomRun,
    pub depth_mask: DepthMaskRun,
    pub histogram: Vec<HistogramRow>,
}

/// Technique 1 on one map size.
#[derive(Clone, Debug, Serialize)]
pub struct PyramidRow {
    pub size: u32,
    pub levels: u32,
    /// Every level of the GPU max and min pyramids equal to the CPU's, bit for bit.
    pub equal_to_cpu: bool,
    /// The mean pyramid: largest |GPU - CPU| over its levels (the map spans 0..1).
    pub mean_max_error: f64,
    /// Median GPU time of the level passes, level 0 uploaded beforehand.
    pub gpu_ms: f64,
    pub gpu_spread: Spread,
    /// Median wall clock of the CPU pyramid (one extreme).
    pub cpu_ms: f64,
    pub cpu_spread: Spread,
}

/// Technique 2.
#[derive(Clone, Debug, Serialize)]
pub struct DisplacementRun {
    /// Which height map (a path, or the shipped generated map).
    pub map: String,
    pub map_size: (u32, u32),
    /// Box height of a white sample (the longer side is 2).
    pub depth: f32,
    /// Image side, pixels.
    pub image: u32,
    pub artifacts: Vec<ArtifactRow>,
    pub speed: Vec<SpeedRow>,
}

/// One view: every method against the exact CPU tracer.
#[derive(Clone, Debug, Serialize)]
pub struct ArtifactRow {
    pub azimuth: f32,
    pub elevation: f32,
    pub methods: Vec<MethodComparison>,
}

#[derive(Clone, Debug, Serialize)]
pub struct MethodComparison {
    pub method: String,
    pub comparison: Comparison,
}

/// One map size at one view: GPU times against the exact CPU tracer.
#[derive(Clone, Debug, Serialize)]
pub struct SpeedRow {
    pub map_size: u32,
    pub levels: u32,
    /// Median GPU time of a pyramid-traversal frame.
    pub pyramid_ms: f64,
    pub pyramid_spread: Spread,
    /// Mean loop iterations of the traversal per pixel that hits.
    pub pyramid_iterations: f64,
    /// Median GPU time of a relief-mapping frame (32 + 8 steps).
    pub relief_ms: f64,
    pub relief_spread: Spread,
    /// Wall clock of the exact CPU tracer for the same frame (f64, one thread).
    pub cpu_ms: f64,
    /// Pixels of the pyramid frame that hit the surface.
    pub hit_pixels: usize,
}

/// Technique 3.
#[derive(Clone, Debug, Serialize)]
pub struct LightRun {
    /// VPL image side (side^2 VPLs).
    pub vpl_side: u32,
    /// VPLs that carry light.
    pub vpls: usize,
    pub image: (u32, u32),
    pub receivers: usize,
    /// GPU time of the VPL pass, the cluster passes and the atlas copies.
    pub build_ms: f64,
    pub build_spread: Spread,
    pub brute_gpu_ms: f64,
    pub brute_gpu_spread: Spread,
    /// The brute-force sum on the CPU (f64, on every core: `brute_cpu_threads` threads, as
    /// the software renderer's passes use them) over every receiver.
    pub brute_cpu_ms: f64,
    pub brute_cpu_threads: usize,
    /// Largest |GPU - CPU| of the brute force, relative to the pixel's value.
    pub brute_gpu_vs_cpu: f64,
    pub rows: Vec<LightRow>,
}

/// One criterion: error against speed.
#[derive(Clone, Debug, Serialize)]
pub struct LightRow {
    pub theta: f32,
    /// sqrt(sum |tree - brute|^2 / sum |brute|^2) over receivers and channels.
    pub relative_rms_error: f64,
    /// Mean nodes visited per receiver.
    pub mean_nodes: f64,
    pub gpu_ms: f64,
    pub gpu_spread: Spread,
}

/// Technique 4.
#[derive(Clone, Debug, Serialize)]
pub struct FunctionRun {
    pub errors: Vec<FunctionErrorRow>,
    pub speed: Vec<FunctionSpeedRow>,
}

#[derive(Clone, Debug, Serialize)]
pub struct FunctionErrorRow {
    pub function: String,
    pub texels: u32,
    pub samples: u64,
    /// max |GPU lookup - exact|.
    pub max_error: f64,
    pub rms_error: f64,
    /// h^2 max|f''| / 8.
    pub bound: f64,
    /// max |GPU lookup - exact linear interpolation of the table| (the filter's own error).
    pub filter_error: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct FunctionSpeedRow {
    pub function: String,
    pub evaluations: u64,
    /// Computed in the shader.
    pub exact_ms: f64,
    pub exact_spread: Spread,
    /// Looked up in a 256-texel table.
    pub lookup_ms: f64,
    pub lookup_spread: Spread,
    /// The same evaluations on the CPU (f64, one thread).
    pub cpu_ms: f64,
}

/// Technique 5.
#[derive(Clone, Debug, Serialize)]
pub struct RandomRun {
    pub side: u32,
    pub steps: usize,
    /// The GPU's numbers of every checked step, as read back: step by step, each `side x side`
    /// row by row from the bottom (not in the report's results).
    #[serde(skip)]
    pub values: Vec<f32>,
    /// States and numbers equal to the CPU generator's after every step.
    pub bit_exact: bool,
    pub gpu_ms_per_step: f64,
    pub gpu_spread: Spread,
    pub cpu_ms_per_step: f64,
    pub cpu_spread: Spread,
    pub chi_square: f64,
    pub chi_square_critical: f64,
    pub serial_correlation: f64,
    pub neighbour_correlation: f64,
    pub correlation_bound: f64,
    /// The numbers of the last step counted into 64 bins by the blending histogram.
    pub histogram: Vec<f32>,
}

/// Technique 6.
#[derive(Clone, Debug, Serialize)]
pub struct DepthMaskRun {
    pub side: u32,
    pub iterations: u32,
    pub rows: Vec<DepthMaskRow>,
}

#[derive(Clone, Debug, Serialize)]
pub struct DepthMaskRow {
    pub mask: MaskShape,
    pub fraction: f32,
    /// Active pixels by the CPU.
    pub active: u64,
    /// Pixels in all.
    pub pixels: u64,
    /// 2x2 quads holding an active pixel (the count is judged at this granularity).
    pub active_quads: u64,
    /// Runs of the expensive shader behind the depth mask, counted (`None`: not countable
    /// on this context, see `counted_by`).
    pub masked_runs: Option<u64>,
    /// Runs of the same shader with the depth test passing every pixel (the counter's check).
    pub unmasked_runs: Option<u64>,
    /// What counted the runs.
    pub counted_by: RunCounter,
    /// The plain shader's invocations behind the mask by the driver's pipeline statistics,
    /// where it has them (llvmpipe counts fragments its early depth test drops).
    pub masked_invocations: Option<u64>,
    /// Fragments that passed the depth test (occlusion query), depth-masked version.
    pub masked_fragments: u64,
    /// Fragments of the branching shader (every pixel).
    pub branching_fragments: u64,
    pub branching_ms: f64,
    pub branching_spread: Spread,
    /// Both passes of the depth-masked version.
    pub masked_ms: f64,
    pub masked_spread: Spread,
    /// Largest |GPU - CPU| of either picture.
    pub max_error: f64,
}

/// Technique 7.
#[derive(Clone, Debug, Serialize)]
pub struct HistogramRow {
    pub values: usize,
    pub bins: u32,
    /// The blended counts, as read back from the GPU (not in the report's results).
    #[serde(skip)]
    pub counts: Vec<f32>,
    /// Blended counts equal to the CPU's.
    pub blend_equal: bool,
    /// Gathered counts equal to the CPU's (when run).
    pub gather_equal: Option<bool>,
    /// Draw calls one blended histogram made, counted by the gl layer's profiler (`None`
    /// where a profile of the caller's was running and was not interrupted to count them).
    pub blend_draws: Option<u64>,
    pub blend_ms: f64,
    pub blend_spread: Spread,
    pub gather_ms: Option<f64>,
    pub gather_spread: Option<Spread>,
    pub cpu_ms: f64,
    pub cpu_spread: Spread,
}
