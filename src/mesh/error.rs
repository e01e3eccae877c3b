//! Errors of mesh loading and checking. Each names the input (a file path, or the name a
//! caller gave an in-memory mesh) and, where it is known, the line of the OBJ file.

use std::fmt;
use std::path::PathBuf;

/// Where a problem is: `file:line` when the line is known, else just `file`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    pub source: String,
    pub line: Option<usize>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{}", self.source, line),
            None => write!(f, "{}", self.source),
        }
    }
}

#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The OS's message is part of this error's text, not a chained source, so that it is
    /// printed once.
    #[error("{}: cannot read the mesh file: {io}", path.display())]
    Io { path: PathBuf, io: std::io::Error },

    #[error("{}: cannot write the mesh file: {io}", path.display())]
    Write { path: PathBuf, io: std::io::Error },

    /// A line the OBJ reader cannot parse. `reason` is `tobj`'s message or ours; `text`
    /// is the offending line when it was found.
    #[error("{at}: malformed OBJ ({reason}){}", quoted(text))]
    Malformed {
        at: Location,
        reason: String,
        text: Option<String>,
    },

    #[error("{at}: vertex {vertex} has a non-finite coordinate ({x}, {y}, {z})")]
    NonFinite {
        at: Location,
        vertex: usize,
        x: f32,
        y: f32,
        z: f32,
    },

    /// `face` and `vertex` are numbered as in the input: from 1 for an OBJ file (face = the
    /// `f` line's rank), from 0 for an in-memory mesh (face = the triangle id).
    #[error("{at}: face {face} uses vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        at: Location,
        face: usize,
        index: i64,
        vertex_count: usize,
    },

    #[error("{at}: the mesh is empty ({vertices} vertices, {triangles} triangles)")]
    Empty {
        at: Location,
        vertices: usize,
        triangles: usize,
    },

    #[error("{source_name}: cannot retessellate to {requested} triangles: {reason}")]
    Retessellate {
        source_name: String,
        requested: usize,
        reason: String,
    },
}

/// The longest part of an offending line an error quotes.
const QUOTE_CHARS: usize = 80;

fn quoted(text: &Option<String>) -> String {
    let Some(t) = text else {
        return String::new();
    };
    let t = t.trim();
    match t.char_indices().nth(QUOTE_CHARS) {
        Some((cut, _)) => format!(": `{}...` ({} bytes in all)", &t[..cut], t.len()),
        None => format!(": `{t}`"),
    }
}

impl MeshError {
    /// The line of the input the error points at, when known.
    pub fn line(&self) -> Option<usize> {
        match self {
            MeshError::Malformed { at, .. }
            | MeshError::NonFinite { at, .. }
            | MeshError::IndexOutOfRange { at, .. }
            | MeshError::Empty { at, .. } => at.line,
            MeshError::Io { .. } | MeshError::Write { .. } | MeshError::Retessellate { .. } => None,
        }
    }
}
