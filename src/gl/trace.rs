//! The GL call recorder (issue 39): every OpenGL call the `gl` module makes goes through
//! [`Gl`], which records it, in order and with its arguments, while a trace is on
//! ([`super::Context::trace_start`]). Enums are shown by their GL names (`GL_FRAMEBUFFER`,
//! `GL_RGBA32F`), objects by their ids, uniforms by name and value, draws with their counts.
//! A trace is grouped by the pass that made the calls: a pass's name (`fb.pass(.., name)`,
//! `program.dispatch(name)`) labels the calls from the pass's start to the end of its draw.
//!
//! Off, a call costs one test of a flag; nothing is formatted or stored.
//!
//! The wrappers keep glow's names and signatures, so a call site reads as before:
//! `ctx.gl().bind_framebuffer(glow::FRAMEBUFFER, Some(id))`. The `traced!` macro makes them
//! from one list (below `impl Gl`), one entry a call. To trace another GL call, add its entry:
//! glow's method with its parameters (and return type), then `=` and the GL function as the
//! trace names it, with what it shows of each argument (anything `Display`):
//!
//! ```text
//! fn draw_arrays(mode: u32, first: i32, count: i32)
//!     = glDrawArrays(primitive_name(mode), first, count);
//! fn create_buffer() -> Result<glow::Buffer, String> = glGenBuffers() -> |made| made_id(&made);
//! ```
//!
//! The first is recorded, then made. The second, ending in `-> |result| shown`, is made first
//! and recorded with what it gave back, as that expression shows it (a new object's id, a
//! status). The list begins with `(gl)`, the name its entries give the recorder, so that an
//! argument can be shown by one of [`Gl`]'s methods: `gl.location(location)`, a uniform by name.
//!
//! The wrappers are public for one reader: a host exercise (`examples/`), which gets this
//! recorder through the learner's door ([`super::learner`]) and writes its GL calls itself.
//! There each draw is also inspected ([`super::learner::DrawFacts`]) before it is made.

use glow::HasContext;
use std::cell::{Cell, RefCell};
use std::collections::VecDeque;
use std::rc::Rc;

/// One recorded call: `glBindFramebuffer(GL_FRAMEBUFFER, 3)`, and the pass that made it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TracedCall {
    /// The name of the pass whose calls these are, or `None` between passes.
    pub pass: Option<Rc<str>>,
    /// The GL function, e.g. `glViewport`.
    pub function: &'static str,
    /// The arguments as shown: enums by name, objects by id.
    pub args: String,
    /// What the call gave back, where that is worth showing (a new object's id, a status).
    pub result: Option<String>,
}

impl std::fmt::Display for TracedCall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}({})", self.function, self.args)?;
        match &self.result {
            Some(r) => write!(f, " -> {r}"),
            None => Ok(()),
        }
    }
}

/// The calls in runs of the same pass, in order: (the pass's name or `None`, its calls).
pub fn grouped(calls: &[TracedCall]) -> Vec<(Option<Rc<str>>, Vec<&TracedCall>)> {
    let mut groups: Vec<(Option<Rc<str>>, Vec<&TracedCall>)> = Vec::new();
    for call in calls {
        match groups.last_mut() {
            Some((pass, list)) if *pass == call.pass => list.push(call),
            _ => groups.push((call.pass.clone(), vec![call])),
        }
    }
    groups
}

/// A trace as text, one call a line, under a heading per pass.
pub fn lines(calls: &[TracedCall]) -> Vec<String> {
    let mut out = vec![if calls.len() >= MOST_CALLS {
        format!("the first {} GL calls (a trace keeps no more)", calls.len())
    } else {
        format!("{} GL calls", calls.len())
    }];
    let mut number = 0;
    for (pass, list) in grouped(calls) {
        out.push(match &pass {
            Some(name) => format!("pass '{name}':"),
            None => "between passes:".to_string(),
        });
        for call in list {
            number += 1;
            out.push(format!("  {number:>5}  {call}"));
        }
    }
    out
}

/// The calls of the first run of pass `name` in a trace.
pub fn first_pass<'a>(calls: &'a [TracedCall], name: &str) -> Vec<&'a TracedCall> {
    grouped(calls)
        .into_iter()
        .find(|(pass, _)| pass.as_deref() == Some(name))
        .map(|(_, list)| list)
        .unwrap_or_default()
}

/// The most calls one recording keeps; [`lines`] says when a trace reached it.
pub const MOST_CALLS: usize = 1_000_000;

/// glow's context with a recorder: what [`super::Context`] holds and every GL call uses.
pub struct Gl {
    raw: glow::Context,
    on: Cell<bool>,
    calls: RefCell<Vec<TracedCall>>,
    /// The pass now making calls, if any.
    pass: RefCell<Option<Rc<str>>>,
    /// The name of the uniform the next glUniform call sets (set by `Program`).
    uniform: RefCell<Option<String>>,
    /// The learner's door: inspect the state of every draw before it is made.
    inspecting: Cell<bool>,
    /// What the inspections saw, draw by draw, since they were last taken.
    draws: RefCell<Vec<super::learner::DrawFacts>>,
    /// GL errors that were pending when an inspection began: the next glGetError answers
    /// them first, so that an inspection neither hides nor invents one.
    held_errors: RefCell<VecDeque<u32>>,
}

impl Gl {
    pub(super) fn new(raw: glow::Context) -> Gl {
        Gl {
            raw,
            on: Cell::new(false),
            calls: RefCell::new(Vec::new()),
            pass: RefCell::new(None),
            uniform: RefCell::new(None),
            inspecting: Cell::new(false),
            draws: RefCell::new(Vec::new()),
            held_errors: RefCell::new(VecDeque::new()),
        }
    }

    /// The calls recorded so far in this recording.
    pub(super) fn recorded(&self) -> usize {
        self.calls.borrow().len()
    }

    /// glow's context itself, whose calls are not recorded: for the learner's door, whose
    /// checks of a learner's step must not show in the learner's trace, and nothing else.
    pub(super) fn untraced(&self) -> &glow::Context {
        &self.raw
    }

    /// Inspect every draw from now on (`true`), or no more.
    pub(super) fn set_inspecting(&self, on: bool) {
        self.inspecting.set(on);
    }

    /// The inspections of the draws made since the last call.
    pub(super) fn take_draws(&self) -> Vec<super::learner::DrawFacts> {
        std::mem::take(&mut *self.draws.borrow_mut())
    }

    /// Keep the GL errors pending now (an inspection is about to query the state).
    pub(super) fn hold_errors(&self) {
        let mut held = self.held_errors.borrow_mut();
        loop {
            // SAFETY: glGetError has no preconditions.
            let code = unsafe { self.raw.get_error() };
            if code == glow::NO_ERROR {
                break;
            }
            held.push_back(code);
        }
    }

    /// `glGetError`, not recorded: an error held by an inspection first, then GL's own.
    pub(super) unsafe fn get_error_untraced(&self) -> u32 {
        let held = self.held_errors.borrow_mut().pop_front();
        held.unwrap_or_else(|| self.raw.get_error())
    }

    /// `glGetError`, recorded: an error held by an inspection first, then GL's own.
    ///
    /// # Safety
    ///
    /// As glow's `get_error`: the context is current on this thread.
    pub unsafe fn get_error(&self) -> u32 {
        let code = self.get_error_untraced();
        if self.on.get() {
            self.push("glGetError", String::new(), Some(error_name(code)));
        }
        code
    }

    /// Start recording (an earlier recording is dropped).
    pub(super) fn start(&self) {
        self.calls.borrow_mut().clear();
        self.on.set(true);
    }

    /// Stop recording; the calls recorded since [`Gl::start`].
    pub(super) fn stop(&self) -> Vec<TracedCall> {
        self.on.set(false);
        *self.pass.borrow_mut() = None;
        std::mem::take(&mut *self.calls.borrow_mut())
    }

    pub(super) fn is_on(&self) -> bool {
        self.on.get()
    }

    /// The calls from here on are pass `name`'s.
    pub(super) fn enter_pass(&self, name: &str) {
        if self.on.get() {
            let same = self.pass.borrow().as_deref() == Some(name);
            if !same {
                *self.pass.borrow_mut() = Some(Rc::from(name));
            }
        }
    }

    /// The pass's calls have ended (after its draw or dispatch).
    pub(super) fn leave_pass(&self) {
        if self.on.get() {
            *self.pass.borrow_mut() = None;
        }
    }

    /// The next glUniform call sets the uniform `name`.
    pub(super) fn name_uniform(&self, name: &str) {
        if self.on.get() {
            *self.uniform.borrow_mut() = Some(name.to_string());
        }
    }

    /// Records `function` with the arguments `args` shows, only while a trace is on: off, the
    /// arguments are never formatted.
    fn record(&self, function: &'static str, args: impl FnOnce() -> String) {
        if self.on.get() {
            if self.inspecting.get() && DRAWS.contains(&function) {
                let call = self.recorded() + 1;
                self.hold_errors();
                let facts = super::learner::inspect_draw(&self.raw, function, call);
                self.draws.borrow_mut().push(facts);
            }
            self.push(function, args(), None);
        }
    }

    #[cold]
    fn push(&self, function: &'static str, args: String, result: Option<String>) {
        let pass = self.pass.borrow().clone();
        let mut calls = self.calls.borrow_mut();
        // A long run (a live viewer) would grow without end: the recording stops at the cap.
        if calls.len() >= MOST_CALLS {
            return;
        }
        calls.push(TracedCall {
            pass,
            function,
            args,
            result,
        });
    }

    /// A uniform's location as shown: `u_a @ 2` when the program named it.
    fn location(&self, location: Option<&glow::UniformLocation>) -> String {
        let at = at_of(location);
        match self.uniform.borrow_mut().take() {
            Some(name) => format!("{name} @ {at}"),
            None => at,
        }
    }

    pub(super) fn supported_extensions(&self) -> &std::collections::HashSet<String> {
        self.raw.supported_extensions()
    }
}

/// The calls that draw: each is inspected first when the learner's door asks.
const DRAWS: [&str; 4] = [
    "glDrawArrays",
    "glDrawArraysInstanced",
    "glDrawElements",
    "glDrawElementsInstanced",
];

/// The wrappers, from the list below: see the module's doc for an entry's form. An entry cannot
/// name `self` (macro hygiene), hence the recorder's name the list begins with.
macro_rules! traced {
    (($gl:ident)
     $(fn $name:ident($($arg:ident: $ty:ty),*) $(-> $ret:ty)?
       = $function:ident($($shown:expr),*) $(-> |$made:ident| $result:expr)?;)*) => {
        // The wrappers keep glow's signatures, however many arguments GL takes.
        #[allow(clippy::too_many_arguments)]
        impl Gl {
            $(#[doc = concat!("`", stringify!($function), "`, recorded while a trace is on: \
                glow's `", stringify!($name), "`.")]
            #[doc = ""]
            #[doc = "# Safety"]
            #[doc = ""]
            #[doc = "As glow's: the context is current on this thread, and every object \
                passed was made by it and is alive."]
            pub unsafe fn $name(&self, $($arg: $ty),*) $(-> $ret)? {
                let $gl = self;
                traced!(@call $gl, $name($($arg),*), $function($($shown),*)
                    $(-> |$made| $result)?)
            })*
        }
    };
    // Recorded, then made.
    (@call $gl:ident, $name:ident($($arg:ident),*), $function:ident($($shown:expr),*)) => {{
        $gl.record(stringify!($function), || shown(&[$(&$shown),*]));
        $gl.raw.$name($($arg),*)
    }};
    // Made, then recorded with what it gave back.
    (@call $gl:ident, $name:ident($($arg:ident),*), $function:ident($($shown:expr),*)
        -> |$made:ident| $result:expr) => {{
        let $made = $gl.raw.$name($($arg),*);
        if $gl.on.get() {
            $gl.push(stringify!($function), shown(&[$(&$shown),*]), Some($result));
        }
        $made
    }};
}

// glow's method(its parameters) -> its return = the GL function(the arguments as shown)
traced! { (gl)
    fn active_texture(unit: u32) = glActiveTexture(unit_name(unit));
    fn attach_shader(program: glow::Program, shader: glow::Shader)
        = glAttachShader(program.id(), shader.id());
    fn begin_query(target: u32, query: glow::Query) = glBeginQuery(name_of(target), query.id());
    fn begin_transform_feedback(primitive_mode: u32)
        = glBeginTransformFeedback(primitive_name(primitive_mode));
    fn bind_buffer(target: u32, buffer: Option<glow::Buffer>)
        = glBindBuffer(name_of(target), id_of(buffer));
    fn bind_buffer_base(target: u32, index: u32, buffer: Option<glow::Buffer>)
        = glBindBufferBase(name_of(target), index, id_of(buffer));
    fn bind_framebuffer(target: u32, framebuffer: Option<glow::Framebuffer>)
        = glBindFramebuffer(name_of(target), id_of(framebuffer));
    fn bind_texture(target: u32, texture: Option<glow::Texture>)
        = glBindTexture(name_of(target), id_of(texture));
    fn bind_vertex_array(vertex_array: Option<glow::VertexArray>)
        = glBindVertexArray(id_of(vertex_array));
    fn blend_equation(mode: u32) = glBlendEquation(primitive_name(mode));
    fn blend_func(src: u32, dst: u32) = glBlendFunc(factor_name(src), factor_name(dst));
    fn blit_framebuffer(src_x0: i32, src_y0: i32, src_x1: i32, src_y1: i32, dst_x0: i32,
                        dst_y0: i32, dst_x1: i32, dst_y1: i32, mask: u32, filter: u32)
        = glBlitFramebuffer(src_x0, src_y0, src_x1, src_y1, dst_x0, dst_y0, dst_x1, dst_y1,
                            hex(mask), name_of(filter));
    fn buffer_data_size(target: u32, size: i32, usage: u32)
        = glBufferData(name_of(target), size, name_of(usage));
    fn buffer_data_u8_slice(target: u32, data: &[u8], usage: u32)
        = glBufferData(name_of(target), byte_count(data.len()), name_of(usage));
    fn buffer_sub_data_u8_slice(target: u32, offset: i32, src_data: &[u8])
        = glBufferSubData(name_of(target), offset, byte_count(src_data.len()));
    fn check_framebuffer_status(target: u32) -> u32
        = glCheckFramebufferStatus(name_of(target)) -> |status| name_of(status);
    fn clear_buffer_depth_stencil(target: u32, draw_buffer: u32, depth: f32, stencil: i32)
        = glClearBufferfi(name_of(target), draw_buffer, depth, stencil);
    fn clear_buffer_f32_slice(target: u32, draw_buffer: u32, values: &[f32])
        = glClearBufferfv(name_of(target), draw_buffer, list(values));
    fn clear_buffer_u32_slice(target: u32, draw_buffer: u32, values: &[u32])
        = glClearBufferuiv(name_of(target), draw_buffer, list(values));
    fn color_mask(red: bool, green: bool, blue: bool, alpha: bool)
        = glColorMask(red, green, blue, alpha);
    fn compile_shader(shader: glow::Shader) = glCompileShader(shader.id());
    fn copy_buffer_sub_data(src_target: u32, dst_target: u32, src_offset: i32, dst_offset: i32,
                            size: i32)
        = glCopyBufferSubData(name_of(src_target), name_of(dst_target), src_offset, dst_offset,
                              size);
    fn create_buffer() -> Result<glow::Buffer, String> = glGenBuffers() -> |made| made_id(&made);
    fn create_framebuffer() -> Result<glow::Framebuffer, String>
        = glGenFramebuffers() -> |made| made_id(&made);
    fn create_program() -> Result<glow::Program, String>
        = glCreateProgram() -> |made| made_id(&made);
    fn create_query() -> Result<glow::Query, String> = glGenQueries() -> |made| made_id(&made);
    fn create_shader(shader_type: u32) -> Result<glow::Shader, String>
        = glCreateShader(name_of(shader_type)) -> |made| made_id(&made);
    fn create_texture() -> Result<glow::Texture, String> = glGenTextures() -> |made| made_id(&made);
    fn create_vertex_array() -> Result<glow::VertexArray, String>
        = glGenVertexArrays() -> |made| made_id(&made);
    fn cull_face(value: u32) = glCullFace(name_of(value));
    fn delete_buffer(buffer: glow::Buffer) = glDeleteBuffers(buffer.id());
    fn delete_framebuffer(framebuffer: glow::Framebuffer) = glDeleteFramebuffers(framebuffer.id());
    fn delete_program(program: glow::Program) = glDeleteProgram(program.id());
    fn delete_query(query: glow::Query) = glDeleteQueries(query.id());
    fn delete_shader(shader: glow::Shader) = glDeleteShader(shader.id());
    fn delete_texture(texture: glow::Texture) = glDeleteTextures(texture.id());
    fn delete_vertex_array(vertex_array: glow::VertexArray)
        = glDeleteVertexArrays(vertex_array.id());
    fn depth_func(func: u32) = glDepthFunc(name_of(func));
    fn depth_mask(value: bool) = glDepthMask(value);
    fn detach_shader(program: glow::Program, shader: glow::Shader)
        = glDetachShader(program.id(), shader.id());
    fn disable(parameter: u32) = glDisable(name_of(parameter));
    fn dispatch_compute(groups_x: u32, groups_y: u32, groups_z: u32)
        = glDispatchCompute(groups_x, groups_y, groups_z);
    fn draw_arrays(mode: u32, first: i32, count: i32)
        = glDrawArrays(primitive_name(mode), first, count);
    fn draw_arrays_instanced(mode: u32, first: i32, count: i32, instance_count: i32)
        = glDrawArraysInstanced(primitive_name(mode), first, count, instance_count);
    fn draw_buffer(buffer: u32) = glDrawBuffer(name_of(buffer));
    fn draw_buffers(buffers: &[u32]) = glDrawBuffers(names_of(buffers));
    fn draw_elements(mode: u32, count: i32, element_type: u32, offset: i32)
        = glDrawElements(primitive_name(mode), count, name_of(element_type), offset);
    fn draw_elements_instanced(mode: u32, count: i32, element_type: u32, offset: i32,
                               instance_count: i32)
        = glDrawElementsInstanced(primitive_name(mode), count, name_of(element_type), offset,
                                  instance_count);
    fn enable(parameter: u32) = glEnable(name_of(parameter));
    fn enable_vertex_attrib_array(index: u32) = glEnableVertexAttribArray(index);
    fn end_query(target: u32) = glEndQuery(name_of(target));
    fn end_transform_feedback() = glEndTransformFeedback();
    fn finish() = glFinish();
    fn flush() = glFlush();
    fn framebuffer_texture(target: u32, attachment: u32, texture: Option<glow::Texture>, level: i32)
        = glFramebufferTexture(name_of(target), name_of(attachment), id_of(texture), level);
    fn framebuffer_texture_2d(target: u32, attachment: u32, texture_target: u32,
                              texture: Option<glow::Texture>, level: i32)
        = glFramebufferTexture2D(name_of(target), name_of(attachment), name_of(texture_target),
                                 id_of(texture), level);
    fn get_active_uniform(program: glow::Program, index: u32) -> Option<glow::ActiveUniform>
        = glGetActiveUniform(program.id(), index);
    fn get_active_uniforms(program: glow::Program) -> u32 = glGetProgramiv(program.id());
    fn get_active_uniforms_parameter(program: glow::Program, uniforms: &[u32],
                                     pname: u32) -> Vec<i32>
        = glGetActiveUniformsiv(program.id(), list(uniforms), name_of(pname));
    fn get_buffer_sub_data(target: u32, offset: i32, dst_data: &mut [u8])
        = glGetBufferSubData(name_of(target), offset, byte_count(dst_data.len()));
    fn get_parameter_i32(parameter: u32) -> i32 = glGetIntegerv(name_of(parameter));
    fn get_parameter_i64(parameter: u32) -> i64 = glGetInteger64v(name_of(parameter));
    fn get_parameter_indexed_i32(parameter: u32, index: u32) -> i32
        = glGetIntegeri_v(name_of(parameter), index);
    fn get_program_info_log(program: glow::Program) -> String = glGetProgramInfoLog(program.id());
    fn get_program_link_status(program: glow::Program) -> bool = glGetProgramiv(program.id());
    fn get_query_parameter_u32(query: glow::Query, parameter: u32) -> u32
        = glGetQueryObjectuiv(query.id(), name_of(parameter));
    fn get_query_parameter_u64_with_offset(query: glow::Query, parameter: u32, offset: usize)
        = glGetQueryObjectui64v(query.id(), name_of(parameter), offset);
    fn get_shader_compile_status(shader: glow::Shader) -> bool = glGetShaderiv(shader.id());
    fn get_shader_info_log(shader: glow::Shader) -> String = glGetShaderInfoLog(shader.id());
    fn get_tex_image(target: u32, level: i32, format: u32, ty: u32, pixels: glow::PixelPackData<'_>)
        = glGetTexImage(name_of(target), level, name_of(format), name_of(ty), pack_into(&pixels));
    fn get_uniform_location(program: glow::Program, name: &str) -> Option<glow::UniformLocation>
        = glGetUniformLocation(program.id(), format!("{name:?}")) -> |found| at_of(found.as_ref());
    fn link_program(program: glow::Program) = glLinkProgram(program.id());
    fn memory_barrier(barriers: u32) = glMemoryBarrier(hex(barriers));
    fn pixel_store_i32(parameter: u32, value: i32) = glPixelStorei(name_of(parameter), value);
    fn polygon_offset(factor: f32, units: f32) = glPolygonOffset(factor, units);
    fn query_counter(query: glow::Query, target: u32) = glQueryCounter(query.id(), name_of(target));
    fn read_buffer(src: u32) = glReadBuffer(name_of(src));
    fn read_pixels(x: i32, y: i32, width: i32, height: i32, format: u32, gltype: u32,
                   pixels: glow::PixelPackData<'_>)
        = glReadPixels(x, y, width, height, name_of(format), name_of(gltype), pack_into(&pixels));
    fn shader_source(shader: glow::Shader, source: &str)
        = glShaderSource(shader.id(), format!("{} chars", source.len()));
    fn stencil_func_separate(face: u32, func: u32, reference: i32, mask: u32)
        = glStencilFuncSeparate(name_of(face), name_of(func), reference, hex(mask));
    fn stencil_mask(mask: u32) = glStencilMask(hex(mask));
    fn stencil_mask_separate(face: u32, mask: u32)
        = glStencilMaskSeparate(name_of(face), hex(mask));
    fn stencil_op_separate(face: u32, stencil_fail: u32, depth_fail: u32, pass: u32)
        = glStencilOpSeparate(name_of(face), name_of(stencil_fail), name_of(depth_fail),
                              name_of(pass));
    fn tex_image_1d(target: u32, level: i32, internal_format: i32, width: i32, border: i32,
                    format: u32, ty: u32, pixels: glow::PixelUnpackData<'_>)
        = glTexImage1D(name_of(target), level, name_of(internal_format as u32), width, border,
                       name_of(format), name_of(ty), unpack_from(&pixels));
    fn tex_image_2d(target: u32, level: i32, internal_format: i32, width: i32, height: i32,
                    border: i32, format: u32, ty: u32, pixels: glow::PixelUnpackData<'_>)
        = glTexImage2D(name_of(target), level, name_of(internal_format as u32), width, height,
                       border, name_of(format), name_of(ty), unpack_from(&pixels));
    fn tex_parameter_i32(target: u32, parameter: u32, value: i32)
        = glTexParameteri(name_of(target), name_of(parameter), parameter_value(parameter, value));
    fn tex_sub_image_2d(target: u32, level: i32, x_offset: i32, y_offset: i32, width: i32,
                        height: i32, format: u32, ty: u32, pixels: glow::PixelUnpackData<'_>)
        = glTexSubImage2D(name_of(target), level, x_offset, y_offset, width, height,
                          name_of(format), name_of(ty), unpack_from(&pixels));
    fn transform_feedback_varyings(program: glow::Program, varyings: &[&str], buffer_mode: u32)
        = glTransformFeedbackVaryings(program.id(), format!("{varyings:?}"), name_of(buffer_mode));
    fn uniform_1_f32(location: Option<&glow::UniformLocation>, x: f32)
        = glUniform1f(gl.location(location), x);
    fn uniform_1_f32_slice(location: Option<&glow::UniformLocation>, v: &[f32])
        = glUniform1fv(gl.location(location), list(v));
    fn uniform_1_i32(location: Option<&glow::UniformLocation>, x: i32)
        = glUniform1i(gl.location(location), x);
    fn uniform_1_i32_slice(location: Option<&glow::UniformLocation>, v: &[i32])
        = glUniform1iv(gl.location(location), list(v));
    fn uniform_1_u32(location: Option<&glow::UniformLocation>, x: u32)
        = glUniform1ui(gl.location(location), x);
    fn uniform_2_f32(location: Option<&glow::UniformLocation>, x: f32, y: f32)
        = glUniform2f(gl.location(location), x, y);
    fn uniform_2_i32(location: Option<&glow::UniformLocation>, x: i32, y: i32)
        = glUniform2i(gl.location(location), x, y);
    fn uniform_3_f32(location: Option<&glow::UniformLocation>, x: f32, y: f32, z: f32)
        = glUniform3f(gl.location(location), x, y, z);
    fn uniform_4_f32(location: Option<&glow::UniformLocation>, x: f32, y: f32, z: f32, w: f32)
        = glUniform4f(gl.location(location), x, y, z, w);
    fn uniform_4_f32_slice(location: Option<&glow::UniformLocation>, v: &[f32])
        = glUniform4fv(gl.location(location), list(v));
    fn uniform_4_i32(location: Option<&glow::UniformLocation>, x: i32, y: i32, z: i32, w: i32)
        = glUniform4i(gl.location(location), x, y, z, w);
    fn uniform_matrix_3_f32_slice(location: Option<&glow::UniformLocation>, transpose: bool,
                                  v: &[f32])
        = glUniformMatrix3fv(gl.location(location), transpose, list(v));
    fn uniform_matrix_4_f32_slice(location: Option<&glow::UniformLocation>, transpose: bool,
                                  v: &[f32])
        = glUniformMatrix4fv(gl.location(location), transpose, list(v));
    fn use_program(program: Option<glow::Program>) = glUseProgram(id_of(program));
    fn vertex_attrib_divisor(index: u32, divisor: u32) = glVertexAttribDivisor(index, divisor);
    fn vertex_attrib_pointer_f32(index: u32, size: i32, data_type: u32, normalized: bool,
                                 stride: i32, offset: i32)
        = glVertexAttribPointer(index, size, name_of(data_type), normalized, stride, offset);
    fn vertex_attrib_pointer_i32(index: u32, size: i32, data_type: u32, stride: i32, offset: i32)
        = glVertexAttribIPointer(index, size, name_of(data_type), stride, offset);
    fn viewport(x: i32, y: i32, width: i32, height: i32) = glViewport(x, y, width, height);
}

/// A GL object's id (its name, as GL numbers it): what the trace shows, and what the
/// learner's door compares a learner's object with.
pub trait Id {
    fn id(&self) -> u32;
}

macro_rules! ids {
    ($($t:ty),*) => {
        $(impl Id for $t {
            fn id(&self) -> u32 {
                self.0.get()
            }
        })*
    };
}

ids!(
    glow::NativeBuffer,
    glow::NativeFramebuffer,
    glow::NativeProgram,
    glow::NativeQuery,
    glow::NativeRenderbuffer,
    glow::NativeShader,
    glow::NativeTexture,
    glow::NativeVertexArray
);

fn id_of<T: Id>(object: Option<T>) -> String {
    object.map_or(0, |o| o.id()).to_string()
}

/// A new object's id, or `error` where GL made none.
fn made_id<T: Id>(made: &Result<T, String>) -> String {
    made.as_ref()
        .map_or(String::from("error"), |o| o.id().to_string())
}

/// A uniform's location as a number, -1 for none.
fn at_of(location: Option<&glow::UniformLocation>) -> String {
    location.map_or(String::from("-1"), |l| l.0.to_string())
}

/// A call's arguments as the trace shows them: each as it displays, `, ` between.
fn shown(args: &[&dyn std::fmt::Display]) -> String {
    let shown: Vec<String> = args.iter().map(|a| a.to_string()).collect();
    shown.join(", ")
}

/// `GL_TEXTURE0 + n`.
fn unit_name(unit: u32) -> String {
    format!("GL_TEXTURE0 + {}", unit.wrapping_sub(glow::TEXTURE0))
}

fn primitive_name(mode: u32) -> String {
    match mode {
        glow::POINTS => "GL_POINTS".into(),
        glow::LINES => "GL_LINES".into(),
        glow::LINE_STRIP => "GL_LINE_STRIP".into(),
        glow::TRIANGLES => "GL_TRIANGLES".into(),
        glow::TRIANGLE_STRIP => "GL_TRIANGLE_STRIP".into(),
        glow::TRIANGLE_FAN => "GL_TRIANGLE_FAN".into(),
        other => name_of(other),
    }
}

fn factor_name(factor: u32) -> String {
    match factor {
        glow::ZERO => "GL_ZERO".into(),
        glow::ONE => "GL_ONE".into(),
        other => name_of(other),
    }
}

fn hex(bits: u32) -> String {
    format!("{bits:#x}")
}

fn byte_count(n: usize) -> String {
    format!("<{n} bytes>")
}

/// A short slice in full, a long one by its length.
fn list<T: std::fmt::Display>(values: &[T]) -> String {
    if values.len() <= 16 {
        let shown: Vec<String> = values.iter().map(|v| v.to_string()).collect();
        format!("[{}]", shown.join(", "))
    } else {
        format!("<{} values>", values.len())
    }
}

fn names_of(values: &[u32]) -> String {
    let shown: Vec<String> = values.iter().map(|&v| name_of(v)).collect();
    format!("[{}]", shown.join(", "))
}

fn unpack_from(data: &glow::PixelUnpackData) -> String {
    match data {
        glow::PixelUnpackData::BufferOffset(offset) => format!("<unpack buffer offset {offset}>"),
        glow::PixelUnpackData::Slice(Some(bytes)) => byte_count(bytes.len()),
        glow::PixelUnpackData::Slice(None) => "NULL".into(),
    }
}

fn pack_into(data: &glow::PixelPackData) -> String {
    match data {
        glow::PixelPackData::BufferOffset(offset) => format!("<pack buffer offset {offset}>"),
        glow::PixelPackData::Slice(Some(bytes)) => byte_count(bytes.len()),
        glow::PixelPackData::Slice(None) => "NULL".into(),
    }
}

/// A texture parameter's value: a level as a number, a filter or wrap mode by name.
fn parameter_value(parameter: u32, value: i32) -> String {
    match parameter {
        glow::TEXTURE_BASE_LEVEL | glow::TEXTURE_MAX_LEVEL => value.to_string(),
        _ => name_of(value as u32),
    }
}

fn error_name(code: u32) -> String {
    match code {
        glow::NO_ERROR => "GL_NO_ERROR".into(),
        other => name_of(other),
    }
}

/// An enum's GL name (`GL_FRAMEBUFFER`), or its value in hex when it is not one the project
/// uses. Values below 0x100 are shown as numbers where their meaning depends on the call
/// (0 is GL_NONE, GL_ZERO and GL_POINTS): the callers above name those.
pub fn name_of(value: u32) -> String {
    if value == glow::NONE {
        return "GL_NONE".into();
    }
    NAMES
        .iter()
        .find(|(v, _)| *v == value)
        .map_or_else(|| format!("{value:#x}"), |(_, name)| (*name).to_string())
}

macro_rules! name {
    ($n:ident) => {
        (glow::$n, concat!("GL_", stringify!($n)))
    };
}

/// The enums the project passes to GL, by value.
const NAMES: &[(u32, &str)] = &[
    name!(ALWAYS),
    name!(ARRAY_BUFFER),
    name!(ATOMIC_COUNTER_BUFFER),
    name!(BACK),
    name!(BLEND),
    name!(CLAMP_TO_EDGE),
    name!(CLIP_DISTANCE0),
    name!(COLOR),
    name!(COLOR_ATTACHMENT0),
    name!(COMPUTE_SHADER),
    name!(COMPUTE_WORK_GROUP_SIZE),
    name!(COPY_READ_BUFFER),
    name!(COPY_WRITE_BUFFER),
    name!(CULL_FACE),
    name!(DECR),
    name!(DECR_WRAP),
    name!(DEPTH),
    name!(DEPTH24_STENCIL8),
    name!(DEPTH32F_STENCIL8),
    name!(DEPTH_ATTACHMENT),
    name!(DEPTH_COMPONENT),
    name!(DEPTH_COMPONENT32F),
    name!(DEPTH_STENCIL),
    name!(DEPTH_STENCIL_ATTACHMENT),
    name!(DEPTH_TEST),
    name!(DRAW_FRAMEBUFFER),
    name!(DYNAMIC_DRAW),
    name!(DYNAMIC_COPY),
    name!(DYNAMIC_READ),
    name!(STATIC_COPY),
    name!(STATIC_READ),
    name!(STREAM_DRAW),
    name!(STREAM_READ),
    name!(ELEMENT_ARRAY_BUFFER),
    name!(EQUAL),
    name!(FLOAT),
    name!(FLOAT_32_UNSIGNED_INT_24_8_REV),
    name!(FRAGMENT_SHADER),
    name!(FRAGMENT_SHADER_INVOCATIONS),
    name!(FRAMEBUFFER),
    name!(FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE),
    name!(FRAMEBUFFER_COMPLETE),
    name!(FRAMEBUFFER_INCOMPLETE_ATTACHMENT),
    name!(FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER),
    name!(FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS),
    name!(FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT),
    name!(FRAMEBUFFER_INCOMPLETE_MULTISAMPLE),
    name!(FRAMEBUFFER_INCOMPLETE_READ_BUFFER),
    name!(FRAMEBUFFER_UNDEFINED),
    name!(FRAMEBUFFER_UNSUPPORTED),
    name!(FRONT),
    name!(FRONT_AND_BACK),
    name!(FUNC_ADD),
    name!(GEOMETRY_SHADER),
    name!(GEQUAL),
    name!(GREATER),
    name!(INCR),
    name!(INCR_WRAP),
    name!(INT),
    name!(INTERLEAVED_ATTRIBS),
    name!(INVALID_ENUM),
    name!(INVALID_FRAMEBUFFER_OPERATION),
    name!(INVALID_OPERATION),
    name!(INVALID_VALUE),
    name!(INVERT),
    name!(KEEP),
    name!(LEQUAL),
    name!(LESS),
    name!(LINEAR),
    name!(LINEAR_MIPMAP_NEAREST),
    name!(LINEAR_MIPMAP_LINEAR),
    name!(MAJOR_VERSION),
    name!(MAX),
    name!(MAX_COLOR_ATTACHMENTS),
    name!(MAX_COMPUTE_WORK_GROUP_COUNT),
    name!(MAX_DRAW_BUFFERS),
    name!(MAX_FRAGMENT_UNIFORM_COMPONENTS),
    name!(MAX_SHADER_STORAGE_BLOCK_SIZE),
    name!(MAX_TEXTURE_IMAGE_UNITS),
    name!(MAX_TEXTURE_SIZE),
    name!(MAX_VERTEX_ATTRIB_STRIDE),
    name!(MAX_VERTEX_TEXTURE_IMAGE_UNITS),
    name!(MAX_VERTEX_UNIFORM_COMPONENTS),
    name!(MAX_VIEWPORT_DIMS),
    name!(MIN),
    name!(MINOR_VERSION),
    name!(NEAREST),
    name!(NEAREST_MIPMAP_NEAREST),
    name!(NEAREST_MIPMAP_LINEAR),
    name!(NEVER),
    name!(NOTEQUAL),
    name!(ONE_MINUS_SRC_ALPHA),
    name!(OUT_OF_MEMORY),
    name!(PACK_ALIGNMENT),
    name!(PIXEL_PACK_BUFFER),
    name!(PIXEL_UNPACK_BUFFER),
    name!(POLYGON_OFFSET_FILL),
    name!(PROGRAM_POINT_SIZE),
    name!(QUERY_COUNTER_BITS),
    name!(QUERY_RESULT),
    name!(QUERY_RESULT_AVAILABLE),
    name!(R16F),
    name!(R32F),
    name!(R8),
    name!(RASTERIZER_DISCARD),
    name!(READ_FRAMEBUFFER),
    name!(RED),
    name!(RENDERBUFFER),
    name!(RENDERER),
    name!(REPEAT),
    name!(REPLACE),
    name!(RG),
    name!(RG32F),
    name!(RG16F),
    name!(RG8),
    name!(RGB),
    name!(RGB8),
    name!(RGB16F),
    name!(RGB32F),
    name!(R16),
    name!(RGBA16),
    name!(R32I),
    name!(R32UI),
    name!(RGBA32I),
    name!(RGBA),
    name!(RGBA16F),
    name!(RGBA32F),
    name!(RGBA32UI),
    name!(RGBA8),
    name!(RGBA_INTEGER),
    name!(SAMPLES_PASSED),
    name!(SCISSOR_TEST),
    name!(SHADER_STORAGE_BUFFER),
    name!(SHADING_LANGUAGE_VERSION),
    name!(SRC_ALPHA),
    name!(STACK_OVERFLOW),
    name!(STACK_UNDERFLOW),
    name!(STATIC_DRAW),
    name!(STENCIL_ATTACHMENT),
    name!(STENCIL_INDEX),
    name!(STENCIL_INDEX8),
    name!(STENCIL_TEST),
    name!(STREAM_COPY),
    name!(SUBPIXEL_BITS),
    name!(TEXTURE_1D),
    name!(TEXTURE_2D),
    name!(TEXTURE_BASE_LEVEL),
    name!(TEXTURE_MAG_FILTER),
    name!(TEXTURE_MAX_LEVEL),
    name!(TEXTURE_MIN_FILTER),
    name!(TEXTURE_WRAP_S),
    name!(TEXTURE_WRAP_T),
    name!(TIMESTAMP),
    name!(TIME_ELAPSED),
    name!(TRANSFORM_FEEDBACK_BUFFER),
    name!(TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN),
    name!(UNIFORM_BLOCK_INDEX),
    name!(UNPACK_ALIGNMENT),
    name!(UNSIGNED_BYTE),
    name!(UNSIGNED_INT),
    name!(UNSIGNED_INT_24_8),
    name!(VENDOR),
    name!(VERSION),
    name!(VERTEX_SHADER),
    name!(LINK_STATUS),
    name!(COMPILE_STATUS),
    name!(ACTIVE_UNIFORMS),
    name!(COLOR_ATTACHMENT1),
    name!(CLIP_DISTANCE1),
    name!(CLIP_DISTANCE2),
    name!(CLIP_DISTANCE3),
    name!(CLIP_DISTANCE4),
    name!(CLIP_DISTANCE5),
    name!(CLIP_DISTANCE6),
    name!(CLIP_DISTANCE7),
    name!(COLOR_ATTACHMENT2),
    name!(COLOR_ATTACHMENT3),
    name!(COLOR_ATTACHMENT4),
    name!(COLOR_ATTACHMENT5),
    name!(COLOR_ATTACHMENT6),
    name!(COLOR_ATTACHMENT7),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enums_have_their_gl_names() {
        assert_eq!(name_of(glow::FRAMEBUFFER), "GL_FRAMEBUFFER");
        assert_eq!(name_of(glow::RGBA32F), "GL_RGBA32F");
        assert_eq!(unit_name(glow::TEXTURE0 + 2), "GL_TEXTURE0 + 2");
        assert_eq!(primitive_name(glow::TRIANGLES), "GL_TRIANGLES");
        assert_eq!(name_of(0x1234_5678), "0x12345678");
    }

    #[test]
    fn calls_group_by_pass_in_order() {
        let call = |pass: Option<&str>, function| TracedCall {
            pass: pass.map(Rc::from),
            function,
            args: String::new(),
            result: None,
        };
        let calls = [
            call(None, "glGenTextures"),
            call(Some("a"), "glUseProgram"),
            call(Some("a"), "glDrawArrays"),
            call(None, "glReadPixels"),
        ];
        let groups = grouped(&calls);
        assert_eq!(groups.len(), 3);
        assert_eq!(groups[1].0.as_deref(), Some("a"));
        assert_eq!(first_pass(&calls, "a").len(), 2);
        assert!(lines(&calls)[0].starts_with("4 GL calls"));
    }
}
