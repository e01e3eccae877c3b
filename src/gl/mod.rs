//! The only module that calls OpenGL or EGL. Everything the papers need from the graphics
//! pipeline is here as safe RAII types: a headless [`Context`], [`Texture`]s (1D and 2D, float
//! and integer formats), [`Framebuffer`]s with several colour targets (MRT) and depth/stencil,
//! [`Buffer`]s usable as vertex, index and pixel buffers (the PBO-to-VBO copy of paper 2),
//! [`Program`]s built from shader files, occlusion and timer [`query`] objects, and a [`Pass`]
//! that draws rectangles or meshes into a framebuffer with a [`DrawState`].
//!
//! On top of them sit the two GPGPU building blocks the papers share: ping-pong
//! [`reduce`]tion and depth [`peel`]ing. Beside them, for OpenGL 4.3 contexts, the compute
//! formulation ([`compute`]): [`ComputeProgram`]s over storage buffers with
//! [`AtomicCounters`], and the same reduction in work-group shared memory
//! ([`reduce_shared`]). [`dump`] writes any texture to PNG, the tutorial's
//! first debugging tip; [`profile`] shows where the time of a run goes, pass by pass.
//!
//! One door opens onto raw GL: [`learner`], for the host exercises (`examples/`), where a
//! learner writes the GL calls with glow on the recorder of [`trace`].
//!
//! GL errors and framebuffer completeness are checked after every pass when
//! [`Context::checks`] is on: always in debug builds, and in tests (which call
//! [`Context::set_checks`]) or with `CLASSIC_GPGPU_GL_CHECKS=1`.
//!
//! Uniforms are set by the names the shader files give them, and a name the program's files do
//! not declare is an error ([`Program::set`]). The files under `glsl/` follow one naming
//! convention (`u_` uniforms, `a_` attributes, `v_` varyings, `o_` outputs: `glsl/README.md`);
//! `cg_ports/` keeps the names of the papers' printed listings it ports line for line.

mod buffer;
pub mod compute;
mod context;
pub mod drawn;
pub mod dump;
mod facing;
pub mod feedback;
mod finite;
mod framebuffer;
pub mod learner;
mod mesh_buffers;
pub mod npy;
mod pass;
pub mod peel;
pub mod period;
pub mod picture;
pub mod profile;
mod program;
pub mod query;
pub mod reduce;
pub mod reduce_shared;
pub mod shaders;
mod storage;
mod texture;
pub mod trace;
mod uniforms;
pub mod window;

pub use buffer::{AttribType, Buffer, BufferUsage, VertexArray};
pub use compute::{
    memory_barrier, time_finished, Barrier, ComputeProgram, Dispatch, COMPUTE_VERSION,
};
pub use context::{
    quiet_display_probes, Context, ContextInfo, Limits, Renderer, CHECKS_ENV, RENDERER_ENV,
};
pub use facing::FragmentFacing;
pub use finite::ensure_finite;
pub use framebuffer::{Framebuffer, Rect};
pub use mesh_buffers::MeshBuffers;
pub use pass::{
    Blend, Compare, DepthTest, DrawState, Face, Pass, Primitive, StencilOp, StencilTest,
};
pub use period::PeriodGpu;
pub use program::{Program, ShaderError};
pub use query::{FragmentInvocationsQuery, OcclusionQuery, TimerQuery};
pub use shaders::ShaderSource;
pub use storage::AtomicCounters;
pub use texture::{Filter, Texture, TextureFormat, Wrap};
pub use window::GlWindow;

/// Everything that can go wrong in the GL layer, each naming what was being done.
#[derive(Debug, thiserror::Error)]
pub enum GlError {
    /// No context could be made, or it is too old.
    #[error("{0}")]
    Context(String),
    /// glGetError reported an error after a pass.
    #[error("GL error after {what}: {error}")]
    Gl { what: String, error: &'static str },
    /// A framebuffer is not complete; `status` is the GL status name.
    #[error("framebuffer {name} is incomplete: {status}")]
    Incomplete { name: String, status: &'static str },
    /// A shader failed to compile: file, line, driver log and the source around it.
    /// (Transparent, so that a chain of causes does not print the message twice.)
    #[error(transparent)]
    Shader(#[from] ShaderError),
    /// A uniform set by a name the program's files do not declare.
    #[error("program ({files}): uniform {uniform} {problem}")]
    Uniform {
        files: String,
        uniform: String,
        problem: String,
    },
    /// A program failed to link.
    #[error("program ({files}) failed to link:\n{log}")]
    Link { files: String, log: String },
    /// A request beyond the context's limits (texture size, draw buffers, ...).
    #[error("{0}")]
    Limit(String),
    /// Bad arguments: sizes that do not match, a missing attachment, ...
    #[error("{0}")]
    Invalid(String),
    /// A result read back from the GPU is NaN or infinite.
    #[error(
        "{what}: the GPU gave {value} (value {index} read back from pass '{pass}'); a result \
         must be a finite number"
    )]
    NonFinite {
        what: String,
        pass: String,
        index: usize,
        value: f64,
    },
    /// Writing a dump.
    #[error("writing {path}: {message}")]
    Io { path: String, message: String },
}

/// A shader file compiled into the binary: `shader!("glsl/reduce.frag")`.
#[macro_export]
macro_rules! shader {
    ($path:literal) => {
        $crate::gl::ShaderSource {
            name: $path,
            source: include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $path)),
        }
    };
}
