//! The paper's test objects [Table 1] by name, and OBJ files, for the CLI and the benchmark.

use crate::mesh::{self, Mesh};
use std::path::Path;

/// The objects of Table 1, in the paper's order.
pub const PAPER_OBJECTS: [&str; 7] = ["cube", "sphere", "teapot", "torus", "knot", "bunny", "pipe"];

/// One of [`PAPER_OBJECTS`] at the paper's size (the mesh module's generators), or `None`.
pub fn paper_object(name: &str) -> Option<Mesh> {
    Some(match name {
        "cube" => mesh::cube(2.0),
        "sphere" => mesh::uv_sphere(1.0, 30, 15),
        "teapot" => mesh::teapot(5),
        "torus" => mesh::torus(1.0, 0.4, 31, 31),
        "knot" => mesh::torus_knot(&mesh::TorusKnot::default()),
        "bunny" => mesh::load_bunny(),
        "pipe" => mesh::pipe(&mesh::Pipe::default()),
        _ => return None,
    })
}

/// A paper object by name, else an OBJ file. Errors name the input and the problem.
pub fn load(model: &str) -> Result<Mesh, String> {
    if let Some(mesh) = paper_object(model) {
        return Ok(mesh);
    }
    let path = Path::new(model);
    if !path.exists() {
        return Err(format!(
            "model '{model}': no such file, and not one of the paper's objects ({})",
            PAPER_OBJECTS.join(", ")
        ));
    }
    let mesh = mesh::load_obj(path).map_err(|e| e.to_string())?;
    if mesh.triangles.is_empty() {
        return Err(format!("model '{model}': the file has no triangles"));
    }
    if mesh.positions.iter().any(|p| !p.is_finite()) {
        return Err(format!(
            "model '{model}': a vertex has a non-finite coordinate"
        ));
    }
    Ok(mesh)
}
