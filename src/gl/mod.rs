//! The only module that calls OpenGL or EGL (placeholder until the foundation lands).

/// A headless OpenGL context.
pub struct Context {}
