//! `classic-gpgpu mesh`: check an OBJ the way the papers' commands will read it, and write
//! the papers' test objects as OBJ files.

use anyhow::bail;
use classic_gpgpu::mass::models;
use classic_gpgpu::mesh::{generate, load_obj, retessellate, write_obj, Mesh, TorusKnot};
use serde_json::json;
use std::path::PathBuf;

/// `--triangles`: refining holds the mesh and its edge map, about 128 bytes a triangle.
const TRIANGLES: classic_gpgpu::values::Count = classic_gpgpu::values::ranges::triangles(128);
#[derive(Clone, Debug, clap::Subcommand)]
pub enum MeshCommand {
    /// Load an OBJ and report its counts, degenerate triangles and closedness.
    Check {
        /// The OBJ file.
        path: PathBuf,
    },
    /// Write one of the papers' test objects (at the papers' sizes) as an OBJ file.
    Generate {
        #[arg(value_enum)]
        shape: Shape,
        /// Refine to this many triangles (longest-edge splits; the surface is unchanged).
        #[arg(long, value_parser = TRIANGLES.of::<usize>())]
        triangles: Option<usize>,
        /// Where to write it.
        #[arg(long)]
        out: PathBuf,
        /// Replace the file if it exists.
        #[arg(long)]
        force: bool,
    },
}

/// The papers' test objects.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum Shape {
    /// 8 vertices, 12 triangles (paper 4, Table 1).
    Cube,
    /// UV sphere, 422 vertices, 840 triangles (paper 4).
    Sphere,
    /// 32 x 32 torus with its seam, 1024 vertices, 1922 triangles (paper 4).
    Torus,
    /// (2, 3) torus knot, 1440 vertices, 2880 triangles (paper 4).
    Knot,
    /// Newell's teapot, 821 vertices (paper 4; not watertight).
    Teapot,
    /// A thick bent pipe, 4626 vertices, 9252 triangles (paper 4).
    Pipe,
    /// The Stanford bunny shipped in assets/bunny.obj, refined to paper 4's 2557 vertices
    /// and 5110 triangles.
    Bunny,
}

impl Shape {
    pub fn mesh(self) -> Mesh {
        match self {
            Shape::Cube => generate::cube(1.0),
            Shape::Sphere => generate::uv_sphere(1.0, 30, 15),
            Shape::Torus => generate::torus(1.0, 0.4, 31, 31),
            Shape::Knot => generate::torus_knot(&TorusKnot::default()),
            Shape::Teapot => generate::teapot(5),
            Shape::Pipe => models::paper_object("pipe").expect("a paper object"),
            Shape::Bunny => models::table1_bunny(),
        }
    }
}

pub fn run(command: &MeshCommand, json: bool) -> anyhow::Result<()> {
    match command {
        MeshCommand::Check { path } => check(path, json),
        MeshCommand::Generate {
            shape,
            triangles,
            out,
            force,
        } => {
            classic_gpgpu::files::check_output("--out", out, &[], *force, &["obj"])?;
            let mut mesh = shape.mesh();
            if let Some(n) = *triangles {
                mesh = retessellate(&mesh, n)?;
                if mesh.triangle_count() != n {
                    let parity = if mesh.is_closed() && n % 2 == 1 {
                        " (a closed mesh has an even number of triangles)"
                    } else {
                        ""
                    };
                    bail!(
                        "--triangles {n}: the {} refines to {} triangles, not {n}{parity}; nothing \
                         was written",
                        format!("{shape:?}").to_lowercase(),
                        mesh.triangle_count()
                    );
                }
            }
            write_obj(&mesh, out)?;
            let summary = json!({
                "shape": format!("{shape:?}").to_lowercase(),
                "vertices": mesh.vertex_count(),
                "triangles": mesh.triangle_count(),
                "closed": mesh.is_closed(),
                "path": out.display().to_string(),
            });
            if json {
                println!("{summary}");
            } else {
                println!(
                    "wrote {}: {} vertices, {} triangles{}",
                    out.display(),
                    mesh.vertex_count(),
                    mesh.triangle_count(),
                    if mesh.is_closed() {
                        ", closed"
                    } else {
                        ", open"
                    }
                );
            }
            Ok(())
        }
    }
}

fn check(path: &std::path::Path, json: bool) -> anyhow::Result<()> {
    let mesh = load_obj(path)?;
    let report = mesh.validate();
    if json {
        let mut value = serde_json::to_value(&report)?;
        value["path"] = json!(path.display().to_string());
        value["closed"] = json!(mesh.is_closed());
        value["signed_volume"] = json!(mesh.signed_volume());
        println!("{value}");
    } else {
        println!("{}:", path.display());
        println!("{}", report.to_string().trim_end());
        println!("signed volume {:.6}", mesh.signed_volume());
    }
    if !report.is_usable() {
        bail!("{} cannot be used: {report}", path.display());
    }
    Ok(())
}
