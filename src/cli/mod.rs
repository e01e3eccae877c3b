//! The command line's commands, one file per paper (and `mesh`): argument parsing, reading
//! and writing the user's files, printing. The algorithms they call live in the library; the
//! `*-bench` commands all go through [`classic_gpgpu::report::bench_command`].

pub mod assets;
pub mod claims;
pub mod collide;
pub mod compare;
pub mod crowd;
pub mod glsl;
pub mod learn;
pub mod lecture1;
pub mod lecture1_fields;
pub mod lecture3;
pub mod lecture3_light;
pub mod limits;
pub mod mass;
pub mod mesh;
pub mod mlp;
pub mod options;
pub mod paths;
pub mod period;
pub mod selftest;

/// `--formulation`: which formulation of a paper's kernels runs ("then and now"):
/// the paper's own, through the graphics pipeline (OpenGL 3.3), or compute shaders (OpenGL
/// 4.3). `mlp` names its classic formulations `faithful` and `packed` instead of `classic`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Formulation {
    /// The paper's 2007 formulation through the graphics pipeline.
    #[default]
    Classic,
    /// Compute shaders, storage buffers, shared memory and atomics (OpenGL 4.3).
    Compute,
}

impl Formulation {
    /// The name the JSON reports under `formulation`.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Classic => "classic",
            Formulation::Compute => "compute",
        }
    }
}
pub mod profile;
pub mod view;
