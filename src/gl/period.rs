//! The papers' own GPUs as a checked budget. Papers 1, 2 and 4 ran on a GeForce 7800 GTX
//! (G70), paper 3 on an ATI RADEON 9700 PRO (R300); both had limits that today's OpenGL hides
//! (no blending or filtering of 32-bit float targets on the G70, vertex texture fetch only
//! from some float formats, no float blending at all on the R300, smaller textures). The
//! limits and the source of each are the table `assets/period_gpus.toml`.
//!
//! While a context runs under a profile ([`Context::set_period`]), the GL layer checks what
//! it makes and draws against it where the objects are made: texture size and format
//! (`texture.rs`), colour attachments (`framebuffer.rs`), blending into a float target,
//! filtering a float texture and reading a texture in a vertex shader (`pass.rs`), compute
//! shaders (`compute.rs`) and occlusion counts (`query.rs`). A request beyond the budget is a
//! [`GlError::Limit`] naming the GPU, the limit and what was asked.

use super::{Context, Filter, GlError, TextureFormat};
use serde::Deserialize;
use std::sync::OnceLock;

/// The table, compiled in.
const TABLE: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/period_gpus.toml"
));

/// One value of the table and where it comes from.
#[derive(Clone, Debug, Deserialize, serde::Serialize)]
pub struct Sourced<T> {
    pub value: T,
    /// The paper's sentence, or the document or specification that gives the value.
    pub source: String,
    /// False where no document at hand confirms the value (the source then says so).
    pub sourced: bool,
}

/// A period GPU and its limits.
#[derive(Clone, Debug, Deserialize, serde::Serialize)]
pub struct PeriodGpu {
    /// `g70`, `r300`.
    pub key: String,
    /// The board the papers name: "GeForce 7800 GTX".
    pub name: String,
    pub chip: String,
    /// The papers that ran on it.
    pub papers: Vec<u8>,
    /// Each side of a texture, in texels.
    pub max_texture_size: Sourced<u32>,
    /// Colour targets one pass may write (MRT).
    pub max_draw_buffers: Sourced<u32>,
    /// The texture formats the chip could allocate.
    pub texture_formats: Sourced<Vec<String>>,
    /// The formats a vertex shader could read (empty: no vertex texture fetch).
    pub vertex_texture_formats: Sourced<Vec<String>>,
    /// `nearest`, or `none` without vertex texture fetch.
    pub vertex_texture_filtering: Sourced<String>,
    /// The float formats that could be blended into.
    pub float_blending: Sourced<Vec<String>>,
    /// The float formats that could be read with linear filtering.
    pub float_filtering: Sourced<Vec<String>>,
    pub occlusion_query_counter_bits: Sourced<u32>,
    /// Bits of a float in the fragment pipeline's arithmetic (32, or 24 on the R300).
    pub fragment_float_bits: Sourced<u32>,
    pub compute_shaders: Sourced<bool>,
}

#[derive(Deserialize)]
struct Table {
    gpu: Vec<PeriodGpu>,
}

/// Every period GPU of the table.
pub fn all() -> &'static [PeriodGpu] {
    static GPUS: OnceLock<Vec<PeriodGpu>> = OnceLock::new();
    GPUS.get_or_init(|| {
        toml::from_str::<Table>(TABLE)
            .expect("assets/period_gpus.toml is compiled in and checked by a test")
            .gpu
    })
}

/// The GPU paper `paper` (1 to 4) ran on, or `None` for another number.
pub fn try_for_paper(paper: u8) -> Option<&'static PeriodGpu> {
    all().iter().find(|g| g.papers.contains(&paper))
}

/// The GPU paper `paper` ran on: the GeForce 7800 GTX for papers 1, 2 and 4, the RADEON
/// 9700 PRO for paper 3. Panics for a number that is not a paper (a programming error).
pub fn for_paper(paper: u8) -> &'static PeriodGpu {
    try_for_paper(paper).unwrap_or_else(|| panic!("there is no paper {paper} (1 to 4)"))
}

/// The GPU whose key is `key` (`g70`, `r300`).
pub fn by_key(key: &str) -> Option<&'static PeriodGpu> {
    all().iter().find(|g| g.key == key)
}

/// One limit of a GPU as the report prints it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LimitRow {
    /// The table's name of the limit (`max_texture_size`).
    pub limit: &'static str,
    pub value: String,
    pub source: String,
    pub sourced: bool,
}

fn list(values: &[String]) -> String {
    if values.is_empty() {
        "none".into()
    } else {
        values.join(", ")
    }
}

impl PeriodGpu {
    /// Every limit with its value and source, in the table's order.
    pub fn limits(&self) -> Vec<LimitRow> {
        fn row<T>(limit: &'static str, s: &Sourced<T>, value: String) -> LimitRow {
            LimitRow {
                limit,
                value,
                source: s.source.clone(),
                sourced: s.sourced,
            }
        }
        vec![
            row(
                "max_texture_size",
                &self.max_texture_size,
                self.max_texture_size.value.to_string(),
            ),
            row(
                "max_draw_buffers",
                &self.max_draw_buffers,
                self.max_draw_buffers.value.to_string(),
            ),
            row(
                "texture_formats",
                &self.texture_formats,
                list(&self.texture_formats.value),
            ),
            row(
                "vertex_texture_formats",
                &self.vertex_texture_formats,
                list(&self.vertex_texture_formats.value),
            ),
            row(
                "vertex_texture_filtering",
                &self.vertex_texture_filtering,
                self.vertex_texture_filtering.value.clone(),
            ),
            row(
                "float_blending",
                &self.float_blending,
                list(&self.float_blending.value),
            ),
            row(
                "float_filtering",
                &self.float_filtering,
                list(&self.float_filtering.value),
            ),
            row(
                "occlusion_query_counter_bits",
                &self.occlusion_query_counter_bits,
                self.occlusion_query_counter_bits.value.to_string(),
            ),
            row(
                "fragment_float_bits",
                &self.fragment_float_bits,
                self.fragment_float_bits.value.to_string(),
            ),
            row(
                "compute_shaders",
                &self.compute_shaders,
                if self.compute_shaders.value {
                    "yes"
                } else {
                    "no"
                }
                .into(),
            ),
        ]
    }

    /// The error for a request beyond limit `limit`: the GPU, what was asked, why not.
    pub fn refusal(&self, limit: &str, asked: &str, allowed: &str) -> GlError {
        GlError::Limit(format!(
            "{}: {asked} was not supported ({allowed}; period limit {limit}, \
             assets/period_gpus.toml)",
            self.name
        ))
    }

    /// A `width x height` texture of `format`.
    pub fn check_texture(
        &self,
        width: u32,
        height: u32,
        format: TextureFormat,
    ) -> Result<(), GlError> {
        let max = self.max_texture_size.value;
        if width > max || height > max {
            return Err(self.refusal(
                "max_texture_size",
                &format!("a {width}x{height} {} texture", format.name()),
                &format!("textures were at most {max}x{max}"),
            ));
        }
        if !self
            .texture_formats
            .value
            .iter()
            .any(|f| f == format.name())
        {
            return Err(self.refusal(
                "texture_formats",
                &format!("a {} texture", format.name()),
                &format!(
                    "the chip allocated {} only",
                    list(&self.texture_formats.value)
                ),
            ));
        }
        Ok(())
    }

    /// A framebuffer `name` with `colors` colour attachments.
    pub fn check_draw_buffers(&self, name: &str, colors: usize) -> Result<(), GlError> {
        let max = self.max_draw_buffers.value;
        if colors > max as usize {
            return Err(self.refusal(
                "max_draw_buffers",
                &format!("framebuffer {name} with {colors} render targets"),
                &format!("a pass wrote at most {max}"),
            ));
        }
        Ok(())
    }

    /// Blending into a colour target of `format` in pass `pass`.
    pub fn check_blend(&self, pass: &str, format: TextureFormat) -> Result<(), GlError> {
        if !format.is_float() || self.float_blending.value.iter().any(|f| f == format.name()) {
            return Ok(());
        }
        Err(self.refusal(
            "float_blending",
            &format!(
                "blending a {}-bit float render target ({}) in pass '{pass}'",
                format.float_bits(),
                format.name()
            ),
            &format!(
                "float targets blended: {}",
                list(&self.float_blending.value)
            ),
        ))
    }

    /// Sampling a texture of `format` with `filter` in pass `pass`, from the vertex shader
    /// when `in_vertex_shader`.
    pub fn check_sampling(
        &self,
        pass: &str,
        sampler: &str,
        format: TextureFormat,
        filter: Filter,
        in_vertex_shader: bool,
    ) -> Result<(), GlError> {
        if in_vertex_shader {
            if !self
                .vertex_texture_formats
                .value
                .iter()
                .any(|f| f == format.name())
            {
                return Err(self.refusal(
                    "vertex_texture_formats",
                    &format!(
                        "reading a {} texture ({sampler}) in the vertex shader of pass '{pass}'",
                        format.name()
                    ),
                    &format!(
                        "vertex texture formats: {}",
                        list(&self.vertex_texture_formats.value)
                    ),
                ));
            }
            if filter != Filter::Nearest {
                return Err(self.refusal(
                    "vertex_texture_filtering",
                    &format!(
                        "linear filtering of a vertex texture ({sampler}, {}) in pass '{pass}'",
                        format.name()
                    ),
                    &format!(
                        "vertex texture filtering: {}",
                        self.vertex_texture_filtering.value
                    ),
                ));
            }
        }
        if filter == Filter::Linear
            && format.is_float()
            && !format.is_depth()
            && !self
                .float_filtering
                .value
                .iter()
                .any(|f| f == format.name())
        {
            return Err(self.refusal(
                "float_filtering",
                &format!(
                    "linear filtering of a {}-bit float texture ({}, {sampler}) in pass '{pass}'",
                    format.float_bits(),
                    format.name()
                ),
                &format!(
                    "float textures filtered: {}",
                    list(&self.float_filtering.value)
                ),
            ));
        }
        Ok(())
    }

    /// A compute shader (`what` needs one).
    pub fn check_compute(&self, what: &str) -> Result<(), GlError> {
        if self.compute_shaders.value {
            return Ok(());
        }
        Err(self.refusal(
            "compute_shaders",
            &format!("a compute shader ({what})"),
            "the chip had no compute shaders: graphics passes only",
        ))
    }

    /// An occlusion query that counted `samples`.
    pub fn check_occlusion_count(&self, samples: u64) -> Result<(), GlError> {
        let bits = self.occlusion_query_counter_bits.value;
        if bits < 64 && samples >> bits != 0 {
            return Err(self.refusal(
                "occlusion_query_counter_bits",
                &format!("an occlusion query counting {samples} samples"),
                &format!("the counter had {bits} bits"),
            ));
        }
        Ok(())
    }
}

impl Context {
    /// Run under `gpu`'s limits from now on (`None`: today's limits only). Objects made
    /// before keep working; what is made or drawn afterwards is checked.
    pub fn set_period(&self, gpu: Option<&'static PeriodGpu>) {
        self.inner.period.set(gpu);
    }

    /// The period GPU this context runs under, if any.
    pub fn period(&self) -> Option<&'static PeriodGpu> {
        self.inner.period.get()
    }

    /// The largest texture side this context may make: the renderer's, or the period GPU's
    /// when that is smaller.
    pub fn max_texture_size(&self) -> u32 {
        let renderer = self.info().limits.max_texture_size;
        match self.period() {
            Some(gpu) => renderer.min(gpu.max_texture_size.value),
            None => renderer,
        }
    }

    /// The most colour targets one pass may write: the renderer's, or the period GPU's.
    pub fn max_render_targets(&self) -> u32 {
        let l = &self.info().limits;
        let renderer = l.max_draw_buffers.min(l.max_color_attachments);
        match self.period() {
            Some(gpu) => renderer.min(gpu.max_draw_buffers.value),
            None => renderer,
        }
    }
}
