//! The command line's commands, one file per paper (and `mesh`): argument parsing, reading
//! and writing the user's files, printing. The algorithms they call live in the library; the
//! `*-bench` commands all go through [`classic_gpgpu::report::bench_command`].

pub mod collide;
pub mod crowd;
pub mod lecture3;
pub mod mass;
pub mod mesh;
pub mod mlp;
pub mod profile;
