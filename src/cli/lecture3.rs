//! `classic-gpgpu lecture3 ...`: one command per technique of the tutorial's lecture 3
//! (`src/lecture3/`), each running the GPU path beside its CPU reference, printing what they
//! found (text or `--json`, timings as ratios measured in the same run, the renderer named)
//! and writing PNGs on request. `lecture3-bench` goes through
//! [`classic_gpgpu::report::bench_command`].

use super::lecture3_light::{self, LightMode};
use anyhow::{bail, Context as _};
use classic_gpgpu::files;
use classic_gpgpu::gl::dump::{texture_png, DumpRange};
use classic_gpgpu::gl::Context;
use classic_gpgpu::lecture3::blend_histogram::{self, Bins};
use classic_gpgpu::lecture3::depth_mask::{self, DepthMask, MaskShape};
use classic_gpgpu::lecture3::displacement::camera::FAR;
use classic_gpgpu::lecture3::displacement::compare::ReferenceImage;
use classic_gpgpu::lecture3::displacement::{exact, Camera, DisplacementRenderer, Method, Surface};
use classic_gpgpu::lecture3::error::check_range;
use classic_gpgpu::lecture3::function_texture::{Function, FunctionPasses};
use classic_gpgpu::lecture3::height_map::{load_grey, HeightMap, SHIPPED_SIZE};
use classic_gpgpu::lecture3::light_hierarchy::normal_cone::compare_clustering;
use classic_gpgpu::lecture3::light_hierarchy::shade::Terms;
use classic_gpgpu::lecture3::light_hierarchy::{Gather, LightUse};
use classic_gpgpu::page::folder::Staged;
use classic_gpgpu::report::lecture3::{
    self as bench,
    images::{gpu_pyramids, pyramid_png, PYRAMID_KINDS},
};
use classic_gpgpu::timing::Runs;
use classic_gpgpu::values::{ranges, Count, Real};
use serde_json::json;
use std::path::{Path, PathBuf};

/// The lecture-3 techniques.
#[derive(clap::Subcommand, Debug)]
pub enum Lecture3Command {
    /// 1. The max, min and mean image pyramids of a height map, drawn level by level on the
    ///    GPU and compared with the CPU's.
    Pyramid(PyramidArgs),
    /// 2. Pyramidal displacement mapping: a height map on a box, traced per pixel through its
    ///    max pyramid (or by relief mapping), checked against an exact CPU ray tracer.
    Displace(DisplaceArgs),
    /// 3. Indirect light from virtual point lights, gathered by a quadtree search of their
    ///    hierarchy, against the brute-force sum.
    Light(LightArgs),
    /// 4. A function in a 1D texture: interpolation error and speed against computing it.
    Function(FunctionArgs),
    /// 5. Random numbers generated into a texture, checked bit for bit against the CPU
    ///    generator and tested for uniformity and independence.
    Random(RandomArgs),
    /// 6. An if removed with the depth buffer: fragments counted, time against branching.
    DepthMask(DepthMaskArgs),
    /// 7. A histogram by additive blending of points, against the CPU histogram.
    Histogram(HistogramArgs),
    /// Write the generated height map (the shipped assets/lecture3/height.png is --size 64).
    HeightMap(HeightMapArgs),
    /// 8. An octree of a voxelized point set built in textures by reduction passes, and rays
    ///    cast through it per pixel against a flat voxel walk and the CPU.
    Octree(OctreeArgs),
}

#[derive(clap::Args, Debug)]
pub struct OctreeArgs {
    /// An OBJ model whose surface is sampled into points [default: random points on three
    /// shapes].
    model: Option<PathBuf>,
    /// Points (random on three shapes, or sampled on the model's triangles).
    #[arg(long, default_value_t = 20_000, value_parser = POINTS.of::<usize>())]
    points: usize,
    /// Voxels per side of the leaf grid (a power of two, 2 to 128).
    #[arg(long, default_value_t = 64, value_parser = OCTREE_RESOLUTION.of::<u32>())]
    resolution: u32,
    /// Image side, pixels.
    #[arg(long, default_value_t = 128, value_parser = IMAGE_SIDE.of::<u32>())]
    size: u32,
    /// The camera's distance from the cube's centre (the cube's side is 2).
    #[arg(long, default_value_t = 3.5, value_parser = OCTREE_DISTANCE.of::<f32>())]
    distance: f32,
    /// Camera azimuth, degrees.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true, value_parser = AZIMUTH.of::<f32>())]
    azimuth: f32,
    /// Camera elevation, degrees.
    #[arg(long, default_value_t = 25.0, allow_negative_numbers = true, value_parser = OCTREE_ELEVATION.of::<f32>())]
    elevation: f32,
    /// Time the octree cast against the flat walk (GPU time, repeated; the median kept).
    #[arg(long)]
    bench: bool,
    /// Write the octree cast's hit.npy (height x width x 4: voxel i, j, l and the entry
    /// parameter, -1 for a miss) and steps.npy into DIR (created); rows from the bottom.
    #[arg(long)]
    npy: Option<PathBuf>,
    #[command(flatten)]
    output: Output,
}

const OCTREE_RESOLUTION: Count = Count::new(
    "a resolution",
    2,
    128,
    "a power of two: the leaf grid of an octree of at most 7 levels",
);
const OCTREE_DISTANCE: Real = Real::new("a distance", 0.1, 1000.0, "in front of the far plane");
const OCTREE_ELEVATION: Real = Real::new(
    "an elevation",
    -89.5,
    89.5,
    "degrees; at the poles the camera's up is undefined",
);
const DEPTH: Real = Real::new(
    "a depth",
    1e-3,
    2.0,
    "in half the box's longer side: the box holds the surface",
);
const DISPLACE_ELEVATION: Real = Real::new(
    "an elevation",
    0.1,
    89.5,
    "degrees above the surface, which is seen from above",
);
const ORBIT_FRAMES: Count = Count::new(
    "a number of frames",
    1,
    360,
    "one orbit at a degree a frame at most",
);
const DISPLACE_DISTANCE: Real = Real::new(
    "a distance",
    0.5,
    (FAR - 5.0) as f64,
    "the box must lie in front of the far plane",
);
const LINEAR_STEPS: Count = Count::new(
    "a number of steps",
    1,
    4096,
    "relief mapping's linear search per pixel",
);
const BINARY_STEPS: Count = Count::new(
    "a number of steps",
    0,
    64,
    "each halves the interval: 64 pass fp32's precision",
);
const VPLS: Count = Count::new(
    "a number of VPLs a side",
    2,
    128,
    "a power of two; the VPL image's side",
);
const THETA: Real = Real::new(
    "a criterion",
    0.0,
    4.0,
    "a cluster's radius over its distance",
);
const EXPOSURE: Real = Real::new("an exposure", -20.0, 20.0, "stops: the picture times 2^E");
const COHERENCE: Real = Real::new("a coherence", 0.0, 1.0, "the length of a mean unit normal");
const TEXELS: Count = Count {
    least: 2,
    ..ranges::TEXTURE_SIDE
};
const PER_PIXEL: Count = Count::new(
    "a number of values per pixel",
    1,
    4096,
    "a power of two; the pass's loop",
);
const GENERATORS: Count = Count::new(
    "a number of generators a side",
    2,
    4096,
    "the neighbour correlation needs two in a row",
);
const RANDOM_STEPS: Count = Count::new(
    "a number of steps",
    2,
    1024,
    "the serial correlation compares a step with the next",
);
const FRACTION: Real = Real::new("a fraction", 0.0, 1.0, "a share of the pixels");
const ITERATIONS: Count = Count::new(
    "a number of iterations",
    1,
    16384,
    "llvmpipe stops a shader's loop after 65535",
);
const VALUES: Count = Count::new(
    "a number of values",
    1,
    1 << 24,
    "fp32 blending counts exactly up to 2^24",
);
const SAMPLES: Count = Count::new(
    "a number of samples a side",
    2,
    4096,
    "a PNG height map of at most 4096 x 4096",
);

/// `--size` of a picture the command draws and checks pixel by pixel.
const IMAGE_SIDE: Count = Count::new(
    "a size in pixels",
    8,
    4096,
    "each pixel is checked against the CPU",
);

/// A camera's azimuth, degrees, up to ten turns either way.
const AZIMUTH: Real = Real::new(
    "an azimuth",
    -3600.0,
    3600.0,
    "degrees, ten turns either way",
);

/// `octree --points`.
const POINTS: Count = Count::new(
    "a number of points",
    1,
    10_000_000,
    "each point is binned on the CPU and on the GPU",
);

/// Where a PNG goes: never over an input, over an existing file only with --force.
#[derive(clap::Args, Debug)]
pub struct Output {
    /// Write the picture to this PNG file.
    #[arg(long)]
    png: Option<PathBuf>,
    /// Replace --png if it exists (never an input).
    #[arg(long)]
    force: bool,
}

impl Output {
    fn check(&self, inputs: &[&Path]) -> anyhow::Result<()> {
        match &self.png {
            Some(out) => check_output(out, inputs, self.force),
            None => Ok(()),
        }
    }
}

fn check_output(out: &Path, inputs: &[&Path], force: bool) -> anyhow::Result<()> {
    classic_gpgpu::files::check_output("the PNG", out, inputs, force, &["png"])
}

#[derive(clap::Args, Debug)]
pub struct PyramidArgs {
    /// A greyscale PNG height map [default: the generated map of assets/lecture3/height.png].
    #[arg(long)]
    height: Option<PathBuf>,
    /// Write every level the GPU drew, as read back, into DIR (created) as float32 .npy, one
    /// file per kind and level: max_L.npy, min_L.npy and mean_L.npy (height x width of level
    /// L; level 0 is the input padded to a power of two a side, the padding max's -3.4e38,
    /// min's 3.4e38 and mean's 0; rows from the bottom). A folder holding files this command
    /// did not write is refused without --force; a rerun replaces the earlier run's files.
    #[arg(long, value_name = "DIR")]
    npy: Option<PathBuf>,
    #[command(flatten)]
    output: Output,
}

#[derive(clap::Args, Debug)]
pub struct DisplaceArgs {
    /// A greyscale PNG height map (black 0, white 1) [default: the shipped generated map].
    #[arg(long)]
    height: Option<PathBuf>,
    /// Height of a white sample, in units of half the box's longer side.
    #[arg(long, default_value_t = bench::DEPTH, value_parser = DEPTH.of::<f32>())]
    depth: f32,
    /// Image side, pixels.
    #[arg(long, default_value_t = 256, value_parser = IMAGE_SIDE.of::<u32>())]
    size: u32,
    /// Camera azimuth about the vertical, degrees.
    #[arg(long, default_value_t = 225.0, allow_negative_numbers = true, value_parser = AZIMUTH.of::<f32>())]
    azimuth: f32,
    /// Camera elevation above the surface, degrees (small: grazing).
    #[arg(long, default_value_t = 20.0, value_parser = DISPLACE_ELEVATION.of::<f32>())]
    elevation: f32,
    /// Frames of a camera orbiting the box (the azimuth turns 360 / frames per frame).
    #[arg(long, default_value_t = 1, value_parser = ORBIT_FRAMES.of::<u32>())]
    frames: u32,
    /// How each pixel finds its hit.
    #[arg(long, value_enum, default_value_t = MethodArg::Pyramid)]
    method: MethodArg,
    /// The camera's distance from the box centre (the box's longer side is 2); far away each
    /// pixel covers many patches.
    #[arg(long, default_value_t = bench::DISTANCE, value_parser = DISPLACE_DISTANCE.of::<f32>())]
    distance: f32,
    /// The minification prefilter (pyramid method): stop at the level of the pixel's footprint
    /// and meet the prefiltered surface there; the check then uses the CPU reference of the
    /// same rule, and the frame's error against a 4x4-supersampled unfiltered image is printed
    /// beside the unfiltered frame's.
    #[arg(long)]
    prefilter: bool,
    /// Relief mapping's linear steps (--method relief) [default: 32].
    #[arg(long, value_parser = LINEAR_STEPS.of::<u32>())]
    linear_steps: Option<u32>,
    /// Relief mapping's binary steps (--method relief) [default: 8].
    #[arg(long, value_parser = BINARY_STEPS.of::<u32>())]
    binary_steps: Option<u32>,
    /// Skip the exact CPU tracer (its check of the first frame and its time).
    #[arg(long)]
    no_check: bool,
    /// Write frame k to DIR/frame_k.png (DIR is created; existing frames only with --force).
    #[arg(long, conflicts_with = "png")]
    out: Option<PathBuf>,
    /// Write the first frame as the GPU read it back into DIR (created): hit.npy (height x
    /// width x 4: grid x, y, z and the ray parameter), depth.npy (window depth, 1 where
    /// nothing was hit) and kind.npy (0 nothing, 1 surface, 2 wall); rows from the bottom.
    #[arg(long)]
    npy: Option<PathBuf>,
    #[command(flatten)]
    output: Output,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum MethodArg {
    /// Top-down traversal of the max pyramid, exact bilinear patches.
    Pyramid,
    /// Relief mapping: linear, then binary search.
    Relief,
}

#[derive(clap::Args, Debug)]
pub struct LightArgs {
    /// VPLs per side of the VPL image (a power of two).
    #[arg(long, default_value_t = 64, value_parser = VPLS.of::<u32>())]
    vpls: u32,
    /// Image side, pixels.
    #[arg(long, default_value_t = 256, value_parser = IMAGE_SIDE.of::<u32>())]
    size: u32,
    /// Criterion: a cluster is one light when its radius < theta x its distance (0: every VPL).
    #[arg(long, default_value_t = 0.5, value_parser = THETA.of::<f32>())]
    theta: f32,
    /// Show only the indirect light in --png (--mode indirect).
    #[arg(long)]
    indirect_only: bool,
    /// What the hierarchy is used for.
    #[arg(long, value_enum, default_value_t = LightMode::Indirect)]
    mode: LightMode,
    /// A Wavefront OBJ model: in the room in place of its block (indirect), alone otherwise
    /// [default: the room's block; the shipped bunny for sss and environment].
    #[arg(long, value_name = "MODEL.obj")]
    scene: Option<PathBuf>,
    /// Exposure of --png in stops (the picture times 2^E); the numbers never change.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = EXPOSURE.of::<f32>())]
    exposure: f32,
    /// Normal-aware clustering (--mode indirect): a cluster is one light only when its mean
    /// unit normal is at least this long (0..1; 0: the fixed merge, 0.9: cones of ~26 degrees).
    #[arg(long, default_value_t = 0.0, value_parser = COHERENCE.of::<f32>())]
    min_coherence: f32,
    /// Write the gathered irradiance (height x width x 3, RGB, rows from the bottom, as the
    /// GPU read it back; radiant exitance for sss) to DIR/irradiance.npy (DIR is created).
    #[arg(long)]
    npy: Option<PathBuf>,
    #[command(flatten)]
    output: Output,
}

#[derive(clap::Args, Debug)]
pub struct FunctionArgs {
    #[arg(long, value_enum, default_value_t = FunctionArg::Sigmoid)]
    function: FunctionArg,
    /// Texels of the lookup table.
    #[arg(long, default_value_t = 256, value_parser = TEXELS.of::<u32>())]
    texels: u32,
    /// Values per pixel of the timed passes (a power of two).
    #[arg(long, default_value_t = 64, value_parser = PER_PIXEL.of::<u32>())]
    per_pixel: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum FunctionArg {
    /// Paper 3's 1 / (1 + e^-x) on [-8, 8].
    Sigmoid,
    /// A square wave from 16 odd harmonics on [0, 1].
    SquareWave,
}

#[derive(clap::Args, Debug)]
pub struct RandomArgs {
    /// Generators per side of the texture.
    #[arg(long, default_value_t = 256, value_parser = GENERATORS.of::<u32>())]
    size: u32,
    /// Steps (one pass each).
    #[arg(long, default_value_t = 16, value_parser = RANDOM_STEPS.of::<usize>())]
    steps: usize,
    #[arg(long, default_value_t = 2007, value_parser = ranges::SEED.of::<u64>())]
    seed: u64,
    /// Write the GPU's numbers, as read back, to this .npy file (steps x size x size, float32,
    /// rows from the bottom).
    #[arg(long)]
    npy: Option<PathBuf>,
    #[command(flatten)]
    output: Output,
}

#[derive(clap::Args, Debug)]
pub struct DepthMaskArgs {
    /// Which pixels are active.
    #[arg(long, value_enum, default_value_t = MaskArg::Scattered)]
    mask: MaskArg,
    /// Share of active pixels, 0 to 1.
    #[arg(long, default_value_t = 0.25, value_parser = FRACTION.of::<f32>())]
    fraction: f32,
    /// Sines per active pixel (the expensive work).
    #[arg(long, default_value_t = 256, value_parser = ITERATIONS.of::<u32>())]
    iterations: u32,
    /// Image side, pixels (a power of two).
    #[arg(long, default_value_t = 256, value_parser = IMAGE_SIDE.of::<u32>())]
    size: u32,
    #[command(flatten)]
    output: Output,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum MaskArg {
    Blobs,
    Scattered,
}

#[derive(clap::Args, Debug)]
pub struct HistogramArgs {
    /// Count the grey levels (0..1) of this PNG [default: random skewed values].
    #[arg(long)]
    image: Option<PathBuf>,
    /// How many random values without --image (with --image, its pixels are the values).
    #[arg(long, default_value_t = 1 << 20, conflicts_with = "image", value_parser = VALUES.of::<usize>())]
    values: usize,
    #[arg(long, default_value_t = 256, value_parser = ranges::TEXTURE_SIDE.of::<u32>())]
    bins: u32,
}

#[derive(clap::Args, Debug)]
pub struct HeightMapArgs {
    /// Samples per side.
    #[arg(long, default_value_t = SHIPPED_SIZE, value_parser = SAMPLES.of::<u32>())]
    size: u32,
    /// Where to write it.
    #[arg(long)]
    out: PathBuf,
    /// Replace --out if it exists.
    #[arg(long)]
    force: bool,
}

/// Runs a `lecture3` subcommand.
pub fn run(cmd: &Lecture3Command, ctx: &Context, json: bool) -> anyhow::Result<()> {
    match cmd {
        Lecture3Command::Pyramid(a) => pyramid(a, ctx, json),
        Lecture3Command::Displace(a) => displace(a, ctx, json),
        Lecture3Command::Light(a) => light(a, ctx, json),
        Lecture3Command::Function(a) => function(a, ctx, json),
        Lecture3Command::Random(a) => random(a, ctx, json),
        Lecture3Command::DepthMask(a) => depth_mask(a, ctx, json),
        Lecture3Command::Histogram(a) => histogram(a, ctx, json),
        Lecture3Command::HeightMap(a) => height_map(a, json),
        Lecture3Command::Octree(a) => octree(a, ctx, json),
    }
}

/// How often the commands repeat a timing (the median is kept): the report's policy.
const RUNS: Runs = Runs::PAPER;

fn print(json: bool, value: serde_json::Value, text: String) -> anyhow::Result<()> {
    if json {
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        println!("{text}");
    }
    Ok(())
}

fn load_map(height: Option<&Path>, ctx: &Context) -> anyhow::Result<(HeightMap, String)> {
    Ok(match height {
        Some(p) => (
            HeightMap::load(p, ctx.info().limits.max_texture_size)?,
            p.display().to_string(),
        ),
        None => (
            HeightMap::generated(SHIPPED_SIZE),
            "the generated map (assets/lecture3/height.png)".into(),
        ),
    })
}

fn check_size(name: &str, size: u32) -> anyhow::Result<()> {
    if !(8..=4096).contains(&size) {
        bail!("{name}: {size} pixels a side; 8 to 4096 are allowed");
    }
    Ok(())
}

/// Memory per pixel of `displace` with its check (the frame's targets read back, the exact
/// tracer's three hits per pixel, the verdicts) and of `octree` (its two casts and their
/// reference), measured as peak resident memory at --size 128 against 512 (431 and 202
/// bytes), rounded up.
const DISPLACE_PIXEL_BYTES: u64 = 512;
const OCTREE_PIXEL_BYTES: u64 = 256;

/// Refuses an image of `size` x `size` pixels of `bytes_each` beyond this machine's memory.
fn check_pixels_memory(size: u32, bytes_each: u64) -> anyhow::Result<()> {
    super::limits::check_memory(
        &format!("--size {size}"),
        size as u64 * size as u64,
        bytes_each,
        "pixels",
        "use a smaller --size",
    )
}

/// The files of `pyramid --npy DIR` for a pyramid of `levels` levels: each kind of
/// [`PYRAMID_KINDS`] (the pyramids [`gpu_pyramids`] draws, in its order), each level.
fn pyramid_npy_files(dir: &Path, levels: u32) -> Vec<PathBuf> {
    use classic_gpgpu::lecture3::pyramid::Extreme;
    PYRAMID_KINDS
        .iter()
        .map(|kind| match kind {
            Extreme::Max => "max",
            Extreme::Min => "min",
            Extreme::Mean => "mean",
        })
        .flat_map(|kind| (0..levels).map(move |l| dir.join(format!("{kind}_{l}.npy"))))
        .collect()
}

fn pyramid(a: &PyramidArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    use classic_gpgpu::lecture3::pyramid::level_count;
    let inputs: Vec<&Path> = a.height.iter().map(|p| p.as_path()).collect();
    a.output.check(&inputs)?;
    // The folder rule of every writer: a folder of the user's refused without --force, and
    // even with it no file of theirs replaced.
    let npy_folder = folder("--npy", "lecture3 pyramid --npy", &a.npy, a.output.force)?;
    let (map, name) = load_map(a.height.as_deref(), ctx)?;
    let npy_files = npy_folder
        .as_ref()
        .map(|f| pyramid_npy_files(f.path(), level_count(map.width(), map.height())));
    let row = bench::pyramid_row(ctx, &map, RUNS)?;
    let mut written: Vec<PathBuf> = Vec::new();
    if a.output.png.is_some() || npy_files.is_some() {
        // The levels the GPU drew, read back: what is shown is what was computed.
        let pyramids = gpu_pyramids(ctx, &map)?;
        if let Some(png) = &a.output.png {
            pyramid_png(&pyramids, (map.width(), map.height()), png)?;
            written.push(png.clone());
        }
        let levels = pyramids.iter().flatten();
        for (path, level) in npy_files.iter().flatten().zip(levels) {
            let shape = [level.height as usize, level.width as usize];
            files::write_npy(path, &shape, &level.values)?;
            written.push(path.clone());
        }
    }
    if !row.equal_to_cpu {
        bail!("the GPU pyramid differs from the CPU pyramid (a bug: max and min are exact)");
    }
    let written = finish_npy(npy_folder, written)?;
    let renderer = ctx.info().renderer_line();
    print(
        json,
        json!({ "renderer": renderer, "gpu_timing": bench::gpu_timing(ctx), "map": name, "width": map.width(), "height": map.height(),
                "pyramid": row, "png": a.output.png, "written": written }),
        format!(
            "{name}: {}x{}, {} levels; GPU max and min pyramids equal to the CPU's bit for bit\n\
             mean pyramid within {:.1e} of the CPU's f64 means\n\
             level passes {:.3} ms (GPU), CPU pyramid {:.3} ms: CPU / GPU {:.2} \
             (renderer: {renderer})",
            map.width(),
            map.height(),
            row.levels,
            row.mean_max_error,
            row.gpu_ms,
            row.cpu_ms,
            row.cpu_ms / row.gpu_ms
        ) + &wrote_lines(&written),
    )
}

fn displace(a: &DisplaceArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let inputs: Vec<&Path> = a.height.iter().map(|p| p.as_path()).collect();
    a.output.check(&inputs)?;
    check_size("--size", a.size)?;
    check_pixels_memory(a.size, DISPLACE_PIXEL_BYTES)?;
    check_range("--azimuth", a.azimuth as f64, -3600.0, 3600.0)?;
    check_range("--elevation", a.elevation as f64, 0.1, 89.5)?;
    // The box (at most 2 x 2 x 2) stays inside the far plane: beyond it no fragment traces.
    let far_limit = (FAR - 5.0) as f64;
    if a.distance as f64 > far_limit {
        bail!(
            "--distance {}: at most {far_limit}, as the projection's far plane is at {FAR} and \
             the box must lie in front of it",
            a.distance
        );
    }
    check_range("--distance", a.distance as f64, 0.5, far_limit)?;
    if a.prefilter && a.method != MethodArg::Pyramid {
        bail!("--prefilter: the prefilter is part of the pyramid traversal (--method pyramid)");
    }
    if !(1..=360).contains(&a.frames) {
        bail!("--frames: {} frames; 1 to 360 are allowed", a.frames);
    }
    if a.frames > 1 && a.output.png.is_some() {
        bail!(
            "--png takes one frame; write --frames {} with --out DIR",
            a.frames
        );
    }
    if a.method != MethodArg::Relief && (a.linear_steps.is_some() || a.binary_steps.is_some()) {
        bail!(
            "--linear-steps and --binary-steps are relief mapping's search; the pyramid method \
             traverses the max pyramid and takes no steps to set: add --method relief, or leave \
             them out"
        );
    }
    let (linear_steps, binary_steps) = (a.linear_steps.unwrap_or(32), a.binary_steps.unwrap_or(8));
    if linear_steps == 0 || linear_steps > 4096 || binary_steps > 64 {
        bail!("--linear-steps must be 1 to 4096 and --binary-steps at most 64");
    }
    if a.out.is_some() && a.out == a.npy {
        bail!(
            "--out and --npy name one folder ({}); give each its own",
            a.npy.as_deref().unwrap_or(Path::new("")).display()
        );
    }
    let frames_folder = folder("--out", "lecture3 displace --out", &a.out, a.output.force)?;
    let npy_folder = folder("--npy", "lecture3 displace --npy", &a.npy, a.output.force)?;
    let npy_files = |dir: &Path| DISPLACE_NPY.map(|f| dir.join(f));
    let (map, name) = load_map(a.height.as_deref(), ctx)?;
    let renderer = DisplacementRenderer::new(ctx, Surface::new(map, a.depth)?)?;
    let method = match a.method {
        MethodArg::Pyramid if a.prefilter => Method::Prefiltered,
        MethodArg::Pyramid => Method::Pyramid,
        MethodArg::Relief => Method::Relief {
            linear_steps,
            binary_steps,
        },
    };
    let target = renderer.target(a.size, a.size)?;
    let camera = |k: u32| {
        Camera::orbit(
            renderer.surface().centre(),
            a.distance,
            a.azimuth + 360.0 * k as f32 / a.frames as f32,
            a.elevation,
            a.size,
            a.size,
        )
    };
    let first = camera(0);
    let gpu_ms = bench::gpu_ms(ctx, RUNS, || Ok(renderer.render(&target, &first, method)?))?.median;
    let frame = renderer.read(&target)?;
    frame.check_finished()?;
    let mut written = Vec::new();
    if let Some(folder) = npy_folder {
        let (w, h) = (a.size as usize, a.size as usize);
        let [hit, depth, kind] = npy_files(folder.path());
        files::write_npy(&hit, &[h, w, 4], frame.hits())?;
        files::write_npy(&depth, &[h, w], &frame.depth)?;
        files::write_npy(&kind, &[h, w], &frame.kinds())?;
        written.extend([hit, depth, kind].map(|p| folder.shown(&p)));
        folder.finish()?;
    }
    let check = if a.no_check {
        None
    } else {
        let cpu_ms = bench::wall_once_ms(|| exact::trace_image(renderer.surface(), &first, 0.0));
        let reference = if a.prefilter {
            ReferenceImage::trace_prefiltered(renderer.surface(), &first)
        } else {
            ReferenceImage::trace(renderer.surface(), &first)
        };
        let (comparison, _) = reference.judge(&frame);
        Some((cpu_ms, comparison))
    };
    let quality = if a.prefilter {
        Some(bench::prefilter_quality(&renderer, &first, &frame)?)
    } else {
        None
    };
    for k in 0..a.frames {
        renderer.render(&target, &camera(k), method)?;
        renderer.read(&target)?.check_finished()?;
        let path = match (&frames_folder, &a.output.png) {
            (Some(folder), _) => folder.path().join(format!("frame_{k:03}.png")),
            (None, Some(png)) => png.clone(),
            (None, None) => continue,
        };
        texture_png(renderer.colour_texture(&target), &path, DumpRange::Auto)?;
        written.push(
            frames_folder
                .as_ref()
                .map_or(path.clone(), |f| f.shown(&path)),
        );
    }
    if let Some(folder) = frames_folder {
        folder.finish()?;
    }
    let hits = frame
        .pixels()
        .iter()
        .filter(|p| matches!(p, classic_gpgpu::lecture3::displacement::Pixel::Hit { .. }))
        .count();
    let renderer_line = ctx.info().renderer_line();
    let mut text = format!(
        "{name}, {}: {}x{} pixels, {hits} hit the surface; first frame {:.2} ms of GPU time \
         (renderer: {renderer_line})",
        method.name(),
        a.size,
        a.size,
        gpu_ms
    );
    if let Some((cpu_ms, c)) = &check {
        text.push_str(&format!(
            "\nexact CPU tracer {cpu_ms:.1} ms (CPU / GPU {:.1}); of {} compared pixels: {} on \
             the wrong surface, {} outside the tolerance, {} drawn as wall for surface or the \
             reverse, {} with a wrong normal, {} with a wrong colour, {} ill-conditioned",
            cpu_ms / gpu_ms,
            c.compared,
            c.wrong_surface,
            c.outside_tolerance,
            c.wrong_kind,
            c.wrong_normal,
            c.wrong_colour,
            c.ambiguous
        ));
    }
    if let Some(q) = &quality {
        text.push_str(&format!(
            "\nagainst {0}x{0} unfiltered rays per pixel (RMS, RGB in 0..1): prefiltered {1:.4}, \
             unfiltered {2:.4}; steps per hit pixel {3:.1} against {4:.1}",
            q.samples,
            q.prefiltered_error,
            q.unfiltered_error,
            q.prefiltered_steps,
            q.unfiltered_steps
        ));
    }
    for p in &written {
        text.push_str(&format!("\nwrote {}", p.display()));
    }
    // The pyramid traversal is exact (relief mapping's misses are its known artifact): a pixel
    // where it disagrees with its own exact tracer is an error, not a result.
    let disagree = check.as_ref().map_or(0, |(_, c)| {
        c.wrong_surface
            + c.outside_tolerance
            + c.wrong_kind
            + c.wrong_normal
            + c.wrong_colour
            + c.unfinished
    });
    let exact_method = matches!(method, Method::Pyramid);
    print(
        json,
        json!({
            "renderer": renderer_line, "gpu_timing": bench::gpu_timing(ctx), "map": name, "method": method, "size": a.size,
            "distance": a.distance, "prefilter_quality": quality,
            "hit_pixels": hits, "gpu_ms": gpu_ms,
            "cpu_exact_ms": check.as_ref().map(|c| c.0),
            "cpu_over_gpu": check.as_ref().map(|c| c.0 / gpu_ms),
            "comparison": check.as_ref().map(|c| c.1), "written": written,
        }),
        text,
    )?;
    if exact_method && disagree > 0 {
        bail!(
            "{disagree} pixels of the pyramid method disagree with its exact CPU tracer (see \
             above): a bug, or a view outside the method's range"
        );
    }
    Ok(())
}

fn light(a: &LightArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let inputs: Vec<&Path> = a.scene.iter().map(PathBuf::as_path).collect();
    a.output.check(&inputs)?;
    check_size("--size", a.size)?;
    // The criterion and the exposure are checked before anything runs.
    Gather::normal_aware(a.theta, a.min_coherence)?;
    lecture3_light::check_exposure(a.exposure)?;
    let npy_folder = folder("--npy", "lecture3 light --npy", &a.npy, a.output.force)?;
    let irradiance_npy = npy_folder.as_ref().map(|f| f.path().join("irradiance.npy"));
    if a.mode != LightMode::Indirect {
        if a.indirect_only || a.min_coherence != 0.0 {
            bail!("--indirect-only and --min-coherence are for --mode indirect");
        }
        let bar = progress(
            json,
            "lecture 3 light: samples, clusters, gathers (GPU and CPU)",
        );
        let (value, text, written) = lecture3_light::run_use(
            &lecture3_light::UseArgs {
                mode: a.mode,
                model: a.scene.as_deref(),
                lights: a.vpls,
                size: a.size,
                theta: a.theta,
                exposure: a.exposure,
                npy: irradiance_npy,
                png: a.output.png.as_deref(),
            },
            ctx,
        )?;
        let written = finish_npy(npy_folder, written)?;
        bar.finish_and_clear();
        let renderer = ctx.info().renderer_line();
        return print(
            json,
            json!({ "renderer": renderer, "light": value, "png": a.output.png, "written": written }),
            format!("{text}\n(renderer: {renderer})") + &wrote_lines(&written),
        );
    }
    let scene = lecture3_light::scene(&LightUse::Indirect, a.scene.as_deref())?;
    let bar = progress(
        json,
        "lecture 3 light: VPLs, clusters, gathers (tree and brute force)",
    );
    let (run, lighting, ()) = bench::light_run_in(
        ctx,
        scene,
        a.vpls,
        (a.size, a.size),
        &[a.theta],
        RUNS,
        |_| Ok(()),
    )?;
    // Normal-aware clustering beside the fixed merge; leaves its gather in the target.
    let clustering = if a.min_coherence > 0.0 {
        compare_clustering(&lighting, &[a.theta], a.min_coherence)?.pop()
    } else {
        None
    };
    bar.finish_and_clear();
    let mut written = Vec::new();
    if let Some(path) = &irradiance_npy {
        // `light_run` (or the clustering comparison) left the gather of `a.theta` in the target.
        let rgb: Vec<f32> = lighting
            .gathers
            .read()?
            .iter()
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        files::write_npy(path, &[a.size as usize, a.size as usize, 3], &rgb)?;
        written.push(path.clone());
    }
    let mut written = finish_npy(npy_folder, written)?;
    if let Some(png) = &a.output.png {
        // `light_run` left the gather of `a.theta` in the target.
        let terms = if a.indirect_only {
            Terms::Indirect
        } else {
            Terms::Both
        };
        lighting.shade(
            terms,
            lecture3_light::exposure(&LightUse::Indirect, a.exposure),
        )?;
        texture_png(lighting.shade.target.color(0), png, DumpRange::Auto)?;
        written.push(png.clone());
    }
    let row = &run.rows[0];
    let renderer = ctx.info().renderer_line();
    print(
        json,
        json!({ "renderer": renderer, "gpu_timing": bench::gpu_timing(ctx), "light": run, "clustering": clustering, "png": a.output.png, "written": written }),
        format!(
            "{} VPLs, {} receivers; theta {}: {:.1} nodes per receiver, relative RMS error \
             {:.2e} against the brute force\nGPU: tree {:.2} ms, brute force {:.2} ms; CPU \
             brute force (f64, on {} cores) {:.1} ms: CPU / tree {:.1}, CPU / GPU brute force \
             {:.1} (renderer: {renderer})",
            run.vpls,
            run.receivers,
            row.theta,
            row.mean_nodes,
            row.relative_rms_error,
            row.gpu_ms,
            run.brute_gpu_ms,
            run.brute_cpu_threads,
            run.brute_cpu_ms,
            run.brute_cpu_ms / row.gpu_ms,
            run.brute_cpu_ms / run.brute_gpu_ms
        ) + &clustering.map_or(String::new(), |c| {
            format!(
                "\nnormal-aware clustering (mean normal at least {} long): relative RMS error \
                 {:.2e} against {:.2e} for the fixed merge, {:.1} lights summed per receiver \
                 against {:.1}",
                c.min_coherence,
                c.normal_aware_error,
                c.fixed_error,
                c.normal_aware_lights,
                c.fixed_lights
            )
        }) + &wrote_lines(&written),
    )
}

/// The files of `.npy` output of `displace --npy DIR`.
const DISPLACE_NPY: [&str; 3] = ["hit.npy", "depth.npy", "kind.npy"];

/// One "wrote PATH" line per file, each after a line break.
/// The folder of a `DIR` option (`--out`, `--npy`), by the rule of every folder writer
/// ([`Staged`]): checked before any work, written in full or not at all.
fn folder(
    what: &str,
    command: &str,
    dir: &Option<PathBuf>,
    force: bool,
) -> anyhow::Result<Option<Staged>> {
    dir.as_deref()
        .map(|d| Staged::begin(what, command, d, force))
        .transpose()
}

/// Puts the `--npy` folder's files in place; `written` then names them where they are.
fn finish_npy(folder: Option<Staged>, written: Vec<PathBuf>) -> anyhow::Result<Vec<PathBuf>> {
    let Some(folder) = folder else {
        return Ok(written);
    };
    let written = written.iter().map(|p| folder.shown(p)).collect();
    folder.finish()?;
    Ok(written)
}

fn wrote_lines(written: &[PathBuf]) -> String {
    written
        .iter()
        .map(|p| format!("\nwrote {}", p.display()))
        .collect()
}

/// A spinner on stderr while a long step runs; hidden under --json (and off a terminal).
fn progress(json: bool, message: &str) -> indicatif::ProgressBar {
    let bar = classic_gpgpu::report::progress_bars(json).add(indicatif::ProgressBar::new_spinner());
    bar.set_message(message.to_string());
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}

fn function(a: &FunctionArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let f = match a.function {
        FunctionArg::Sigmoid => Function::Sigmoid,
        FunctionArg::SquareWave => Function::SquareWave,
    };
    let passes = FunctionPasses::new(ctx, 256, 256)?;
    let error = bench::function_error_row(ctx, &passes, f, a.texels)?;
    let speed = bench::function_speed_row(ctx, &passes, f, a.texels, a.per_pixel, RUNS)?;
    let renderer = ctx.info().renderer_line();
    print(
        json,
        json!({ "renderer": renderer, "gpu_timing": bench::gpu_timing(ctx), "error": error, "speed": speed }),
        format!(
            "{} in {} texels: max error {:.2e} (bound {:.2e}), RMS {:.2e}, filter error {:.2e}\n\
             {} values: computed {:.2} ms, looked up {:.2} ms (computed / looked up {:.2}); \
             CPU {:.1} ms (CPU / lookup {:.1}) (renderer: {renderer})",
            f.name(),
            a.texels,
            error.max_error,
            error.bound,
            error.rms_error,
            error.filter_error,
            speed.evaluations,
            speed.exact_ms,
            speed.lookup_ms,
            speed.exact_ms / speed.lookup_ms,
            speed.cpu_ms,
            speed.cpu_ms / speed.lookup_ms
        ),
    )
}

/// Memory per generated number of `random`: each is kept in its generator's stream, in the
/// raw read-back, in the list the chi-square counts and in two lists of pairs (serial and
/// neighbour): 33 bytes, measured as peak resident memory at 256 x 256 x 64 against 512 x 512
/// x 64; with 4 more when written as .npy, rounded up.
const RANDOM_BYTES: u64 = 40;

fn random(a: &RandomArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    a.output.check(&[])?;
    // Two generators a side at least: the neighbour correlation needs a pair in a row.
    if !(2..=4096).contains(&a.size) {
        bail!(
            "--size {}: must be 2 to 4096 generators a side (the neighbour correlation needs two \
             in a row)",
            a.size
        );
    }
    if !(2..=1024).contains(&a.steps) {
        bail!(
            "--steps {}: must be 2 to 1024 (the serial correlation compares a step with the next)",
            a.steps
        );
    }
    super::limits::check_memory(
        &format!("--size {} --steps {}", a.size, a.steps),
        a.size as u64 * a.size as u64 * a.steps as u64,
        RANDOM_BYTES,
        "numbers",
        "use a smaller --size or fewer --steps",
    )?;
    if let Some(npy) = &a.npy {
        files::check_output("--npy", npy, &[], a.output.force, &["npy"])?;
    }
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-random-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let opts = classic_gpgpu::report::BenchOptions {
        gl: ctx,
        quick: false,
        out_dir: dir.clone(),
        progress: classic_gpgpu::report::progress_bars(true),
        runs: None,
    };
    let run = bench::random(&opts, a.size, a.steps, a.seed, RUNS);
    if let (Ok(_), Some(png)) = (&run, &a.output.png) {
        std::fs::read(dir.join(bench::images::RANDOM_PNG))
            .map_err(anyhow::Error::from)
            .and_then(|bytes| classic_gpgpu::files::write_bytes(png, &bytes))
            .with_context(|| format!("writing {}", png.display()))?;
    }
    let _ = std::fs::remove_dir_all(&dir);
    let run = run?;
    if !run.bit_exact {
        bail!("the GPU generators differ from the CPU generator (a bug: integer arithmetic)");
    }
    let mut written: Vec<PathBuf> = a.output.png.iter().cloned().collect();
    if let Some(npy) = &a.npy {
        let side = a.size as usize;
        files::write_npy(npy, &[run.steps, side, side], &run.values)?;
        written.push(npy.clone());
    }
    for value in [
        run.chi_square,
        run.serial_correlation,
        run.neighbour_correlation,
    ] {
        if !value.is_finite() {
            bail!("a statistic of the numbers is not finite ({value}): too few numbers to test");
        }
    }
    let renderer = ctx.info().renderer_line();
    print(
        json,
        json!({ "renderer": renderer, "gpu_timing": bench::gpu_timing(ctx), "random": run, "png": a.output.png }),
        format!(
            "{0}x{0} generators, {1} steps: bit-exact with the CPU; chi-square {2:.1} (0.1% \
             limit {3:.1}), serial r {4:.1e}, neighbour r {5:.1e} (|r| < {6:.1e})\nGPU {7:.3} ms \
             per step, CPU {8:.3} ms: CPU / GPU {9:.2} (renderer: {renderer})",
            run.side,
            run.steps,
            run.chi_square,
            run.chi_square_critical,
            run.serial_correlation,
            run.neighbour_correlation,
            run.correlation_bound,
            run.gpu_ms_per_step,
            run.cpu_ms_per_step,
            run.cpu_ms_per_step / run.gpu_ms_per_step
        ) + &wrote_lines(&written),
    )
}

fn depth_mask(a: &DepthMaskArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    a.output.check(&[])?;
    check_size("--size", a.size)?;
    let shape = match a.mask {
        MaskArg::Blobs => MaskShape::Blobs,
        MaskArg::Scattered => MaskShape::Scattered,
    };
    let mask = depth_mask::mask(shape, a.size, a.size, 1);
    let passes = DepthMask::new(ctx, &mask, a.size, a.size)?;
    let row = bench::depth_mask_row(
        ctx,
        &passes,
        &mask,
        shape,
        a.size,
        a.fraction,
        a.iterations,
        None,
        RUNS,
    )?;
    if row.masked_fragments != row.active {
        bail!(
            "the occlusion query counted {} fragments for {} active pixels",
            row.masked_fragments,
            row.active
        );
    }
    if let Some(png) = &a.output.png {
        // `depth_mask_row` left the depth-masked picture in the target.
        texture_png(passes.target.color(0), png, DumpRange::Auto)?;
    }
    let renderer = ctx.info().renderer_line();
    print(
        json,
        json!({ "renderer": renderer, "gpu_timing": bench::gpu_timing(ctx), "depth_mask": row, "png": a.output.png }),
        format!(
            "{} active of {} pixels; {} fragments passed the depth test behind the mask, {} \
             when branching\nruns of the expensive shader behind the mask: {}\nbranching {:.2} \
             ms, depth-masked {:.2} ms: branching / masked {:.2}; max |GPU - CPU| {:.1e} \
             (renderer: {renderer})",
            row.active,
            a.size * a.size,
            row.masked_fragments,
            row.branching_fragments,
            match (row.masked_runs, row.unmasked_runs) {
                (Some(masked), Some(all)) =>
                    format!(
                        "{masked} for {} active pixels in {} 2x2 quads ({} without the mask), \
                     counted by {}",
                        row.active,
                        row.active_quads,
                        all,
                        row.counted_by.describe()
                    ) + &row.masked_invocations.map_or(String::new(), |n| {
                        format!("; pipeline statistics: {n} invocations of the plain shader")
                    }),
                _ => row.counted_by.describe(),
            },
            row.branching_ms,
            row.masked_ms,
            row.branching_ms / row.masked_ms,
            row.max_error
        ),
    )
}

fn histogram(a: &HistogramArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let values = match &a.image {
        Some(path) => load_grey(path, u32::MAX, "image")?.2,
        None => {
            if !(1..=blend_histogram::MAX_VALUES).contains(&a.values) {
                bail!(
                    "--values: {} values; 1 to 2^24 can be counted exactly",
                    a.values
                );
            }
            bench::skewed_values(a.values, 3)
        }
    };
    // Grey levels run from 0 to 1 inclusive: bins over [0, 1 + 1 / bins), so that white
    // falls in the last bin (with 256 bins, grey level k in bin k).
    let hi = if a.image.is_some() {
        1.0 + 1.0 / a.bins as f32
    } else {
        1.0
    };
    let bins = Bins::new(0.0, hi, a.bins, ctx.info().limits.max_texture_size)?;
    let with_gather = values.len() <= blend_histogram::MAX_GATHER_VALUES;
    let row = bench::histogram_row(ctx, &values, bins, with_gather, RUNS)?;
    if !row.blend_equal || row.gather_equal == Some(false) {
        bail!("the GPU histogram differs from the CPU histogram (a bug: counts are exact)");
    }
    let (_, outside) = blend_histogram::cpu_histogram(&values, None, &bins);
    let renderer = ctx.info().renderer_line();
    print(
        json,
        // The counts the GPU blended, as read back (checked equal to the CPU's above).
        json!({ "renderer": renderer, "gpu_timing": bench::gpu_timing(ctx), "histogram": row, "counts": row.counts,
                "outside": outside }),
        format!(
            "{} values in {} bins over [0, {hi}) ({outside} outside): blended counts equal to \
             the CPU's\nblending {:.3} ms{}, CPU {:.3} ms: CPU / blending {:.2} (renderer: \
             {renderer})",
            row.values,
            row.bins,
            row.blend_ms,
            row.gather_ms
                .map_or(String::new(), |g| format!(", gather pass {g:.2} ms")),
            row.cpu_ms,
            row.cpu_ms / row.blend_ms
        ),
    )
}

fn height_map(a: &HeightMapArgs, json: bool) -> anyhow::Result<()> {
    if !(2..=4096).contains(&a.size) {
        bail!("--size: {} samples a side; 2 to 4096 are allowed", a.size);
    }
    check_output(&a.out, &[], a.force)?;
    HeightMap::generated(a.size).save_png(&a.out)?;
    print(
        json,
        json!({ "size": a.size, "written": a.out }),
        format!("wrote {} ({}x{} samples)", a.out.display(), a.size, a.size),
    )
}

/// The files of `octree --npy DIR`.
const OCTREE_NPY: [&str; 2] = ["hit.npy", "steps.npy"];

fn octree(a: &OctreeArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    use classic_gpgpu::lecture3::octree::{cast, grid, levels, reference, OctreeCaster, Search};
    let inputs: Vec<&Path> = a.model.iter().map(|p| p.as_path()).collect();
    a.output.check(&inputs)?;
    check_size("--size", a.size)?;
    check_pixels_memory(a.size, OCTREE_PIXEL_BYTES)?;
    check_range("--distance", a.distance as f64, 0.1, 1000.0)?;
    check_range("--elevation", a.elevation as f64, -89.5, 89.5)?;
    check_range("--azimuth", a.azimuth as f64, -3600.0, 3600.0)?;
    if !(1..=10_000_000).contains(&a.points) {
        bail!("--points: {}; 1 to 10000000 are allowed", a.points);
    }
    let npy_files = |dir: &Path| OCTREE_NPY.map(|f| dir.join(f));
    let npy_folder = folder("--npy", "lecture3 octree --npy", &a.npy, a.output.force)?;
    let (points, source) = match &a.model {
        Some(path) => {
            let mesh = classic_gpgpu::mesh::obj::load_obj(path)
                .with_context(|| format!("{}: cannot load the model", path.display()))?;
            (
                grid::mesh_points(&mesh, a.points, 1)?,
                format!("{} points on {}", a.points, path.display()),
            )
        }
        None => (
            grid::shape_points(a.points, 1),
            format!(
                "{} random points on a sphere, a torus and a cluster",
                a.points
            ),
        ),
    };
    let voxels = grid::VoxelGrid::from_points(a.resolution, &points)?;
    let caster = OctreeCaster::new(ctx, &voxels)?;
    let gpu_levels = caster.levels.read()?;
    let cpu_levels = levels::cpu_levels(&voxels);
    if gpu_levels != cpu_levels {
        bail!("the GPU octree levels differ from the CPU's (a bug: a max of 0/1 is exact)");
    }
    let camera = Camera::orbit(
        cast::centre(),
        a.distance,
        a.azimuth,
        a.elevation,
        a.size,
        a.size,
    );
    let target = caster.target(a.size, a.size)?;
    let reference = reference::CastReference::trace(&cpu_levels, &camera);
    let mut results = Vec::new();
    let mut octree_frame = None;
    for search in [Search::Octree, Search::Flat] {
        caster.cast(&target, &camera, search)?;
        let frame = caster.read(&target)?;
        frame.check_finished()?;
        let comparison = reference.judge(&frame);
        let steps = frame.steps().iter().map(|&s| s as f64).sum::<f64>() / (a.size * a.size) as f64;
        let ms = if a.bench {
            Some(bench::gpu_ms(ctx, RUNS, || Ok(caster.cast(&target, &camera, search)?))?.median)
        } else {
            None
        };
        results.push(
            json!({ "search": search, "steps_per_pixel": steps, "gpu_ms": ms,
                             "comparison": comparison }),
        );
        if search == Search::Octree {
            octree_frame = Some(frame);
        }
    }
    let frame = octree_frame.expect("the octree cast ran");
    let mut written = Vec::new();
    if let Some(folder) = npy_folder {
        let (w, h) = (a.size as usize, a.size as usize);
        let [hit, steps] = npy_files(folder.path());
        files::write_npy(&hit, &[h, w, 4], frame.hits())?;
        files::write_npy(&steps, &[h, w], &frame.steps())?;
        written.extend([hit, steps].map(|p| folder.shown(&p)));
        folder.finish()?;
    }
    if let Some(png) = &a.output.png {
        // The octree cast's distance to the hit as grey (near bright), rows from the top.
        let distances = frame.distances();
        let far = distances
            .iter()
            .cloned()
            .fold(0.0f32, f32::max)
            .max(f32::MIN_POSITIVE);
        let rgba: Vec<u8> = distances
            .chunks_exact(a.size as usize)
            .rev()
            .flatten()
            .flat_map(|&t| {
                let g = if t > 0.0 {
                    (255.0 * (1.2f32 - t / far).clamp(0.2, 1.0)) as u8
                } else {
                    0
                };
                [g, g, g, 255]
            })
            .collect();
        files::write_png(png, &rgba, a.size, a.size)?;
        written.push(png.clone());
    }
    let renderer_line = ctx.info().renderer_line();
    let wrong: usize = results
        .iter()
        .map(|r| {
            let c = &r["comparison"];
            ["wrong_voxel", "wrong_t", "unfinished", "cpu_octree_vs_flat"]
                .iter()
                .map(|k| c[k].as_u64().unwrap_or(0) as usize)
                .sum::<usize>()
        })
        .sum();
    let mut text = format!(
        "{source}: {}^3 voxels, {} occupied, {} levels (GPU levels equal to the CPU's)\n\
         {}x{} rays: octree {:.1} steps per pixel, flat {:.1}; against the CPU: {} pixels \
         differ, {} ill-conditioned (renderer: {renderer_line})",
        a.resolution,
        voxels.count(),
        cpu_levels.len(),
        a.size,
        a.size,
        results[0]["steps_per_pixel"].as_f64().unwrap_or(0.0),
        results[1]["steps_per_pixel"].as_f64().unwrap_or(0.0),
        wrong,
        results[0]["comparison"]["ambiguous"].as_u64().unwrap_or(0),
    );
    if let (Some(o), Some(f)) = (results[0]["gpu_ms"].as_f64(), results[1]["gpu_ms"].as_f64()) {
        text.push_str(&format!(
            "\nGPU time ({}): octree {o:.3} ms, flat {f:.3} ms, flat / octree {:.2}",
            bench::gpu_timing(ctx),
            f / o
        ));
    }
    text.push_str(&wrote_lines(&written));
    print(
        json,
        json!({
            "renderer": renderer_line, "gpu_timing": bench::gpu_timing(ctx), "source": source,
            "resolution": a.resolution, "occupied": voxels.count(), "levels": cpu_levels.len(),
            "size": a.size, "searches": results, "written": written,
        }),
        text,
    )?;
    if wrong > 0 {
        bail!("{wrong} pixels of the GPU casts differ from the CPU's (see above)");
    }
    Ok(())
}
