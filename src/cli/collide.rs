//! The commands `collide` (two static meshes) and `collide-scene` (a deforming scene of
//! Table III, frame by frame). `collide-bench` is `report::paper1`'s section, run through
//! `report::bench_command`.

use anyhow::{bail, Context as _};
use clap::builder::TypedValueParser as _;
use classic_gpgpu::collide::compute_pipeline::ComputeCollider;
use classic_gpgpu::collide::pipeline::{FrameResult, Options, StreamingCollider};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::collide::scenes::Scene;
use classic_gpgpu::collide::snapshot::{dump_buffers, frame_png};
use classic_gpgpu::collide::stream_setup::auto_leaf_size_for_pair;
use classic_gpgpu::collide::tri_test::{Predicate, MOLLER_SAFE_SCALES};
use classic_gpgpu::gl::Context;
use classic_gpgpu::mesh::Mesh;
use classic_gpgpu::report::paper1::TRIANGLE_BYTES;
use classic_gpgpu::values::ranges;
use indicatif::ProgressBar;
use serde_json::json;
use std::path::{Path, PathBuf};

/// Options shared by both commands.
#[derive(clap::Args, Debug, Clone)]
pub struct PipelineArgs {
    /// Most triangles per leaf AABB (`n`); default: 32, doubled until a model's stream has
    /// at most 512 slots on a software renderer (4096 on a GPU).
    #[arg(long, value_parser = ranges::LEAF_SIZE.of::<usize>())]
    pub leaf_size: Option<usize>,
    /// Stream reduction scheme; `auto` calibrates all three on this renderer and picks by eta,
    /// `paper-switch` is the paper's: hierarchical below eta = 0.095%, reduced from it
    /// [default: auto].
    #[arg(long, value_parser = readback_parser())]
    pub readback: Option<ReadbackMode>,
    /// How triangle pairs are decided: `exact` orientation predicates (the default: every
    /// pair brute force with exact arithmetic finds, at any scale), or `moller`, the paper's
    /// floating-point test (Möller 1997), which can miss or invent contacts where triangles
    /// only touch and far from unit scale.
    #[arg(long, default_value_t = Predicate::Exact, value_parser = predicate_parser())]
    pub predicate: Predicate,
    /// Largest tile side (slots); default 4096 (the paper's GPU limit), at most the
    /// renderer's maximum texture size.
    #[arg(long, value_parser = ranges::TEXTURE_SIDE.of::<usize>())]
    pub max_tile: Option<usize>,
    /// The paper's pipeline (classic) or compute passes with an atomic-counter pair list
    /// (compute, OpenGL 4.3; --readback and --max-tile do not apply).
    #[arg(long, value_enum, default_value_t)]
    pub formulation: super::Formulation,
    #[command(flatten)]
    pub period: super::period::PeriodArg,
}

/// `--predicate`: the names of [`Predicate`], listed in `--help`, parsed by its `FromStr`.
fn predicate_parser() -> impl clap::builder::TypedValueParser<Value = Predicate> {
    clap::builder::PossibleValuesParser::new(Predicate::ALL.map(Predicate::name))
        .try_map(|name| name.parse::<Predicate>())
}

/// `--readback`: the names of [`ReadbackMode`], listed in `--help`, parsed by its `FromStr`.
fn readback_parser() -> impl clap::builder::TypedValueParser<Value = ReadbackMode> {
    clap::builder::PossibleValuesParser::new(ReadbackMode::ALL.map(ReadbackMode::name))
        .try_map(|name| name.parse::<ReadbackMode>())
}

impl PipelineArgs {
    /// The pipeline options for models `x` and `y` on `ctx`'s renderer.
    pub fn options(&self, ctx: &Context, x: &Mesh, y: &Mesh) -> anyhow::Result<Options> {
        if self.formulation == super::Formulation::Compute {
            let classic_only = [
                self.readback.map(|r| format!("--readback {}", r.name())),
                self.max_tile.map(|t| format!("--max-tile {t}")),
            ];
            if let Some(option) = classic_only.into_iter().flatten().next() {
                bail!(
                    "{option}: the compute formulation has no stream textures to read back or \
                     tile (its pairs come from an atomic-counter list); drop it, or use \
                     --formulation classic"
                );
            }
        }
        if self.predicate == Predicate::Moller {
            if let Some(warning) = moller_scale_warning(x, y) {
                eprintln!("warning: {warning}");
            }
        }
        let leaf_size = match self.leaf_size {
            Some(n) => n,
            None => auto_leaf_size_for_pair(x, y, ctx.info().is_software())?,
        };
        Ok(Options {
            leaf_size,
            readback: self.readback.unwrap_or(ReadbackMode::Auto),
            predicate: self.predicate,
            max_tile: self.max_tile,
        })
    }
}

/// Möller's floating-point test multiplies plane distances together: outside the scales
/// where it was measured to agree with the exact predicate on every pair
/// ([`MOLLER_SAFE_SCALES`], measured by `tests/moller_scale.rs`), those products overflow or
/// underflow and it invents and misses pairs. Said when the models' largest coordinate lies
/// outside that band.
fn moller_scale_warning(x: &Mesh, y: &Mesh) -> Option<String> {
    let largest = x
        .positions
        .iter()
        .chain(&y.positions)
        .map(|p| p.abs().max_element())
        .fold(0.0f32, f32::max);
    let [low, high] = MOLLER_SAFE_SCALES;
    (largest > high || largest < low).then(|| {
        format!(
            "--predicate moller: the models' largest coordinate is {largest:.1e}, outside \
             {low:.0e}..{high:.0e}, where the floating-point test was measured to agree with \
             the exact one; beyond it its products overflow or underflow and it invents or \
             misses contacts; --predicate exact decides every pair exactly at any scale"
        )
    })
}

/// Every intersecting triangle pair between two meshes (OBJ files).
#[derive(clap::Args, Debug)]
pub struct CollideArgs {
    /// Model X (OBJ).
    pub a: PathBuf,
    /// Model Y (OBJ).
    pub b: PathBuf,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    /// Write P0..P3, P1' and the AABB textures as PNG into this directory (paper Fig. 6),
    /// and each one's exact float values beside it as .npy (numpy, float32, shape [height,
    /// width, channels]; row 0 is the texture's bottom row, GL's order, so a[y, x] is texel
    /// (x, y) and the PNG's top row is the array's last).
    /// A folder holding files `collide --dump` did not write is refused without --force; a
    /// rerun replaces the files of the earlier dump.
    #[arg(long)]
    pub dump: Option<PathBuf>,
    /// Write the --dump files into a folder that holds other files (they are never removed
    /// or replaced).
    #[arg(long, requires = "dump")]
    pub force: bool,
    #[command(flatten)]
    pub profile: super::profile::ProfileArg,
}

/// `collide`: one frame of the pipeline on two static meshes; `json` prints one object.
pub fn run_collide(args: &CollideArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    args.pipeline.period.apply(ctx, 1);
    let load = |p: &Path| -> anyhow::Result<classic_gpgpu::mesh::Mesh> {
        let mesh = classic_gpgpu::mesh::load_obj(p)
            .with_context(|| format!("reading model {}", p.display()))?;
        classic_gpgpu::collide::stream_setup::validate_mesh(&mesh)
            .with_context(|| format!("model {}", p.display()))?;
        Ok(mesh)
    };
    let dump = match &args.dump {
        Some(dir) if args.pipeline.formulation == super::Formulation::Classic => {
            Some(classic_gpgpu::page::folder::Staged::begin(
                "--dump",
                "collide --dump",
                dir,
                args.force,
            )?)
        }
        _ => None,
    };
    let (x, y) = (load(&args.a)?, load(&args.b)?);
    let options = args.pipeline.options(ctx, &x, &y)?;
    if args.pipeline.formulation == super::Formulation::Compute {
        anyhow::ensure!(
            args.dump.is_none(),
            "--dump writes the classic pipeline's textures; the compute formulation has none"
        );
        return run_collide_compute(ctx, &x, &y, options, json);
    }
    let mut collider =
        StreamingCollider::new(ctx, &x, &y, options).context("setting up the AABB streams")?;
    // The first frame pays for shader compilation (llvmpipe compiles on first draw); the
    // timings reported are those of a second, identical frame.
    collider.frame(&x.positions, &y.positions)?;
    args.profile.start(ctx);
    let frame = collider.frame(&x.positions, &y.positions)?;
    super::profile::print(ctx);
    if let Some(dump) = dump {
        dump_buffers(&collider, dump.path())?;
        frame_png(
            &collider,
            &frame,
            (&x, &y),
            &dump.path().join("snapshot.png"),
        )?;
        dump.finish()?;
    }
    let renderer = ctx.info().renderer_line();
    let report = json!({
        "renderer": renderer,
        "formulation": "classic",
        "triangles": [x.triangles.len(), y.triangles.len()],
        "leaf_size": collider.options.leaf_size,
        "predicate": collider.options.predicate.name(),
        "leaves": [collider.x.stream.leaves.len(), collider.y.stream.leaves.len()],
        "stream_lengths": [collider.x.stream.len(), collider.y.stream.len()],
        "tiles": collider.layout.count(),
        "caps": frame.caps,
        "pctps": frame.pctps,
        "ctps": frame.ctps,
        "eta": frame.eta,
        "readback": {"scheme": frame.scheme, "bytes": frame.readback_bytes, "reads": frame.readback_reads},
        "pairs": frame.pairs.iter().map(|&(a, b)| [a, b]).collect::<Vec<_>>(),
        "timings_ms": timings_json(&frame),
    });
    if json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!("renderer: {renderer}");
        println!(
            "triangles {} x {}, leaves {} x {} (streams of {} x {}), {} tile(s)",
            x.triangles.len(),
            y.triangles.len(),
            collider.x.stream.leaves.len(),
            collider.y.stream.leaves.len(),
            collider.x.stream.len(),
            collider.y.stream.len(),
            collider.layout.count()
        );
        print_frame(&frame);
        // Written through a handle so that a closed pipe (`| head`) is an error, not a panic.
        use std::io::Write as _;
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        for (a, b) in &frame.pairs {
            writeln!(out, "{a} {b}")?;
        }
        out.flush()?;
    }
    Ok(())
}

/// `collide --formulation compute`: the same frame with compute passes.
fn run_collide_compute(
    ctx: &Context,
    x: &Mesh,
    y: &Mesh,
    options: Options,
    json: bool,
) -> anyhow::Result<()> {
    let mut collider = ComputeCollider::new(ctx, x, y, options)?;
    collider.frame(&x.positions, &y.positions)?;
    let frame = collider.frame(&x.positions, &y.positions)?;
    let renderer = ctx.info().renderer_line();
    if json {
        let report = json!({
            "renderer": renderer,
            "formulation": "compute",
            "triangles": [x.triangles.len(), y.triangles.len()],
            "leaf_size": collider.options.leaf_size,
            "leaves": [collider.x.leaves, collider.y.leaves],
            "caps": frame.caps,
            "pctps": frame.pctps,
            "ctps": frame.ctps,
            "eta": frame.eta,
            "readback": {"bytes": frame.readback_bytes, "reads": frame.readback_reads},
            "pairs": frame.pairs.iter().map(|&(a, b)| [a, b]).collect::<Vec<_>>(),
            "timings_ms": timings_json(&frame),
        });
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!("renderer: {renderer} (compute formulation)");
        print_frame(&frame);
        use std::io::Write as _;
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        for (a, b) in &frame.pairs {
            writeln!(out, "{a} {b}")?;
        }
        out.flush()?;
    }
    Ok(())
}

/// Either formulation, frame by frame.
enum AnyCollider {
    Classic(Box<StreamingCollider>),
    Compute(Box<ComputeCollider>),
}

impl AnyCollider {
    fn frame(&mut self, px: &[glam::Vec3], py: &[glam::Vec3]) -> anyhow::Result<FrameResult> {
        match self {
            AnyCollider::Classic(c) => c.frame(px, py),
            AnyCollider::Compute(c) => c.frame(px, py),
        }
    }

    fn leaves(&self) -> [usize; 2] {
        match self {
            AnyCollider::Classic(c) => [c.x.stream.leaves.len(), c.y.stream.leaves.len()],
            AnyCollider::Compute(c) => [c.x.leaves as usize, c.y.leaves as usize],
        }
    }
}

/// Run a deforming scene of Table III.
#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    /// One of: interlocking-tori, touching-tori, merging-tori, bump-bunnies, happy-buddhas,
    /// intimate-animals.
    pub scene: String,
    /// Frames of the scene's deformation.
    #[arg(long, default_value_t = 30, value_parser = ranges::frames_kept(1 << 10).of::<usize>())]
    pub frames: usize,
    /// Triangles per model instead of the paper's count.
    #[arg(long, value_parser = ranges::triangles(TRIANGLE_BYTES).of::<usize>())]
    pub triangles: Option<usize>,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    #[command(flatten)]
    pub profile: super::profile::ProfileArg,
}

/// `collide-scene`: a deforming scene frame by frame; `json` prints one object.
pub fn run_scene(args: &SceneArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    args.pipeline.period.apply(ctx, 1);
    // Millions of triangles take minutes to build and stream: say what is happening.
    let bar = classic_gpgpu::report::progress_bars(json).add(ProgressBar::new_spinner());
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar.set_message(format!(
        "building the scene {}{}",
        args.scene,
        args.triangles
            .map(|n| format!(" ({n} triangles a model)"))
            .unwrap_or_default()
    ));
    // The error names the scene and lists the scenes.
    let scene = Scene::build(&args.scene, args.triangles)?;
    if let Some(asked) = args.triangles.filter(|&n| n != scene.triangles) {
        // The generators make whole rings (tori, knots), and the bunny is never coarser
        // than the shipped one: the count made is said.
        bar.suspend(|| {
            eprintln!(
                "note: --triangles {asked}: the scene's generator makes {} triangles a model, \
                 the nearest it can",
                scene.triangles
            )
        });
    }
    bar.set_message("building the streams and uploading them to the GPU");
    let options = args.pipeline.options(ctx, &scene.x.rest, &scene.y.rest)?;
    let (rest_x, rest_y) = (&scene.x.rest, &scene.y.rest);
    let mut collider = match args.pipeline.formulation {
        super::Formulation::Classic => AnyCollider::Classic(Box::new(StreamingCollider::new(
            ctx, rest_x, rest_y, options,
        )?)),
        super::Formulation::Compute => AnyCollider::Compute(Box::new(ComputeCollider::new(
            ctx, rest_x, rest_y, options,
        )?)),
    };
    let mut frames = Vec::new();
    let mut summary = SceneSummary::default();
    args.profile.start(ctx);
    for f in 0..args.frames {
        bar.set_message(format!("frame {} of {}", f + 1, args.frames));
        let (px, py) = scene.frame(f);
        let r = collider.frame(&px, &py)?;
        if !json {
            bar.suspend(|| {
                print!("frame {f:4}: ");
                print_frame(&r);
            });
        }
        summary.add(&r);
        frames.push(json!({
            "frame": f, "caps": r.caps, "pctps": r.pctps, "ctps": r.ctps, "eta": r.eta,
            "scheme": r.scheme, "readback_bytes": r.readback_bytes, "timings_ms": timings_json(&r),
        }));
    }
    bar.finish_and_clear();
    super::profile::print(ctx);
    if !json {
        println!(
            "{}",
            summary.line(scene.name, scene.triangles, &ctx.info().renderer_line())
        );
    }
    if json {
        let out = json!({
            "renderer": ctx.info().renderer_line(),
            "formulation": args.pipeline.formulation.name(),
            "scene": scene.name,
            "label": scene.label,
            "triangles": [scene.triangles, scene.triangles],
            "leaf_size": options.leaf_size,
            "leaves": collider.leaves(),
            "frames": frames,
        });
        println!("{}", serde_json::to_string(&out)?);
    }
    Ok(())
}

/// What a scene's run comes to, for its last line: the range of CAPs and colliding triangle
/// pairs over the frames, and the median frame time.
#[derive(Default)]
struct SceneSummary {
    caps: Vec<usize>,
    ctps: Vec<usize>,
    total_ms: Vec<f64>,
}

impl SceneSummary {
    fn add(&mut self, frame: &FrameResult) {
        self.caps.push(frame.caps);
        self.ctps.push(frame.ctps);
        self.total_ms.push(frame.timings.total);
    }

    fn line(&self, scene: &str, triangles: usize, renderer: &str) -> String {
        let range = |v: &[usize]| {
            let (lo, hi) = (v.iter().min(), v.iter().max());
            match (lo, hi) {
                (Some(lo), Some(hi)) if lo == hi => format!("{lo}"),
                (Some(lo), Some(hi)) => format!("{lo}-{hi}"),
                _ => "none".into(),
            }
        };
        let median = classic_gpgpu::timing::Spread::of(&self.total_ms).median;
        format!(
            "{scene}: {} frames of {triangles} x {triangles} triangles, colliding triangle \
             pairs {} per frame (CAPs {}), median frame {median:.2} ms on {renderer}",
            self.caps.len(),
            range(&self.ctps),
            range(&self.caps),
        )
    }
}

fn timings_json(f: &FrameResult) -> serde_json::Value {
    let t = &f.timings;
    // "readback" is the paper's Readback column: encoding plus reading and decoding.
    json!({
        "overlap": t.overlap, "stencil": t.stencil, "readback": t.encode + t.readback, "encode": t.encode,
        "decode": t.readback, "tri_test": t.tri_test, "download": t.download,
        "update": t.update, "total": t.total,
    })
}

fn print_frame(f: &FrameResult) {
    let t = &f.timings;
    println!(
        "CAPs {} PCTPs {} CTPs {} eta {:.4}% readback {} {} B | overlap {:.2} encode {:.2} \
         read+decode {:.2} tri {:.2} download {:.2} update {:.2} total {:.2} ms",
        f.caps,
        f.pctps,
        f.ctps,
        f.eta * 100.0,
        f.scheme
            .map(|s| format!("{s:?}").to_lowercase())
            .unwrap_or_else(|| "none".into()),
        f.readback_bytes,
        t.overlap,
        t.encode,
        t.readback,
        t.tri_test,
        t.download,
        t.update,
        t.total
    );
}
