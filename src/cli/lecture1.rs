//! `classic-gpgpu lecture1 ...`: the tutorial's lecture 1 beyond paper 1 (`src/lecture1/`):
//! self-collision with streaming AABBs, pairwise triangle tests with the triangles in
//! textures (classic, or as one compute dispatch with `--formulation compute`), a
//! comparison of the two with brute force by triangle count, 2D Voronoi diagrams, distance
//! fields, swept volumes, penetration depth and avatar CCD. The report's `lecture1` section
//! (`reproduce --only lecture1`) and `view lecture1 ...` show the same techniques.

use anyhow::Context as _;
use classic_gpgpu::collide::deform::{Deformation, Deforming, Pulsating, Wavy};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::collide::stream_setup::auto_leaf_size;
use classic_gpgpu::gl::Context;
use classic_gpgpu::lecture1::knotted_tube::KnottedTube;
use classic_gpgpu::lecture1::pairwise::{PairwiseTester, DEFAULT_TILE};
use classic_gpgpu::lecture1::pairwise_compute::ComputePairwiseTester;
use classic_gpgpu::lecture1::reference;
use classic_gpgpu::lecture1::self_collision::{Options, SelfCollider};
use classic_gpgpu::lecture1::weld::weld;
use classic_gpgpu::mesh::{load_obj, Mesh};
use classic_gpgpu::values::{ranges, Count, Real};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod avatar_ccd;
mod penetration;

/// The lecture-1 techniques.
#[derive(clap::Subcommand, Debug)]
pub enum Lecture1Command {
    /// Self-collision of a deforming mesh with paper 1's streaming AABBs: per frame, every
    /// pair of intersecting triangles that share no vertex.
    SelfCollision(SelfCollisionArgs),
    /// Pairwise triangle tests with the triangles in textures (a reconstruction of Choi, Kim
    /// & Kim 2006): every intersecting pair between two models, or within one; with
    /// `--formulation compute`, the same test as one OpenGL 4.3 compute dispatch.
    Pairwise(PairwiseArgs),
    /// Pairwise tests, streaming AABBs and brute force on the swelling knot, by triangle
    /// count (wall-clock times, measured side by side; the renderer named).
    Compare(CompareArgs),
    /// The 2D generalized Voronoi diagram of points, segments and triangles by rasterization
    /// (Hoff et al. 1999): exact distances written as depth (the default, ours) or Hoff's
    /// distance meshes (--method mesh); per pixel the nearest site and its distance, checked
    /// against brute force. SITES.json:
    /// {"sites": [{"point": [x, y]}, {"segment": [[x, y], [x, y]]}, {"triangle": [[x, y],
    /// [x, y], [x, y]]}, ...], "domain": {"min": [x, y], "size": s}}; the domain (optional,
    /// the square the pixels cover) defaults to the sites' box made square and grown by a
    /// tenth of its side on every side. Site ids are list positions; on a tie (equal fp32
    /// depth) the smaller id wins.
    Voronoi(VoronoiArgs),
    /// The unsigned distance field of a mesh on an N^3 grid, slice by slice: by default exact
    /// per-fragment distances kept by GL_MIN blending (DiFi-style, a reconstruction); with
    /// --method mesh Hoff's distance meshes (every vertex, edge and face's distance drawn as
    /// triangles, the depth test keeping the nearest), its error against the exact field
    /// printed. Written as float32 .npy indexed [z][y][x]; the grid is the cube over the
    /// model's box grown by the margin, voxel centres at origin + spacing * (x, y, z).
    DistanceField(DistanceFieldArgs),
    /// The swept volume of a model moving along a path (Kim, Varadhan, Lin & Manocha 2003, a
    /// reconstruction): ruled surfaces and posed faces, their distance field, a flood fill
    /// from the border, the outer boundary by marching tetrahedra (a closed 2-manifold: its
    /// Euler characteristic and genus). PATH.json: [{"translation": [x, y, z], "rotation":
    /// [w, x, y, z]}, ...], keyframes equally spaced in time, translation
    /// interpolated linearly and rotation by slerp; a rotation that is not a unit quaternion
    /// (within 1e-6) is refused.
    SweptVolume(SweptVolumeArgs),
    /// Penetration depth by rasterized Minkowski sums (a reconstruction of Kim, Otaduy, Lin
    /// & Manocha 2002): how far, and along which direction, B must move to touch A without
    /// overlap. Each OBJ object or group is a convex piece; a non-convex piece is refused.
    Penetration(penetration::PenetrationArgs),
    /// Continuous collision of a walking figure of capsule links with a triangle environment
    /// (a reconstruction of Kim, Redon, Lin, Manocha & Templeman 2007): swept capsule bounds,
    /// a BVH, CULLIDE-style occlusion-query culling, exact distances and conservative
    /// advancement; prints the first time of contact (keyframe k at time k; null when none),
    /// the link and the contact point. K.json: {"keyframes": [{"root": [x, y, z], "angles":
    /// {"left thigh": [rx, ry, rz], ...}}, ...]} (radians, R = Rx Ry Rz in the parent's
    /// frame; links left out have zero angles).
    AvatarCcd(avatar_ccd::AvatarCcdArgs),
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeformArg {
    Wavy,
    Pulsating,
    None,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneArg {
    /// A tube around a trefoil knot that swells until its strands press through each other.
    KnottedTube,
}

#[derive(clap::Args, Debug)]
pub struct SelfCollisionArgs {
    /// The model (OBJ); or leave it out and name a --scene.
    pub model: Option<PathBuf>,
    /// A generated scene that folds onto itself instead of a model (it moves by itself:
    /// --deform does not apply).
    #[arg(long, value_enum)]
    pub scene: Option<SceneArg>,
    /// Triangles of the generated scene (the tube is made of whole rings, so the count made
    /// is the nearest it can be, and is said).
    #[arg(long, default_value_t = 2000, value_parser = TUBE_TRIANGLES.of::<usize>())]
    pub triangles: usize,
    /// Paper 1's deformation of the model (section 7.2).
    #[arg(long, value_enum, default_value_t = DeformArg::None)]
    pub deform: DeformArg,
    /// Frames of the motion.
    #[arg(long, default_value_t = 1, value_parser = ranges::frames_kept(1 << 10).of::<usize>())]
    pub frames: usize,
    /// Seconds of animation between frames.
    #[arg(long, default_value_t = 0.1, value_parser = DT.of::<f32>())]
    pub dt: f32,
    /// Most triangles per leaf (default: 32, doubled until the stream has at most 512 slots
    /// on a software renderer, 4096 on a GPU).
    #[arg(long, value_parser = ranges::LEAF_SIZE.of::<usize>())]
    pub leaf_size: Option<usize>,
    /// Check every frame against brute force with the same exact predicate (quadratic).
    #[arg(long)]
    pub check: bool,
}

#[derive(clap::Args, Debug)]
pub struct PairwiseArgs {
    /// Model A (OBJ).
    pub a: PathBuf,
    /// Model B (OBJ); without it, A against itself (neighbours excluded).
    pub b: Option<PathBuf>,
    /// Largest tile side (triangle pairs per side of the pair texture) of the classic
    /// formulation [default: 1024].
    #[arg(long, value_parser = ranges::TEXTURE_SIDE.of::<usize>())]
    pub tile: Option<usize>,
    /// Check the pairs against brute force with the same exact predicate (quadratic).
    #[arg(long)]
    pub check: bool,
    /// classic: the pair quad over triangle textures, hierarchical readback (OpenGL 3.3);
    /// compute: one compute dispatch over all pairs with an atomic-append pair list (OpenGL
    /// 4.3, then and now).
    #[arg(long, value_enum, default_value_t = Formulation::Classic)]
    pub formulation: Formulation,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    Classic,
    Compute,
}

pub use super::lecture1_fields::{DistanceFieldArgs, SweptVolumeArgs, VoronoiArgs};

#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// Triangle counts of the swelling knot (at its thickest).
    #[arg(long, value_delimiter = ',', num_args = 1.., default_values_t = [300, 500, 1000, 2000],
          value_parser = TUBE_TRIANGLES.of::<usize>())]
    pub triangles: Vec<usize>,
}

pub fn run(command: &Lecture1Command, ctx: &Context, json: bool) -> anyhow::Result<()> {
    match command {
        Lecture1Command::SelfCollision(a) => self_collision(a, ctx, json),
        Lecture1Command::Pairwise(a) => pairwise(a, ctx, json),
        Lecture1Command::Compare(a) => compare(a, ctx, json),
        Lecture1Command::Voronoi(a) => super::lecture1_fields::voronoi(a, ctx, json),
        Lecture1Command::DistanceField(a) => super::lecture1_fields::distance_field(a, ctx, json),
        Lecture1Command::SweptVolume(a) => super::lecture1_fields::swept_volume(a, ctx, json),
        Lecture1Command::Penetration(a) => penetration::run(a, ctx, json),
        Lecture1Command::AvatarCcd(a) => avatar_ccd::run(a, ctx, json),
    }
}

fn load(path: &Path) -> anyhow::Result<Mesh> {
    let mesh = load_obj(path).with_context(|| format!("reading model {}", path.display()))?;
    classic_gpgpu::collide::stream_setup::validate_mesh(&mesh)
        .with_context(|| format!("model {}", path.display()))?;
    Ok(mesh)
}

/// A model's positions at time `t`, or the scene's.
enum Motion {
    Model(Deforming),
    Tube(KnottedTube),
}

impl Motion {
    fn mesh(&self) -> &Mesh {
        match self {
            Motion::Model(d) => &d.rest,
            Motion::Tube(t) => &t.mesh,
        }
    }

    fn positions(&self, t: f32) -> Vec<glam::Vec3> {
        match self {
            Motion::Model(d) => d.positions(t),
            Motion::Tube(k) => k.positions(t),
        }
    }
}

/// Memory per triangle of the generated knotted tube with its collision setup (the mesh, its
/// welded copy, the stream of leaves, the GPU textures; `compare` also the pairwise tester and
/// brute force), measured as peak resident memory: 0.15 KiB for `self-collision` (20,000
/// against 80,000 triangles), 0.9 KiB for `compare` (2,000 against 16,000); rounded up.
const TUBE_TRIANGLE_BYTES: u64 = 1 << 10;

/// `--triangles` of the knotted tube: from its smallest (24 rings of 6 sides) to what fits.
const TUBE_TRIANGLES: Count = Count {
    least: 288,
    ..ranges::triangles(TUBE_TRIANGLE_BYTES)
};

/// `--dt`: seconds of animation between frames, either way (the motion is a function of
/// time), where fp32 time still has milliseconds.
const DT: Real = Real::new(
    "a time step in seconds",
    -1e4,
    1e4,
    "the motion's time is fp32, which keeps milliseconds up to 1e4 s",
);

/// The tube of about `asked` triangles, and a note when it has another count (the tube is
/// made of whole rings, so most counts are rounded).
fn tube_of(asked: usize) -> (KnottedTube, Option<String>) {
    let tube = KnottedTube::with_triangles(asked);
    let made = tube.mesh.triangles.len();
    let note = (made != asked).then(|| {
        format!(
            "--triangles {asked}: the knotted tube is made of whole rings, so it has {made} \
             triangles, the nearest it makes"
        )
    });
    (tube, note)
}

fn self_collision(args: &SelfCollisionArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let motion = match (&args.model, args.scene) {
        (Some(_), Some(_)) => anyhow::bail!("give a model or a --scene, not both"),
        (None, None) => anyhow::bail!("give a model (OBJ) or a --scene"),
        (None, Some(SceneArg::KnottedTube)) => {
            anyhow::ensure!(
                args.deform == DeformArg::None,
                "the knotted tube moves by itself; --deform applies to a model"
            );
            let (tube, note) = tube_of(args.triangles);
            if let Some(note) = note {
                eprintln!("note: {note}");
            }
            Motion::Tube(tube)
        }
        (Some(path), None) => {
            // Welded before deforming, so that split copies of a vertex move as one.
            let mesh = weld(&load(path)?);
            let size = mesh.bounds().size().max_element().max(f32::MIN_POSITIVE);
            let deformation = match args.deform {
                DeformArg::Wavy => Deformation::Wavy(Wavy::for_size(size, 11)),
                DeformArg::Pulsating => Deformation::Pulsating(Pulsating::for_size(size)),
                DeformArg::None => Deformation::Rigid,
            };
            Motion::Model(Deforming::new(mesh, deformation))
        }
    };
    let mesh = motion.mesh();
    let leaf_size = match args.leaf_size {
        Some(n) => n,
        None => auto_leaf_size(
            mesh,
            classic_gpgpu::collide::stream_setup::max_slots(ctx.info().is_software()),
        )?,
    };
    let options = Options {
        leaf_size,
        readback: ReadbackMode::PaperSwitch,
        ..Options::default()
    };
    let mut collider = SelfCollider::new(ctx, mesh, options)?;
    let mut frames = Vec::new();
    for f in 0..args.frames {
        let positions = motion.positions(f as f32 * args.dt);
        let start = Instant::now();
        let frame = collider.frame(&positions)?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        if args.check {
            let expected = reference::self_pairs(&collider.mesh, &positions);
            anyhow::ensure!(
                expected == frame.pairs,
                "frame {f}: streaming AABBs found {} pairs, brute force {}",
                frame.pairs.len(),
                expected.len()
            );
        }
        frames.push((frame, ms));
    }
    let renderer = ctx.info().renderer_line();
    if json {
        let report = json!({
            "renderer": renderer,
            "asked_triangles": args.scene.map(|_| args.triangles),
            "triangles": mesh.triangles.len(),
            "leaf_size": leaf_size,
            "leaves": collider.stream.leaves.len(),
            "checked": args.check,
            "frames": frames.iter().enumerate().map(|(f, (r, ms))| json!({
                "frame": f,
                "pairs": r.pairs.iter().map(|&(i, j)| [i, j]).collect::<Vec<_>>(),
                "caps": r.caps,
                "pctps": r.pctps,
                "tiles": r.tiles,
                "wall_ms": ms,
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {renderer}");
    println!(
        "{} triangles, {} leaves of at most {leaf_size}",
        mesh.triangles.len(),
        collider.stream.leaves.len()
    );
    for (f, (r, ms)) in frames.iter().enumerate() {
        println!(
            "frame {f}: {} pairs ({} CAPs, {} triangle pairs tested, {ms:.1} ms wall){}",
            r.pairs.len(),
            r.caps,
            r.pctps,
            if args.check {
                ", equal to brute force"
            } else {
                ""
            }
        );
    }
    Ok(())
}

fn pairwise(args: &PairwiseArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    if let (Formulation::Compute, Some(tile)) = (args.formulation, args.tile) {
        anyhow::bail!(
            "--tile {tile} sets the tiles of the classic formulation's pair texture; \
             --formulation compute tests every pair in one dispatch, without tiles: leave out \
             --tile, or use --formulation classic"
        );
    }
    let a = load(&args.a)?;
    let b = args.b.as_deref().map(load).transpose()?;
    let start = Instant::now();
    let (result, tile) = match args.formulation {
        Formulation::Classic => {
            let tester = PairwiseTester::new(ctx, args.tile.unwrap_or(DEFAULT_TILE))?;
            (tester.run(&a, b.as_ref())?, Some(tester.tile))
        }
        Formulation::Compute => {
            let mut tester = ComputePairwiseTester::new(ctx)?;
            (tester.run(&a, b.as_ref())?, None)
        }
    };
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if args.check {
        let expected = match &b {
            Some(b) => reference::pairs_between(&a, b),
            None => reference::self_pairs(&weld(&a), &a.positions),
        };
        anyhow::ensure!(
            expected == result.pairs,
            "the pairwise test found {} pairs, brute force {}",
            result.pairs.len(),
            expected.len()
        );
    }
    let renderer = ctx.info().renderer_line();
    let counts = [
        a.triangles.len(),
        b.as_ref().map_or(0, |b| b.triangles.len()),
    ];
    if json {
        let report = json!({
            "renderer": renderer,
            "triangles": if b.is_some() { counts.to_vec() } else { vec![counts[0]] },
            "formulation": format!("{:?}", args.formulation).to_lowercase(),
            "tile": tile,
            "tiles": result.tiles,
            "candidates": result.candidates,
            "readback_bytes": result.readback_bytes,
            "checked": args.check,
            "pairs": result.pairs.iter().map(|&(i, j)| [i, j]).collect::<Vec<_>>(),
            "timings_ms": {
                "pair_passes_gpu": result.test_ms,
                "total_wall": ms,
                "pair_passes_timing": match args.formulation {
                    Formulation::Classic => "GL timer query",
                    Formulation::Compute => "wall clock between glFinish calls (with the list's readback)",
                },
            },
        });
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {renderer}");
    let passes = match tile {
        Some(tile) => format!("{} tile(s) of at most {tile}", result.tiles),
        None => format!("{} compute dispatch(es)", result.tiles),
    };
    println!(
        "{} pairs ({} reported by the GPU, {passes}; {ms:.1} ms wall){}",
        result.pairs.len(),
        result.candidates,
        if args.check {
            ", equal to brute force"
        } else {
            ""
        }
    );
    use std::io::Write as _;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for (i, j) in &result.pairs {
        writeln!(out, "{i} {j}")?;
    }
    out.flush()?;
    Ok(())
}

/// Wall time of `f`, ms, with its result.
fn timed<T>(f: impl FnOnce() -> anyhow::Result<T>) -> anyhow::Result<(T, f64)> {
    let start = Instant::now();
    let value = f()?;
    Ok((value, start.elapsed().as_secs_f64() * 1e3))
}

fn compare(args: &CompareArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    // Each count's tube, said where it is not the count asked; two counts that make one tube
    // would only repeat a row.
    let mut tubes: Vec<(usize, KnottedTube)> = Vec::new();
    for &n in &args.triangles {
        let (tube, note) = tube_of(n);
        let made = tube.mesh.triangles.len();
        if let Some((other, _)) = tubes.iter().find(|(_, t)| t.mesh.triangles.len() == made) {
            anyhow::bail!(
                "--triangles {other} and {n} both make the knotted tube of {made} triangles (it \
                 is made of whole rings), so the second row would repeat the first: give counts \
                 further apart"
            );
        }
        if let Some(note) = note {
            eprintln!("note: {note}");
        }
        tubes.push((n, tube));
    }
    let tester = PairwiseTester::new(ctx, DEFAULT_TILE)?;
    let mut rows = Vec::new();
    for (n, tube) in &tubes {
        let n = *n;
        let mut mesh = tube.mesh.clone();
        mesh.positions =
            tube.positions_at_radius(classic_gpgpu::lecture1::knotted_tube::RADIUS_RANGE.1);
        let leaf_size = auto_leaf_size(
            &mesh,
            classic_gpgpu::collide::stream_setup::max_slots(ctx.info().is_software()),
        )?;
        let mut collider = SelfCollider::new(
            ctx,
            &mesh,
            Options {
                leaf_size,
                ..Options::default()
            },
        )?;
        // One untimed run of each GPU path first (shader compilation, first draws).
        collider.frame(&mesh.positions)?;
        tester.run(&mesh, None)?;
        let (brute, brute_ms) =
            timed(|| Ok(reference::self_pairs(&collider.mesh, &mesh.positions)))?;
        let (streaming, streaming_ms) = timed(|| collider.frame(&mesh.positions))?;
        let (pairwise, pairwise_ms) = timed(|| tester.run(&mesh, None))?;
        anyhow::ensure!(
            streaming.pairs == brute && pairwise.pairs == brute,
            "{n} triangles: the methods disagree (brute force {}, streaming {}, pairwise {})",
            brute.len(),
            streaming.pairs.len(),
            pairwise.pairs.len()
        );
        rows.push(json!({
            "asked_triangles": n,
            "triangles": mesh.triangles.len(),
            "pairs": brute.len(),
            "brute_force_ms": brute_ms,
            "streaming_aabb_ms": streaming_ms,
            "pairwise_ms": pairwise_ms,
            "pairwise_gpu_pass_ms": pairwise.test_ms,
            "pairwise_candidates": pairwise.candidates,
        }));
    }
    let renderer = ctx.info().renderer_line();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let load = load
        .split_whitespace()
        .next()
        .unwrap_or("unknown")
        .to_string();
    if json {
        println!(
            "{}",
            serde_json::to_string(
                &json!({"renderer": renderer, "load_average": load, "rows": rows})
            )?
        );
        return Ok(());
    }
    println!("renderer: {renderer} (load average {load}); wall clock, ms, one run each");
    println!(
        "{:>9} {:>6} {:>12} {:>14} {:>10}",
        "triangles", "pairs", "brute force", "streaming AABB", "pairwise"
    );
    for r in &rows {
        println!(
            "{:>9} {:>6} {:>12.1} {:>14.1} {:>10.1}",
            r["triangles"],
            r["pairs"],
            r["brute_force_ms"].as_f64().unwrap_or(f64::NAN),
            r["streaming_aabb_ms"].as_f64().unwrap_or(f64::NAN),
            r["pairwise_ms"].as_f64().unwrap_or(f64::NAN)
        );
    }
    Ok(())
}
