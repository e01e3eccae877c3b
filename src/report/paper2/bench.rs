//! The measurements: Table 1 (both skinning methods, the vertex-shader one also at one
//! character per draw) and the LOD runs of Fig. 4-5 in the paper's setup and, side by side
//! on the same crowds, with this project's sprite level, with the snapshots that need live
//! GL state (Fig. 2's render target, Fig. 3-5's frames, the impostor atlases).

use crate::timing::Load;
use anyhow::Context as _;
use serde::Serialize;

use crate::crowd::pass1_skinning;
use crate::crowd::renderer::{CrowdRenderer, Method};
use crate::crowd::scene::{self, Config, RunStats};
use crate::crowd::{sprites, CharacterModel, LodPolicy, ModelKind};
use crate::gl::dump::{self, DumpRange};
use crate::gl::Texture;
use crate::report::{published, BenchOptions};

// region: workload quick-counts
/// Character counts measured in quick mode (the paper's first three rows).
const QUICK_COUNTS: [usize; 3] = [1, 16, 64];
// endregion

/// The LOD runs use the paper's crowd divided by this in quick mode.
const QUICK_LOD_DIVISOR: usize = 10;

/// Everything the section measures.
#[derive(Clone, Debug, Serialize)]
pub struct Paper2Results {
    pub renderer: String,
    pub quick: bool,
    /// The scene target, width x height.
    pub size: [u32; 2],
    pub setup: Setup,
    /// The two characters as built here (this project's stand-ins).
    pub models: Vec<ModelInfo>,
    /// Table 1: every model x count x [`Variant`].
    pub table1: Vec<RunStats>,
    /// Fig. 4-5 in the paper's setup (three LOD meshes, culling, no sprites): both methods
    /// on each LOD scene.
    pub lod_runs: Vec<RunStats>,
    /// The same scenes with this project's sprite level, measured side by side with
    /// `lod_runs` (an extension, not in the paper).
    pub sprite_runs: Vec<RunStats>,
    /// PNGs written during the run, in the order they were taken.
    pub snapshots: Vec<Snapshot>,
    /// Classic vs compute vs CPU: the 2007 formulation beside today's compute shaders.
    pub then_and_now: crate::report::then_and_now::ThenAndNow,
    /// Where the time of this run went, pass by pass.
    pub profile: Option<crate::gl::profile::ProfileTable>,
    /// The machine's highest load when each model's Table 1 runs ended (the timing claims).
    pub table1_load: Option<Load>,
}

/// What the runs were set up with.
#[derive(Clone, Debug, Serialize)]
pub struct Setup {
    /// The largest texture side, which bounds the characters of one pass-1 draw.
    pub max_texture_size: u32,
    /// Characters per render-target row (the vertex-stride cap).
    pub row_characters: u32,
    /// The LOD runs use the paper's crowds divided by this.
    pub lod_divisor: usize,
    /// The paper's setup at this project's distances.
    pub lod_policy: LodPolicy,
    /// The extension: the same plus sprites.
    pub sprite_policy: LodPolicy,
}

/// One character model as built here.
#[derive(Clone, Debug, Serialize)]
pub struct ModelInfo {
    pub model: ModelKind,
    pub bones: usize,
    /// Whether the skeleton has a spear bone (the soldier's prop, this project's choice).
    pub spear: bool,
    /// Per LOD mesh, finest first.
    pub lods: Vec<LodInfo>,
}

/// One LOD mesh of a model.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct LodInfo {
    pub triangles: usize,
    /// m.
    pub vertices: usize,
    /// The most characters one pass-1 draw skins on this renderer.
    pub characters_per_draw: usize,
}

impl ModelInfo {
    fn of(model: &CharacterModel, renderer: &CrowdRenderer) -> ModelInfo {
        ModelInfo {
            model: model.kind,
            bones: model.bone_count(),
            spear: model.skeleton.index_of("spear").is_some(),
            lods: model
                .lods
                .iter()
                .enumerate()
                .map(|(lod, mesh)| LodInfo {
                    triangles: mesh.triangle_count(),
                    vertices: mesh.vertex_count(),
                    characters_per_draw: renderer.batch_limit(lod),
                })
                .collect(),
        }
    }
}

/// A PNG written from live GL state, and what it shows.
#[derive(Clone, Debug, Serialize)]
pub struct Snapshot {
    /// Relative to the output folder.
    pub file: String,
    pub shows: Shows,
}

/// What a snapshot shows.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Shows {
    /// Fig. 3: the Table 1 scene without LOD and culling.
    Fig3 { characters: usize },
    /// Fig. 2: the pass-1 render target after a model's last Table 1 run.
    RenderTarget { model: ModelKind },
    /// The sprite level's impostor atlas.
    ImpostorAtlas {
        model: ModelKind,
        views: u32,
        frames: u32,
    },
    /// Fig. 4 or 5: a frame of the LOD scene (two-pass), with or without sprites.
    LodRun {
        figure: String,
        model: ModelKind,
        characters: usize,
        sprites: bool,
    },
}

/// A measured configuration of Table 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    /// Vertex-shader skinning, as many characters per draw as the uniforms hold.
    VertexShader,
    /// Vertex-shader skinning, one character per draw call (the paper's era).
    VertexShaderSingle,
    /// The paper's method.
    TwoPass,
}

impl Variant {
    pub const ALL: [Variant; 3] = [
        Variant::VertexShader,
        Variant::VertexShaderSingle,
        Variant::TwoPass,
    ];

    fn config(self) -> Config {
        match self {
            Variant::TwoPass => Config::new(Method::TwoPass),
            Variant::VertexShader => Config::new(Method::VertexShader),
            // Only its frame time is reported (Table 1's "VS 1/draw" column), so its runs
            // make no stage-timed frame.
            Variant::VertexShaderSingle => Config {
                method: Method::VertexShader,
                vertex_shader_batch: 1,
                stage_times: false,
            },
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Variant::VertexShader => "VS",
            Variant::VertexShaderSingle => "VS 1/draw",
            Variant::TwoPass => "2-pass",
        }
    }

    pub fn of(run: &RunStats) -> Variant {
        if run.method == Method::TwoPass.name() {
            Variant::TwoPass
        } else if run.vertex_shader_batch == 1 {
            Variant::VertexShaderSingle
        } else {
            Variant::VertexShader
        }
    }
}

impl Paper2Results {
    /// The run of `kind` x `n` in `runs` measured as `variant`.
    pub fn find(
        runs: &[RunStats],
        kind: ModelKind,
        n: usize,
        variant: Variant,
    ) -> Option<&RunStats> {
        runs.iter()
            .find(|r| r.model == kind.name() && r.characters == n && Variant::of(r) == variant)
    }

    /// The model as built here.
    pub fn model(&self, kind: ModelKind) -> Option<&ModelInfo> {
        self.models.iter().find(|m| m.model == kind)
    }

    /// Table 1's frame rate of `kind` x `n` as `variant`.
    pub fn fps(&self, kind: ModelKind, n: usize, variant: Variant) -> Option<f64> {
        Self::find(&self.table1, kind, n, variant).map(|r| r.fps)
    }

    /// The character counts of Table 1 that were measured, in order.
    pub fn counts(&self) -> Vec<usize> {
        let mut counts: Vec<usize> = self.table1.iter().map(|r| r.characters).collect();
        counts.sort_unstable();
        counts.dedup();
        counts
    }

    /// Characters per instanced draw of the vertex-shader baseline (as many as fit).
    pub fn vertex_shader_batch(&self) -> u32 {
        self.table1
            .iter()
            .find(|r| Variant::of(r) == Variant::VertexShader)
            .map_or(0, |r| r.vertex_shader_batch)
    }
}

// region: workload frames
/// The target size of the measured frames.
pub fn size(quick: bool) -> (u32, u32) {
    if quick {
        (320, 240)
    } else {
        (640, 480)
    }
}

/// What the LOD runs divide the paper's crowd by.
pub fn lod_divisor(quick: bool) -> usize {
    if quick {
        QUICK_LOD_DIVISOR
    } else {
        1
    }
}

/// Timed frames per measurement: enough to take a median, few enough for llvmpipe. Each
/// measurement also draws a warm-up frame and (but VS 1/draw, whose stages no table shows) a
/// frame with timer queries (the per-pass times), untimed. The largest crowds (2048 and 4096
/// characters) take three: their frames are the longest of the table, where one frame's
/// noise matters least, and they are most of its work: counted in characters times frames
/// drawn, 73% of Table 1 at five frames, so two frames fewer there save a fifth of the
/// table's skinning.
fn frames_for(n: usize, quick: bool) -> usize {
    match (quick, n) {
        (true, _) => 3,
        (false, 0..=64) => 21,
        (false, 65..=1024) => 9,
        _ => 3,
    }
}
// endregion

/// One of the paper's LOD runs (Fig. 4-5), as measured here.
struct LodRun {
    figure: String,
    kind: ModelKind,
    characters: usize,
}

fn lod_runs(paper: &published::Paper2, divisor: usize) -> anyhow::Result<Vec<LodRun>> {
    paper
        .runs
        .iter()
        .filter(|r| r.lod_and_culling)
        .map(|r| {
            Ok(LodRun {
                figure: r.figure.clone(),
                kind: r
                    .model
                    .parse()
                    .map_err(anyhow::Error::msg)
                    .context("assets/paper_tables.toml [[paper2.runs]] model")?,
                characters: r.characters / divisor,
            })
        })
        .collect()
}

/// Runs every measurement and writes the snapshots.
pub fn measure(opts: &BenchOptions) -> anyhow::Result<Paper2Results> {
    let paper = &published::Published::get()?.paper2;
    // region: workload counts
    let counts: Vec<usize> = if opts.quick {
        QUICK_COUNTS.to_vec()
    } else {
        paper.table1.characters.clone()
    };
    let (w, h) = size(opts.quick);
    // endregion
    let lod = lod_runs(paper, lod_divisor(opts.quick))?;
    std::fs::create_dir_all(&opts.out_dir)
        .with_context(|| format!("creating {}", opts.out_dir.display()))?;
    let ctx = opts.gl;
    let target = scene::scene_target(ctx, w, h)?;
    let aspect = w as f32 / h as f32;
    let total = (ModelKind::ALL.len() * counts.len() * Variant::ALL.len() + lod.len() * 4) as u64;
    let bar = opts.progress.add(indicatif::ProgressBar::new(total));
    bar.set_style(
        indicatif::ProgressStyle::with_template("paper 2 {bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let (lod_policy, sprite_policy) = (LodPolicy::default(), LodPolicy::with_sprites());
    let mut results = Paper2Results {
        renderer: ctx.info().renderer.clone(),
        quick: opts.quick,
        size: [w, h],
        setup: Setup {
            max_texture_size: ctx.info().limits.max_texture_size,
            row_characters: pass1_skinning::MAX_ROW_CHARACTERS,
            lod_divisor: lod_divisor(opts.quick),
            lod_policy,
            sprite_policy,
        },
        models: Vec::new(),
        table1: Vec::new(),
        lod_runs: Vec::new(),
        sprite_runs: Vec::new(),
        snapshots: Vec::new(),
        then_and_now: Default::default(),
        profile: None,
        table1_load: None,
    };
    let mut snapshots = Vec::new();
    // Frames and the atlas are images (RGBA8), written as they are; pass 1's float target is
    // data: x, y and z of each skinned vertex as three panels with their colour keys (a
    // column per character, a row per vertex).
    let mut snapshot = |texture: &Texture, file: String, shows: Shows| -> anyhow::Result<()> {
        let path = opts.out_dir.join(&file);
        if texture.format().is_float() {
            let channels = ["pass 1 x", "pass 1 y", "pass 1 z"];
            // As wide as the page: panels side by side where they fit (a narrow target, its
            // columns enlarged), else one above the other, so a render target of 1024
            // characters is shown texel for pixel.
            let page = crate::page::html::CONTENT_WIDTH;
            let panels = channels.len() as u32;
            let rows = if panels * (texture.width() + 12) <= page {
                1
            } else {
                panels
            };
            let size = (page, rows * (texture.height() + 100));
            dump::texture_picture_png(texture, &channels, DumpRange::Auto, size, &path)?;
        } else {
            dump::texture_png(texture, &path, DumpRange::Auto)?;
        }
        snapshots.push(Snapshot { file, shows });
        Ok(())
    };
    let fig3_n = if opts.quick { 64 } else { 1024 };
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind)?;
        let mut renderer = CrowdRenderer::new(ctx, model.clone())?;
        results.models.push(ModelInfo::of(&model, &renderer));
        for &n in &counts {
            bar.set_message(format!("{} x {n}", kind.name()));
            let mut scenes: Vec<_> = Variant::ALL
                .iter()
                .map(|_| scene::table1_scene(kind, n, aspect, 1))
                .collect();
            let configs = Variant::ALL.map(Variant::config);
            let fig3 = kind == ModelKind::Soldier && n == fig3_n;
            // Fig. 3 is the two-pass configuration's last frame, taken while the target
            // holds it.
            let two_pass = Variant::ALL.iter().position(|&v| v == Variant::TwoPass);
            results.table1.extend(scene::run_side_by_side(
                ctx,
                &mut renderer,
                &target,
                &mut scenes,
                &configs,
                frames_for(n, opts.quick),
                1.0 / 30.0,
                |i, target| {
                    if !fig3 || Some(i) != two_pass {
                        return Ok(());
                    }
                    snapshot(
                        target.color(0),
                        format!("fig3_{n}_soldiers.png"),
                        Shows::Fig3 { characters: n },
                    )
                },
            )?);
            bar.inc(Variant::ALL.len() as u64);
        }
        crate::timing::mark(&format!("paper2: Table 1, {}", kind.name()));
        results.table1_load = [results.table1_load, Load::now()]
            .into_iter()
            .flatten()
            .max_by(|a, b| a.one_minute.total_cmp(&b.one_minute));
        renderer.set_vertex_shader_batch(u32::MAX);
        if let Some(texture) = renderer.render_target(0) {
            snapshot(
                texture,
                format!("fig2_{}_render_target.png", kind.name()),
                Shows::RenderTarget { model: kind },
            )?;
        }
        snapshot(
            renderer.sprites().atlas(),
            format!("{}_impostor_atlas.png", kind.name()),
            Shows::ImpostorAtlas {
                model: kind,
                views: sprites::VIEWS,
                frames: sprites::FRAMES,
            },
        )?;
        for run in lod.iter().filter(|r| r.kind == kind) {
            let n = run.characters;
            bar.set_message(format!("{} x {n} with LOD", kind.name()));
            // The paper's setup and the sprite extension on identical crowds (same seed,
            // same steps), frame by frame in turn.
            let mut scenes = [lod_policy, lod_policy, sprite_policy, sprite_policy]
                .map(|policy| scene::lod_scene(kind, n, aspect, 1, policy));
            // The figures' table shows the vertex-shader runs' frame rates alone: no
            // stage-timed frame for them.
            let vertex_shader = Config {
                stage_times: false,
                ..Config::new(Method::VertexShader)
            };
            let configs = [vertex_shader, Config::new(Method::TwoPass)];
            let configs = [configs, configs].concat();
            let number = run.figure.trim_start_matches("Fig. ");
            // The figures are the two-pass configurations' last frames (the paper's setup,
            // then with sprites), taken while the target still holds them.
            let mut runs = scene::run_side_by_side(
                ctx,
                &mut renderer,
                &target,
                &mut scenes,
                &configs,
                if opts.quick { 2 } else { 5 },
                1.0 / 30.0,
                |i, target| {
                    let sprites = match i {
                        1 => false,
                        3 => true,
                        _ => return Ok(()),
                    };
                    snapshot(
                        target.color(0),
                        format!(
                            "fig{number}_{n}_{}s_lod{}.png",
                            kind.name(),
                            if sprites { "_sprites" } else { "" }
                        ),
                        Shows::LodRun {
                            figure: run.figure.clone(),
                            model: kind,
                            characters: n,
                            sprites,
                        },
                    )
                },
            )?;
            bar.inc(4);
            results.sprite_runs.extend(runs.split_off(2));
            results.lod_runs.extend(runs);
        }
        crate::timing::mark(&format!("paper2: snapshots and LOD runs, {}", kind.name()));
    }
    bar.finish_and_clear();
    results.snapshots = snapshots;
    results.then_and_now = super::then_and_now::measure(opts)?;
    crate::timing::mark("paper2: then and now");
    Ok(results)
}
