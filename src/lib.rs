//! # classic-gpgpu
//!
//! The GPGPU papers of the 2007 tutorial "General Purpose Computation using Graphics
//! Processing Units", reproduced through their original graphics-pipeline formulation:
//! OpenGL (through `glow`), shaders in GLSL, on a headless EGL context.
//!
//! Layers, and which way the arrows point: the binary (`main.rs` and its `cli/`, which parse
//! arguments and print) -> the rooms it runs: [`report`] (the papers' reproduction), the
//! course ([`learn`]: the lessons and their guide), [`compare`], [`selftest`] and [`view`]
//! (the live viewer) -> the paper modules ([`collide`], [`crowd`], [`mlp`], [`mass`]) and the
//! tutorial's lectures ([`lecture1`], [`lecture3`]) -> [`mesh`], [`gl`]. The page layer
//! ([`page`]: HTML, plots, the folder writer) sits under report, course and `compare`;
//! [`timing`], [`files`] and [`values`] (the ranges of the command line's numbers) under
//! everything. A paper module is the algorithm alone: no
//! command line, no report, no other paper. Only [`gl`] calls OpenGL or EGL, and it alone
//! holds the code the compiler cannot check (raw GL calls): `unsafe` is denied everywhere else.

#![deny(unsafe_code)]

pub mod collide;
pub mod compare;
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
pub mod page;
pub mod report;
pub mod selftest;
// How timings are repeated, summarised and judged: used by the papers' races, the report and
// the course.
pub mod timing;
// The one typed layer for the numbers options take: ranges, checks, messages.
pub mod values;
pub mod view;
