//! The GL call recorder (issue 39): every OpenGL call the `gl` module makes goes through
//! [`Gl`], which records it, in order and with its arguments, while a trace is on
//! ([`super::Context::trace_start`]). Enums are shown by their GL names (`GL_FRAMEBUFFER`,
//! `GL_RGBA32F`), objects by their ids, uniforms by name and value, draws with their counts.
//! A trace is grouped by the pass that made the calls: a pass's name (`fb.pass(.., name)`,
//! `program.dispatch(name)`) labels the calls from the pass's start to the end of its draw.
//!
//! Off, a call costs one test of a flag; nothing is formatted or stored.
//!
//! The wrappers below keep glow's names and signatures, so a call site reads as before:
//! `ctx.gl().bind_framebuffer(glow::FRAMEBUFFER, Some(id))`.

use glow::HasContext;
use std::cell::{Cell, RefCell};
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
}

// The wrappers keep glow's signatures, however many arguments GL takes.
#[allow(clippy::too_many_arguments)]
impl Gl {
    pub(super) fn new(raw: glow::Context) -> Gl {
        Gl {
            raw,
            on: Cell::new(false),
            calls: RefCell::new(Vec::new()),
            pass: RefCell::new(None),
            uniform: RefCell::new(None),
        }
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
        let at = location.map_or(String::from("-1"), |l| l.0.to_string());
        match self.uniform.borrow_mut().take() {
            Some(name) => format!("{name} @ {at}"),
            None => at,
        }
    }

    pub(super) fn supported_extensions(&self) -> &std::collections::HashSet<String> {
        self.raw.supported_extensions()
    }

    pub(super) unsafe fn active_texture(&self, unit: u32) {
        self.record("glActiveTexture", || [unit_name(unit)].join(", "));
        self.raw.active_texture(unit)
    }

    pub(super) unsafe fn attach_shader(&self, program: glow::Program, shader: glow::Shader) {
        self.record("glAttachShader", || {
            [program.id().to_string(), shader.id().to_string()].join(", ")
        });
        self.raw.attach_shader(program, shader)
    }

    pub(super) unsafe fn begin_query(&self, target: u32, query: glow::Query) {
        self.record("glBeginQuery", || {
            [name_of(target), query.id().to_string()].join(", ")
        });
        self.raw.begin_query(target, query)
    }

    pub(super) unsafe fn begin_transform_feedback(&self, primitive_mode: u32) {
        self.record("glBeginTransformFeedback", || {
            [primitive_name(primitive_mode)].join(", ")
        });
        self.raw.begin_transform_feedback(primitive_mode)
    }

    pub(super) unsafe fn bind_buffer(&self, target: u32, buffer: Option<glow::Buffer>) {
        self.record("glBindBuffer", || {
            [name_of(target), id_of(buffer)].join(", ")
        });
        self.raw.bind_buffer(target, buffer)
    }

    pub(super) unsafe fn bind_buffer_base(
        &self,
        target: u32,
        index: u32,
        buffer: Option<glow::Buffer>,
    ) {
        self.record("glBindBufferBase", || {
            [name_of(target), index.to_string(), id_of(buffer)].join(", ")
        });
        self.raw.bind_buffer_base(target, index, buffer)
    }

    pub(super) unsafe fn bind_framebuffer(
        &self,
        target: u32,
        framebuffer: Option<glow::Framebuffer>,
    ) {
        self.record("glBindFramebuffer", || {
            [name_of(target), id_of(framebuffer)].join(", ")
        });
        self.raw.bind_framebuffer(target, framebuffer)
    }

    pub(super) unsafe fn bind_texture(&self, target: u32, texture: Option<glow::Texture>) {
        self.record("glBindTexture", || {
            [name_of(target), id_of(texture)].join(", ")
        });
        self.raw.bind_texture(target, texture)
    }

    pub(super) unsafe fn bind_vertex_array(&self, vertex_array: Option<glow::VertexArray>) {
        self.record("glBindVertexArray", || [id_of(vertex_array)].join(", "));
        self.raw.bind_vertex_array(vertex_array)
    }

    pub(super) unsafe fn blend_equation(&self, mode: u32) {
        self.record("glBlendEquation", || [primitive_name(mode)].join(", "));
        self.raw.blend_equation(mode)
    }

    pub(super) unsafe fn blend_func(&self, src: u32, dst: u32) {
        self.record("glBlendFunc", || {
            [factor_name(src), factor_name(dst)].join(", ")
        });
        self.raw.blend_func(src, dst)
    }

    pub(super) unsafe fn blit_framebuffer(
        &self,
        src_x0: i32,
        src_y0: i32,
        src_x1: i32,
        src_y1: i32,
        dst_x0: i32,
        dst_y0: i32,
        dst_x1: i32,
        dst_y1: i32,
        mask: u32,
        filter: u32,
    ) {
        self.record("glBlitFramebuffer", || {
            [
                src_x0.to_string(),
                src_y0.to_string(),
                src_x1.to_string(),
                src_y1.to_string(),
                dst_x0.to_string(),
                dst_y0.to_string(),
                dst_x1.to_string(),
                dst_y1.to_string(),
                hex(mask),
                name_of(filter),
            ]
            .join(", ")
        });
        self.raw.blit_framebuffer(
            src_x0, src_y0, src_x1, src_y1, dst_x0, dst_y0, dst_x1, dst_y1, mask, filter,
        )
    }

    pub(super) unsafe fn buffer_data_size(&self, target: u32, size: i32, usage: u32) {
        self.record("glBufferData", || {
            [name_of(target), size.to_string(), name_of(usage)].join(", ")
        });
        self.raw.buffer_data_size(target, size, usage)
    }

    pub(super) unsafe fn buffer_data_u8_slice(&self, target: u32, data: &[u8], usage: u32) {
        self.record("glBufferData", || {
            [name_of(target), byte_count(data.len()), name_of(usage)].join(", ")
        });
        self.raw.buffer_data_u8_slice(target, data, usage)
    }

    pub(super) unsafe fn buffer_sub_data_u8_slice(
        &self,
        target: u32,
        offset: i32,
        src_data: &[u8],
    ) {
        self.record("glBufferSubData", || {
            [
                name_of(target),
                offset.to_string(),
                byte_count(src_data.len()),
            ]
            .join(", ")
        });
        self.raw.buffer_sub_data_u8_slice(target, offset, src_data)
    }

    pub(super) unsafe fn check_framebuffer_status(&self, target: u32) -> u32 {
        let status = self.raw.check_framebuffer_status(target);
        if self.on.get() {
            self.push(
                "glCheckFramebufferStatus",
                [name_of(target)].join(", "),
                Some(name_of(status)),
            );
        }
        status
    }

    pub(super) unsafe fn clear_buffer_depth_stencil(
        &self,
        target: u32,
        draw_buffer: u32,
        depth: f32,
        stencil: i32,
    ) {
        self.record("glClearBufferfi", || {
            [
                name_of(target),
                draw_buffer.to_string(),
                depth.to_string(),
                stencil.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .clear_buffer_depth_stencil(target, draw_buffer, depth, stencil)
    }

    pub(super) unsafe fn clear_buffer_f32_slice(
        &self,
        target: u32,
        draw_buffer: u32,
        values: &[f32],
    ) {
        self.record("glClearBufferfv", || {
            [name_of(target), draw_buffer.to_string(), list(values)].join(", ")
        });
        self.raw.clear_buffer_f32_slice(target, draw_buffer, values)
    }

    pub(super) unsafe fn clear_buffer_u32_slice(
        &self,
        target: u32,
        draw_buffer: u32,
        values: &[u32],
    ) {
        self.record("glClearBufferuiv", || {
            [name_of(target), draw_buffer.to_string(), list(values)].join(", ")
        });
        self.raw.clear_buffer_u32_slice(target, draw_buffer, values)
    }

    pub(super) unsafe fn color_mask(&self, red: bool, green: bool, blue: bool, alpha: bool) {
        self.record("glColorMask", || {
            [
                red.to_string(),
                green.to_string(),
                blue.to_string(),
                alpha.to_string(),
            ]
            .join(", ")
        });
        self.raw.color_mask(red, green, blue, alpha)
    }

    pub(super) unsafe fn compile_shader(&self, shader: glow::Shader) {
        self.record("glCompileShader", || [shader.id().to_string()].join(", "));
        self.raw.compile_shader(shader)
    }

    pub(super) unsafe fn copy_buffer_sub_data(
        &self,
        src_target: u32,
        dst_target: u32,
        src_offset: i32,
        dst_offset: i32,
        size: i32,
    ) {
        self.record("glCopyBufferSubData", || {
            [
                name_of(src_target),
                name_of(dst_target),
                src_offset.to_string(),
                dst_offset.to_string(),
                size.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .copy_buffer_sub_data(src_target, dst_target, src_offset, dst_offset, size)
    }

    pub(super) unsafe fn create_buffer(&self) -> Result<glow::Buffer, String> {
        let made = self.raw.create_buffer();
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push("glGenBuffers", String::new(), Some(id));
        }
        made
    }

    pub(super) unsafe fn create_framebuffer(&self) -> Result<glow::Framebuffer, String> {
        let made = self.raw.create_framebuffer();
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push("glGenFramebuffers", String::new(), Some(id));
        }
        made
    }

    pub(super) unsafe fn create_program(&self) -> Result<glow::Program, String> {
        let made = self.raw.create_program();
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push("glCreateProgram", String::new(), Some(id));
        }
        made
    }

    pub(super) unsafe fn create_query(&self) -> Result<glow::Query, String> {
        let made = self.raw.create_query();
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push("glGenQueries", String::new(), Some(id));
        }
        made
    }

    pub(super) unsafe fn create_shader(&self, shader_type: u32) -> Result<glow::Shader, String> {
        let made = self.raw.create_shader(shader_type);
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push(
                "glCreateShader",
                [name_of(shader_type)].join(", "),
                Some(id),
            );
        }
        made
    }

    pub(super) unsafe fn create_texture(&self) -> Result<glow::Texture, String> {
        let made = self.raw.create_texture();
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push("glGenTextures", String::new(), Some(id));
        }
        made
    }

    pub(super) unsafe fn create_vertex_array(&self) -> Result<glow::VertexArray, String> {
        let made = self.raw.create_vertex_array();
        if self.on.get() {
            let id = made
                .as_ref()
                .map_or(String::from("error"), |o| o.id().to_string());
            self.push("glGenVertexArrays", String::new(), Some(id));
        }
        made
    }

    pub(super) unsafe fn cull_face(&self, value: u32) {
        self.record("glCullFace", || [name_of(value)].join(", "));
        self.raw.cull_face(value)
    }

    pub(super) unsafe fn delete_buffer(&self, buffer: glow::Buffer) {
        self.record("glDeleteBuffers", || [buffer.id().to_string()].join(", "));
        self.raw.delete_buffer(buffer)
    }

    pub(super) unsafe fn delete_framebuffer(&self, framebuffer: glow::Framebuffer) {
        self.record("glDeleteFramebuffers", || {
            [framebuffer.id().to_string()].join(", ")
        });
        self.raw.delete_framebuffer(framebuffer)
    }

    pub(super) unsafe fn delete_program(&self, program: glow::Program) {
        self.record("glDeleteProgram", || [program.id().to_string()].join(", "));
        self.raw.delete_program(program)
    }

    pub(super) unsafe fn delete_query(&self, query: glow::Query) {
        self.record("glDeleteQueries", || [query.id().to_string()].join(", "));
        self.raw.delete_query(query)
    }

    pub(super) unsafe fn delete_shader(&self, shader: glow::Shader) {
        self.record("glDeleteShader", || [shader.id().to_string()].join(", "));
        self.raw.delete_shader(shader)
    }

    pub(super) unsafe fn delete_texture(&self, texture: glow::Texture) {
        self.record("glDeleteTextures", || [texture.id().to_string()].join(", "));
        self.raw.delete_texture(texture)
    }

    pub(super) unsafe fn delete_vertex_array(&self, vertex_array: glow::VertexArray) {
        self.record("glDeleteVertexArrays", || {
            [vertex_array.id().to_string()].join(", ")
        });
        self.raw.delete_vertex_array(vertex_array)
    }

    pub(super) unsafe fn depth_func(&self, func: u32) {
        self.record("glDepthFunc", || [name_of(func)].join(", "));
        self.raw.depth_func(func)
    }

    pub(super) unsafe fn depth_mask(&self, value: bool) {
        self.record("glDepthMask", || [value.to_string()].join(", "));
        self.raw.depth_mask(value)
    }

    pub(super) unsafe fn detach_shader(&self, program: glow::Program, shader: glow::Shader) {
        self.record("glDetachShader", || {
            [program.id().to_string(), shader.id().to_string()].join(", ")
        });
        self.raw.detach_shader(program, shader)
    }

    pub(super) unsafe fn disable(&self, parameter: u32) {
        self.record("glDisable", || [name_of(parameter)].join(", "));
        self.raw.disable(parameter)
    }

    pub(super) unsafe fn dispatch_compute(&self, groups_x: u32, groups_y: u32, groups_z: u32) {
        self.record("glDispatchCompute", || {
            [
                groups_x.to_string(),
                groups_y.to_string(),
                groups_z.to_string(),
            ]
            .join(", ")
        });
        self.raw.dispatch_compute(groups_x, groups_y, groups_z)
    }

    pub(super) unsafe fn draw_arrays(&self, mode: u32, first: i32, count: i32) {
        self.record("glDrawArrays", || {
            [primitive_name(mode), first.to_string(), count.to_string()].join(", ")
        });
        self.raw.draw_arrays(mode, first, count)
    }

    pub(super) unsafe fn draw_arrays_instanced(
        &self,
        mode: u32,
        first: i32,
        count: i32,
        instance_count: i32,
    ) {
        self.record("glDrawArraysInstanced", || {
            [
                primitive_name(mode),
                first.to_string(),
                count.to_string(),
                instance_count.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .draw_arrays_instanced(mode, first, count, instance_count)
    }

    pub(super) unsafe fn draw_buffer(&self, buffer: u32) {
        self.record("glDrawBuffer", || [name_of(buffer)].join(", "));
        self.raw.draw_buffer(buffer)
    }

    pub(super) unsafe fn draw_buffers(&self, buffers: &[u32]) {
        self.record("glDrawBuffers", || [names_of(buffers)].join(", "));
        self.raw.draw_buffers(buffers)
    }

    pub(super) unsafe fn draw_elements(
        &self,
        mode: u32,
        count: i32,
        element_type: u32,
        offset: i32,
    ) {
        self.record("glDrawElements", || {
            [
                primitive_name(mode),
                count.to_string(),
                name_of(element_type),
                offset.to_string(),
            ]
            .join(", ")
        });
        self.raw.draw_elements(mode, count, element_type, offset)
    }

    pub(super) unsafe fn draw_elements_instanced(
        &self,
        mode: u32,
        count: i32,
        element_type: u32,
        offset: i32,
        instance_count: i32,
    ) {
        self.record("glDrawElementsInstanced", || {
            [
                primitive_name(mode),
                count.to_string(),
                name_of(element_type),
                offset.to_string(),
                instance_count.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .draw_elements_instanced(mode, count, element_type, offset, instance_count)
    }

    pub(super) unsafe fn enable(&self, parameter: u32) {
        self.record("glEnable", || [name_of(parameter)].join(", "));
        self.raw.enable(parameter)
    }

    pub(super) unsafe fn enable_vertex_attrib_array(&self, index: u32) {
        self.record("glEnableVertexAttribArray", || {
            [index.to_string()].join(", ")
        });
        self.raw.enable_vertex_attrib_array(index)
    }

    pub(super) unsafe fn end_query(&self, target: u32) {
        self.record("glEndQuery", || [name_of(target)].join(", "));
        self.raw.end_query(target)
    }

    pub(super) unsafe fn end_transform_feedback(&self) {
        self.record("glEndTransformFeedback", String::new);
        self.raw.end_transform_feedback()
    }

    pub(super) unsafe fn finish(&self) {
        self.record("glFinish", String::new);
        self.raw.finish()
    }

    pub(super) unsafe fn flush(&self) {
        self.record("glFlush", String::new);
        self.raw.flush()
    }

    pub(super) unsafe fn framebuffer_texture(
        &self,
        target: u32,
        attachment: u32,
        texture: Option<glow::Texture>,
        level: i32,
    ) {
        self.record("glFramebufferTexture", || {
            [
                name_of(target),
                name_of(attachment),
                id_of(texture),
                level.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .framebuffer_texture(target, attachment, texture, level)
    }

    pub(super) unsafe fn get_active_uniform(
        &self,
        program: glow::Program,
        index: u32,
    ) -> Option<glow::ActiveUniform> {
        self.record("glGetActiveUniform", || {
            [program.id().to_string(), index.to_string()].join(", ")
        });
        self.raw.get_active_uniform(program, index)
    }

    pub(super) unsafe fn get_active_uniforms(&self, program: glow::Program) -> u32 {
        self.record("glGetProgramiv", || [program.id().to_string()].join(", "));
        self.raw.get_active_uniforms(program)
    }

    pub(super) unsafe fn get_active_uniforms_parameter(
        &self,
        program: glow::Program,
        uniforms: &[u32],
        pname: u32,
    ) -> Vec<i32> {
        self.record("glGetActiveUniformsiv", || {
            [program.id().to_string(), list(uniforms), name_of(pname)].join(", ")
        });
        self.raw
            .get_active_uniforms_parameter(program, uniforms, pname)
    }

    pub(super) unsafe fn get_buffer_sub_data(&self, target: u32, offset: i32, dst_data: &mut [u8]) {
        self.record("glGetBufferSubData", || {
            [
                name_of(target),
                offset.to_string(),
                byte_count(dst_data.len()),
            ]
            .join(", ")
        });
        self.raw.get_buffer_sub_data(target, offset, dst_data)
    }

    pub(super) unsafe fn get_error(&self) -> u32 {
        let status = self.raw.get_error();
        if self.on.get() {
            self.push("glGetError", String::new(), Some(error_name(status)));
        }
        status
    }

    pub(super) unsafe fn get_parameter_i32(&self, parameter: u32) -> i32 {
        self.record("glGetIntegerv", || [name_of(parameter)].join(", "));
        self.raw.get_parameter_i32(parameter)
    }

    pub(super) unsafe fn get_parameter_i64(&self, parameter: u32) -> i64 {
        self.record("glGetInteger64v", || [name_of(parameter)].join(", "));
        self.raw.get_parameter_i64(parameter)
    }

    pub(super) unsafe fn get_parameter_indexed_i32(&self, parameter: u32, index: u32) -> i32 {
        self.record("glGetIntegeri_v", || {
            [name_of(parameter), index.to_string()].join(", ")
        });
        self.raw.get_parameter_indexed_i32(parameter, index)
    }

    pub(super) unsafe fn get_program_info_log(&self, program: glow::Program) -> String {
        self.record("glGetProgramInfoLog", || {
            [program.id().to_string()].join(", ")
        });
        self.raw.get_program_info_log(program)
    }

    pub(super) unsafe fn get_program_link_status(&self, program: glow::Program) -> bool {
        self.record("glGetProgramiv", || [program.id().to_string()].join(", "));
        self.raw.get_program_link_status(program)
    }

    pub(super) unsafe fn get_query_parameter_u32(&self, query: glow::Query, parameter: u32) -> u32 {
        self.record("glGetQueryObjectuiv", || {
            [query.id().to_string(), name_of(parameter)].join(", ")
        });
        self.raw.get_query_parameter_u32(query, parameter)
    }

    pub(super) unsafe fn get_query_parameter_u64_with_offset(
        &self,
        query: glow::Query,
        parameter: u32,
        offset: usize,
    ) {
        self.record("glGetQueryObjectui64v", || {
            [
                query.id().to_string(),
                name_of(parameter),
                offset.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .get_query_parameter_u64_with_offset(query, parameter, offset)
    }

    pub(super) unsafe fn get_shader_compile_status(&self, shader: glow::Shader) -> bool {
        self.record("glGetShaderiv", || [shader.id().to_string()].join(", "));
        self.raw.get_shader_compile_status(shader)
    }

    pub(super) unsafe fn get_shader_info_log(&self, shader: glow::Shader) -> String {
        self.record("glGetShaderInfoLog", || {
            [shader.id().to_string()].join(", ")
        });
        self.raw.get_shader_info_log(shader)
    }

    pub(super) unsafe fn get_tex_image(
        &self,
        target: u32,
        level: i32,
        format: u32,
        ty: u32,
        pixels: glow::PixelPackData<'_>,
    ) {
        self.record("glGetTexImage", || {
            [
                name_of(target),
                level.to_string(),
                name_of(format),
                name_of(ty),
                pack_into(&pixels),
            ]
            .join(", ")
        });
        self.raw.get_tex_image(target, level, format, ty, pixels)
    }

    pub(super) unsafe fn get_uniform_location(
        &self,
        program: glow::Program,
        name: &str,
    ) -> Option<glow::UniformLocation> {
        let found = self.raw.get_uniform_location(program, name);
        if self.on.get() {
            let at = found
                .as_ref()
                .map_or(String::from("-1"), |l| l.0.to_string());
            self.push(
                "glGetUniformLocation",
                [program.id().to_string(), format!("{name:?}")].join(", "),
                Some(at),
            );
        }
        found
    }

    pub(super) unsafe fn link_program(&self, program: glow::Program) {
        self.record("glLinkProgram", || [program.id().to_string()].join(", "));
        self.raw.link_program(program)
    }

    pub(super) unsafe fn memory_barrier(&self, barriers: u32) {
        self.record("glMemoryBarrier", || [hex(barriers)].join(", "));
        self.raw.memory_barrier(barriers)
    }

    pub(super) unsafe fn pixel_store_i32(&self, parameter: u32, value: i32) {
        self.record("glPixelStorei", || {
            [name_of(parameter), value.to_string()].join(", ")
        });
        self.raw.pixel_store_i32(parameter, value)
    }

    pub(super) unsafe fn polygon_offset(&self, factor: f32, units: f32) {
        self.record("glPolygonOffset", || {
            [factor.to_string(), units.to_string()].join(", ")
        });
        self.raw.polygon_offset(factor, units)
    }

    pub(super) unsafe fn query_counter(&self, query: glow::Query, target: u32) {
        self.record("glQueryCounter", || {
            [query.id().to_string(), name_of(target)].join(", ")
        });
        self.raw.query_counter(query, target)
    }

    pub(super) unsafe fn read_buffer(&self, src: u32) {
        self.record("glReadBuffer", || [name_of(src)].join(", "));
        self.raw.read_buffer(src)
    }

    pub(super) unsafe fn read_pixels(
        &self,
        x: i32,
        y: i32,
        width: i32,
        height: i32,
        format: u32,
        gltype: u32,
        pixels: glow::PixelPackData<'_>,
    ) {
        self.record("glReadPixels", || {
            [
                x.to_string(),
                y.to_string(),
                width.to_string(),
                height.to_string(),
                name_of(format),
                name_of(gltype),
                pack_into(&pixels),
            ]
            .join(", ")
        });
        self.raw
            .read_pixels(x, y, width, height, format, gltype, pixels)
    }

    pub(super) unsafe fn shader_source(&self, shader: glow::Shader, source: &str) {
        self.record("glShaderSource", || {
            [shader.id().to_string(), format!("{} chars", source.len())].join(", ")
        });
        self.raw.shader_source(shader, source)
    }

    pub(super) unsafe fn stencil_func_separate(
        &self,
        face: u32,
        func: u32,
        reference: i32,
        mask: u32,
    ) {
        self.record("glStencilFuncSeparate", || {
            [
                name_of(face),
                name_of(func),
                reference.to_string(),
                hex(mask),
            ]
            .join(", ")
        });
        self.raw.stencil_func_separate(face, func, reference, mask)
    }

    pub(super) unsafe fn stencil_mask(&self, mask: u32) {
        self.record("glStencilMask", || [hex(mask)].join(", "));
        self.raw.stencil_mask(mask)
    }

    pub(super) unsafe fn stencil_mask_separate(&self, face: u32, mask: u32) {
        self.record("glStencilMaskSeparate", || {
            [name_of(face), hex(mask)].join(", ")
        });
        self.raw.stencil_mask_separate(face, mask)
    }

    pub(super) unsafe fn stencil_op_separate(
        &self,
        face: u32,
        stencil_fail: u32,
        depth_fail: u32,
        pass: u32,
    ) {
        self.record("glStencilOpSeparate", || {
            [
                name_of(face),
                name_of(stencil_fail),
                name_of(depth_fail),
                name_of(pass),
            ]
            .join(", ")
        });
        self.raw
            .stencil_op_separate(face, stencil_fail, depth_fail, pass)
    }

    pub(super) unsafe fn tex_image_1d(
        &self,
        target: u32,
        level: i32,
        internal_format: i32,
        width: i32,
        border: i32,
        format: u32,
        ty: u32,
        pixels: glow::PixelUnpackData<'_>,
    ) {
        self.record("glTexImage1D", || {
            [
                name_of(target),
                level.to_string(),
                name_of(internal_format as u32),
                width.to_string(),
                border.to_string(),
                name_of(format),
                name_of(ty),
                unpack_from(&pixels),
            ]
            .join(", ")
        });
        self.raw.tex_image_1d(
            target,
            level,
            internal_format,
            width,
            border,
            format,
            ty,
            pixels,
        )
    }

    pub(super) unsafe fn tex_image_2d(
        &self,
        target: u32,
        level: i32,
        internal_format: i32,
        width: i32,
        height: i32,
        border: i32,
        format: u32,
        ty: u32,
        pixels: glow::PixelUnpackData<'_>,
    ) {
        self.record("glTexImage2D", || {
            [
                name_of(target),
                level.to_string(),
                name_of(internal_format as u32),
                width.to_string(),
                height.to_string(),
                border.to_string(),
                name_of(format),
                name_of(ty),
                unpack_from(&pixels),
            ]
            .join(", ")
        });
        self.raw.tex_image_2d(
            target,
            level,
            internal_format,
            width,
            height,
            border,
            format,
            ty,
            pixels,
        )
    }

    pub(super) unsafe fn tex_parameter_i32(&self, target: u32, parameter: u32, value: i32) {
        self.record("glTexParameteri", || {
            [
                name_of(target),
                name_of(parameter),
                parameter_value(parameter, value),
            ]
            .join(", ")
        });
        self.raw.tex_parameter_i32(target, parameter, value)
    }

    pub(super) unsafe fn tex_sub_image_2d(
        &self,
        target: u32,
        level: i32,
        x_offset: i32,
        y_offset: i32,
        width: i32,
        height: i32,
        format: u32,
        ty: u32,
        pixels: glow::PixelUnpackData<'_>,
    ) {
        self.record("glTexSubImage2D", || {
            [
                name_of(target),
                level.to_string(),
                x_offset.to_string(),
                y_offset.to_string(),
                width.to_string(),
                height.to_string(),
                name_of(format),
                name_of(ty),
                unpack_from(&pixels),
            ]
            .join(", ")
        });
        self.raw.tex_sub_image_2d(
            target, level, x_offset, y_offset, width, height, format, ty, pixels,
        )
    }

    pub(super) unsafe fn transform_feedback_varyings(
        &self,
        program: glow::Program,
        varyings: &[&str],
        buffer_mode: u32,
    ) {
        self.record("glTransformFeedbackVaryings", || {
            [
                program.id().to_string(),
                format!("{varyings:?}"),
                name_of(buffer_mode),
            ]
            .join(", ")
        });
        self.raw
            .transform_feedback_varyings(program, varyings, buffer_mode)
    }

    pub(super) unsafe fn uniform_1_f32(&self, location: Option<&glow::UniformLocation>, x: f32) {
        self.record("glUniform1f", || {
            [self.location(location), x.to_string()].join(", ")
        });
        self.raw.uniform_1_f32(location, x)
    }

    pub(super) unsafe fn uniform_1_f32_slice(
        &self,
        location: Option<&glow::UniformLocation>,
        v: &[f32],
    ) {
        self.record("glUniform1fv", || {
            [self.location(location), list(v)].join(", ")
        });
        self.raw.uniform_1_f32_slice(location, v)
    }

    pub(super) unsafe fn uniform_1_i32(&self, location: Option<&glow::UniformLocation>, x: i32) {
        self.record("glUniform1i", || {
            [self.location(location), x.to_string()].join(", ")
        });
        self.raw.uniform_1_i32(location, x)
    }

    pub(super) unsafe fn uniform_1_i32_slice(
        &self,
        location: Option<&glow::UniformLocation>,
        v: &[i32],
    ) {
        self.record("glUniform1iv", || {
            [self.location(location), list(v)].join(", ")
        });
        self.raw.uniform_1_i32_slice(location, v)
    }

    pub(super) unsafe fn uniform_1_u32(&self, location: Option<&glow::UniformLocation>, x: u32) {
        self.record("glUniform1ui", || {
            [self.location(location), x.to_string()].join(", ")
        });
        self.raw.uniform_1_u32(location, x)
    }

    pub(super) unsafe fn uniform_2_f32(
        &self,
        location: Option<&glow::UniformLocation>,
        x: f32,
        y: f32,
    ) {
        self.record("glUniform2f", || {
            [self.location(location), x.to_string(), y.to_string()].join(", ")
        });
        self.raw.uniform_2_f32(location, x, y)
    }

    pub(super) unsafe fn uniform_2_i32(
        &self,
        location: Option<&glow::UniformLocation>,
        x: i32,
        y: i32,
    ) {
        self.record("glUniform2i", || {
            [self.location(location), x.to_string(), y.to_string()].join(", ")
        });
        self.raw.uniform_2_i32(location, x, y)
    }

    pub(super) unsafe fn uniform_3_f32(
        &self,
        location: Option<&glow::UniformLocation>,
        x: f32,
        y: f32,
        z: f32,
    ) {
        self.record("glUniform3f", || {
            [
                self.location(location),
                x.to_string(),
                y.to_string(),
                z.to_string(),
            ]
            .join(", ")
        });
        self.raw.uniform_3_f32(location, x, y, z)
    }

    pub(super) unsafe fn uniform_4_f32(
        &self,
        location: Option<&glow::UniformLocation>,
        x: f32,
        y: f32,
        z: f32,
        w: f32,
    ) {
        self.record("glUniform4f", || {
            [
                self.location(location),
                x.to_string(),
                y.to_string(),
                z.to_string(),
                w.to_string(),
            ]
            .join(", ")
        });
        self.raw.uniform_4_f32(location, x, y, z, w)
    }

    pub(super) unsafe fn uniform_4_f32_slice(
        &self,
        location: Option<&glow::UniformLocation>,
        v: &[f32],
    ) {
        self.record("glUniform4fv", || {
            [self.location(location), list(v)].join(", ")
        });
        self.raw.uniform_4_f32_slice(location, v)
    }

    pub(super) unsafe fn uniform_4_i32(
        &self,
        location: Option<&glow::UniformLocation>,
        x: i32,
        y: i32,
        z: i32,
        w: i32,
    ) {
        self.record("glUniform4i", || {
            [
                self.location(location),
                x.to_string(),
                y.to_string(),
                z.to_string(),
                w.to_string(),
            ]
            .join(", ")
        });
        self.raw.uniform_4_i32(location, x, y, z, w)
    }

    pub(super) unsafe fn uniform_matrix_3_f32_slice(
        &self,
        location: Option<&glow::UniformLocation>,
        transpose: bool,
        v: &[f32],
    ) {
        self.record("glUniformMatrix3fv", || {
            [self.location(location), transpose.to_string(), list(v)].join(", ")
        });
        self.raw.uniform_matrix_3_f32_slice(location, transpose, v)
    }

    pub(super) unsafe fn uniform_matrix_4_f32_slice(
        &self,
        location: Option<&glow::UniformLocation>,
        transpose: bool,
        v: &[f32],
    ) {
        self.record("glUniformMatrix4fv", || {
            [self.location(location), transpose.to_string(), list(v)].join(", ")
        });
        self.raw.uniform_matrix_4_f32_slice(location, transpose, v)
    }

    pub(super) unsafe fn use_program(&self, program: Option<glow::Program>) {
        self.record("glUseProgram", || [id_of(program)].join(", "));
        self.raw.use_program(program)
    }

    pub(super) unsafe fn vertex_attrib_divisor(&self, index: u32, divisor: u32) {
        self.record("glVertexAttribDivisor", || {
            [index.to_string(), divisor.to_string()].join(", ")
        });
        self.raw.vertex_attrib_divisor(index, divisor)
    }

    pub(super) unsafe fn vertex_attrib_pointer_f32(
        &self,
        index: u32,
        size: i32,
        data_type: u32,
        normalized: bool,
        stride: i32,
        offset: i32,
    ) {
        self.record("glVertexAttribPointer", || {
            [
                index.to_string(),
                size.to_string(),
                name_of(data_type),
                normalized.to_string(),
                stride.to_string(),
                offset.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .vertex_attrib_pointer_f32(index, size, data_type, normalized, stride, offset)
    }

    pub(super) unsafe fn vertex_attrib_pointer_i32(
        &self,
        index: u32,
        size: i32,
        data_type: u32,
        stride: i32,
        offset: i32,
    ) {
        self.record("glVertexAttribIPointer", || {
            [
                index.to_string(),
                size.to_string(),
                name_of(data_type),
                stride.to_string(),
                offset.to_string(),
            ]
            .join(", ")
        });
        self.raw
            .vertex_attrib_pointer_i32(index, size, data_type, stride, offset)
    }

    pub(super) unsafe fn viewport(&self, x: i32, y: i32, width: i32, height: i32) {
        self.record("glViewport", || {
            [
                x.to_string(),
                y.to_string(),
                width.to_string(),
                height.to_string(),
            ]
            .join(", ")
        });
        self.raw.viewport(x, y, width, height)
    }
}

/// A GL object's id, as the trace shows it.
trait Id {
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
