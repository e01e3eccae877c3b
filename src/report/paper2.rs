//! Paper 2 (Kang & Han 2006): Table 1 (vertex-shader vs two-pass skinning, 1 to 4096
//! soldiers and horses, no culling) and the LOD runs of Fig. 4-5 (10,240 soldiers, 5,120
//! horses with LOD and culling), measured here beside the published frame rates.

use anyhow::Context as _;
use serde_json::json;

use crate::crowd::renderer::{CrowdRenderer, Method};
use crate::crowd::scene::{self, RunStats, Scene};
use crate::crowd::{sprites, CharacterModel, ModelKind};
use crate::gl::dump::{self, DumpRange};
use crate::report::{paper_tables, BenchOptions, Claim, Fidelity, Figure, Section, Table};

/// Character counts measured in quick mode (the paper's first three rows).
const QUICK_COUNTS: [usize; 3] = [1, 16, 64];

/// Timed frames per measurement: enough to average, few enough for llvmpipe.
fn frames_for(n: usize, quick: bool) -> usize {
    match (quick, n) {
        (true, _) => 3,
        (false, 0..=64) => 20,
        (false, 65..=1024) => 5,
        _ => 2,
    }
}

fn paper_row(table: &toml::Value, key: &str) -> Vec<f64> {
    table[key]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|v| v.as_float().or(v.as_integer().map(|i| i as f64)))
                .collect()
        })
        .unwrap_or_default()
}

/// Runs the benchmark and returns the section.
pub fn run(opts: &BenchOptions) -> anyhow::Result<Section> {
    let tables = paper_tables::load();
    let paper = &tables["paper2"];
    let table1 = &paper["table1"];
    let all_counts: Vec<usize> = paper_row(table1, "characters")
        .iter()
        .map(|&x| x as usize)
        .collect();
    let counts: Vec<usize> = if opts.quick {
        QUICK_COUNTS.to_vec()
    } else {
        all_counts.clone()
    };
    let (w, h) = if opts.quick { (320, 240) } else { (640, 480) };
    let lod_scale = if opts.quick { 10 } else { 1 };
    std::fs::create_dir_all(&opts.out_dir)
        .with_context(|| format!("creating {}", opts.out_dir.display()))?;
    let ctx = opts.gl;
    let target = scene::scene_target(ctx, w, h)?;
    let aspect = w as f32 / h as f32;

    let runs_toml = paper["runs"].as_array().cloned().unwrap_or_default();
    let lod_runs: Vec<(ModelKind, usize, f64)> = runs_toml
        .iter()
        .filter(|r| r["lod_and_culling"].as_bool() == Some(true))
        .map(|r| {
            let kind = if r["model"].as_str() == Some("horse") {
                ModelKind::Horse
            } else {
                ModelKind::Soldier
            };
            (
                kind,
                r["characters"].as_integer().unwrap_or(0) as usize,
                r["fps"].as_integer().unwrap_or(0) as f64,
            )
        })
        .collect();

    let total = (ModelKind::ALL.len() * counts.len() * 2 + lod_runs.len() * 2) as u64;
    let bar = opts.progress.add(indicatif::ProgressBar::new(total));
    bar.set_style(
        indicatif::ProgressStyle::with_template("paper 2 {bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );

    let mut table1_runs: Vec<RunStats> = Vec::new();
    let mut lod_results: Vec<RunStats> = Vec::new();
    let mut figures = Vec::new();
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind)?;
        let mut renderer = CrowdRenderer::new(ctx, model)?;
        for &n in &counts {
            for method in [Method::VertexShader, Method::TwoPass] {
                bar.set_message(format!("{} x {n}, {}", kind.name(), method.name()));
                let mut scene: Scene = scene::table1_scene(kind, n, aspect, 1);
                let stats = scene::run(
                    ctx,
                    &mut renderer,
                    &target,
                    &mut scene,
                    method,
                    frames_for(n, opts.quick),
                    1.0 / 30.0,
                )?;
                table1_runs.push(stats);
                bar.inc(1);
            }
            let fig3_n = if opts.quick { 64 } else { 1024 };
            if kind == ModelKind::Soldier && n == fig3_n {
                let file = format!("fig3_{n}_soldiers.png");
                dump::texture_png(target.color(0), &opts.out_dir.join(&file), DumpRange::Auto)?;
                figures.push(Figure {
                    file,
                    caption: format!(
                        "Fig. 3: {n} soldiers without LOD and frustum culling (two-pass)"
                    ),
                });
            }
        }
        let file = format!("{}_impostor_atlas.png", kind.name());
        dump::texture_png(
            renderer.sprites().atlas(),
            &opts.out_dir.join(&file),
            DumpRange::Auto,
        )?;
        figures.push(Figure {
            file,
            caption: format!(
                "Sprite level: impostor atlas of the {} ({} views x {} animation phases)",
                kind.name(),
                sprites::VIEWS,
                sprites::FRAMES
            ),
        });
        if let Some(texture) = renderer.render_target(0) {
            let file = format!("fig2_{}_render_target.png", kind.name());
            dump::texture_png(texture, &opts.out_dir.join(&file), DumpRange::Auto)?;
            figures.push(Figure {
                file,
                caption: format!(
                    "Fig. 2: pass-1 render target of the last {} run, skinned positions as colour (column = character, row = vertex)",
                    kind.name()
                ),
            });
        }
        for &(run_kind, n, _) in lod_runs.iter().filter(|r| r.0 == kind) {
            let n = n / lod_scale;
            for method in [Method::VertexShader, Method::TwoPass] {
                bar.set_message(format!("{} x {n} with LOD, {}", kind.name(), method.name()));
                let mut scene = scene::lod_scene(run_kind, n, aspect, 1);
                let stats = scene::run(
                    ctx,
                    &mut renderer,
                    &target,
                    &mut scene,
                    method,
                    if opts.quick { 2 } else { 3 },
                    1.0 / 30.0,
                )?;
                lod_results.push(stats);
                bar.inc(1);
            }
            let figure = if kind == ModelKind::Soldier {
                "fig4"
            } else {
                "fig5"
            };
            let file = format!("{figure}_{n}_{}s_lod.png", kind.name());
            dump::texture_png(target.color(0), &opts.out_dir.join(&file), DumpRange::Auto)?;
            figures.push(Figure {
                file,
                caption: format!(
                    "Fig. {}: {n} {}s with LOD, sprites and frustum culling (two-pass)",
                    &figure[3..],
                    kind.name()
                ),
            });
        }
    }
    bar.finish_and_clear();

    let fps_of = |kind: ModelKind, n: usize, method: Method| -> f64 {
        table1_runs
            .iter()
            .find(|r| r.model == kind.name() && r.characters == n && r.method == method.name())
            .map_or(f64::NAN, |r| r.fps)
    };
    let paper_fps = |key: &str, n: usize| -> String {
        let row = paper_row(table1, key);
        all_counts
            .iter()
            .position(|&c| c == n)
            .and_then(|i| row.get(i))
            .map_or("-".into(), |v| format!("{v:.0}"))
    };
    let mut fps_table = Table {
        caption: format!(
            "Table 1: FPS, vertex-shader (VS) vs two-pass skinning, no culling, all characters at LOD 0 ({w}x{h}; paper: GeForce 7800 GTX; here: {})",
            ctx.info().renderer
        ),
        header: ["n", "soldier VS paper", "VS here", "2-pass paper", "2-pass here", "horse VS paper", "VS here", "2-pass paper", "2-pass here"]
            .map(String::from)
            .to_vec(),
        rows: Vec::new(),
    };
    let mut ratio_table = Table {
        caption: "Two-pass / VS frame-rate ratio (> 1: the paper's method is faster)".into(),
        header: [
            "n",
            "soldier paper",
            "soldier here",
            "horse paper",
            "horse here",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for &n in &counts {
        let mut row = vec![n.to_string()];
        let mut ratios = vec![n.to_string()];
        for (kind, vs_key, tp_key) in [
            (ModelKind::Soldier, "soldier_vs", "soldier_two_pass"),
            (ModelKind::Horse, "horse_vs", "horse_two_pass"),
        ] {
            let (vs, tp) = (
                fps_of(kind, n, Method::VertexShader),
                fps_of(kind, n, Method::TwoPass),
            );
            row.extend([
                paper_fps(vs_key, n),
                format!("{vs:.1}"),
                paper_fps(tp_key, n),
                format!("{tp:.1}"),
            ]);
            let paper_ratio = paper_fps(tp_key, n)
                .parse::<f64>()
                .ok()
                .zip(paper_fps(vs_key, n).parse::<f64>().ok());
            ratios.push(paper_ratio.map_or("-".into(), |(t, v)| format!("{:.2}", t / v)));
            ratios.push(format!("{:.2}", tp / vs));
        }
        fps_table.rows.push(row);
        ratio_table.rows.push(ratios);
    }
    let mut pass_table = Table {
        caption: "Per-stage time of one frame (ms, wall clock between glFinish calls; the GL \
                  timer-query values are in the JSON results) and whole frames"
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
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for kind in ModelKind::ALL {
        for &n in &counts {
            let find = |m: Method| {
                table1_runs
                    .iter()
                    .find(|r| r.model == kind.name() && r.characters == n && r.method == m.name())
            };
            if let (Some(tp), Some(vs)) = (find(Method::TwoPass), find(Method::VertexShader)) {
                pass_table.rows.push(vec![
                    kind.name().into(),
                    n.to_string(),
                    format!("{:.2}", tp.passes.bones_ms),
                    format!("{:.2}", tp.passes.wall.pass1),
                    format!("{:.2}", tp.passes.wall.copy),
                    format!("{:.2}", tp.passes.wall.pass2),
                    format!("{:.2}", tp.frame_ms),
                    format!("{:.2}", vs.passes.wall.vertex_shader),
                    format!("{:.2}", vs.frame_ms),
                ]);
            }
        }
    }
    let mut lod_table = Table {
        caption: "Fig. 4-5: LOD (1,084 / 544 / 312 polygons), sprites and view-frustum culling"
            .into(),
        header: [
            "model",
            "n",
            "paper FPS",
            "2-pass FPS",
            "VS FPS",
            "LOD 0/1/2",
            "sprites",
            "culled",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for &(kind, n, paper) in &lod_runs {
        let n = n / lod_scale;
        let find = |m: Method| {
            lod_results
                .iter()
                .find(|r| r.model == kind.name() && r.characters == n && r.method == m.name())
        };
        if let (Some(tp), Some(vs)) = (find(Method::TwoPass), find(Method::VertexShader)) {
            lod_table.rows.push(vec![
                kind.name().into(),
                n.to_string(),
                if lod_scale == 1 {
                    format!("{paper:.0}")
                } else {
                    format!("{paper:.0} (at {})", n * lod_scale)
                },
                format!("{:.1}", tp.fps),
                format!("{:.1}", vs.fps),
                format!("{} / {} / {}", tp.per_lod[0], tp.per_lod[1], tp.per_lod[2]),
                tp.passes.sprites.to_string(),
                tp.culled.to_string(),
            ]);
        }
    }

    let claims = vec![crossover_claim(
        &counts,
        &fps_of,
        ctx.info().renderer.as_str(),
    )];
    let summary = format!(
        "Procedural stand-ins for the paper's rigged models (a soldier of 18 bones, a horse of 20; \
         LODs of exactly 1,084, 544 and 312 triangles; walk and gallop clips), each character with \
         its own animation phase and steering. Table 1 runs with culling off and every character \
         at LOD 0 on a {w}x{h} target; FPS is wall clock over whole frames (culling, bone matrices, \
         GPU passes, glFinish), per-pass times come from GL timer queries. Renderer: {}.{}",
        ctx.info().renderer,
        if opts.quick { " Quick mode: first three rows of Table 1 only, LOD runs at a tenth of the paper's crowd." } else { "" }
    );
    let fidelity = fidelity_rows();
    Ok(Section {
        id: "paper2".into(),
        title: "Kang & Han 2006: Real-Time Animation of Large Crowds".into(),
        summary,
        tables: vec![fps_table, ratio_table, pass_table, lod_table],
        claims,
        figures,
        fidelity,
        results: json!({ "renderer": ctx.info().renderer, "size": [w, h], "table1": table1_runs, "lod_runs": lod_results }),
    })
}

/// Smallest n from which two-pass is faster than VS for every larger n measured.
fn crossover_claim(
    counts: &[usize],
    fps_of: &dyn Fn(ModelKind, usize, Method) -> f64,
    renderer: &str,
) -> Claim {
    let mut parts = Vec::new();
    let mut holds = true;
    for kind in ModelKind::ALL {
        let faster: Vec<bool> = counts
            .iter()
            .map(|&n| fps_of(kind, n, Method::TwoPass) > fps_of(kind, n, Method::VertexShader))
            .collect();
        let from = (0..counts.len()).find(|&i| faster[i..].iter().all(|&f| f));
        match from {
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
        claim: "Two-pass (pixel-shader) skinning overtakes vertex-shader skinning once there are enough characters".into(),
        paper: "VS is faster for 1 character; two-pass is faster from 16 characters on (Table 1, GeForce 7800 GTX)".into(),
        measured: format!("{} ({renderer})", parts.join("; ")),
        holds: Some(holds),
    }
}

fn fidelity_rows() -> Vec<Fidelity> {
    let row = |feature: &str, paper: &str, code: &str| Fidelity {
        feature: feature.into(),
        paper: paper.into(),
        code: code.into(),
    };
    vec![
        row(
            "Vertex data in 1D float textures",
            "Fig. 1-(a): position, normal, bone indices, weights",
            "src/crowd/vertex_textures.rs",
        ),
        row(
            "Bone matrices as three row textures",
            "Fig. 1-(b), 3x4 matrices computed on the CPU per frame",
            "src/crowd/bone_textures.rs",
        ),
        row(
            "Skinning in a pixel shader, one draw over n x m",
            "Fig. 2, a row per vertex index",
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
            "src/crowd/pass2_draw.rs",
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
            "src/crowd/sprites.rs, glsl/crowd/sprite.*",
        ),
        row(
            "Behaviour control",
            "Tutorial lecture 2",
            "src/crowd/steering.rs",
        ),
    ]
}
