//! Where a frame's time goes: the CPU bone matrices, pass 1, the render-to-VBO copy and
//! pass 2 of the two-pass method, against the vertex-shader stage, at every Table 1 size.

use super::bench::{Paper2Results, Variant};
use crate::crowd::ModelKind;
use crate::report::Table;

pub fn table(results: &Paper2Results) -> Table {
    let mut table = Table {
        caption: "Time of one frame's stages (ms): CPU bone matrices; pass-1 draws (one per \
                  batch of at most what a render target holds; the paper has one); GPU stages by \
                  wall clock between glFinish calls (GL timer-query values are in the JSON \
                  results); whole frames (median)"
            .into(),
        header: [
            "model",
            "n",
            "bones (CPU)",
            "pass-1 draws",
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
        for n in results.counts() {
            let find = |v| Paper2Results::find(&results.table1, kind, n, v);
            let (Some(tp), Some(vs), Some(single)) = (
                find(Variant::TwoPass),
                find(Variant::VertexShader),
                find(Variant::VertexShaderSingle),
            ) else {
                continue;
            };
            let ms = |x: f64| format!("{x:.2}");
            table.rows.push(vec![
                kind.name().into(),
                n.to_string(),
                ms(tp.passes.bones_ms),
                tp.passes.pass1_draws.to_string(),
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
    table
}
