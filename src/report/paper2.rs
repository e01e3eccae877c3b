//! Paper 2 (Kang & Han 2006): Table 1 (vertex-shader vs two-pass skinning, 1 to 4096
//! soldiers and horses, no culling) and the LOD runs of Fig. 3-5 (10,240 soldiers, 5,120
//! horses with LOD and culling), measured here beside the published frame rates.
//!
//! The vertex-shader baseline runs twice: as fast as this renderer allows (as many
//! characters per instanced draw as the uniforms hold), and one character per draw call,
//! as the paper's generation of hardware had to (a few hundred constant registers, no
//! instancing in OpenGL 2).

use anyhow::Context as _;
use serde_json::json;

use crate::crowd::renderer::{CrowdRenderer, Method};
use crate::crowd::scene::{self, Config, RunStats};
use crate::crowd::{sprites, CharacterModel, ModelKind};
use crate::gl::dump::{self, DumpRange};
use crate::report::plot::{Plot, Series};
use crate::report::{published, BenchOptions, Claim, Fidelity, Figure, Section, Table};

/// Character counts measured in quick mode (the paper's first three rows).
const QUICK_COUNTS: [usize; 3] = [1, 16, 64];

/// A measured configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Variant {
    /// Vertex-shader skinning, as many characters per draw as the uniforms hold.
    VertexShader,
    /// Vertex-shader skinning, one character per draw call (the paper's era).
    VertexShaderSingle,
    /// The paper's method.
    TwoPass,
}

impl Variant {
    const ALL: [Variant; 3] = [
        Variant::VertexShader,
        Variant::VertexShaderSingle,
        Variant::TwoPass,
    ];

    fn method(self) -> Method {
        match self {
            Variant::TwoPass => Method::TwoPass,
            _ => Method::VertexShader,
        }
    }

    fn batch(self) -> u32 {
        match self {
            Variant::VertexShaderSingle => 1,
            _ => u32::MAX,
        }
    }

    fn label(self) -> &'static str {
        match self {
            Variant::VertexShader => "VS",
            Variant::VertexShaderSingle => "VS 1/draw",
            Variant::TwoPass => "2-pass",
        }
    }

    fn of(run: &RunStats) -> Variant {
        if run.method == Method::TwoPass.name() {
            Variant::TwoPass
        } else if run.vertex_shader_batch == 1 {
            Variant::VertexShaderSingle
        } else {
            Variant::VertexShader
        }
    }
}

/// Timed frames per measurement: enough to take a median, few enough for llvmpipe.
fn frames_for(n: usize, quick: bool) -> usize {
    match (quick, n) {
        (true, _) => 3,
        (false, 0..=64) => 21,
        (false, 65..=1024) => 9,
        _ => 5,
    }
}

/// One of the paper's Fig. 3-5 runs.
struct PaperRun {
    figure: String,
    kind: ModelKind,
    characters: usize,
    lod: bool,
    fps: f64,
}

fn paper_runs(paper: &published::Paper2) -> Vec<PaperRun> {
    paper
        .runs
        .iter()
        .map(|r| PaperRun {
            figure: r.figure.clone(),
            kind: if r.model == "horse" {
                ModelKind::Horse
            } else {
                ModelKind::Soldier
            },
            characters: r.characters,
            lod: r.lod_and_culling,
            fps: r.fps,
        })
        .collect()
}

/// Everything measured.
struct Measured {
    table1: Vec<RunStats>,
    lod: Vec<RunStats>,
    figures: Vec<Figure>,
}

impl Measured {
    fn find(runs: &[RunStats], kind: ModelKind, n: usize, v: Variant) -> Option<&RunStats> {
        runs.iter()
            .find(|r| r.model == kind.name() && r.characters == n && Variant::of(r) == v)
    }

    fn fps(&self, kind: ModelKind, n: usize, v: Variant) -> f64 {
        Self::find(&self.table1, kind, n, v).map_or(f64::NAN, |r| r.fps)
    }
}

/// Runs the benchmark and returns the section.
pub fn run(opts: &BenchOptions) -> anyhow::Result<Section> {
    let paper = &published::Published::get()?.paper2;
    let table1 = &paper.table1;
    let paper_counts: Vec<usize> = table1.characters.clone();
    let counts: Vec<usize> = if opts.quick {
        QUICK_COUNTS.to_vec()
    } else {
        paper_counts.clone()
    };
    let (w, h) = if opts.quick { (320, 240) } else { (640, 480) };
    let lod_scale = if opts.quick { 10 } else { 1 };
    std::fs::create_dir_all(&opts.out_dir)
        .with_context(|| format!("creating {}", opts.out_dir.display()))?;
    let runs = paper_runs(paper);
    let measured = measure(opts, &counts, (w, h), &runs, lod_scale)?;

    let renderer_name = opts.gl.info().renderer.clone();
    let paper_fps = |key: &str, n: usize| -> Option<f64> {
        let row = match key {
            "soldier_vs" => &table1.soldier_vs,
            "soldier_two_pass" => &table1.soldier_two_pass,
            "horse_vs" => &table1.horse_vs,
            _ => &table1.horse_two_pass,
        };
        paper_counts
            .iter()
            .position(|&c| c == n)
            .and_then(|i| row.get(i).copied())
    };
    let show = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.0}"));
    let models = [
        (ModelKind::Soldier, "soldier_vs", "soldier_two_pass"),
        (ModelKind::Horse, "horse_vs", "horse_two_pass"),
    ];

    let mut fps_table = Table {
        caption: format!(
            "Table 1: frames per second, no culling, every character at LOD 0 ({w}x{h}). Paper: \
             GeForce 7800 GTX. Here: {renderer_name}"
        ),
        header: vec!["n".into()],
        rows: Vec::new(),
    };
    for (kind, _, _) in models {
        for label in [
            "VS paper",
            "VS here",
            "VS 1/draw here",
            "2-pass paper",
            "2-pass here",
        ] {
            fps_table.header.push(format!("{} {label}", kind.name()));
        }
    }
    let mut ratio_table = Table {
        caption: "Two-pass / vertex-shader frame-rate ratio (> 1: the paper's method is faster)"
            .into(),
        header: vec!["n".into()],
        rows: Vec::new(),
    };
    for (kind, _, _) in models {
        for label in ["paper", "here vs VS", "here vs VS 1/draw"] {
            ratio_table.header.push(format!("{} {label}", kind.name()));
        }
    }
    for &n in &counts {
        let mut row = vec![n.to_string()];
        let mut ratios = vec![n.to_string()];
        for (kind, vs_key, tp_key) in models {
            let vs = measured.fps(kind, n, Variant::VertexShader);
            let single = measured.fps(kind, n, Variant::VertexShaderSingle);
            let tp = measured.fps(kind, n, Variant::TwoPass);
            let (pv, pt) = (paper_fps(vs_key, n), paper_fps(tp_key, n));
            row.extend([
                show(pv),
                format!("{vs:.1}"),
                format!("{single:.1}"),
                show(pt),
                format!("{tp:.1}"),
            ]);
            ratios.push(
                pv.zip(pt)
                    .map_or("-".into(), |(v, t)| format!("{:.2}", t / v)),
            );
            ratios.push(format!("{:.2}", tp / vs));
            ratios.push(format!("{:.2}", tp / single));
        }
        fps_table.rows.push(row);
        ratio_table.rows.push(ratios);
    }

    let mut pass_table = Table {
        caption: "Time of one frame's stages (ms): CPU bone matrices; GPU stages by wall clock \
                  between glFinish calls (GL timer-query values are in the JSON results); whole \
                  frames (median)"
            .into(),
        header: [
            "model",
            "n",
            "bones (CPU)",
            "pass 1",
            "render-to-VBO",
            "pass 2",
            "2-pass frame",
            "VS skinning",
            "VS frame",
            "VS 1/draw frame",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for kind in ModelKind::ALL {
        for &n in &counts {
            let find = |v| Measured::find(&measured.table1, kind, n, v);
            let (Some(tp), Some(vs), Some(single)) = (
                find(Variant::TwoPass),
                find(Variant::VertexShader),
                find(Variant::VertexShaderSingle),
            ) else {
                continue;
            };
            let ms = |x: f64| format!("{x:.2}");
            pass_table.rows.push(vec![
                kind.name().into(),
                n.to_string(),
                ms(tp.passes.bones_ms),
                ms(tp.passes.wall.pass1),
                ms(tp.passes.wall.copy),
                ms(tp.passes.wall.pass2),
                ms(tp.frame_ms),
                ms(vs.passes.wall.vertex_shader),
                ms(vs.frame_ms),
                ms(single.frame_ms),
            ]);
        }
    }

    let mut lod_table = Table {
        caption: "Fig. 3-5: frames per second of the snapshot scenes; Fig. 4-5 with LOD (1,084 / \
                  544 / 312 polygons), sprites and view-frustum culling"
            .into(),
        header: [
            "figure",
            "model",
            "n",
            "paper FPS",
            "2-pass here",
            "VS here",
            "LOD 0/1/2",
            "sprites",
            "culled",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for run in &runs {
        let n = if run.lod {
            run.characters / lod_scale
        } else {
            run.characters
        };
        let source = if run.lod {
            &measured.lod
        } else {
            &measured.table1
        };
        let find = |v| Measured::find(source, run.kind, n, v);
        let (Some(tp), Some(vs)) = (find(Variant::TwoPass), find(Variant::VertexShader)) else {
            continue;
        };
        lod_table.rows.push(vec![
            run.figure.clone(),
            run.kind.name().into(),
            n.to_string(),
            if n == run.characters {
                format!("{:.0}", run.fps)
            } else {
                format!("{:.0} (at {})", run.fps, run.characters)
            },
            format!("{:.1}", tp.fps),
            format!("{:.1}", vs.fps),
            format!("{} / {} / {}", tp.per_lod[0], tp.per_lod[1], tp.per_lod[2]),
            tp.passes.sprites.to_string(),
            tp.culled.to_string(),
        ]);
    }

    let mut figures = measured.figures.clone();
    for (kind, vs_key, tp_key) in models {
        let paper_series = |key: &str| -> Vec<(f64, f64)> {
            paper_counts
                .iter()
                .filter_map(|&n| paper_fps(key, n).map(|f| (n as f64, f)))
                .collect()
        };
        let here = |v: Variant| -> Vec<(f64, f64)> {
            counts
                .iter()
                .map(|&n| (n as f64, measured.fps(kind, n, v)))
                .collect()
        };
        let plot = Plot {
            title: format!(
                "Table 1, {}: frames per second against crowd size",
                kind.name()
            ),
            x_label: "characters".into(),
            y_label: "frames per second".into(),
            log_x: true,
            log_y: true,
            series: vec![
                Series::new("VS, paper (GeForce 7800 GTX)", paper_series(vs_key)),
                Series::new("2-pass, paper (GeForce 7800 GTX)", paper_series(tp_key)),
                Series::new("VS, here", here(Variant::VertexShader)),
                Series::new("VS 1/draw, here", here(Variant::VertexShaderSingle)),
                Series::new("2-pass, here", here(Variant::TwoPass)),
            ],
        };
        let file = format!("table1_{}.png", kind.name());
        plot.write_png(&opts.out_dir.join(&file))?;
        figures.push(Figure {
            file,
            caption: format!(
                "Table 1 as a plot, {}: the paper's frame rates and this renderer's ({renderer_name})",
                kind.name()
            ),
        });
    }

    let mut claims = vec![
        crossover_claim(&counts, &measured, Variant::VertexShader, &renderer_name),
        crossover_claim(
            &counts,
            &measured,
            Variant::VertexShaderSingle,
            &renderer_name,
        ),
    ];
    claims.extend(stage_claim(&counts, &measured, &renderer_name));
    let summary = format!(
        "Procedural stand-ins for the paper's rigged models (a soldier of 18 bones, a horse of 20; \
         LOD meshes of exactly 1,084, 544 and 312 triangles; walk and gallop clips), each \
         character with its own animation phase and steering. Table 1 runs with culling off and \
         every character at LOD 0 on a {w}x{h} target; FPS is the median wall-clock frame \
         (culling, bone matrices, GPU passes, glFinish). The vertex-shader baseline is measured \
         both at {} characters per instanced draw (all the uniforms hold here) and at one per \
         draw, as on the paper's hardware. Pass 1 folds n characters into rows of at most 128 \
         (the 2048-byte vertex-stride cap of OpenGL 4.4+). Renderer: {renderer_name}.{}",
        measured
            .table1
            .iter()
            .find(|r| Variant::of(r) == Variant::VertexShader)
            .map_or(0, |r| r.vertex_shader_batch),
        if opts.quick {
            " Quick mode: first three rows of Table 1 only, LOD runs at a tenth of the paper's crowd."
        } else {
            ""
        }
    );
    Ok(Section {
        id: "paper2".into(),
        title: "Kang & Han 2006: Real-Time Animation of Large Crowds".into(),
        summary,
        tables: vec![fps_table, ratio_table, pass_table, lod_table],
        claims,
        figures,
        fidelity: fidelity_rows(),
        results: json!({
            "renderer": renderer_name,
            "size": [w, h],
            "table1": measured.table1,
            "lod_runs": measured.lod,
        }),
    })
}

/// Runs every measurement and writes the figures.
fn measure(
    opts: &BenchOptions,
    counts: &[usize],
    (w, h): (u32, u32),
    runs: &[PaperRun],
    lod_scale: usize,
) -> anyhow::Result<Measured> {
    let ctx = opts.gl;
    let target = scene::scene_target(ctx, w, h)?;
    let aspect = w as f32 / h as f32;
    let lod_runs: Vec<&PaperRun> = runs.iter().filter(|r| r.lod).collect();
    let total =
        (ModelKind::ALL.len() * counts.len() * Variant::ALL.len() + lod_runs.len() * 2) as u64;
    let bar = opts.progress.add(indicatif::ProgressBar::new(total));
    bar.set_style(
        indicatif::ProgressStyle::with_template("paper 2 {bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let mut measured = Measured {
        table1: Vec::new(),
        lod: Vec::new(),
        figures: Vec::new(),
    };
    let mut figure =
        |texture: &crate::gl::Texture, file: String, caption: String| -> anyhow::Result<()> {
            dump::texture_png(texture, &opts.out_dir.join(&file), DumpRange::Auto)?;
            measured.figures.push(Figure { file, caption });
            Ok(())
        };
    let mut table1 = Vec::new();
    let mut lod = Vec::new();
    let fig3_n = if opts.quick { 64 } else { 1024 };
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind)?;
        let mut renderer = CrowdRenderer::new(ctx, model)?;
        for &n in counts {
            bar.set_message(format!("{} x {n}", kind.name()));
            let mut scenes: Vec<_> = Variant::ALL
                .iter()
                .map(|_| scene::table1_scene(kind, n, aspect, 1))
                .collect();
            let configs = Variant::ALL.map(|v| Config {
                method: v.method(),
                vertex_shader_batch: v.batch(),
            });
            let frames = frames_for(n, opts.quick);
            table1.extend(scene::run_side_by_side(
                ctx,
                &mut renderer,
                &target,
                &mut scenes,
                &configs,
                frames,
                1.0 / 30.0,
            )?);
            bar.inc(Variant::ALL.len() as u64);
            if kind == ModelKind::Soldier && n == fig3_n {
                figure(
                    target.color(0),
                    format!("fig3_{n}_soldiers.png"),
                    format!("Fig. 3: {n} soldiers without LOD and frustum culling (two-pass)"),
                )?;
            }
        }
        renderer.set_vertex_shader_batch(u32::MAX);
        if let Some(texture) = renderer.render_target(0) {
            figure(
                texture,
                format!("fig2_{}_render_target.png", kind.name()),
                format!(
                    "Fig. 2: the pass-1 render target after the last {} run, skinned positions as \
                     colour (a column per character, a row per vertex index, blocks of 128 \
                     characters stacked)",
                    kind.name()
                ),
            )?;
        }
        figure(
            renderer.sprites().atlas(),
            format!("{}_impostor_atlas.png", kind.name()),
            format!(
                "Sprite level: impostor atlas of the {} ({} view directions x {} animation phases)",
                kind.name(),
                sprites::VIEWS,
                sprites::FRAMES
            ),
        )?;
        for run in lod_runs.iter().filter(|r| r.kind == kind) {
            let n = run.characters / lod_scale;
            bar.set_message(format!("{} x {n} with LOD", kind.name()));
            let mut scenes = [
                scene::lod_scene(kind, n, aspect, 1),
                scene::lod_scene(kind, n, aspect, 1),
            ];
            let configs = [
                Config::new(Method::VertexShader),
                Config::new(Method::TwoPass),
            ];
            let frames = if opts.quick { 2 } else { 5 };
            lod.extend(scene::run_side_by_side(
                ctx,
                &mut renderer,
                &target,
                &mut scenes,
                &configs,
                frames,
                1.0 / 30.0,
            )?);
            bar.inc(2);
            let number = run.figure.trim_start_matches("Fig. ");
            figure(
                target.color(0),
                format!("fig{number}_{n}_{}s_lod.png", kind.name()),
                format!(
                    "{}: {n} {}s with LOD, sprites and frustum culling (two-pass)",
                    run.figure,
                    kind.name()
                ),
            )?;
        }
    }
    bar.finish_and_clear();
    measured.table1 = table1;
    measured.lod = lod;
    Ok(measured)
}

/// Smallest measured n from which two-pass beats `baseline` at every larger n.
fn crossover_claim(
    counts: &[usize],
    measured: &Measured,
    baseline: Variant,
    renderer: &str,
) -> Claim {
    let mut parts = Vec::new();
    let mut holds = true;
    for kind in ModelKind::ALL {
        let faster: Vec<bool> = counts
            .iter()
            .map(|&n| measured.fps(kind, n, Variant::TwoPass) > measured.fps(kind, n, baseline))
            .collect();
        match (0..counts.len()).find(|&i| faster[i..].iter().all(|&f| f)) {
            Some(i) => {
                parts.push(format!(
                    "{}: two-pass faster from n = {} on",
                    kind.name(),
                    counts[i]
                ));
                holds &= i > 0 && counts[i] <= 16;
            }
            None => {
                parts.push(format!(
                    "{}: no crossover up to n = {}",
                    kind.name(),
                    counts.last().copied().unwrap_or(0)
                ));
                holds = false;
            }
        }
    }
    Claim {
        claim: format!(
            "Two-pass (pixel-shader) skinning overtakes vertex-shader skinning ({}) once there \
             are enough characters",
            baseline.label()
        ),
        paper: "VS is faster for 1 character; two-pass is faster from 16 characters on (Table 1, \
                GeForce 7800 GTX)"
            .into(),
        measured: format!("{} ({renderer})", parts.join("; ")),
        holds: Some(holds),
    }
}

/// Why the crossover does or does not happen: at the largest crowd, the two-pass GPU work
/// (pass 1 + copy + pass 2) against the vertex-shader stage (skinning and drawing).
fn stage_claim(counts: &[usize], measured: &Measured, renderer: &str) -> Option<Claim> {
    let n = *counts.last()?;
    let mut parts = Vec::new();
    let mut holds = true;
    for kind in ModelKind::ALL {
        let tp = Measured::find(&measured.table1, kind, n, Variant::TwoPass)?;
        let vs = Measured::find(&measured.table1, kind, n, Variant::VertexShader)?;
        let w = &tp.passes.wall;
        let two_pass = w.pass1 + w.copy + w.pass2;
        let baseline = vs.passes.wall.vertex_shader;
        holds &= two_pass < baseline;
        parts.push(format!(
            "{} x {n}: pass 1 {:.1} + copy {:.1} + pass 2 {:.1} = {two_pass:.1} ms against {baseline:.1} ms \
             for VS skinning and drawing (pass 2 alone is {:.0}% of it)",
            kind.name(),
            w.pass1,
            w.copy,
            w.pass2,
            100.0 * w.pass2 / baseline
        ));
    }
    Some(Claim {
        claim:
            "Skinning once in a pixel shader and drawing pre-skinned vertices costs the GPU less \
                than skinning in the vertex shader while drawing"
                .into(),
        paper: "Implied by Table 1: 2-pass is 3.6-7x faster than VS from 256 characters on".into(),
        measured: format!("{} ({renderer})", parts.join("; ")),
        holds: Some(holds),
    })
}

fn fidelity_rows() -> Vec<Fidelity> {
    let row = |f: &str, p: &str, c: &str| Fidelity::new(f, p, c, "");
    vec![
        row(
            "Vertex data in 1D float textures",
            "Fig. 1-(a): position, normal, bone indices, weights",
            "src/crowd/vertex_textures.rs",
        ),
        row(
            "Bone matrices as three row textures",
            "Fig. 1-(b): 3x4 matrices computed on the CPU each frame",
            "src/crowd/bone_textures.rs",
        ),
        row(
            "Skinning in a pixel shader, one draw over n x m",
            "Fig. 2: a row per vertex index",
            "glsl/crowd/pass1_skinning.frag, src/crowd/pass1_skinning.rs",
        ),
        row(
            "Render target to VBO through a PBO, RGBA32F",
            "Section 2 [7, 8]",
            "src/crowd/render_to_vbo.rs",
        ),
        row(
            "Pass 2 with a shared index buffer",
            "Section 2",
            "glsl/crowd/pass2_draw.vert, src/crowd/pass2_draw.rs",
        ),
        row(
            "Vertex-shader skinning baseline, matrices in uniforms",
            "Table 1 'VS' [4]",
            "glsl/crowd/vs_skinning.vert, src/crowd/vertex_shader_skinning.rs",
        ),
        row(
            "3 LODs (1,084 / 544 / 312 polygons), view-frustum culling",
            "Section 3, Fig. 4-5",
            "src/crowd/lod.rs, src/crowd/culling.rs",
        ),
        row(
            "Sprites in the far field",
            "Tutorial lecture 2 (sprite LOD)",
            "src/crowd/sprites.rs, glsl/crowd/sprite.vert, glsl/crowd/sprite.frag",
        ),
        row(
            "Behaviour control",
            "Tutorial lecture 2",
            "src/crowd/steering.rs",
        ),
    ]
}

/// The paper-2 section.
pub struct Paper2;

impl super::Paper for Paper2 {
    const ID: &'static str = "paper2";
    const TITLE: &'static str = "Kang & Han 2006: Real-Time Animation of Large Crowds";
    type Options = super::NoOptions;
    type Results = super::LegacySection;

    fn measure(opts: &BenchOptions, _: &super::NoOptions) -> anyhow::Result<super::LegacySection> {
        run(opts).map(super::LegacySection)
    }

    fn section(_: &BenchOptions, results: &super::LegacySection) -> anyhow::Result<Section> {
        Ok(results.section())
    }
}
