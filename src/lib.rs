//! # classic-gpgpu
//!
//! The GPGPU papers of the 2007 tutorial "General Purpose Computation using Graphics
//! Processing Units", reproduced through their original graphics-pipeline formulation:
//! OpenGL (through `glow`), shaders in GLSL, on a headless EGL context.
//!
//! Layers, and which way the arrows point: the binary (`main.rs` and its `cli/`, which parse
//! arguments and print) -> [`report`] and [`view`] (the live viewer) -> the four paper modules ([`collide`], [`crowd`],
//! [`mlp`], [`mass`]) and the tutorial's [`lecture3`] -> [`mesh`], [`gl`]. A paper module is
//! the algorithm alone: no command line, no report, no other paper. Only [`gl`] calls OpenGL
//! or EGL, and it alone holds the code the compiler cannot check (raw GL calls): `unsafe` is
//! denied everywhere else.

#![deny(unsafe_code)]

pub mod collide;
pub mod crowd;
pub mod files;
// Raw GL and EGL calls, behind safe RAII types; GL ids never leave the module.
#[allow(unsafe_code)]
pub mod gl;
pub mod learn;
pub mod lecture1;
pub mod lecture3;
pub mod mass;
pub mod mesh;
pub mod mlp;
pub mod report;
// How timings are repeated, summarised and judged: used by the papers' races and the report.
pub mod timing;
pub mod view;
