//! `classic-gpgpu lecture1 voronoi | distance-field | swept-volume`: distance fields by
//! rasterization and the swept volumes built on them (`src/lecture1/voronoi`,
//! `distance_field`, `swept_volume`).

use anyhow::Context as _;
use classic_gpgpu::files;
use classic_gpgpu::gl::picture::{picture, Panel, Scale};
use classic_gpgpu::gl::Context;
use classic_gpgpu::lecture1::distance_field::compute::ComputeField;
use classic_gpgpu::lecture1::distance_field::mesh_slices::{MeshBound, MeshSlices};
use classic_gpgpu::lecture1::distance_field::meshes::DEFAULT_ERROR_VOXELS;
use classic_gpgpu::lecture1::distance_field::slices::SliceRasterizer;
use classic_gpgpu::lecture1::distance_field::DistanceField;
use classic_gpgpu::lecture1::distance_field::{reference as field_reference, Grid};
use classic_gpgpu::lecture1::swept_volume::{self, path::Path3, Options, DEFAULT_POSES};
use classic_gpgpu::lecture1::voronoi::mesh::DEFAULT_ERROR_PIXELS;
use classic_gpgpu::lecture1::voronoi::raster::{Method, VoronoiRasterizer};
use classic_gpgpu::lecture1::voronoi::{reference as voronoi_reference, Sites};
use classic_gpgpu::mesh::{load_obj, write_obj, Mesh};
use classic_gpgpu::values::{ranges, Count, Real, SMALLEST};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A field's voxels per axis: N x N x N float32, so 1024 is 4 GiB.
const FIELD_RESOLUTION: Count = Count::new(
    "a resolution",
    2,
    1024,
    "the field holds N x N x N float32 voxels: 1024 is 4 GiB",
);

/// A distance in mesh units (`--clamp`, `--epsilon`): positive and finite (the model's own
/// scale is checked when it is loaded).
const DISTANCE: Real = Real::new(
    "a distance",
    SMALLEST,
    f64::MAX,
    "positive and finite, in mesh units",
);

/// `--margin`: room around the model, none or more (checked against the model's scale when it
/// is loaded).
const MARGIN: Real = Real::new("a margin", 0.0, f64::MAX, "finite, in mesh units");

/// `--mesh-error`: the distance meshes' error bound, pixels or voxels.
const MESH_ERROR: Real = Real::new(
    "an error bound",
    1e-4,
    1e4,
    "a cone's sides grow as one over the square root of the error",
);

/// `--poses`: the poses sampled along the path, each a pass over the field.
const POSES: Count = Count::new(
    "a number of poses",
    1,
    10_000,
    "each pose is drawn into every slice of the field",
);

#[derive(clap::Args, Debug)]
pub struct VoronoiArgs {
    /// The sites (JSON; the format is in this command's description).
    pub sites: PathBuf,
    /// Pixels per side of the diagram.
    #[arg(long, default_value_t = 256, value_parser = ranges::TEXTURE_SIDE.of::<usize>())]
    pub resolution: usize,
    /// The picture: nearest site and distance, each with its colour key.
    #[arg(long)]
    pub png: PathBuf,
    /// The diagram as float32 .npy, shape [N, N, 2] indexed [y][x][c] (y from the bottom):
    /// c = 0 the nearest site's id, c = 1 its distance.
    #[arg(long)]
    pub npy: Option<PathBuf>,
    /// How each site's distance reaches the depth buffer: `mesh`, Hoff's distance meshes
    /// (cones and tents, depth interpolated, within --mesh-error of the distance); `exact`,
    /// the exact distance per fragment through gl_FragDepth.
    #[arg(long, value_enum, default_value_t = VoronoiMethod::Exact)]
    pub method: VoronoiMethod,
    /// The distance meshes' tessellation error, pixels: the cones get the fewest sides that
    /// keep every distance within it (only with --method mesh).
    #[arg(long, value_parser = MESH_ERROR.of::<f64>())]
    pub mesh_error: Option<f64>,
    /// Overwrite existing output files.
    #[arg(long)]
    pub force: bool,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum VoronoiMethod {
    /// The exact distance per fragment (gl_FragDepth).
    Exact,
    /// Hoff's bounded-error distance meshes.
    Mesh,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// OpenGL 3.3: slices, rectangles, GL_MIN blending.
    Classic,
    /// OpenGL 4.3 compute shader: one invocation per voxel.
    Compute,
}

#[derive(clap::Args, Debug)]
pub struct DistanceFieldArgs {
    /// The model (OBJ).
    pub model: PathBuf,
    /// N: voxels per axis.
    #[arg(long, default_value_t = 64, value_parser = FIELD_RESOLUTION.of::<usize>())]
    pub resolution: usize,
    /// The field (float32 .npy, shape [N, N, N], indexed [z][y][x]).
    #[arg(long)]
    pub npy: PathBuf,
    /// Bound the work: voxels farther than D from the mesh hold D (mesh units). Without it
    /// every voxel holds its exact distance.
    #[arg(long, value_parser = DISTANCE.of::<f64>())]
    pub clamp: Option<f64>,
    /// Room around the model's box on every side, mesh units [default: a tenth of the box's
    /// longest side].
    #[arg(long, value_parser = MARGIN.of::<f64>())]
    pub margin: Option<f64>,
    #[arg(long, value_enum, default_value_t = Formulation::Classic)]
    pub formulation: Formulation,
    /// How each slice is drawn (classic formulation): `exact`, every triangle's exact
    /// distance per fragment kept by GL_MIN blending; `mesh`, Hoff's distance meshes kept by
    /// the depth test, within --mesh-error of the distance (the exact slices are then also
    /// computed and the difference printed).
    #[arg(long, value_enum, default_value_t = VoronoiMethod::Exact)]
    pub method: VoronoiMethod,
    /// The distance meshes' tessellation error, voxels [default: 0.5] (only with --method
    /// mesh).
    #[arg(long, value_parser = MESH_ERROR.of::<f64>())]
    pub mesh_error: Option<f64>,
    /// Also compute the field by brute force on the CPU and report the largest difference.
    #[arg(long)]
    pub check: bool,
    /// Overwrite an existing output file.
    #[arg(long)]
    pub force: bool,
}

#[derive(clap::Args, Debug)]
pub struct SweptVolumeArgs {
    /// The model (OBJ), a closed mesh.
    pub model: PathBuf,
    /// The keyframes (JSON; the format is in this command's description).
    #[arg(long)]
    pub path: PathBuf,
    /// N: voxels per axis of the distance field.
    #[arg(long, default_value_t = 64,
          value_parser = Count { least: 16, ..FIELD_RESOLUTION }.of::<usize>())]
    pub resolution: usize,
    /// The swept volume's boundary (OBJ).
    #[arg(long)]
    pub out: PathBuf,
    /// K: poses sampled along the path.
    #[arg(long, default_value_t = DEFAULT_POSES, value_parser = POSES.of::<usize>())]
    pub poses: usize,
    /// ε: how far the ruled quads' triangles may be from the quads, mesh units [default: a
    /// quarter of a voxel].
    #[arg(long, value_parser = DISTANCE.of::<f64>())]
    pub epsilon: Option<f64>,
    /// Overwrite an existing output file.
    #[arg(long)]
    pub force: bool,
}

fn load(path: &Path) -> anyhow::Result<Mesh> {
    load_obj(path).with_context(|| format!("reading model {}", path.display()))
}

fn renderer(ctx: &Context) -> String {
    ctx.info().renderer_line()
}

pub fn voronoi(args: &VoronoiArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    files::check_output("--png", &args.png, &[&args.sites], args.force, &["png"])?;
    if let Some(npy) = &args.npy {
        files::check_output("--npy", npy, &[&args.sites], args.force, &["npy"])?;
        anyhow::ensure!(
            !files::same_file(npy, &args.png) && npy != &args.png,
            "--npy and --png name the same file"
        );
    }
    anyhow::ensure!(args.resolution >= 1, "--resolution must be at least 1");
    let method = match (args.method, args.mesh_error) {
        (VoronoiMethod::Exact, None) => Method::Exact,
        (VoronoiMethod::Exact, Some(_)) => {
            anyhow::bail!("--mesh-error applies to --method mesh only")
        }
        (VoronoiMethod::Mesh, error) => {
            let error_pixels = error.unwrap_or(DEFAULT_ERROR_PIXELS);
            anyhow::ensure!(
                error_pixels.is_finite() && error_pixels > 0.0,
                "--mesh-error must be a positive number of pixels, not {error_pixels}"
            );
            Method::Mesh { error_pixels }
        }
    };
    let sites = Sites::load(&args.sites)?;
    let domain = sites.domain()?;
    let n = args.resolution;
    let rasterizer = VoronoiRasterizer::new(ctx)?;
    let start = Instant::now();
    let (diagram, timings) = rasterizer.diagram_by(&sites.sites, domain, n, method)?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let agreement = voronoi_reference::compare(&diagram, &sites.sites);
    anyhow::ensure!(
        agreement.agrees(),
        "the GPU diagram disagrees with brute force: {} pixel(s) given a farther site, largest \
         distance error {} (tolerance {})",
        agreement.wrong,
        agreement.max_distance_error,
        agreement.tolerance
    );
    // The picture: the nearest site and the distance, each on its own scale and key.
    let ids: Vec<f32> = diagram.site.iter().map(|&s| s as f32).collect();
    let panels = [
        Panel {
            title: "nearest site (id)".into(),
            values: ids.clone(),
            width: n as u32,
            height: n as u32,
            scale: Scale::fixed(0.0, (sites.sites.len() - 1) as f32),
        },
        Panel {
            title: "distance".into(),
            values: diagram.distance.clone(),
            width: n as u32,
            height: n as u32,
            scale: Scale::of([diagram.distance.as_slice()]),
        },
    ];
    let side = (2 * n as u32).clamp(256, 1024);
    let (image, _) = picture(&panels, (2 * side, side + side / 4));
    files::write_image(&args.png, &image::DynamicImage::ImageRgba8(image))?;
    if let Some(npy) = &args.npy {
        let data: Vec<f32> = ids
            .iter()
            .zip(&diagram.distance)
            .flat_map(|(&s, &d)| [s, d])
            .collect();
        files::write_npy(npy, &[n, n, 2], &data)?;
    }
    let counts = diagram.pixel_counts(sites.sites.len());
    if json {
        let report = json!({
            "renderer": renderer(ctx),
            "resolution": n,
            "sites": sites.sites.len(),
            "domain": domain,
            "pixel_counts": counts,
            "method": match method { Method::Exact => "exact", Method::Mesh { .. } => "mesh" },
            "mesh_error_bound": diagram.mesh_error,
            "coverage_error_bound": diagram.coverage_error,
            "agreement": agreement,
            "tie_rule": "equal fp32 depth (distance / depth range): the smaller site id wins",
            "timings_ms": {"site_pass_gpu": timings.pass_ms, "readback": timings.readback_ms,
                           "total_wall": wall_ms},
            "png": args.png,
            "npy": args.npy,
        });
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {}", renderer(ctx));
    println!(
        "{} sites at {n} x {n}: equal to brute force at {} pixels, ties at {}, largest \
         distance difference {:.3e} (tolerance {:.3e})",
        sites.sites.len(),
        agreement.same_site,
        agreement.ties,
        agreement.max_distance_error,
        agreement.tolerance
    );
    for (i, c) in counts.iter().enumerate() {
        println!("site {i}: {c} pixels");
    }
    Ok(())
}

pub fn distance_field(args: &DistanceFieldArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    files::check_output("--npy", &args.npy, &[&args.model], args.force, &["npy"])?;
    let mesh = load(&args.model)?;
    let margin = args.margin.unwrap_or_else(|| Grid::default_margin(&mesh));
    let grid = Grid::around(&mesh, args.resolution, margin)
        .with_context(|| format!("the grid of model {}", args.model.display()))?;
    let mesh_error = match (args.method, args.mesh_error, args.formulation) {
        (VoronoiMethod::Exact, None, _) => None,
        (VoronoiMethod::Exact, Some(_), _) => {
            anyhow::bail!("--mesh-error applies to --method mesh only")
        }
        (VoronoiMethod::Mesh, _, Formulation::Compute) => {
            anyhow::bail!("--method mesh draws slices: it has no compute formulation")
        }
        (VoronoiMethod::Mesh, error, Formulation::Classic) => {
            let error = error.unwrap_or(DEFAULT_ERROR_VOXELS);
            anyhow::ensure!(
                error.is_finite() && error > 0.0,
                "--mesh-error {error}: give a positive number of voxels (for example 0.5)"
            );
            Some(error)
        }
    };
    let start = Instant::now();
    let (field, timings, meshes) = match (args.formulation, mesh_error) {
        (Formulation::Classic, Some(error)) => {
            let (f, t, b) = MeshSlices::new(ctx)?.field(&mesh, &grid, args.clamp, error)?;
            (f, t, Some(b))
        }
        (Formulation::Classic, None) => {
            let (f, t) = SliceRasterizer::new(ctx)?.field(&mesh, &grid, args.clamp)?;
            (f, t, None)
        }
        (Formulation::Compute, _) => {
            let (f, t) = ComputeField::new(ctx)?.field(&mesh, &grid, args.clamp)?;
            (f, t, None)
        }
    };
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    // The meshes against the exact slices, in voxels.
    let against_exact = match &meshes {
        Some(bound) => {
            let start = Instant::now();
            let (exact, _) = SliceRasterizer::new(ctx)?.field(&mesh, &grid, args.clamp)?;
            let exact_ms = start.elapsed().as_secs_f64() * 1e3;
            Some(MeshCheck::of(&field, &exact, bound, exact_ms))
        }
        None => None,
    };
    let check = if args.check {
        let reference = field_reference::brute_force(&mesh, &grid, args.clamp);
        let error = field
            .values
            .iter()
            .zip(&reference.values)
            .map(|(&a, &b)| (a as f64 - b as f64).abs())
            .fold(0.0, f64::max);
        Some(error)
    } else {
        None
    };
    files::write_npy(&args.npy, &grid.shape(), &field.values)?;
    let (lo, hi) = field
        .values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if json {
        let report = json!({
            "renderer": renderer(ctx),
            "formulation": format!("{:?}", args.formulation).to_lowercase(),
            "triangles": mesh.triangles.len(),
            "resolution": grid.n,
            "shape": grid.shape(),
            "origin": grid.origin.to_array(),
            "spacing": vec![grid.spacing; 3],
            "margin": margin,
            "clamp": args.clamp,
            "min": lo,
            "max": hi,
            "max_error_vs_cpu": check,
            "timings_ms": {"passes": timings.passes_ms, "readback": timings.readback_ms,
                           "upload": timings.upload_ms, "total_wall": wall_ms},
            "method": if meshes.is_some() { "mesh" } else { "exact" },
            "triangles_drawn": timings.triangles_drawn,
            "mesh": against_exact.as_ref().map(|c| json!({
                "asked_error_voxels": c.bound.asked_voxels,
                "tessellation_bound_voxels": c.bound.tessellation_voxels,
                "coverage_voxels": c.bound.coverage_voxels,
                "features": {"vertices": c.bound.features[0], "edges": c.bound.features[1],
                             "faces": c.bound.features[2]},
                "max_error_vs_exact_voxels": c.max,
                "mean_error_vs_exact_voxels": c.mean,
                "lowest_vs_exact_voxels": c.lowest,
                "within_bound": c.within,
                "exact_slices_wall_ms": c.exact_ms,
            })),
            "npy": args.npy,
        });
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {}", renderer(ctx));
    println!(
        "{}^3 voxels of side {} from {:?} (margin {margin}{}); distances {lo} .. {hi}",
        grid.n,
        grid.spacing,
        grid.origin.to_array(),
        args.clamp
            .map_or(String::new(), |d| format!(", clamped at {d}"))
    );
    if let Some(c) = &against_exact {
        println!(
            "Hoff's distance meshes ({} vertices, {} edges, {} faces, {} triangles drawn, \
             {wall_ms:.0} ms; the exact slices {:.0} ms): against the exact field max {:.4} \
             and mean {:.4} voxels, lowest {:.4} ({} the bound [-{:.4}, +{:.4}]: tessellation \
             {:.4} of the asked {}, rasterizer coverage {:.4})",
            c.bound.features[0],
            c.bound.features[1],
            c.bound.features[2],
            timings.triangles_drawn,
            c.exact_ms,
            c.max,
            c.mean,
            c.lowest,
            if c.within { "within" } else { "BEYOND" },
            c.tolerance.0,
            c.tolerance.1,
            c.bound.tessellation_voxels,
            c.bound.asked_voxels,
            c.bound.coverage_voxels,
        );
    }
    if let Some(e) = check {
        println!("largest difference from brute force on the CPU: {e:.3e}");
    }
    println!("written to {}", args.npy.display());
    if let Some(c) = against_exact.filter(|c| !c.within) {
        anyhow::bail!(
            "the distance meshes left their bound: {:.4} .. {:.4} voxels from the exact field",
            c.lowest,
            c.max
        );
    }
    Ok(())
}

/// The distance meshes' field against the exact slices (voxels).
struct MeshCheck {
    bound: MeshBound,
    /// Largest and mean |mesh - exact|, and the lowest mesh - exact.
    max: f64,
    mean: f64,
    lowest: f64,
    tolerance: (f64, f64),
    within: bool,
    exact_ms: f64,
}

impl MeshCheck {
    fn of(
        meshes: &DistanceField,
        exact: &DistanceField,
        bound: &MeshBound,
        exact_ms: f64,
    ) -> MeshCheck {
        let error = bound.compare(meshes, exact);
        MeshCheck {
            bound: bound.clone(),
            max: error.max(),
            mean: error.mean,
            lowest: error.lowest,
            tolerance: error.tolerance,
            within: error.within(),
            exact_ms,
        }
    }
}

pub fn swept_volume(args: &SweptVolumeArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    files::check_output(
        "--out",
        &args.out,
        &[&args.model, &args.path],
        args.force,
        &["obj"],
    )?;
    let mesh = load(&args.model)?;
    let path = Path3::load(&args.path)?;
    let options = Options {
        resolution: args.resolution,
        poses: args.poses,
        epsilon: args.epsilon,
    };
    let start = Instant::now();
    let swept = swept_volume::sweep(ctx, &mesh, &path, options)
        .with_context(|| format!("sweeping model {}", args.model.display()))?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    write_obj(&swept.surface.mesh, &args.out)?;
    let s = &swept.surface;
    if json {
        let report = json!({
            "renderer": renderer(ctx),
            "resolution": swept.grid.n,
            "volume": s.volume,
            "euler_characteristic": s.topology.euler_characteristic,
            "genus": s.topology.genus,
            "manifold": s.topology.is_manifold(),
            "watertight": s.watertight(),
            "topology": s.topology,
            "vertices": s.mesh.positions.len(),
            "triangles": s.mesh.triangles.len(),
            "poses": args.poses,
            "epsilon": swept.epsilon,
            "primitives": {"face_triangles": swept.primitives.face_triangles,
                           "ruled_triangles": swept.primitives.ruled_triangles,
                           "most_splits": swept.primitives.most_splits},
            "grid": {"origin": swept.grid.origin.to_array(), "spacing": swept.grid.spacing,
                     "margin": swept.grid.margin},
            "field_clamp": swept.clamp,
            "outside_voxels": swept.classification.outside_voxels,
            "segment_tests": swept.classification.segment_tests,
            "timings_ms": {"primitives": swept.timings.primitives_ms,
                           "field_passes_gpu": swept.timings.field.passes_ms,
                           "field_readback": swept.timings.field.readback_ms,
                           "field_wall": swept.timings.field_wall_ms,
                           "classify": swept.timings.classify_ms,
                           "extract": swept.timings.extract_ms,
                           "total_wall": wall_ms},
            "out": args.out,
        });
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {}", renderer(ctx));
    println!(
        "swept volume at {}^3: volume {}, {}, {} triangles, written to {}",
        swept.grid.n,
        s.volume,
        describe_topology(&s.topology),
        s.mesh.triangles.len(),
        args.out.display()
    );
    Ok(())
}

/// `V - E + F` and the genus for a manifold surface, else what stops it being one (of the
/// mesh as written, welded by position).
fn describe_topology(t: &swept_volume::topology::Topology) -> String {
    match (t.euler_characteristic, t.genus) {
        (Some(chi), Some(genus)) => format!(
            "a closed 2-manifold of {} component(s), V - E + F = {chi}, genus {genus}",
            t.components
        ),
        _ => format!(
            "not a closed 2-manifold ({} boundary, {} misoriented, {} non-manifold edges, {} \
             non-manifold vertices, {} zero-area triangles): no Euler characteristic",
            t.boundary_edges,
            t.misoriented_edges,
            t.non_manifold_edges,
            t.non_manifold_vertices,
            t.zero_area_triangles
        ),
    }
}
