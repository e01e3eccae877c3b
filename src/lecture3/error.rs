//! What can go wrong in lecture 3's techniques: bad input (named, with the problem), or the
//! GL layer.

use crate::gl::GlError;

/// An error of a lecture-3 technique. Bad input names the input and what is wrong with it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An input (a file, an image, a parameter) that cannot be used.
    #[error("{input}: {problem}")]
    Input { input: String, problem: String },
    /// The GL layer failed (a shader, a limit, a GL error after a pass).
    #[error(transparent)]
    Gl(#[from] GlError),
    /// A GPU result that cannot be right (a non-finite value, a traversal that did not end).
    #[error("{0}")]
    Result(String),
}

impl Error {
    /// Bad input: `input` names it (a path, `--theta`), `problem` says what is wrong.
    pub fn input(input: impl Into<String>, problem: impl Into<String>) -> Error {
        Error::Input {
            input: input.into(),
            problem: problem.into(),
        }
    }
}

/// Checks that a parameter is finite and within `lo..=hi`.
pub fn check_range(name: &str, value: f64, lo: f64, hi: f64) -> Result<(), Error> {
    if !value.is_finite() {
        return Err(Error::input(
            name,
            format!("{value} is not a finite number"),
        ));
    }
    if value < lo || value > hi {
        return Err(Error::input(
            name,
            format!("{value} is outside the allowed range {lo} to {hi}"),
        ));
    }
    Ok(())
}
