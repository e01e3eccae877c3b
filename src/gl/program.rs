//! Programs built from shader files. Several files can make one stage (a shared snippet
//! followed by the shader that uses it); each is numbered with `#line 1 N`, so a compile error
//! names the file and line it is really on, with the source lines around it.

use super::shaders::ShaderSource;
use super::uniforms::{base_name, Declared};
use super::{Context, GlError};
use glam::{IVec2, IVec4, Mat3, Mat4, Vec2, Vec3, Vec4};
use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt;

/// A shader that failed to compile.
#[derive(Debug)]
pub struct ShaderError {
    pub stage: &'static str,
    /// The file the first error is in.
    pub file: String,
    /// The line of the first error in that file, when the driver said.
    pub line: Option<u32>,
    /// The driver's log, with source numbers replaced by file names.
    pub log: String,
    /// The numbered source lines around the error.
    pub excerpt: String,
}

impl fmt::Display for ShaderError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self.line {
            Some(line) => write!(
                f,
                "{} shader {}:{line} failed to compile",
                self.stage, self.file
            )?,
            None => write!(f, "{} shader {} failed to compile", self.stage, self.file)?,
        }
        write!(f, "\n{}", self.log.trim_end())?;
        if !self.excerpt.is_empty() {
            write!(f, "\n{}", self.excerpt.trim_end())?;
        }
        Ok(())
    }
}

impl std::error::Error for ShaderError {}

/// A linked program. It knows the uniforms its files declare, so that setting one they do
/// not is an error (see [`Program::set`]); locations are looked up once and cached.
pub struct Program {
    ctx: Context,
    id: glow::Program,
    files: String,
    uniforms: Declared,
    /// The sampler uniforms the vertex stage declares (vertex texture fetch).
    vertex_samplers: Vec<String>,
    locations: RefCell<HashMap<String, Option<glow::UniformLocation>>>,
}

impl Drop for Program {
    fn drop(&mut self) {
        unsafe { self.ctx.gl().delete_program(self.id) };
    }
}

/// The vertex shader of every rectangle pass ([`super::Pass::draw_rect`]).
pub(super) const RECT_VERTEX: ShaderSource<'static> = crate::shader!("glsl/gl/rect.vert");

impl Program {
    /// Compile and link a program whose vertex stage is the concatenation of `vertex` and
    /// whose fragment stage is the concatenation of `fragment`. The first file of each stage
    /// carries the `#version` line.
    pub fn new(
        ctx: &Context,
        vertex: &[ShaderSource],
        fragment: &[ShaderSource],
    ) -> Result<Program, GlError> {
        Program::link(
            ctx,
            &[
                (glow::VERTEX_SHADER, "vertex", vertex),
                (glow::FRAGMENT_SHADER, "fragment", fragment),
            ],
        )
    }

    /// Compile each stage `(GL shader kind, stage name, files)` and link them into one program.
    pub(super) fn link(
        ctx: &Context,
        stages: &[(u32, &'static str, &[ShaderSource])],
    ) -> Result<Program, GlError> {
        Program::link_capturing(ctx, stages, &[])
    }

    /// A program of a vertex stage alone whose outputs `varyings` are captured, interleaved in
    /// that order, into a buffer by transform feedback ([`super::feedback`]): vertices computed
    /// by a vertex shader and kept, with nothing rasterized.
    pub fn feedback(
        ctx: &Context,
        vertex: &[ShaderSource],
        varyings: &[&str],
    ) -> Result<Program, GlError> {
        Program::link_capturing(ctx, &[(glow::VERTEX_SHADER, "vertex", vertex)], varyings)
    }

    /// [`Program::link`], declaring `varyings` for transform feedback before linking.
    fn link_capturing(
        ctx: &Context,
        stages: &[(u32, &'static str, &[ShaderSource])],
        varyings: &[&str],
    ) -> Result<Program, GlError> {
        // `--glsl-dir`: each file the folder has replaces the compiled-in copy.
        let loaded: Vec<Vec<(String, Option<String>)>> = stages
            .iter()
            .map(|(_, _, parts)| parts.iter().map(|p| from_glsl_dir(ctx, p)).collect())
            .collect::<Result<_, _>>()?;
        let replaced: Vec<Vec<ShaderSource>> = stages
            .iter()
            .zip(&loaded)
            .map(|((_, _, parts), loaded)| {
                parts
                    .iter()
                    .zip(loaded)
                    .map(|(part, (name, text))| match text {
                        Some(text) => ShaderSource { name, source: text },
                        None => *part,
                    })
                    .collect()
            })
            .collect();
        let stages: Vec<(u32, &'static str, &[ShaderSource])> = stages
            .iter()
            .zip(&replaced)
            .map(|(&(kind, stage, _), parts)| (kind, stage, parts.as_slice()))
            .collect();
        let stages = stages.as_slice();
        let gl = ctx.gl();
        let files: Vec<&str> = stages
            .iter()
            .flat_map(|(_, _, parts)| parts.iter().map(|s| s.name))
            .collect();
        let files = files.join(", ");
        let all: Vec<ShaderSource> = stages
            .iter()
            .flat_map(|(_, _, parts)| parts.iter().copied())
            .collect();
        let id = unsafe { gl.create_program() }.map_err(GlError::Invalid)?;
        let mut program = Program {
            ctx: ctx.clone(),
            id,
            files,
            uniforms: Declared::parse(&all),
            vertex_samplers: stages
                .iter()
                .filter(|(kind, _, _)| *kind == glow::VERTEX_SHADER)
                .flat_map(|(_, _, parts)| parts.iter())
                .flat_map(|part| sampler_names(part.source))
                .collect(),
            locations: RefCell::new(HashMap::new()),
        };
        let shaders = stages
            .iter()
            .map(|&(kind, stage, parts)| compile(ctx, kind, stage, parts));
        let mut compiled = Vec::new();
        let mut first_error = None;
        for s in shaders {
            match s {
                Ok(s) => compiled.push(s),
                Err(e) => first_error = first_error.or(Some(e)),
            }
        }
        if let Some(e) = first_error {
            unsafe { compiled.into_iter().for_each(|s| gl.delete_shader(s)) };
            return Err(e);
        }
        unsafe {
            for &s in &compiled {
                gl.attach_shader(id, s);
            }
            if !varyings.is_empty() {
                gl.transform_feedback_varyings(id, varyings, glow::INTERLEAVED_ATTRIBS);
            }
            gl.link_program(id);
            for s in compiled {
                gl.detach_shader(id, s);
                gl.delete_shader(s);
            }
            if !gl.get_program_link_status(id) {
                return Err(GlError::Link {
                    files: program.files.clone(),
                    log: gl.get_program_info_log(id),
                });
            }
        }
        program.add_active_uniforms();
        ctx.check_now(&format!("linking {}", program.files))?;
        Ok(program)
    }

    /// Compile the concatenation of `parts` as one `stage`, without linking it into a program:
    /// whether a file (with what comes before it in its stage) compiles on this context. A
    /// file of a 4.3 stage (compute) on an older context is [`Context::require_compute`]'s
    /// error.
    pub fn check_compiles(
        ctx: &Context,
        stage: super::shaders::Stage,
        parts: &[ShaderSource],
    ) -> Result<(), GlError> {
        use super::shaders::Stage;
        let (kind, name) = match stage {
            Stage::Vertex => (glow::VERTEX_SHADER, "vertex"),
            Stage::Fragment => (glow::FRAGMENT_SHADER, "fragment"),
            Stage::Geometry => (glow::GEOMETRY_SHADER, "geometry"),
            Stage::Compute => {
                let names: Vec<&str> = parts.iter().map(|p| p.name).collect();
                ctx.require_compute(&format!("the compute shader {}", names.join(", ")))?;
                (glow::COMPUTE_SHADER, "compute")
            }
        };
        let shader = compile(ctx, kind, name, parts)?;
        unsafe { ctx.gl().delete_shader(shader) };
        Ok(())
    }

    /// Whatever the driver reports active counts as declared too (a declaration made by a
    /// macro, which the parser does not expand); members of uniform blocks do not.
    fn add_active_uniforms(&mut self) {
        let gl = self.ctx.gl();
        unsafe {
            let count = gl.get_active_uniforms(self.id);
            let indices: Vec<u32> = (0..count).collect();
            let blocks =
                gl.get_active_uniforms_parameter(self.id, &indices, glow::UNIFORM_BLOCK_INDEX);
            for (index, block) in indices.into_iter().zip(blocks) {
                if block != -1 {
                    continue;
                }
                if let Some(active) = gl.get_active_uniform(self.id, index) {
                    self.uniforms.add_active(&active.name);
                }
            }
        }
    }

    /// A program for rectangle passes: the built-in rectangle vertex shader (which passes
    /// `v_uv`, 0..1 across the rectangle) and the given fragment stage.
    pub fn rect(ctx: &Context, fragment: &[ShaderSource]) -> Result<Program, GlError> {
        Program::new(ctx, &[RECT_VERTEX], fragment)
    }

    /// The files this program was built from.
    pub fn files(&self) -> &str {
        &self.files
    }

    pub(super) fn id(&self) -> glow::Program {
        self.id
    }

    pub(super) fn bind(&self) {
        unsafe { self.ctx.gl().use_program(Some(self.id)) };
    }

    /// Set uniform `name` (an array element `u_rows[2]` or struct member `u_light.colour`
    /// too). A uniform the files declare is set, or skipped when the driver removed it as
    /// unused; a name they do not declare is an error naming the files and the name. Where a
    /// uniform is optional, say so with [`Program::set_if_used`].
    pub fn set<U: Uniform>(&self, name: &str, value: U) -> Result<(), GlError> {
        self.check_declared(name)?;
        self.set_if_used(name, value);
        Ok(())
    }

    /// Set uniform `name` if the program has it; nothing happens if it does not.
    pub fn set_if_used<U: Uniform>(&self, name: &str, value: U) {
        if let Some(location) = self.location(name) {
            self.bind();
            self.ctx.gl().name_uniform(name);
            unsafe { value.apply(self.ctx.gl(), &location) };
        }
    }

    /// Whether the program's files declare uniform `name` (used or not).
    pub fn declares_uniform(&self, name: &str) -> bool {
        self.uniforms.names.contains(base_name(name))
    }

    /// Whether the vertex stage declares sampler `name` (it reads a texture there).
    pub fn vertex_stage_samples(&self, name: &str) -> bool {
        self.vertex_samplers.iter().any(|s| s == base_name(name))
    }

    /// Whether the linked program uses uniform `name` (the driver kept it).
    pub fn uses_uniform(&self, name: &str) -> bool {
        self.location(name).is_some()
    }

    fn check_declared(&self, name: &str) -> Result<(), GlError> {
        if self.declares_uniform(name) {
            return Ok(());
        }
        let problem = match self.uniforms.block_members.get(base_name(name)) {
            Some(block) => {
                format!("is a member of uniform block {block}, which is set through a buffer")
            }
            None if self.uniforms.names.is_empty() => "is not declared (it has none)".into(),
            None => format!(
                "is not declared (it has {})",
                self.uniforms
                    .names
                    .iter()
                    .map(String::as_str)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        Err(GlError::Uniform {
            files: self.files.clone(),
            uniform: name.to_string(),
            problem,
        })
    }

    fn location(&self, name: &str) -> Option<glow::UniformLocation> {
        if let Some(known) = self.locations.borrow().get(name) {
            return *known;
        }
        let location = unsafe { self.ctx.gl().get_uniform_location(self.id, name) };
        self.locations
            .borrow_mut()
            .insert(name.to_string(), location);
        location
    }
}

/// The file `part` names under the context's `--glsl-dir` folder, if that folder has it: its
/// path on disk (which errors then name) and its text. `(_, None)`: use the compiled-in copy,
/// only where the folder has nothing of that name; an entry that is there but is not a regular
/// file (a folder, a dangling link, a FIFO) is an error, never silently the compiled-in copy.
fn from_glsl_dir(ctx: &Context, part: &ShaderSource) -> Result<(String, Option<String>), GlError> {
    let Some(dir) = ctx.glsl_dir() else {
        return Ok((String::new(), None));
    };
    let path = dir.join(part.name);
    let refused = |message: String| GlError::Invalid(format!("{}: {message}", path.display()));
    if !super::shaders::in_glsl_dir(&path).map_err(refused)? {
        return Ok((String::new(), None));
    }
    let text = std::fs::read_to_string(&path).map_err(|e| {
        refused(format!(
            "cannot read this shader (given by --glsl-dir): {e}"
        ))
    })?;
    Ok((path.display().to_string(), Some(text)))
}

/// The names of the sampler uniforms `source` declares (`uniform sampler2D u_tiles;`,
/// `uniform highp usampler2D a, b;`), comments aside.
fn sampler_names(source: &str) -> Vec<String> {
    let mut names = Vec::new();
    for line in source.lines() {
        let code = line.split("//").next().unwrap_or("");
        for statement in code.split(';') {
            let words: Vec<&str> = statement
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|w| !w.is_empty())
                .collect();
            let Some(u) = words.iter().position(|w| *w == "uniform") else {
                continue;
            };
            let Some(t) = words[u + 1..].iter().position(|w| w.contains("sampler")) else {
                continue;
            };
            names.extend(
                words[u + 1 + t + 1..]
                    .iter()
                    .map(|w| w.split('[').next().unwrap_or(w).to_string()),
            );
        }
    }
    names
}

/// Join the files of one stage, each numbered as its own source string.
fn assemble(parts: &[ShaderSource]) -> String {
    let version = parts
        .iter()
        .flat_map(|p| p.source.lines())
        .find(|l| l.trim_start().starts_with("#version"))
        .unwrap_or("#version 330 core");
    let mut out = format!("{}\n", version.trim());
    for (i, part) in parts.iter().enumerate() {
        out.push_str(&format!("#line 1 {i}\n"));
        for line in part.source.lines() {
            // The version line stays in place as a blank line, so line numbers keep matching.
            if !line.trim_start().starts_with("#version") {
                out.push_str(line);
            }
            out.push('\n');
        }
    }
    out
}

fn compile(
    ctx: &Context,
    kind: u32,
    stage: &'static str,
    parts: &[ShaderSource],
) -> Result<glow::Shader, GlError> {
    if parts.is_empty() {
        return Err(GlError::Invalid(format!(
            "a program needs a {stage} shader"
        )));
    }
    let gl = ctx.gl();
    unsafe {
        let shader = gl.create_shader(kind).map_err(GlError::Invalid)?;
        gl.shader_source(shader, &assemble(parts));
        gl.compile_shader(shader);
        if gl.get_shader_compile_status(shader) {
            return Ok(shader);
        }
        let log = gl.get_shader_info_log(shader);
        gl.delete_shader(shader);
        Err(GlError::Shader(explain(stage, parts, &log)))
    }
}

/// Turn a driver log into an error naming the file and line, with an excerpt.
fn explain(stage: &'static str, parts: &[ShaderSource], log: &str) -> ShaderError {
    let located = log.lines().find_map(parse_location);
    let (file_index, line) = match located {
        Some((source, line)) if (source as usize) < parts.len() => (source as usize, Some(line)),
        _ => (0, None),
    };
    let log = log
        .lines()
        .map(|l| match parse_location(l) {
            Some((source, line)) if (source as usize) < parts.len() => {
                format!("{}:{line}: {}", parts[source as usize].name, message_of(l))
            }
            _ => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    let excerpt = line
        .map(|line| excerpt(parts[file_index].source, line, 2))
        .unwrap_or_default();
    ShaderError {
        stage,
        file: parts[file_index].name.to_string(),
        line,
        log,
        excerpt,
    }
}

/// `0:12(5): error ...` (Mesa) or `0(12) : error ...` (NVIDIA): the source number and line.
fn parse_location(line: &str) -> Option<(u32, u32)> {
    let line = line.trim_start();
    let source_end = line.find(|c: char| !c.is_ascii_digit())?;
    let source: u32 = line[..source_end].parse().ok()?;
    let rest = &line[source_end..];
    let rest = rest.strip_prefix(':').or_else(|| rest.strip_prefix('('))?;
    let line_end = rest.find(|c: char| !c.is_ascii_digit())?;
    let number: u32 = rest[..line_end].parse().ok()?;
    Some((source, number))
}

/// The log line without its location prefix.
fn message_of(line: &str) -> &str {
    match line.find("): ").or_else(|| line.find(") : ")) {
        Some(i) => line[i + 1..].trim_start_matches([':', ' ']),
        None => line,
    }
}

/// The lines `line - context ..= line + context` of `source`, numbered, the error marked.
fn excerpt(source: &str, line: u32, context: u32) -> String {
    let first = line.saturating_sub(context).max(1);
    source
        .lines()
        .enumerate()
        .map(|(i, text)| (i as u32 + 1, text))
        .filter(|(n, _)| *n >= first && *n <= line + context)
        .map(|(n, text)| {
            let mark = if n == line { '>' } else { ' ' };
            format!("{mark}{n:5} | {text}\n")
        })
        .collect()
}

/// A value that can be assigned to a GLSL uniform.
pub trait Uniform {
    /// # Safety
    /// The program owning `location` must be current.
    unsafe fn apply(&self, gl: &super::trace::Gl, location: &glow::UniformLocation);
}

macro_rules! uniform {
    ($t:ty, |$v:ident, $gl:ident, $l:ident| $body:expr) => {
        impl Uniform for $t {
            unsafe fn apply(&self, $gl: &super::trace::Gl, $l: &glow::UniformLocation) {
                let $v = self;
                $body
            }
        }
    };
}

uniform!(f32, |v, gl, l| gl.uniform_1_f32(Some(l), *v));
uniform!(i32, |v, gl, l| gl.uniform_1_i32(Some(l), *v));
uniform!(u32, |v, gl, l| gl.uniform_1_u32(Some(l), *v));
uniform!(bool, |v, gl, l| gl.uniform_1_i32(Some(l), *v as i32));
uniform!(Vec2, |v, gl, l| gl.uniform_2_f32(Some(l), v.x, v.y));
uniform!(Vec3, |v, gl, l| gl.uniform_3_f32(Some(l), v.x, v.y, v.z));
uniform!(Vec4, |v, gl, l| gl.uniform_4_f32(
    Some(l),
    v.x,
    v.y,
    v.z,
    v.w
));
uniform!(IVec2, |v, gl, l| gl.uniform_2_i32(Some(l), v.x, v.y));
uniform!(IVec4, |v, gl, l| gl.uniform_4_i32(
    Some(l),
    v.x,
    v.y,
    v.z,
    v.w
));
uniform!(Mat3, |v, gl, l| gl.uniform_matrix_3_f32_slice(
    Some(l),
    false,
    &v.to_cols_array()
));
uniform!(Mat4, |v, gl, l| gl.uniform_matrix_4_f32_slice(
    Some(l),
    false,
    &v.to_cols_array()
));
uniform!(&[f32], |v, gl, l| gl.uniform_1_f32_slice(Some(l), v));
uniform!(&[i32], |v, gl, l| gl.uniform_1_i32_slice(Some(l), v));
uniform!(&[Vec4], |v, gl, l| gl
    .uniform_4_f32_slice(Some(l), bytemuck::cast_slice(v)));
uniform!(&[Mat4], |v, gl, l| gl.uniform_matrix_4_f32_slice(
    Some(l),
    false,
    bytemuck::cast_slice(v)
));

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locations_of_mesa_and_nvidia_logs() {
        assert_eq!(
            parse_location("0:12(5): error: syntax error"),
            Some((0, 12))
        );
        assert_eq!(
            parse_location("1(7) : error C0000: syntax error"),
            Some((1, 7))
        );
        assert_eq!(parse_location("error: no location"), None);
    }

    #[test]
    fn assembled_sources_keep_line_numbers() {
        let a = ShaderSource {
            name: "a",
            source: "#version 330 core\nfloat a;\n",
        };
        let b = ShaderSource {
            name: "b",
            source: "float b;\n",
        };
        let text = assemble(&[a, b]);
        assert_eq!(
            text,
            "#version 330 core\n#line 1 0\n\nfloat a;\n#line 1 1\nfloat b;\n"
        );
    }

    #[test]
    fn excerpt_marks_the_line() {
        let text = excerpt("l1\nl2\nl3\nl4\nl5\nl6", 4, 1);
        assert_eq!(text, "     3 | l3\n>    4 | l4\n     5 | l5\n");
    }
}
