//! Wavefront OBJ reading (through `tobj`) and writing, positions only.
//!
//! Reading keeps the file's face order: triangle `t` of the mesh is the `t`-th triangle
//! of the file's `f` lines, each polygon fanned from its first corner (`1 2 3 4` gives
//! `1 2 3` and `1 3 4`), so ids match the file. All objects and groups of a file become
//! one mesh, and vertex `k` of the mesh is the file's `k`-th `v` line (vertices no face
//! uses are kept; [`Mesh::validate`] counts them). Texture coordinates, normals,
//! materials and `l`/`p` elements are ignored.
//!
//! Errors name the file and, where it can be found, the line: `tobj` reports what is
//! wrong but not where, so on failure the text is scanned again for the first line with
//! that problem.

use std::path::Path;

use glam::Vec3;

use super::error::Location;
use super::{Mesh, MeshError};

/// The Stanford bunny of `assets/bunny.obj` (npm `bunny` 1.0.1, public domain): closed,
/// genus 0, 1839 vertices and 3674 triangles, counter-clockwise outward. Built into the
/// binary, so it needs no file at run time.
pub fn load_bunny() -> Mesh {
    const BUNNY: &str = include_str!("../../assets/bunny.obj");
    parse_obj(BUNNY, "assets/bunny.obj").expect("the shipped bunny is a valid OBJ (tested)")
}

/// Reads an OBJ file into one mesh (see the module documentation for what is kept).
pub fn load_obj(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|io| MeshError::Io {
        path: path.to_owned(),
        io,
    })?;
    let source = path.display().to_string();
    parse_obj(&obj_text(&bytes, &source)?, &source)
}

/// The file as text. OBJ is ASCII in practice, but exporters write names and comments in
/// other encodings: a line that is not UTF-8 is accepted when it is a comment (its text is
/// never read) and is an error naming its line otherwise.
fn obj_text(bytes: &[u8], source: &str) -> Result<String, MeshError> {
    if let Ok(text) = std::str::from_utf8(bytes) {
        return Ok(text.to_owned());
    }
    let mut text = String::with_capacity(bytes.len());
    for (i, line) in bytes.split(|&b| b == b'\n').enumerate() {
        match std::str::from_utf8(line) {
            Ok(line) => text.push_str(line),
            Err(_) if line.trim_ascii_start().starts_with(b"#") => text.push('#'),
            Err(e) => {
                return Err(MeshError::Malformed {
                    at: Location {
                        source: source.to_owned(),
                        line: Some(i + 1),
                    },
                    reason: format!("byte {} of the line is not UTF-8 text", e.valid_up_to() + 1),
                    text: Some(String::from_utf8_lossy(line).into_owned()),
                })
            }
        }
        text.push('\n');
    }
    Ok(text)
}

/// Parses OBJ text; `source` names it in errors (a file name, usually).
pub fn parse_obj(text: &str, source: &str) -> Result<Mesh, MeshError> {
    // A byte-order mark is not part of the first line's keyword.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let at = |line: Option<usize>| Location {
        source: source.to_owned(),
        line,
    };
    let models = match run_tobj(text) {
        Ok(models) => models,
        Err(e) => return Err(locate_tobj_error(e, text, source)),
    };
    // tobj drops faces with fewer than three corners, which would shift the ids of every
    // later triangle: reject them.
    if let Some((line, content)) = first_short_face(text) {
        return Err(MeshError::Malformed {
            at: at(Some(line)),
            reason: "a face needs at least three vertices".into(),
            text: Some(content.to_owned()),
        });
    }
    if let Some(err) = first_non_finite_vertex(text, source) {
        return Err(err);
    }
    let mesh = in_file_vertex_order(&models, text).unwrap_or_else(|| merge_models(&models));
    if mesh.triangles.is_empty() || mesh.positions.is_empty() {
        return Err(MeshError::Empty {
            at: at(None),
            vertices: vertex_lines(text).count(),
            triangles: mesh.triangles.len(),
        });
    }
    Ok(mesh)
}

/// tobj's models as one mesh, in tobj's vertex numbering.
fn merge_models(models: &[tobj::Model]) -> Mesh {
    let mut mesh = Mesh::default();
    for model in models {
        let base = mesh.positions.len() as u32;
        let m = &model.mesh;
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        mesh.triangles.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]].map(|i| i + base)),
        );
    }
    mesh
}

/// tobj's triangles over the file's own vertex list, so that vertex `k` is the file's
/// `k`-th `v` line (unused ones included). tobj numbers vertices in the order faces
/// first use them; replaying that order maps its numbers back to the file's. `None` if
/// the replay does not agree with tobj (then its numbering is kept).
fn in_file_vertex_order(models: &[tobj::Model], text: &str) -> Option<Mesh> {
    let [model] = models else { return None };
    let file_positions: Vec<Vec3> = vertex_lines(text)
        .map(|(_, args)| vertex_position(&args))
        .collect();
    let mut first_use: Vec<u32> = Vec::new();
    let mut seen = vec![false; file_positions.len()];
    let mut defined = 0usize;
    for (_, keyword, args, _) in records(text) {
        match keyword {
            "v" => defined += 1,
            "f" => {
                for index in args.iter().filter_map(|c| parse_corner(c)) {
                    let k = if index < 0 {
                        defined as i64 + index
                    } else {
                        index - 1
                    };
                    let k = usize::try_from(k).ok().filter(|&k| k < seen.len())?;
                    if !std::mem::replace(&mut seen[k], true) {
                        first_use.push(k as u32);
                    }
                }
            }
            _ => {}
        }
    }
    let tobj_positions = &model.mesh.positions;
    let agrees = first_use.len() * 3 == tobj_positions.len()
        && first_use
            .iter()
            .zip(tobj_positions.chunks_exact(3))
            .all(|(&k, p)| {
                file_positions[k as usize].to_array().map(f32::to_bits)
                    == [p[0], p[1], p[2]].map(f32::to_bits)
            });
    if !agrees {
        return None;
    }
    let triangles = model
        .mesh
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]].map(|i| first_use[i as usize]))
        .collect();
    Some(Mesh::new(file_positions, triangles))
}

/// The position of a valid `v` line, divided by its `w` if it has one (as tobj does).
fn vertex_position(args: &[&str]) -> Vec3 {
    let number = |k: usize| args.get(k).and_then(|a| a.parse::<f32>().ok());
    let mut xyz = [0, 1, 2].map(|k| number(k).unwrap_or(f32::NAN));
    if args.len() == 4 {
        let w = number(3).unwrap_or(1.0);
        xyz.iter_mut().for_each(|c| *c /= w);
    }
    Vec3::from(xyz)
}

/// Writes `mesh` as OBJ: one `v` line per position (shortest text that reads back to
/// the same f32), one `f` line per triangle, 1-based.
pub fn write_obj(mesh: &Mesh, path: impl AsRef<Path>) -> Result<(), MeshError> {
    let path = path.as_ref();
    crate::files::write_bytes(path, to_obj_string(mesh, "").as_bytes()).map_err(|e| {
        MeshError::Write {
            path: path.to_owned(),
            io: std::io::Error::other(format!("{e:#}")),
        }
    })
}

/// The OBJ text of `mesh`, after `header` written as `#` comment lines (none if empty).
pub fn to_obj_string(mesh: &Mesh, header: &str) -> String {
    use std::fmt::Write;
    let mut out = String::with_capacity(32 * (mesh.positions.len() + mesh.triangles.len()));
    for line in header.lines() {
        let _ = writeln!(out, "# {line}");
    }
    for p in &mesh.positions {
        let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
    }
    for [a, b, c] in &mesh.triangles {
        let _ = writeln!(out, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    out
}

/// tobj on the text with its grouping lines blanked, so that all faces land in one
/// model in file order (tobj would otherwise give each object, group and material its
/// own model with its own vertex numbering). Blanking keeps the line count.
fn run_tobj(text: &str) -> Result<Vec<tobj::Model>, tobj::LoadError> {
    let mut flat = String::with_capacity(text.len());
    for line in text.lines() {
        let keyword = line.split_whitespace().next().unwrap_or("");
        if !matches!(keyword, "o" | "g" | "usemtl" | "mtllib") {
            flat.push_str(line);
        }
        flat.push('\n');
    }
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) = tobj::load_obj_buf(&mut flat.as_bytes(), &options, |_| {
        Err(tobj::LoadError::GenericFailure) // no `mtllib` line reaches tobj
    })?;
    Ok(models)
}

/// Turns a tobj error into ours, with the first line that shows the problem.
fn locate_tobj_error(e: tobj::LoadError, text: &str, source: &str) -> MeshError {
    use tobj::LoadError as E;
    let found = match e {
        E::PositionParseError | E::ScalingByZeroError | E::ColorParseError => {
            first_line_where(text, |kw, args| kw == "v" && !vertex_line_ok(args))
        }
        E::NormalParseError => first_line_where(text, |kw, args| kw == "vn" && !floats_ok(args, 3)),
        E::TexcoordParseError => {
            first_line_where(text, |kw, args| kw == "vt" && !floats_ok(args, 2))
        }
        E::FaceParseError => first_line_where(text, |kw, args| {
            matches!(kw, "f" | "l") && args.iter().any(|c| parse_corner(c).is_none())
        }),
        E::FaceVertexOutOfBounds => {
            if let Some(err) = first_out_of_range_face(text, source) {
                return err;
            }
            None
        }
        _ => None,
    };
    let (line, content) = found.map_or((None, None), |(n, s)| (Some(n), Some(s.to_owned())));
    MeshError::Malformed {
        at: Location {
            source: source.to_owned(),
            line,
        },
        reason: e.to_string(),
        text: content,
    }
}

/// Lines as (1-based number, keyword, arguments).
fn records(text: &str) -> impl Iterator<Item = (usize, &str, Vec<&str>, &str)> {
    text.lines().enumerate().filter_map(|(i, line)| {
        let mut words = line.split_whitespace();
        let keyword = words.next()?;
        Some((i + 1, keyword, words.collect(), line))
    })
}

fn first_line_where(text: &str, bad: impl Fn(&str, &[&str]) -> bool) -> Option<(usize, &str)> {
    records(text)
        .find(|(_, kw, args, _)| bad(kw, args))
        .map(|(n, _, _, line)| (n, line))
}

fn vertex_lines(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    records(text)
        .filter(|(_, kw, _, _)| *kw == "v")
        .map(|(n, _, args, _)| (n, args))
}

fn floats_ok(args: &[&str], n: usize) -> bool {
    args.len() >= n && args[..n].iter().all(|a| a.parse::<f32>().is_ok())
}

/// `v x y z`, `v x y z w` (w nonzero) or `v x y z r g b`, as tobj accepts them.
fn vertex_line_ok(args: &[&str]) -> bool {
    let all_floats = args.iter().all(|a| a.parse::<f32>().is_ok());
    match args.len() {
        3 => all_floats,
        6 => floats_ok(args, 3), // tobj skips colours it cannot read
        4 => all_floats && args[3].parse::<f32>() != Ok(0.0),
        _ => false,
    }
}

/// The position index of a face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`, as written.
fn parse_corner(corner: &str) -> Option<i64> {
    let mut parts = corner.split('/');
    let v = parts.next()?.parse::<i64>().ok()?;
    let rest: Vec<&str> = parts.collect();
    let rest_ok = rest.len() <= 2
        && rest
            .iter()
            .all(|p| p.is_empty() || p.parse::<i64>().is_ok());
    rest_ok.then_some(v)
}

fn first_short_face(text: &str) -> Option<(usize, &str)> {
    first_line_where(text, |kw, args| kw == "f" && args.len() < 3)
}

/// A coordinate that parses but is NaN or infinite (Rust reads `nan` and `inf`).
fn first_non_finite_vertex(text: &str, source: &str) -> Option<MeshError> {
    vertex_lines(text)
        .enumerate()
        .find_map(|(k, (line, args))| {
            let xyz: Vec<f32> = args.iter().take(3).filter_map(|a| a.parse().ok()).collect();
            let &[x, y, z] = xyz.as_slice() else {
                return None;
            };
            (!(x.is_finite() && y.is_finite() && z.is_finite())).then(|| MeshError::NonFinite {
                at: Location {
                    source: source.to_owned(),
                    line: Some(line),
                },
                vertex: k + 1,
                x,
                y,
                z,
            })
        })
}

/// The first face corner that points at no vertex. OBJ indices start at 1; negative ones
/// count back from the last vertex defined so far.
fn first_out_of_range_face(text: &str, source: &str) -> Option<MeshError> {
    let total = vertex_lines(text).count();
    let mut seen = 0usize;
    let mut face = 0usize;
    for (line, kw, args, _) in records(text) {
        match kw {
            "v" => seen += 1,
            "f" => {
                face += 1;
                for index in args.iter().filter_map(|c| parse_corner(c)) {
                    let resolved = if index < 0 {
                        seen as i64 + index
                    } else {
                        index - 1
                    };
                    if resolved < 0 || resolved >= total as i64 {
                        return Some(MeshError::IndexOutOfRange {
                            at: Location {
                                source: source.to_owned(),
                                line: Some(line),
                            },
                            face,
                            index,
                            vertex_count: total,
                        });
                    }
                }
            }
            _ => {}
        }
    }
    None
}
