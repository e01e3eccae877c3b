//! A render pass: one program drawing into one framebuffer with a given fixed-function
//! state. This is where the papers' GL features meet: the stencil test (paper 1), MRT (papers
//! 1 and 4), the depth test of depth peeling (paper 4), MIN/MAX blending, clip planes.

use super::program::Uniform;
use super::{
    Context, Framebuffer, GlError, MeshBuffers, OcclusionQuery, Program, Rect, Texture, VertexArray,
};
use glam::{Vec2, Vec4};

/// A comparison function (depth and stencil tests).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compare {
    Never,
    Less,
    Equal,
    LessEqual,
    Greater,
    NotEqual,
    GreaterEqual,
    Always,
}

impl Compare {
    fn gl(self) -> u32 {
        match self {
            Compare::Never => glow::NEVER,
            Compare::Less => glow::LESS,
            Compare::Equal => glow::EQUAL,
            Compare::LessEqual => glow::LEQUAL,
            Compare::Greater => glow::GREATER,
            Compare::NotEqual => glow::NOTEQUAL,
            Compare::GreaterEqual => glow::GEQUAL,
            Compare::Always => glow::ALWAYS,
        }
    }
}

/// The depth test, and whether passing fragments write their depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DepthTest {
    pub func: Compare,
    pub write: bool,
}

/// What the stencil test does to the stored value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StencilOp {
    Keep,
    Zero,
    Replace,
    Increment,
    IncrementWrap,
    Decrement,
    DecrementWrap,
    Invert,
}

impl StencilOp {
    fn gl(self) -> u32 {
        match self {
            StencilOp::Keep => glow::KEEP,
            StencilOp::Zero => glow::ZERO,
            StencilOp::Replace => glow::REPLACE,
            StencilOp::Increment => glow::INCR,
            StencilOp::IncrementWrap => glow::INCR_WRAP,
            StencilOp::Decrement => glow::DECR,
            StencilOp::DecrementWrap => glow::DECR_WRAP,
            StencilOp::Invert => glow::INVERT,
        }
    }
}

/// The stencil test: pass when `(reference & read_mask) func (stored & read_mask)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StencilTest {
    pub func: Compare,
    pub reference: i32,
    pub read_mask: u32,
    /// Applied when the stencil test fails.
    pub fail: StencilOp,
    /// Applied when the stencil test passes and the depth test fails.
    pub depth_fail: StencilOp,
    /// Applied when both pass.
    pub pass: StencilOp,
    pub write_mask: u32,
}

impl StencilTest {
    /// Draw only where the stored stencil equals `reference`; leave the stencil as it is.
    pub fn equal(reference: i32) -> StencilTest {
        StencilTest {
            func: Compare::Equal,
            reference,
            read_mask: 0xff,
            fail: StencilOp::Keep,
            depth_fail: StencilOp::Keep,
            pass: StencilOp::Keep,
            write_mask: 0,
        }
    }

    /// Draw everywhere and write `reference` where fragments land.
    pub fn write(reference: i32) -> StencilTest {
        StencilTest {
            func: Compare::Always,
            reference,
            read_mask: 0xff,
            fail: StencilOp::Keep,
            depth_fail: StencilOp::Keep,
            pass: StencilOp::Replace,
            write_mask: 0xff,
        }
    }
}

/// How a fragment's colour combines with the stored one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blend {
    /// stored + fragment (accumulation).
    Add,
    /// min(stored, fragment), per component.
    Min,
    /// max(stored, fragment), per component.
    Max,
    /// Ordinary transparency: src * a + stored * (1 - a).
    Alpha,
}

/// Which faces are culled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    Back,
    Front,
}

/// The fixed-function state of a draw. The default is plain: no depth, stencil, blending or
/// culling, colour written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawState {
    pub depth: Option<DepthTest>,
    /// The stencil test; for front faces only when `stencil_back` is set.
    pub stencil: Option<StencilTest>,
    /// Two-sided stencil: the test of back-facing polygons (`glStencilFuncSeparate`,
    /// `glStencilOpSeparate`, `glStencilMaskSeparate`), while `stencil` then serves front
    /// faces. Ignored without `stencil`.
    pub stencil_back: Option<StencilTest>,
    pub blend: Option<Blend>,
    pub color_write: bool,
    pub cull: Option<Face>,
    /// How many `gl_ClipDistance[i]` the vertex shader writes (clip planes).
    pub clip_distances: u32,
    /// Polygon offset (factor, units), for coplanar surfaces.
    pub polygon_offset: Option<(f32, f32)>,
}

impl Default for DrawState {
    fn default() -> Self {
        DrawState {
            depth: None,
            stencil: None,
            stencil_back: None,
            blend: None,
            color_write: true,
            cull: None,
            clip_distances: 0,
            polygon_offset: None,
        }
    }
}

impl DrawState {
    /// Depth test `func`, depth writes as `write` says, no colour: a depth or occlusion pass
    /// (CULLIDE's two passes, the avatar's visibility culling).
    pub fn depth_only(func: Compare, write: bool) -> DrawState {
        DrawState {
            depth: Some(DepthTest { func, write }),
            color_write: false,
            ..DrawState::default()
        }
    }
}

/// Primitive types for mesh draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    Points,
    Lines,
    LineStrip,
    Triangles,
    TriangleStrip,
}

impl Primitive {
    fn gl(self) -> u32 {
        match self {
            Primitive::Points => glow::POINTS,
            Primitive::Lines => glow::LINES,
            Primitive::LineStrip => glow::LINE_STRIP,
            Primitive::Triangles => glow::TRIANGLES,
            Primitive::TriangleStrip => glow::TRIANGLE_STRIP,
        }
    }
}

/// One program drawing into one framebuffer. Made by [`Framebuffer::pass`]; configure it with
/// the builder methods, then draw. Each draw is checked for GL errors when checks are on.
pub struct Pass<'a> {
    ctx: &'a Context,
    target: &'a Framebuffer,
    program: &'a Program,
    name: &'a str,
    viewport: Rect,
    state: DrawState,
    textures: Vec<(u32, Texture)>,
    /// The sampler uniform of each of `textures`.
    samplers: Vec<String>,
    error: Option<GlError>,
}

impl<'a> Pass<'a> {
    pub(super) fn begin(
        target: &'a Framebuffer,
        program: &'a Program,
        name: &'a str,
    ) -> Result<Pass<'a>, GlError> {
        let ctx = target.context();
        if ctx.checks() {
            target.check_complete()?;
        }
        ctx.gl().enter_pass(name);
        Ok(Pass {
            ctx,
            target,
            program,
            name,
            viewport: target.rect(),
            state: DrawState::default(),
            textures: Vec::new(),
            samplers: Vec::new(),
            error: None,
        })
    }

    /// Draw into `rect` of the framebuffer only; rectangles are then relative to it.
    pub fn viewport(&mut self, rect: Rect) -> &mut Self {
        self.viewport = rect;
        self
    }

    pub fn state(&mut self, state: DrawState) -> &mut Self {
        self.state = state;
        self
    }

    /// Bind `texture` to the sampler uniform `sampler` (the next free texture unit).
    pub fn texture(&mut self, sampler: &str, texture: &Texture) -> &mut Self {
        let unit = self.textures.len() as u32;
        if unit >= self.ctx.info().limits.max_texture_image_units {
            self.error.get_or_insert(GlError::Limit(format!(
                "pass {} binds more textures than the {} units of this renderer",
                self.name,
                self.ctx.info().limits.max_texture_image_units
            )));
            return self;
        }
        self.uniform(sampler, unit as i32);
        self.textures.push((unit, texture.clone()));
        self.samplers.push(sampler.to_string());
        self
    }

    /// The GL check for a rendering feedback loop (GL 4.5 section 9.3.1): the sampler
    /// uniforms bound to a single-level texture that this pass also draws into, whose result
    /// GL leaves undefined. Empty when there is none. (A texture of several mipmap levels may
    /// be read at one level and drawn at another, as a pyramid does: not reported.)
    pub fn feedback_loops(&self) -> Vec<String> {
        let attached: Vec<glow::Texture> = self
            .target
            .colors()
            .iter()
            .chain(self.target.depth())
            .map(|t| t.id())
            .collect();
        self.textures
            .iter()
            .zip(&self.samplers)
            .filter(|((_, t), _)| t.levels() == 1 && attached.contains(&t.id()))
            .map(|(_, sampler)| sampler.clone())
            .collect()
    }

    /// Under a period GPU ([`Context::set_period`]): whether it could have drawn this pass,
    /// blending into these targets and sampling these textures as set up.
    fn check_period(&self) -> Result<(), GlError> {
        let Some(gpu) = self.ctx.period() else {
            return Ok(());
        };
        if self.state.blend.is_some() && self.state.color_write {
            for target in self.target.colors() {
                gpu.check_blend(self.name, target.format())?;
            }
        }
        for ((_, texture), sampler) in self.textures.iter().zip(&self.samplers) {
            gpu.check_sampling(
                self.name,
                sampler,
                texture.format(),
                texture.filter(),
                self.program.vertex_stage_samples(sampler),
            )?;
        }
        Ok(())
    }

    /// Set a uniform of the pass's program. A name the program does not declare is an error,
    /// returned by the next draw ([`Program::set`]).
    pub fn uniform<U: Uniform>(&mut self, name: &str, value: U) -> &mut Self {
        if let Err(e) = self.program.set(name, value) {
            self.error.get_or_insert(e);
        }
        self
    }

    /// Set a uniform the pass's program may not have ([`Program::set_if_used`]).
    pub fn uniform_if_used<U: Uniform>(&mut self, name: &str, value: U) -> &mut Self {
        self.program.set_if_used(name, value);
        self
    }

    /// Draw the rectangle `rect` (pixels, relative to the viewport) with the rectangle vertex
    /// shader ([`Program::rect`]): one fragment per covered pixel.
    pub fn draw_rect(&mut self, rect: Rect) -> Result<(), GlError> {
        let (x0, y0) = (rect.x as f32, rect.y as f32);
        self.draw_rect_f32(x0, y0, x0 + rect.w as f32, y0 + rect.h as f32)
    }

    /// Draw the whole viewport.
    pub fn draw_full(&mut self) -> Result<(), GlError> {
        self.draw_rect(Rect::sized(self.viewport.w, self.viewport.h))
    }

    /// Draw a rectangle with fractional pixel corners. The vertex shader takes the corners as
    /// `u_rect`, and the viewport size as `u_viewport` if it needs it.
    pub fn draw_rect_f32(&mut self, x0: f32, y0: f32, x1: f32, y1: f32) -> Result<(), GlError> {
        let viewport = Vec2::new(self.viewport.w as f32, self.viewport.h as f32);
        self.uniform("u_rect", Vec4::new(x0, y0, x1, y1))
            .uniform_if_used("u_viewport", viewport);
        self.draw_attributeless(Primitive::TriangleStrip, 4, 1)
    }

    /// Draw `count` vertices with no vertex buffer (the shader builds them from
    /// `gl_VertexID` / `gl_InstanceID`), `instances` times.
    pub fn draw_attributeless(
        &mut self,
        primitive: Primitive,
        count: usize,
        instances: usize,
    ) -> Result<(), GlError> {
        let vao = self.ctx.inner.empty_vao;
        self.draw(vao, |gl| unsafe {
            gl.draw_arrays_instanced(primitive.gl(), 0, count as i32, instances as i32)
        })
    }

    /// Draw `count` vertices from `first` of `vertices`.
    pub fn draw_arrays(
        &mut self,
        vertices: &VertexArray,
        primitive: Primitive,
        first: usize,
        count: usize,
    ) -> Result<(), GlError> {
        self.draw_arrays_instanced(vertices, primitive, first, count, 1)
    }

    /// Draw `count` vertices from `first` of `vertices`, `instances` times.
    pub fn draw_arrays_instanced(
        &mut self,
        vertices: &VertexArray,
        primitive: Primitive,
        first: usize,
        count: usize,
        instances: usize,
    ) -> Result<(), GlError> {
        self.draw(vertices.id(), |gl| unsafe {
            gl.draw_arrays_instanced(primitive.gl(), first as i32, count as i32, instances as i32)
        })
    }

    /// Draw `count` indices from index `first` of the vertex array's index buffer, `instances`
    /// times.
    pub fn draw_elements_instanced(
        &mut self,
        vertices: &VertexArray,
        primitive: Primitive,
        first: usize,
        count: usize,
        instances: usize,
    ) -> Result<(), GlError> {
        if !vertices.has_indices() {
            return Err(GlError::Invalid(format!(
                "pass {}: draw_elements on a vertex array without an index buffer",
                self.name
            )));
        }
        self.draw(vertices.id(), |gl| unsafe {
            gl.draw_elements_instanced(
                primitive.gl(),
                count as i32,
                glow::UNSIGNED_INT,
                (first * 4) as i32,
                instances as i32,
            )
        })
    }

    /// Draw each index range `(first, count)` of `ranges` of the vertex array's index buffer,
    /// with one pass set-up (state, program, vertex array, profile scope) for all of them.
    pub fn draw_element_ranges(
        &mut self,
        vertices: &VertexArray,
        primitive: Primitive,
        ranges: &[(usize, usize)],
    ) -> Result<(), GlError> {
        if !vertices.has_indices() {
            return Err(GlError::Invalid(format!(
                "pass {}: draw_element_ranges on a vertex array without an index buffer",
                self.name
            )));
        }
        self.draw(vertices.id(), |gl| {
            for &range in ranges {
                draw_index_range(gl, primitive, range);
            }
        })
    }

    /// Draw each index range `(first, count)` of `ranges` inside its own occlusion query
    /// (`queries[k]` counts `ranges[k]`): a visibility test of many objects, issued with one
    /// pass set-up (state, program, vertex array, profile scope) instead of one per object.
    pub fn draw_elements_counted(
        &mut self,
        vertices: &VertexArray,
        primitive: Primitive,
        ranges: &[(usize, usize)],
        queries: &[OcclusionQuery],
    ) -> Result<(), GlError> {
        if !vertices.has_indices() {
            return Err(GlError::Invalid(format!(
                "pass {}: draw_elements_counted on a vertex array without an index buffer",
                self.name
            )));
        }
        if queries.len() < ranges.len() {
            return Err(GlError::Invalid(format!(
                "pass {}: {} ranges to count with {} occlusion queries",
                self.name,
                ranges.len(),
                queries.len()
            )));
        }
        self.draw(vertices.id(), |gl| {
            for (&range, query) in ranges.iter().zip(queries) {
                query.begin();
                draw_index_range(gl, primitive, range);
                query.end();
            }
        })
    }

    /// Draw `count` indices from index `first` of each of `arrays` in turn, one draw call per
    /// vertex array, with the framebuffer, program, textures and state bound once for all of
    /// them (a draw per character, say, without issuing the same state again between draws).
    pub fn draw_elements_each(
        &mut self,
        arrays: &[&VertexArray],
        primitive: Primitive,
        first: usize,
        count: usize,
    ) -> Result<(), GlError> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.check_period()?;
        if arrays.iter().any(|va| !va.has_indices()) {
            return Err(GlError::Invalid(format!(
                "pass {}: draw_elements on a vertex array without an index buffer",
                self.name
            )));
        }
        let _scope = super::profile::scope(self.ctx, self.name);
        let gl = self.ctx.gl();
        self.bind_all();
        for va in arrays {
            unsafe { gl.bind_vertex_array(Some(va.id())) };
            draw_index_range(gl, primitive, (first, count));
        }
        unsafe { gl.bind_vertex_array(None) };
        let checked = self.ctx.check(&format!("pass {}", self.name));
        gl.leave_pass();
        checked
    }

    /// Draw every triangle of `mesh`.
    pub fn draw_mesh(&mut self, mesh: &MeshBuffers) -> Result<(), GlError> {
        self.draw_elements_instanced(
            mesh.vertex_array(),
            Primitive::Triangles,
            0,
            mesh.index_count(),
            1,
        )
    }

    fn draw(
        &mut self,
        vao: glow::VertexArray,
        call: impl FnOnce(&super::trace::Gl),
    ) -> Result<(), GlError> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.check_period()?;
        let _scope = super::profile::scope(self.ctx, self.name);
        let gl = self.ctx.gl();
        self.bind_all();
        unsafe {
            gl.bind_vertex_array(Some(vao));
            call(gl);
            gl.bind_vertex_array(None);
        }
        let checked = self.ctx.check(&format!("pass {}", self.name));
        gl.leave_pass();
        checked
    }
}

/// One `glDrawElements` of the `count` 32-bit indices from index `first` of the bound
/// vertex array's index buffer.
fn draw_index_range(gl: &super::trace::Gl, primitive: Primitive, (first, count): (usize, usize)) {
    unsafe {
        gl.draw_elements(
            primitive.gl(),
            count as i32,
            glow::UNSIGNED_INT,
            (first * 4) as i32,
        )
    };
}

impl Pass<'_> {
    /// Bind the framebuffer, program, viewport, textures and fixed-function state.
    fn bind_all(&self) {
        let gl = self.ctx.gl();
        gl.enter_pass(self.name);
        self.target.bind();
        self.program.bind();
        unsafe {
            let v = self.viewport;
            gl.viewport(v.x as i32, v.y as i32, v.w as i32, v.h as i32);
            for (unit, texture) in &self.textures {
                gl.active_texture(glow::TEXTURE0 + unit);
                gl.bind_texture(texture.target(), Some(texture.id()));
            }
            apply_state(gl, &self.state);
        }
    }
}

unsafe fn apply_state(gl: &super::trace::Gl, s: &DrawState) {
    let toggle = |cap, on: bool| {
        if on {
            gl.enable(cap)
        } else {
            gl.disable(cap)
        }
    };
    toggle(glow::DEPTH_TEST, s.depth.is_some());
    match s.depth {
        Some(d) => {
            gl.depth_func(d.func.gl());
            gl.depth_mask(d.write);
        }
        None => gl.depth_mask(false),
    }
    toggle(glow::STENCIL_TEST, s.stencil.is_some());
    if let Some(st) = s.stencil {
        let back = s.stencil_back.unwrap_or(st);
        for (face, t) in [(glow::FRONT, st), (glow::BACK, back)] {
            gl.stencil_func_separate(face, t.func.gl(), t.reference, t.read_mask);
            gl.stencil_op_separate(face, t.fail.gl(), t.depth_fail.gl(), t.pass.gl());
            gl.stencil_mask_separate(face, t.write_mask);
        }
    }
    toggle(glow::BLEND, s.blend.is_some());
    if let Some(b) = s.blend {
        match b {
            Blend::Add => {
                gl.blend_equation(glow::FUNC_ADD);
                gl.blend_func(glow::ONE, glow::ONE);
            }
            Blend::Min => gl.blend_equation(glow::MIN),
            Blend::Max => gl.blend_equation(glow::MAX),
            Blend::Alpha => {
                gl.blend_equation(glow::FUNC_ADD);
                gl.blend_func(glow::SRC_ALPHA, glow::ONE_MINUS_SRC_ALPHA);
            }
        }
    }
    let c = s.color_write;
    gl.color_mask(c, c, c, c);
    toggle(glow::CULL_FACE, s.cull.is_some());
    if let Some(face) = s.cull {
        gl.cull_face(match face {
            Face::Back => glow::BACK,
            Face::Front => glow::FRONT,
        });
    }
    for i in 0..8 {
        toggle(glow::CLIP_DISTANCE0 + i, i < s.clip_distances);
    }
    toggle(glow::POLYGON_OFFSET_FILL, s.polygon_offset.is_some());
    if let Some((factor, units)) = s.polygon_offset {
        gl.polygon_offset(factor, units);
    }
    // Shaders may set gl_PointSize (point-sprite passes).
    gl.enable(glow::PROGRAM_POINT_SIZE);
}
