//! Paper 2's section (Kang & Han 2006): Table 1 (vertex-shader vs two-pass skinning, 1 to 4096
//! soldiers and horses, no culling), its ratios and a per-stage breakdown, and the snapshot
//! scenes of Fig. 3-5 (10,240 soldiers, 5,120 horses with LOD and culling), beside the
//! published frame rates (`[paper2]` of `assets/paper_tables.toml`). The Fig. 4-5 runs are the
//! paper's setup; this project's sprite level is measured on the same crowds and reported
//! apart, as an extension.
//!
//! The vertex-shader baseline runs twice: as fast as this renderer allows (as many
//! characters per instanced draw as the uniforms hold), and one character per draw call,
//! as the paper's generation of hardware had to (a few hundred constant registers, no
//! instancing in OpenGL 2).

mod bench;
mod claims;
mod fidelity;
mod fig3_5;
pub mod period;
mod profile;
mod ratios;
mod snapshots;
mod stages;
mod table1;
mod then_and_now;

pub use bench::{LodInfo, ModelInfo, Paper2Results, Setup, Shows, Snapshot, Variant};

use super::period::WithPeriod;
use super::published::Published;
use super::{checks, BenchOptions, NoOptions, Paper, Section};
use crate::crowd::ModelKind;

/// The paper-2 section.
pub struct Paper2;

impl Paper for Paper2 {
    const PERIOD_PAPER: Option<u8> = Some(2);
    const ID: &'static str = "paper2";
    const CLAIMS: &'static [super::ClaimDef] = claims::CLAIMS;
    const TITLE: &'static str = "Paper 2: Kang & Han 2006, real-time animation of large crowds";
    type Options = NoOptions;
    type Results = WithPeriod<Paper2Results>;

    fn measure(opts: &BenchOptions, _: &NoOptions) -> anyhow::Result<Self::Results> {
        crate::timing::mark("paper2: start");
        let (mut results, table) = super::profile::profiled(opts.gl, || bench::measure(opts))?;
        results.profile = Some(table);
        crate::timing::mark("paper2: measured");
        let with = WithPeriod::measure(results, opts, period::measure);
        crate::timing::mark("paper2: period");
        with
    }

    fn section(opts: &BenchOptions, results: &Self::Results) -> anyhow::Result<Section> {
        let paper = &Published::get()?.paper2;
        let mut figures = snapshots::figures(results);
        figures.extend(table1::figures(opts, results, &paper.table1)?);
        Ok(Section {
            summary: summary(results),
            tables: vec![
                table1::table(results, &paper.table1),
                ratios::table(results, &paper.table1),
                stages::table(results),
                fig3_5::table(results, paper),
                results.then_and_now.table(&results.renderer),
            ]
            .into_iter()
            .chain(profile::table(results))
            .chain(results.period_tables())
            .collect(),
            claims: claims::claims(results),
            figures,
            fidelity: fidelity::rows(results),
            checks_listed: checks::ids(checks::PAPER2),
            checks_made: Vec::new(),
            ..Section::default()
        })
    }
}

fn summary(results: &Paper2Results) -> String {
    let [w, h] = results.size;
    let bones = |kind| results.model(kind).map_or(0, |m| m.bones);
    let lod0_limit = results
        .models
        .iter()
        .filter_map(|m| m.lods.first().map(|l| l.characters_per_draw))
        .min()
        .unwrap_or(0);
    format!(
        "Procedural stand-ins for the paper's rigged models, whose meshes are not published (a \
         soldier of {} bones, a horse of {}: this project's choices; LOD meshes of exactly the \
         paper's 1,084, 544 and 312 triangles; walk and gallop clips), each character with its \
         own animation phase and steering. Table 1 runs with culling off and every character at \
         LOD 0 on a {w}x{h} target; FPS is the median wall-clock frame (culling, bone matrices, \
         GPU passes, glFinish). The vertex-shader baseline is measured both at {} characters per \
         instanced draw (all the uniforms hold here) and at one per draw, as on the paper's \
         hardware. Pass 1 folds n characters into rows of at most {} (the 2048-byte \
         vertex-stride cap of OpenGL 4.4+), so one draw skins at most {lod0_limit} characters \
         at LOD 0 here ({}-texel textures), not all of them as in the paper; larger crowds go in \
         several draws. The Fig. 4-5 runs are the paper's setup, three LOD meshes and frustum \
         culling with no sprites; the same crowds with this project's sprite level are measured \
         side by side and shown apart as an extension. Renderer: {}.{} {}",
        bones(ModelKind::Soldier),
        bones(ModelKind::Horse),
        results.vertex_shader_batch(),
        results.setup.row_characters,
        results.setup.max_texture_size,
        results.renderer,
        if results.quick {
            " Quick mode: first three rows of Table 1 only, LOD runs at a tenth of the paper's crowd."
        } else {
            ""
        },
        checks::sentence_or_none(
            checks::PAPER2,
            "No answer is compared in this run, which times: the skinned vertices are \
             compared with linear blend skinning on the CPU by the tests (tests/crowd_gpu.rs).",
        ),
    )
}
