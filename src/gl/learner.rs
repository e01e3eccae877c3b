//! The learner's door (issue 51): what a host exercise (`examples/`) gets from the GL layer.
//! Everywhere else the crate reaches OpenGL through this module's RAII types; a host exercise
//! is the one place a reader writes the GL calls themselves, as Göddeke's tutorial shows every
//! call, with glow's names and signatures on the recorder [`Gl`], so that the calls can be set
//! beside the solution's.
//!
//! [`LearnerGl`] hands the exercise that recorder and, for the harness that checks each step
//! (`crate::learn::host`), reads state back without recording it: a texture's size, format
//! and values, a framebuffer's colour attachment and status, the viewport, the program in use
//! and its uniforms, the pixel pack buffer. Every draw the learner makes is inspected just
//! before it is made ([`DrawFacts`]: the textures its program samples, the textures it draws
//! into, the viewport), and [`DrawFacts::problems`] names what GL would not complain about: a
//! feedback loop, a target that is not a float format, a viewport that is not the target's.
//!
//! The queries change no state that the learner can see: each binding a query needs is put
//! back, GL errors pending before it are kept for the learner's own `glGetError`, and errors
//! a query itself raises (asking about an object that is not what it should be) are dropped.

use super::trace::{name_of, Gl, Id};
use super::Context;
use glow::HasContext;
use std::fmt;
use std::num::NonZeroU32;

/// The door: the recorder whose calls a host exercise makes, and untraced reads of the state.
pub struct LearnerGl {
    ctx: Context,
}

impl Context {
    /// The learner's door for a host exercise: from now on every draw on this context is
    /// inspected before it is made. Code under `src/` never uses it: it draws through
    /// [`super::Pass`].
    ///
    /// The state this layer's own setup touched (the viewport, the bindings) is put back as a
    /// fresh headless context has it, so the learner starts where GL starts: a viewport of
    /// 0 x 0, nothing bound.
    pub fn learner(&self) -> LearnerGl {
        let gl = self.gl();
        // SAFETY: state changes on the current context; no object is made or deleted.
        unsafe {
            let raw = gl.untraced();
            raw.viewport(0, 0, 0, 0);
            raw.bind_framebuffer(glow::FRAMEBUFFER, None);
            raw.use_program(None);
            raw.bind_vertex_array(None);
            raw.active_texture(glow::TEXTURE0);
            raw.bind_texture(glow::TEXTURE_2D, None);
        }
        gl.set_inspecting(true);
        LearnerGl { ctx: self.clone() }
    }
}

/// A texture as read back: its size, its format and its level 0.
#[derive(Clone, Debug)]
pub struct TextureFacts {
    pub id: u32,
    pub width: u32,
    pub height: u32,
    /// The internal format's GL name, e.g. `GL_R32F`.
    pub format: String,
    pub kind: FormatKind,
    pub channels: usize,
    /// Level 0, `channels` floats a texel, rows from the bottom (empty for integer formats).
    pub values: Vec<f32>,
}

/// What a format keeps of a float written into it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatKind {
    /// 32- or 16-bit floats: any value, rounded to the format's precision.
    Float,
    /// Normalized bytes or shorts (`GL_RGBA8`, `GL_R16`): clamped to [0, 1], then rounded.
    Normalized,
    /// Integers (`GL_R32UI`): not a float array at all.
    Integer,
}

/// A framebuffer's first colour attachment and its status.
#[derive(Clone, Debug)]
pub struct FramebufferFacts {
    pub id: u32,
    /// `GL_FRAMEBUFFER_COMPLETE`, or why not.
    pub status: String,
    pub complete: bool,
    /// The texture attached as `GL_COLOR_ATTACHMENT0`, if one is.
    pub color0: Option<u32>,
}

/// A program: linked or not, with its log.
#[derive(Clone, Debug)]
pub struct ProgramFacts {
    pub id: u32,
    pub linked: bool,
    pub log: String,
}

/// A uniform's value in the program in use.
#[derive(Clone, Debug, PartialEq)]
pub enum UniformValue {
    Float(Vec<f32>),
    Int(Vec<i32>),
    /// A sampler: the texture unit it reads.
    Sampler(i32),
}

/// One sampler of the program a draw uses: the unit it reads and the texture bound there.
#[derive(Clone, Debug)]
pub struct SamplerFacts {
    pub name: String,
    pub unit: i32,
    /// The texture bound to the sampler's target on that unit (0: none).
    pub texture: u32,
}

/// One texture a draw writes: its attachment point, size and format.
#[derive(Clone, Debug)]
pub struct TargetFacts {
    /// `GL_COLOR_ATTACHMENT0`, ..., `GL_DEPTH_ATTACHMENT`.
    pub attachment: String,
    pub texture: u32,
    pub width: u32,
    pub height: u32,
    pub format: String,
    pub kind: FormatKind,
    /// A colour attachment (the viewport and the format rules apply to these).
    pub color: bool,
}

/// The state a draw was made in, seen just before it was made.
#[derive(Clone, Debug)]
pub struct DrawFacts {
    /// The draw's number in the recorded trace (1-based) and its GL function.
    pub call: usize,
    pub function: &'static str,
    /// The program in use (0: none).
    pub program: u32,
    /// The framebuffer bound for drawing (0: the context's own, which a headless context
    /// does not have).
    pub framebuffer: u32,
    /// x, y, width, height.
    pub viewport: [i32; 4],
    pub samplers: Vec<SamplerFacts>,
    pub targets: Vec<TargetFacts>,
}

/// What is wrong with a draw that GL itself lets pass.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DrawProblem {
    /// No program is in use.
    NoProgram,
    /// It draws into framebuffer 0, which a headless context does not have.
    DefaultFramebuffer,
    /// A sampler reads a texture the draw writes (a rendering feedback loop: undefined).
    FeedbackLoop {
        sampler: String,
        unit: i32,
        texture: u32,
        attachment: String,
    },
    /// A colour target that clamps or is not a float array.
    NotFloat {
        texture: u32,
        format: String,
        attachment: String,
    },
    /// The viewport is not the colour target's rectangle.
    Viewport {
        viewport: [i32; 4],
        width: u32,
        height: u32,
    },
}

impl fmt::Display for DrawProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DrawProblem::NoProgram => write!(f, "no program is in use (glUseProgram)"),
            DrawProblem::DefaultFramebuffer => write!(
                f,
                "it draws into framebuffer 0, the context's own, which a headless context does \
                 not have: bind your framebuffer (glBindFramebuffer)"
            ),
            DrawProblem::FeedbackLoop {
                sampler,
                unit,
                texture,
                attachment,
            } => write!(
                f,
                "sampler {sampler} reads unit {unit}, which holds texture {texture}, and \
                 texture {texture} is the framebuffer's {attachment}, the target being drawn: \
                 a feedback loop, whose result GL leaves undefined"
            ),
            DrawProblem::NotFloat {
                texture,
                format,
                attachment,
            } => write!(
                f,
                "its target ({attachment}, texture {texture}) is {format}, not a float format: \
                 what the shader writes is clamped or converted, not kept"
            ),
            DrawProblem::Viewport {
                viewport,
                width,
                height,
            } => write!(
                f,
                "the viewport is {}, {}, {} x {} but the target is {width} x {height}: the draw \
                 covers {}",
                viewport[0],
                viewport[1],
                viewport[2],
                viewport[3],
                if viewport[2] <= 0 || viewport[3] <= 0 {
                    "no texel at all".to_string()
                } else {
                    "other texels than the target's (glViewport)".to_string()
                }
            ),
        }
    }
}

impl DrawFacts {
    /// What is wrong with the draw, in order: no program, no target, feedback loops, targets
    /// that are not float, a viewport that is not the first colour target's rectangle.
    pub fn problems(&self) -> Vec<DrawProblem> {
        let mut problems = Vec::new();
        if self.program == 0 {
            problems.push(DrawProblem::NoProgram);
        }
        if self.framebuffer == 0 {
            problems.push(DrawProblem::DefaultFramebuffer);
        }
        for s in &self.samplers {
            if let Some(t) = self
                .targets
                .iter()
                .find(|t| s.texture != 0 && t.texture == s.texture)
            {
                problems.push(DrawProblem::FeedbackLoop {
                    sampler: s.name.clone(),
                    unit: s.unit,
                    texture: s.texture,
                    attachment: t.attachment.clone(),
                });
            }
        }
        for t in self.targets.iter().filter(|t| t.color) {
            if t.kind != FormatKind::Float {
                problems.push(DrawProblem::NotFloat {
                    texture: t.texture,
                    format: t.format.clone(),
                    attachment: t.attachment.clone(),
                });
            }
        }
        if let Some(t) = self.targets.iter().find(|t| t.color) {
            let whole = [0, 0, t.width as i32, t.height as i32];
            if self.viewport != whole {
                problems.push(DrawProblem::Viewport {
                    viewport: self.viewport,
                    width: t.width,
                    height: t.height,
                });
            }
        }
        problems
    }
}

impl LearnerGl {
    /// The recorder, with glow's methods: every call the exercise makes goes through it.
    pub fn gl(&self) -> &Gl {
        self.ctx.gl()
    }

    /// The context the exercise runs on.
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// How many calls the trace holds now (a mark in it: the harness's stopwatch).
    pub fn calls_so_far(&self) -> usize {
        self.ctx.gl().recorded()
    }

    /// Inspect the draws from now on (`true`, as from the start), or not: a stopwatch pauses
    /// the inspections while it runs, so that it times the learner's calls alone.
    pub fn inspect_draws(&self, on: bool) {
        self.ctx.gl().set_inspecting(on);
    }

    /// The draws inspected since the last call, in order.
    pub fn take_draws(&self) -> Vec<DrawFacts> {
        self.ctx.gl().take_draws()
    }

    /// The GL errors pending, by name, in the order GL gives them (none: empty); they are
    /// taken, so the next check starts clean.
    pub fn take_errors(&self) -> Vec<String> {
        let gl = self.ctx.gl();
        let mut names = Vec::new();
        loop {
            // SAFETY: glGetError has no preconditions; errors held by inspections come first.
            let code = unsafe { gl.get_error_untraced() };
            if code == glow::NO_ERROR {
                return names;
            }
            names.push(name_of(code));
        }
    }

    /// A 2D texture's size, format and level 0.
    pub fn texture(&self, texture: glow::Texture) -> Result<TextureFacts, String> {
        let id = texture.id();
        self.quietly(|raw| unsafe {
            let before = raw.get_parameter_texture(glow::TEXTURE_BINDING_2D);
            raw.bind_texture(glow::TEXTURE_2D, Some(texture));
            if raw.get_error() != glow::NO_ERROR {
                raw.bind_texture(glow::TEXTURE_2D, before);
                return Err(format!(
                    "texture {id} is not a 2D texture (it was first bound to another target)"
                ));
            }
            let facts = level_zero(raw, id);
            let facts = facts.map(|mut f| {
                f.values = read_level_zero(raw, &f);
                f
            });
            raw.bind_texture(glow::TEXTURE_2D, before);
            facts
        })
    }

    /// A framebuffer's status and its first colour attachment.
    pub fn framebuffer(&self, framebuffer: glow::Framebuffer) -> Result<FramebufferFacts, String> {
        let id = framebuffer.id();
        self.quietly(|raw| unsafe {
            let before = raw.get_parameter_framebuffer(glow::DRAW_FRAMEBUFFER_BINDING);
            raw.bind_framebuffer(glow::DRAW_FRAMEBUFFER, Some(framebuffer));
            if raw.get_error() != glow::NO_ERROR {
                raw.bind_framebuffer(glow::DRAW_FRAMEBUFFER, before);
                return Err(format!("{id} is not a framebuffer"));
            }
            let status = raw.check_framebuffer_status(glow::DRAW_FRAMEBUFFER);
            let color0 = attached_texture(raw, glow::COLOR_ATTACHMENT0);
            raw.bind_framebuffer(glow::DRAW_FRAMEBUFFER, before);
            Ok(FramebufferFacts {
                id,
                status: name_of(status),
                complete: status == glow::FRAMEBUFFER_COMPLETE,
                color0,
            })
        })
    }

    /// Why sampling `texture` (a 2D texture) reads 0, or `None`: a minifying filter that
    /// uses mipmaps a texture does not have makes it incomplete, as GL calls it.
    pub fn sampling_incomplete(&self, texture: glow::Texture) -> Option<String> {
        let id = texture.id();
        self.quietly(|raw| unsafe {
            let before = raw.get_parameter_texture(glow::TEXTURE_BINDING_2D);
            raw.bind_texture(glow::TEXTURE_2D, Some(texture));
            let filter =
                raw.get_tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MIN_FILTER) as u32;
            let max_level = raw.get_tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MAX_LEVEL);
            let level_one =
                raw.get_tex_level_parameter_i32(glow::TEXTURE_2D, 1, glow::TEXTURE_WIDTH);
            raw.bind_texture(glow::TEXTURE_2D, before);
            let mipmapped = !matches!(filter, glow::NEAREST | glow::LINEAR);
            (mipmapped && max_level > 0 && level_one == 0).then(|| {
                format!(
                    "texture {id} has the minifying filter {} (the default) and no mipmaps: GL \
                     calls it incomplete, and every read of it gives 0; set \
                     GL_TEXTURE_MIN_FILTER to GL_NEAREST (glTexParameteri)",
                    name_of(filter)
                )
            })
        })
    }

    /// The framebuffer bound for drawing (0: the context's own).
    pub fn draw_framebuffer(&self) -> u32 {
        self.quietly(|raw| unsafe { binding(raw, glow::DRAW_FRAMEBUFFER_BINDING) })
    }

    /// The framebuffer bound for reading (0: the context's own).
    pub fn read_framebuffer(&self) -> u32 {
        self.quietly(|raw| unsafe { binding(raw, glow::READ_FRAMEBUFFER_BINDING) })
    }

    /// The viewport: x, y, width, height.
    pub fn viewport(&self) -> [i32; 4] {
        self.quietly(|raw| unsafe { viewport(raw) })
    }

    /// The program in use (0: none).
    pub fn program_in_use(&self) -> u32 {
        self.quietly(|raw| unsafe { binding(raw, glow::CURRENT_PROGRAM) })
    }

    /// Whether `program` is linked, with its log.
    pub fn program(&self, program: glow::Program) -> ProgramFacts {
        self.quietly(|raw| unsafe {
            ProgramFacts {
                id: program.id(),
                linked: raw.get_program_link_status(program),
                log: raw.get_program_info_log(program),
            }
        })
    }

    /// The value of uniform `name` of the program in use.
    pub fn uniform(&self, name: &str) -> Result<UniformValue, String> {
        self.quietly(|raw| unsafe {
            let Some(program) = object(binding(raw, glow::CURRENT_PROGRAM), glow::NativeProgram)
            else {
                return Err("no program is in use (glUseProgram)".into());
            };
            uniform_value(raw, program, name)
        })
    }

    /// The 2D texture bound on texture unit `unit` (0: none).
    pub fn texture_on_unit(&self, unit: i32) -> u32 {
        self.quietly(|raw| unsafe { bound_on_unit(raw, unit, glow::TEXTURE_BINDING_2D) })
    }

    /// The buffer bound as `GL_PIXEL_PACK_BUFFER` and its size in bytes, if one is.
    pub fn pack_buffer(&self) -> Option<(u32, i64)> {
        self.quietly(|raw| unsafe {
            let id = binding(raw, glow::PIXEL_PACK_BUFFER_BINDING);
            (id != 0).then(|| {
                let size = raw.get_buffer_parameter_i32(glow::PIXEL_PACK_BUFFER, glow::BUFFER_SIZE);
                (id, size as i64)
            })
        })
    }

    /// A buffer's bytes, read without disturbing its bindings.
    pub fn buffer_bytes(&self, buffer: glow::Buffer) -> Result<Vec<u8>, String> {
        let id = buffer.id();
        self.quietly(|raw| unsafe {
            let before = raw.get_parameter_buffer(glow::COPY_READ_BUFFER_BINDING);
            raw.bind_buffer(glow::COPY_READ_BUFFER, Some(buffer));
            if raw.get_error() != glow::NO_ERROR {
                raw.bind_buffer(glow::COPY_READ_BUFFER, before);
                return Err(format!("{id} is not a buffer"));
            }
            let size = raw.get_buffer_parameter_i32(glow::COPY_READ_BUFFER, glow::BUFFER_SIZE);
            let mut bytes = vec![0u8; size.max(0) as usize];
            if !bytes.is_empty() {
                raw.get_buffer_sub_data(glow::COPY_READ_BUFFER, 0, &mut bytes);
            }
            raw.bind_buffer(glow::COPY_READ_BUFFER, before);
            Ok(bytes)
        })
    }

    /// Run untraced queries: errors pending before are held for the learner, errors the
    /// queries raise are dropped.
    fn quietly<T>(&self, query: impl FnOnce(&glow::Context) -> T) -> T {
        let gl = self.ctx.gl();
        gl.hold_errors();
        let raw = gl.untraced();
        let result = query(raw);
        // SAFETY: glGetError has no preconditions.
        unsafe { while raw.get_error() != glow::NO_ERROR {} }
        result
    }
}

/// Inspect the state a draw is about to be made in (untraced; the recorder holds the errors
/// pending before and drops those raised here).
pub(super) fn inspect_draw(raw: &glow::Context, function: &'static str, call: usize) -> DrawFacts {
    // SAFETY: queries of the current context's state; each binding changed is put back.
    let facts = unsafe {
        let program = binding(raw, glow::CURRENT_PROGRAM);
        let framebuffer = binding(raw, glow::DRAW_FRAMEBUFFER_BINDING);
        DrawFacts {
            call,
            function,
            program,
            framebuffer,
            viewport: viewport(raw),
            samplers: object(program, glow::NativeProgram)
                .map_or_else(Vec::new, |p| samplers(raw, p)),
            targets: if framebuffer == 0 {
                Vec::new()
            } else {
                targets(raw)
            },
        }
    };
    unsafe { while raw.get_error() != glow::NO_ERROR {} }
    facts
}

/// A handle from an id, `None` for 0.
fn object<T>(id: u32, make: fn(NonZeroU32) -> T) -> Option<T> {
    NonZeroU32::new(id).map(make)
}

unsafe fn binding(raw: &glow::Context, parameter: u32) -> u32 {
    raw.get_parameter_i32(parameter).max(0) as u32
}

unsafe fn viewport(raw: &glow::Context) -> [i32; 4] {
    let mut v = [0; 4];
    raw.get_parameter_i32_slice(glow::VIEWPORT, &mut v);
    v
}

/// The texture bound to `binding_of` (e.g. `GL_TEXTURE_BINDING_2D`) on unit `unit`.
unsafe fn bound_on_unit(raw: &glow::Context, unit: i32, binding_of: u32) -> u32 {
    let active = raw.get_parameter_i32(glow::ACTIVE_TEXTURE);
    raw.active_texture(glow::TEXTURE0 + unit.max(0) as u32);
    let texture = binding(raw, binding_of);
    raw.active_texture(active as u32);
    texture
}

/// The texture attached at `attachment` of the draw framebuffer, if one is.
unsafe fn attached_texture(raw: &glow::Context, attachment: u32) -> Option<u32> {
    let kind = raw.get_framebuffer_attachment_parameter_i32(
        glow::DRAW_FRAMEBUFFER,
        attachment,
        glow::FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
    );
    (kind as u32 == glow::TEXTURE).then(|| {
        raw.get_framebuffer_attachment_parameter_i32(
            glow::DRAW_FRAMEBUFFER,
            attachment,
            glow::FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
        ) as u32
    })
}

/// Size and format of level 0 of the texture bound to `GL_TEXTURE_2D` (values not read).
unsafe fn level_zero(raw: &glow::Context, id: u32) -> Result<TextureFacts, String> {
    let level = |p| {
        raw.get_tex_level_parameter_i32(glow::TEXTURE_2D, 0, p)
            .max(0) as u32
    };
    let (width, height) = (level(glow::TEXTURE_WIDTH), level(glow::TEXTURE_HEIGHT));
    if width == 0 || height == 0 {
        return Err(format!(
            "texture {id} has no storage: its level 0 is {width} x {height} (glTexImage2D was \
             not called on it)"
        ));
    }
    let internal = level(glow::TEXTURE_INTERNAL_FORMAT);
    let (channels, kind) = format_facts(internal);
    Ok(TextureFacts {
        id,
        width,
        height,
        format: name_of(internal),
        kind,
        channels,
        values: Vec::new(),
    })
}

/// Level 0 of the texture bound to `GL_TEXTURE_2D` as floats (none for integer formats),
/// past any pixel pack buffer the learner left bound.
unsafe fn read_level_zero(raw: &glow::Context, f: &TextureFacts) -> Vec<f32> {
    if f.kind == FormatKind::Integer {
        return Vec::new();
    }
    let format = [glow::RED, glow::RG, glow::RGB, glow::RGBA][f.channels.clamp(1, 4) - 1];
    let mut values = vec![0f32; (f.width * f.height) as usize * f.channels];
    let pack = raw.get_parameter_buffer(glow::PIXEL_PACK_BUFFER_BINDING);
    let alignment = raw.get_parameter_i32(glow::PACK_ALIGNMENT);
    raw.bind_buffer(glow::PIXEL_PACK_BUFFER, None);
    raw.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
    raw.get_tex_image(
        glow::TEXTURE_2D,
        0,
        format,
        glow::FLOAT,
        glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut values))),
    );
    raw.pixel_store_i32(glow::PACK_ALIGNMENT, alignment);
    raw.bind_buffer(glow::PIXEL_PACK_BUFFER, pack);
    values
}

/// Channels and kind of an internal format.
fn format_facts(internal: u32) -> (usize, FormatKind) {
    use FormatKind::*;
    match internal {
        glow::R32F | glow::R16F => (1, Float),
        glow::RG32F | glow::RG16F => (2, Float),
        glow::RGB32F | glow::RGB16F => (3, Float),
        glow::RGBA32F | glow::RGBA16F => (4, Float),
        glow::R8 | glow::R16 | glow::RED => (1, Normalized),
        glow::RG8 | glow::RG16 | glow::RG => (2, Normalized),
        glow::RGB8 | glow::RGB16 | glow::RGB => (3, Normalized),
        glow::R32UI | glow::R32I | glow::R16UI | glow::R16I | glow::R8UI | glow::R8I => {
            (1, Integer)
        }
        glow::RGBA32UI | glow::RGBA32I | glow::RGBA16UI | glow::RGBA16I | glow::RGBA8UI => {
            (4, Integer)
        }
        glow::DEPTH_COMPONENT32F => (1, Float),
        _ => (4, Normalized),
    }
}

/// Every sampler of `program` with the unit it reads and the texture bound there.
unsafe fn samplers(raw: &glow::Context, program: glow::Program) -> Vec<SamplerFacts> {
    let mut found = Vec::new();
    for index in 0..raw.get_active_uniforms(program) {
        let Some(u) = raw.get_active_uniform(program, index) else {
            continue;
        };
        let Some(binding_of) = sampler_binding(u.utype) else {
            continue;
        };
        let Some(location) = raw.get_uniform_location(program, &u.name) else {
            continue;
        };
        let mut unit = [0i32];
        raw.get_uniform_i32(program, &location, &mut unit);
        found.push(SamplerFacts {
            name: u.name.trim_end_matches("[0]").to_string(),
            unit: unit[0],
            texture: bound_on_unit(raw, unit[0], binding_of),
        });
    }
    found
}

/// The texture binding a sampler type reads, `None` for a type that is not a sampler.
fn sampler_binding(utype: u32) -> Option<u32> {
    match utype {
        glow::SAMPLER_1D | glow::INT_SAMPLER_1D | glow::UNSIGNED_INT_SAMPLER_1D => {
            Some(glow::TEXTURE_BINDING_1D)
        }
        glow::SAMPLER_2D
        | glow::INT_SAMPLER_2D
        | glow::UNSIGNED_INT_SAMPLER_2D
        | glow::SAMPLER_2D_SHADOW => Some(glow::TEXTURE_BINDING_2D),
        glow::SAMPLER_3D | glow::INT_SAMPLER_3D | glow::UNSIGNED_INT_SAMPLER_3D => {
            Some(glow::TEXTURE_BINDING_3D)
        }
        glow::SAMPLER_2D_RECT => Some(glow::TEXTURE_BINDING_RECTANGLE),
        _ => None,
    }
}

/// The textures attached to the draw framebuffer: colour attachments, then depth.
unsafe fn targets(raw: &glow::Context) -> Vec<TargetFacts> {
    let colours = raw
        .get_parameter_i32(glow::MAX_COLOR_ATTACHMENTS)
        .clamp(1, 16) as u32;
    let points = (0..colours)
        .map(|i| (glow::COLOR_ATTACHMENT0 + i, true))
        .chain([(glow::DEPTH_ATTACHMENT, false)]);
    let mut found = Vec::new();
    for (attachment, color) in points {
        let Some(texture) = attached_texture(raw, attachment) else {
            continue;
        };
        let before = raw.get_parameter_texture(glow::TEXTURE_BINDING_2D);
        raw.bind_texture(glow::TEXTURE_2D, object(texture, glow::NativeTexture));
        if let Ok(f) = level_zero(raw, texture) {
            found.push(TargetFacts {
                attachment: name_of(attachment),
                texture,
                width: f.width,
                height: f.height,
                format: f.format,
                kind: f.kind,
                color,
            });
        }
        raw.bind_texture(glow::TEXTURE_2D, before);
    }
    found
}

/// The value of the active uniform `name` of `program`.
unsafe fn uniform_value(
    raw: &glow::Context,
    program: glow::Program,
    name: &str,
) -> Result<UniformValue, String> {
    let active = (0..raw.get_active_uniforms(program))
        .filter_map(|i| raw.get_active_uniform(program, i))
        .find(|u| u.name == name || u.name == format!("{name}[0]"));
    let (Some(u), Some(location)) = (active, raw.get_uniform_location(program, name)) else {
        return Err(format!(
            "the program in use ({}) has no active uniform {name}: its shaders do not declare \
             it, or do not use it",
            program.id()
        ));
    };
    if sampler_binding(u.utype).is_some() {
        let mut unit = [0i32];
        raw.get_uniform_i32(program, &location, &mut unit);
        return Ok(UniformValue::Sampler(unit[0]));
    }
    let (count, float) = match u.utype {
        glow::FLOAT => (1, true),
        glow::FLOAT_VEC2 => (2, true),
        glow::FLOAT_VEC3 => (3, true),
        glow::FLOAT_VEC4 => (4, true),
        glow::INT | glow::BOOL | glow::UNSIGNED_INT => (1, false),
        glow::INT_VEC2 | glow::UNSIGNED_INT_VEC2 => (2, false),
        glow::INT_VEC3 | glow::UNSIGNED_INT_VEC3 => (3, false),
        glow::INT_VEC4 | glow::UNSIGNED_INT_VEC4 => (4, false),
        _ => {
            return Err(format!(
                "uniform {name} is of a type this check does not read"
            ))
        }
    };
    Ok(if float {
        let mut v = vec![0f32; count];
        raw.get_uniform_f32(program, &location, &mut v);
        UniformValue::Float(v)
    } else {
        let mut v = vec![0i32; count];
        raw.get_uniform_i32(program, &location, &mut v);
        UniformValue::Int(v)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn target(width: u32, kind: FormatKind, texture: u32) -> TargetFacts {
        TargetFacts {
            attachment: "GL_COLOR_ATTACHMENT0".into(),
            texture,
            width,
            height: 4,
            format: "GL_R32F".into(),
            kind,
            color: true,
        }
    }

    fn draw(targets: Vec<TargetFacts>, viewport: [i32; 4], sampled: u32) -> DrawFacts {
        DrawFacts {
            call: 7,
            function: "glDrawArrays",
            program: 3,
            framebuffer: 1,
            viewport,
            samplers: vec![SamplerFacts {
                name: "u_x".into(),
                unit: 0,
                texture: sampled,
            }],
            targets,
        }
    }

    #[test]
    fn a_clean_draw_has_no_problem() {
        let d = draw(vec![target(8, FormatKind::Float, 2)], [0, 0, 8, 4], 1);
        assert!(d.problems().is_empty(), "{:?}", d.problems());
    }

    #[test]
    fn loops_formats_and_viewports_are_named() {
        let d = draw(vec![target(8, FormatKind::Normalized, 2)], [0, 0, 4, 4], 2);
        let problems = d.problems();
        assert!(matches!(
            problems[0],
            DrawProblem::FeedbackLoop { texture: 2, .. }
        ));
        assert!(matches!(
            problems[1],
            DrawProblem::NotFloat { texture: 2, .. }
        ));
        assert!(matches!(
            problems[2],
            DrawProblem::Viewport { width: 8, .. }
        ));
        assert!(problems[0].to_string().contains("feedback loop"));
        let none = draw(vec![target(8, FormatKind::Float, 2)], [0, 0, 0, 0], 1);
        assert!(none.problems()[0].to_string().contains("no texel at all"));
    }
}
