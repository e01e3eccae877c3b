//! Compute shaders (OpenGL 4.3, GLSL 430): the CUDA-era way to do what the papers did through
//! rasterization. A [`ComputeProgram`] runs a grid of work groups that read and write
//! [`Buffer`]s bound as shader storage blocks, count with atomic counters
//! ([`super::AtomicCounters`]), share data inside a work group, and make their writes
//! visible to later passes with an explicit [`memory_barrier`].
//!
//! The faithful paths keep their OpenGL 3.3 floor; everything here first asks
//! [`Context::require_compute`], which names the missing version on an older context
//! (softpipe is 3.3).

use super::program::Uniform;
use super::{Buffer, Context, GlError, Program, ShaderSource, Texture};

/// The first OpenGL version with compute shaders, storage buffers and atomic counters.
pub const COMPUTE_VERSION: (i32, i32) = (4, 3);

impl Context {
    /// Whether this context runs compute shaders (OpenGL 4.3 or newer).
    pub fn has_compute(&self) -> bool {
        self.info().gl_version >= COMPUTE_VERSION
    }

    /// `Ok` when this context runs compute shaders; otherwise an error naming `what` needed
    /// them, the version it needs and the version the context has.
    pub fn require_compute(&self, what: &str) -> Result<(), GlError> {
        if let Some(gpu) = self.period() {
            gpu.check_compute(what)?;
        }
        if self.has_compute() {
            return Ok(());
        }
        let info = self.info();
        Err(GlError::Context(format!(
            "{what} needs OpenGL {}.{} (compute shaders, shader storage buffers, atomic \
             counters), but this context is OpenGL {}.{} ({}); the classic formulation runs \
             on OpenGL 3.3",
            COMPUTE_VERSION.0,
            COMPUTE_VERSION.1,
            info.gl_version.0,
            info.gl_version.1,
            info.renderer
        )))
    }
}

/// Which earlier writes a barrier makes visible, by how later commands read them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Barrier {
    /// Storage-block reads in later shaders.
    Storage,
    /// Vertex attributes fetched from the buffer by later draws.
    VertexAttrib,
    /// Atomic counters in later shaders.
    AtomicCounter,
    /// Reads through the buffer API (`glGetBufferSubData`, copies).
    BufferUpdate,
}

impl Barrier {
    fn bit(self) -> u32 {
        match self {
            Barrier::Storage => glow::SHADER_STORAGE_BARRIER_BIT,
            Barrier::VertexAttrib => glow::VERTEX_ATTRIB_ARRAY_BARRIER_BIT,
            Barrier::AtomicCounter => glow::ATOMIC_COUNTER_BARRIER_BIT,
            Barrier::BufferUpdate => glow::BUFFER_UPDATE_BARRIER_BIT,
        }
    }
}

/// Make the incoherent writes of earlier compute passes visible to the reads named.
pub fn memory_barrier(ctx: &Context, barriers: &[Barrier]) {
    let bits = barriers.iter().fold(0, |bits, b| bits | b.bit());
    unsafe { ctx.gl().memory_barrier(bits) };
}

/// A linked compute program and its work group size (read from the driver).
pub struct ComputeProgram {
    ctx: Context,
    program: Program,
    local_size: [u32; 3],
}

impl ComputeProgram {
    /// Compile the concatenation of `parts` as a compute shader; the first file carries
    /// `#version 430`. On a context older than 4.3 this is [`Context::require_compute`]'s
    /// error, naming the files.
    pub fn new(ctx: &Context, parts: &[ShaderSource]) -> Result<ComputeProgram, GlError> {
        let names: Vec<&str> = parts.iter().map(|p| p.name).collect();
        ctx.require_compute(&format!("the compute shader {}", names.join(", ")))?;
        let program = Program::link(ctx, &[(glow::COMPUTE_SHADER, "compute", parts)])?;
        let mut size = [1i32; 3];
        let get_program_iv = ctx.inner.extra.get_program_iv.ok_or_else(|| {
            GlError::Context("this OpenGL library has no glGetProgramiv".to_string())
        })?;
        // SAFETY: COMPUTE_WORK_GROUP_SIZE writes three integers, and `size` holds three.
        unsafe {
            get_program_iv(
                program.id().0.get(),
                glow::COMPUTE_WORK_GROUP_SIZE,
                size.as_mut_ptr(),
            )
        };
        Ok(ComputeProgram {
            ctx: ctx.clone(),
            program,
            local_size: size.map(|s| s.max(1) as u32),
        })
    }

    /// The work group size the shader declares (`local_size_x/y/z`).
    pub fn local_size(&self) -> [u32; 3] {
        self.local_size
    }

    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// The underlying program (uniforms are set through it, checked by name).
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Start a dispatch named `name` (for error messages); bind its inputs, then run it.
    pub fn dispatch<'a>(&'a self, name: &'a str) -> Dispatch<'a> {
        self.ctx.gl().enter_pass(name);
        Dispatch {
            compute: self,
            name,
            textures: Vec::new(),
            storage: Vec::new(),
            counters: Vec::new(),
            error: None,
        }
    }
}

/// One dispatch of a [`ComputeProgram`]: the builder binds textures, storage buffers and
/// atomic counter buffers, sets uniforms, then runs a grid of work groups.
pub struct Dispatch<'a> {
    compute: &'a ComputeProgram,
    name: &'a str,
    textures: Vec<Texture>,
    storage: Vec<(u32, Buffer)>,
    counters: Vec<(u32, Buffer)>,
    error: Option<GlError>,
}

impl Dispatch<'_> {
    /// Bind `texture` to the sampler uniform `sampler` (the next free texture unit).
    pub fn texture(&mut self, sampler: &str, texture: &Texture) -> &mut Self {
        let unit = self.textures.len() as i32;
        self.uniform(sampler, unit);
        self.textures.push(texture.clone());
        self
    }

    /// Bind `buffer` to the storage block with `layout(binding = binding)`.
    pub fn storage(&mut self, binding: u32, buffer: &Buffer) -> &mut Self {
        self.storage.push((binding, buffer.clone()));
        self
    }

    /// Bind `buffer` to the atomic counters with `layout(binding = binding)`.
    pub fn counters(&mut self, binding: u32, buffer: &Buffer) -> &mut Self {
        self.counters.push((binding, buffer.clone()));
        self
    }

    /// Set a uniform; a name the shader does not declare is an error returned by `run`.
    pub fn uniform<U: Uniform>(&mut self, name: &str, value: U) -> &mut Self {
        if let Err(e) = self.compute.program.set(name, value) {
            self.error.get_or_insert(e);
        }
        self
    }

    /// Run `groups` work groups (x, y, z).
    pub fn run(&mut self, groups: [u32; 3]) -> Result<(), GlError> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let ctx = &self.compute.ctx;
        if let Some(gpu) = ctx.period() {
            gpu.check_compute(&format!("dispatch {}", self.name))?;
        }
        let gl = ctx.gl();
        for (axis, &count) in groups.iter().enumerate() {
            let max = ctx.max_work_groups(axis as u32);
            if count > max {
                return Err(GlError::Limit(format!(
                    "dispatch {} asks for {count} work groups along axis {axis}; this renderer \
                     allows {max}",
                    self.name
                )));
            }
        }
        if groups.contains(&0) {
            return Ok(());
        }
        gl.enter_pass(self.name);
        self.compute.program.bind();
        unsafe {
            for (unit, texture) in self.textures.iter().enumerate() {
                gl.active_texture(glow::TEXTURE0 + unit as u32);
                gl.bind_texture(texture.target(), Some(texture.id()));
            }
            for (binding, buffer) in &self.storage {
                gl.bind_buffer_base(glow::SHADER_STORAGE_BUFFER, *binding, Some(buffer.id()));
            }
            for (binding, buffer) in &self.counters {
                gl.bind_buffer_base(glow::ATOMIC_COUNTER_BUFFER, *binding, Some(buffer.id()));
            }
            gl.dispatch_compute(groups[0], groups[1], groups[2]);
        }
        let checked = ctx.check(&format!("dispatch {}", self.name));
        gl.leave_pass();
        checked
    }

    /// Run enough work groups along x to cover `items` invocations (one per item).
    pub fn run_over(&mut self, items: u32) -> Result<(), GlError> {
        let groups = items.div_ceil(self.compute.local_size[0]);
        self.run([groups, 1, 1])
    }

    /// [`Self::run_over`] for any number of items: split into as many dispatches as the
    /// renderer's work-group limit needs, each told its first item through the uniform
    /// `first_item` (the shader's item is `first_item + gl_GlobalInvocationID.x`).
    pub fn run_over_in_chunks(&mut self, items: u32, first_item: &str) -> Result<(), GlError> {
        let local = self.compute.local_size[0].max(1);
        let most = self.compute.ctx.max_work_groups(0).max(1) as u64 * local as u64;
        let mut first = 0u32;
        loop {
            let count = (items - first).min(most.min(u32::MAX as u64) as u32);
            self.uniform(first_item, first).run_over(count)?;
            first += count;
            if first >= items {
                return Ok(());
            }
        }
    }
}

/// Run `work` between two `glFinish` calls: its result and the wall-clock milliseconds.
/// Compute passes are timed this way: llvmpipe (Mesa 22.3) answers a TIME_ELAPSED query
/// around a dispatch with about zero (measured: 1e-6 ms for a pass that took milliseconds),
/// so the timer queries that time the classic passes would not see them.
pub fn time_finished<T>(
    ctx: &Context,
    work: impl FnOnce() -> Result<T, GlError>,
) -> Result<(T, f64), GlError> {
    ctx.finish_all();
    let start = std::time::Instant::now();
    let value = work()?;
    ctx.finish_all();
    Ok((value, start.elapsed().as_secs_f64() * 1e3))
}
