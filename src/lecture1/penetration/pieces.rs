//! Step 1, "both models are decomposed into convex pieces": here the decomposition is the
//! user's. Each `o` object or `g` group of an OBJ file is one piece (a file with neither is
//! one piece), and every piece must be a closed convex polyhedron. A piece that is not convex
//! is refused, with an error naming the piece and a face with vertices on both sides of its
//! plane: using its hull instead would silently fill its concavities and change the answer.

use crate::mesh::{parse_obj, Mesh};
use anyhow::Context as _;
use glam::DVec3;
use std::path::Path;

/// One convex piece of a model.
#[derive(Clone, Debug)]
pub struct Piece {
    /// The `o`/`g` name, or `piece K` (K from 1) when the group has none.
    pub name: String,
    /// The piece's own vertices (only those its faces use) and triangles.
    pub mesh: Mesh,
}

/// The pieces of an OBJ file, each checked ([`check_piece`]).
pub fn load_pieces(path: &Path) -> anyhow::Result<Vec<Piece>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("reading model {}", path.display()))?;
    pieces_of_obj(&text, &path.display().to_string())
}

/// The pieces of OBJ text (`source` names it in errors), each checked.
pub fn pieces_of_obj(text: &str, source: &str) -> anyhow::Result<Vec<Piece>> {
    let mesh = parse_obj(text, source).with_context(|| format!("model {source}"))?;
    let groups = face_groups(text);
    let counted: usize = groups.iter().map(|g| g.1).sum();
    anyhow::ensure!(
        counted == mesh.triangles.len(),
        "model {source}: its faces make {} triangles, but its groups count {counted}",
        mesh.triangles.len()
    );
    let mut pieces = Vec::new();
    let mut first = 0;
    for (k, (name, count)) in groups.into_iter().enumerate() {
        if count == 0 {
            continue;
        }
        let name = name.unwrap_or_else(|| format!("piece {}", k + 1));
        let piece = Piece {
            name,
            mesh: compact(&mesh, first..first + count),
        };
        first += count;
        check_piece(&piece).with_context(|| format!("model {source}"))?;
        pieces.push(piece);
    }
    Ok(pieces)
}

/// Pieces made in code (tests, generated scenes), each checked.
pub fn pieces_of_meshes(model: &str, meshes: &[Mesh]) -> anyhow::Result<Vec<Piece>> {
    anyhow::ensure!(!meshes.is_empty(), "model {model}: it has no pieces");
    meshes
        .iter()
        .enumerate()
        .map(|(k, mesh)| {
            let piece = Piece {
                name: format!("piece {}", k + 1),
                mesh: mesh.clone(),
            };
            check_piece(&piece).with_context(|| format!("model {model}"))?;
            Ok(piece)
        })
        .collect()
}

/// Each group's name (from its `o`/`g` line) and number of triangles, in file order; faces
/// before the first `o`/`g` line form an unnamed group. A face of `n` corners is `n - 2`
/// triangles (the loader fans it).
fn face_groups(text: &str) -> Vec<(Option<String>, usize)> {
    let mut groups: Vec<(Option<String>, usize)> = vec![(None, 0)];
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("o") | Some("g") => {
                let name = words.collect::<Vec<_>>().join(" ");
                groups.push(((!name.is_empty()).then_some(name), 0));
            }
            Some("f") => {
                let corners = words.count();
                if let Some(last) = groups.last_mut() {
                    last.1 += corners.saturating_sub(2);
                }
            }
            _ => {}
        }
    }
    groups
}

/// The triangles `range` of `mesh` with only the vertices they use.
fn compact(mesh: &Mesh, range: std::ops::Range<usize>) -> Mesh {
    let mut index = std::collections::HashMap::new();
    let mut positions = Vec::new();
    let triangles = mesh.triangles[range]
        .iter()
        .map(|tri| {
            tri.map(|v| {
                *index.entry(v).or_insert_with(|| {
                    positions.push(mesh.positions[v as usize]);
                    (positions.len() - 1) as u32
                })
            })
        })
        .collect();
    Mesh::new(positions, triangles)
}

/// A piece must be finite, closed (every edge shared by two oppositely oriented triangles, as
/// the rest of the project asks of solids), one part with volume, and convex: every vertex on
/// the inner side of every face's plane, within a relative tolerance of 1e-5 of its size
/// (fp32 coordinates).
pub fn check_piece(piece: &Piece) -> anyhow::Result<()> {
    let name = &piece.name;
    let mesh = &piece.mesh;
    mesh.check(name).map_err(|e| anyhow::anyhow!("{e}"))?;
    let closed = mesh.closedness();
    anyhow::ensure!(
        closed.faces > 0,
        "piece '{name}' has no triangle with three distinct vertices (every one of its {} \
         triangles repeats a vertex position): it bounds no volume; each piece must be a \
         closed convex polyhedron",
        mesh.triangles.len()
    );
    anyhow::ensure!(
        closed.is_closed(),
        "piece '{name}' is not a closed surface ({} boundary, {} non-manifold and {} \
         misoriented edges): each piece must be a closed convex polyhedron",
        closed.boundary_edges,
        closed.non_manifold_edges,
        closed.misoriented_edges
    );
    anyhow::ensure!(
        closed.components == 1,
        "piece '{name}' has {} separate parts: give each convex part its own `o` or `g` group",
        closed.components
    );
    let size = mesh.bounds().size().max_element() as f64;
    let volume = mesh.signed_volume();
    anyhow::ensure!(
        volume.abs() > 1e-9 * size.powi(3) && size > 0.0,
        "piece '{name}' is flat (no volume): each piece must be a solid convex polyhedron"
    );
    let outward = if volume > 0.0 { 1.0 } else { -1.0 };
    let tolerance = 1e-5 * size;
    let points: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| points[v as usize]);
        let normal = (b - a).cross(c - a) * outward;
        let length = normal.length();
        if length <= 1e-12 * size * size {
            continue; // a degenerate triangle has no plane
        }
        let normal = normal / length;
        if let Some((v, p)) = points
            .iter()
            .enumerate()
            .find(|(_, p)| normal.dot(**p - a) > tolerance)
        {
            anyhow::bail!(
                "piece '{name}' is not convex: vertex {v} ({:.6}, {:.6}, {:.6}) lies {:.3e} \
                 outside the plane of its triangle {t}; split it into convex pieces, one \
                 `o` or `g` group each",
                p.x,
                p.y,
                p.z,
                normal.dot(*p - a)
            );
        }
    }
    Ok(())
}
