//! `classic-gpgpu lecture1 penetration A.obj B.obj`: the penetration depth of two models given
//! as unions of convex pieces, by rasterized Minkowski sums (`src/lecture1/penetration/`).

use classic_gpgpu::files;
use classic_gpgpu::gl::dump::picture_png;
use classic_gpgpu::gl::Context;
use classic_gpgpu::lecture1::penetration::pieces::load_pieces;
use classic_gpgpu::lecture1::penetration::{
    exit_panels, Formulation, Options, PenetrationQuery, DEFAULT_RESOLUTION,
};
use classic_gpgpu::values::{ranges, Count};
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormulationArg {
    /// Rasterized back faces, MAX blending, occlusion queries (OpenGL 3.3).
    Classic,
    /// One compute invocation per ray (OpenGL 4.3).
    Compute,
}

#[derive(clap::Args, Debug)]
pub struct PenetrationArgs {
    /// Model A (OBJ): each `o` object or `g` group is one convex piece (a file with neither
    /// is one piece). A piece that is not a closed convex polyhedron is refused (its hull is
    /// not used instead).
    pub a: PathBuf,
    /// Model B (OBJ), pieces as for A.
    pub b: PathBuf,
    /// Texels per side of each of the six cube faces around the origin.
    #[arg(long, default_value_t = DEFAULT_RESOLUTION,
          value_parser = Count { least: 2, ..ranges::TEXTURE_SIDE }.of::<usize>())]
    pub resolution: usize,
    /// Closest-point query on the classic pipeline or as a compute pass.
    #[arg(long, value_enum, default_value_t = FormulationArg::Classic)]
    pub formulation: FormulationArg,
    /// Write the T buffer (where each pixel's ray leaves the union of the sums), the six
    /// cube faces with one shared scale, as a PNG.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Write the T buffer as .npy: shape [N, 6N], float32, bottom row first, faces +x -x +y
    /// -y +z -z side by side.
    #[arg(long)]
    pub npy: Option<PathBuf>,
    /// Overwrite existing output files (never an input).
    #[arg(long)]
    pub force: bool,
}

pub fn run(args: &PenetrationArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let inputs = [args.a.as_path(), args.b.as_path()];
    if let Some(png) = &args.png {
        files::check_output("the PNG", png, &inputs, args.force, &["png"])?;
    }
    if let Some(npy) = &args.npy {
        files::check_output("--npy", npy, &inputs, args.force, &["npy"])?;
    }
    let a = load_pieces(&args.a)?;
    let b = load_pieces(&args.b)?;
    let query = PenetrationQuery::new(ctx)?;
    let options = Options {
        resolution: args.resolution,
        formulation: match args.formulation {
            FormulationArg::Classic => Formulation::Classic,
            FormulationArg::Compute => Formulation::Compute,
        },
        keep_exits: args.png.is_some() || args.npy.is_some(),
    };
    let result = query.run(&a, &b, &options)?;
    let n = result.resolution;
    if let Some(exits) = &result.exits {
        if let Some(png) = &args.png {
            let panels = exit_panels(exits, n);
            let width = (6 * n as u32 * 2).clamp(640, 1536);
            picture_png(&panels, (width, width / 2), png)?;
        }
        if let Some(npy) = &args.npy {
            files::write_npy(npy, &[n, 6 * n], exits)?;
        }
    }
    let renderer = ctx.info().renderer_line();
    if json {
        let mut report = serde_json::to_value(&result)?;
        report["renderer"] = json!(renderer);
        report["piece_names"] = json!([
            a.iter().map(|p| p.name.clone()).collect::<Vec<_>>(),
            b.iter().map(|p| p.name.clone()).collect::<Vec<_>>()
        ]);
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {renderer}");
    println!(
        "{} x {} pieces, {} Minkowski sums ({} kept), {} cube texels per face, {:?} \
         formulation, {} passes",
        result.pieces[0],
        result.pieces[1],
        result.sums,
        result.sums_kept,
        n,
        result.formulation,
        result.passes
    );
    match result.direction {
        None => println!("no overlap: depth 0"),
        Some(d) => {
            println!(
                "depth {} along ({:.6}, {:.6}, {:.6}) (B moves so to touch A)",
                result.depth, d[0], d[1], d[2]
            );
            println!(
                "rasterized upper bound {} (refinement: {} planes within it, {} candidates{})",
                result.upper_bound,
                result.refinement.planes,
                result.refinement.candidates,
                if result.refinement.complete {
                    ""
                } else {
                    ", too many planes for all combinations: an upper bound"
                }
            );
        }
    }
    Ok(())
}
