//! Paper 2 live: a walking crowd skinned in two passes (pass 1 skins every vertex into a
//! render target, the target is copied into a vertex buffer, pass 2 draws it) or in the vertex
//! shader (the baseline), switchable with `m`; pass 1's render target as an inset; the LOD
//! meshes coloured on demand with `c` [Dudash, "Skinned instancing" / paper 2, Sec. 3-4].

use crate::crowd::renderer::FrameStats;
use crate::crowd::scene::{self, Scene};
use crate::crowd::{CharacterModel, CrowdRenderer, LodPolicy, Method, ModelKind};
use crate::gl::dump::DumpRange;
use crate::gl::{Context, Rect};
use crate::view::{inset, Canvas, Demo, ViewState};

pub struct CrowdDemo {
    scene: Scene,
    renderer: CrowdRenderer,
    method: Method,
    lod_colours: bool,
    stride: f64,
    steps: usize,
    characters: usize,
    last: Option<FrameStats>,
    per_lod: [usize; 3],
    culled: usize,
}

const DT: f32 = 1.0 / 30.0;

impl CrowdDemo {
    pub fn new(ctx: &Context, characters: usize, size: (u32, u32)) -> anyhow::Result<Self> {
        if characters == 0 || characters > 4096 {
            anyhow::bail!("--characters {characters}: must be between 1 and 4096 in the viewer");
        }
        let kind = ModelKind::Soldier;
        let model = CharacterModel::build(kind)?;
        let renderer = CrowdRenderer::new(ctx, model)?;
        let aspect = size.0 as f32 / size.1.max(1) as f32;
        let scene = scene::lod_scene(kind, characters, aspect, 1, LodPolicy::default());
        let stride = renderer.model.clip.stride;
        Ok(CrowdDemo {
            scene,
            renderer,
            method: Method::TwoPass,
            lod_colours: false,
            stride,
            steps: 0,
            characters,
            last: None,
            per_lod: [0; 3],
            culled: 0,
        })
    }
}

impl Demo for CrowdDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        self.scene.crowd.step(DT, self.stride);
        self.steps += 1;
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        let target = canvas.target();
        scene::clear(target)?;
        self.renderer.set_lod_colours(self.lod_colours);
        let (stats, plan) =
            scene::render_frame(&mut self.renderer, target, &self.scene, self.method, true)?;
        self.per_lod = [plan.lods[0].len(), plan.lods[1].len(), plan.lods[2].len()];
        self.culled = plan.culled;
        self.last = Some(stats);
        let pass1 = (self.method == Method::TwoPass)
            .then(|| self.renderer.render_target(0))
            .flatten();
        // Pass 1 writes each skinned vertex's position: a column per character, a row per
        // vertex; x, y and z are separate quantities, so three panels.
        let channels = |full: bool| {
            let what = if full {
                " (column: character, row: vertex)"
            } else {
                ""
            };
            [
                format!("pass 1 x{what}"),
                format!("pass 1 y{what}"),
                format!("pass 1 z{what}"),
            ]
        };
        match (view.shown, pass1) {
            (1, Some(t)) => {
                canvas.clear([0.0, 0.0, 0.0, 1.0])?;
                let names = channels(true);
                let names: Vec<&str> = names.iter().map(|s| s.as_str()).collect();
                let panels = inset::texture_panels(t, &names, DumpRange::Auto)?;
                let rect = canvas.below_text();
                inset::draw_picture(canvas, panels.into_iter().map(Into::into).collect(), rect)?;
            }
            (1, None) => {
                canvas.clear([0.0, 0.0, 0.0, 1.0])?;
            }
            (_, Some(t)) => {
                let names = channels(false);
                let names: Vec<&str> = names.iter().map(|s| s.as_str()).collect();
                let panels = inset::texture_panels(t, &names, DumpRange::Auto)?;
                // Three panels a fifth of the width each, at least a third of the height.
                let (w, h) = (canvas.width(), canvas.height());
                let rect = Rect::new(w - 3 * (w / 5), 0, 3 * (w / 5), h / 3);
                inset::draw_picture(canvas, panels.into_iter().map(Into::into).collect(), rect)?;
            }
            _ => {}
        }
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec!["crowd".into(), "pass-1 render target (LOD 0)".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let method = match self.method {
            Method::TwoPass => "two-pass (pass 1 -> VBO -> pass 2)",
            Method::VertexShader => "vertex-shader skinning (baseline)",
        };
        let mut lines = vec![
            format!("crowd: {} soldiers, {method}", self.characters),
            format!(
                "LOD 0/1/2: {} / {} / {}  culled {}",
                self.per_lod[0], self.per_lod[1], self.per_lod[2], self.culled
            ),
        ];
        if self.lod_colours {
            lines.push("LOD colours: 0 red, 1 yellow, 2 green".into());
        }
        if self.method == Method::VertexShader {
            lines.push("(no pass-1 target: [m] for two-pass)".into());
        }
        lines
    }

    fn timings(&self) -> String {
        let Some(s) = &self.last else {
            return String::new();
        };
        let t = &s.gl_timer;
        format!(
            "bones {:.2} upload {:.2} pass1 {:.2} copy {:.2} pass2 {:.2} vs {:.2} ms",
            s.bones_ms, s.upload_ms, t.pass1, t.copy, t.pass2, t.vertex_shader
        )
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        vec![("m", "two-pass / vertex shader"), ("c", "LOD colours")]
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        match key {
            "m" => {
                self.method = match self.method {
                    Method::TwoPass => Method::VertexShader,
                    Method::VertexShader => Method::TwoPass,
                }
            }
            "c" => self.lod_colours = !self.lod_colours,
            _ => return Ok(false),
        }
        Ok(true)
    }
}
