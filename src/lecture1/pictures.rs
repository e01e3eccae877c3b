//! The buffers of the lecture-1 GPU paths as picture panels ([`crate::gl::picture`]), for the
//! report's figures and the viewer's insets: the pair texture `P0` (a texel per pair, 1 where
//! the pair was reported) and its hierarchical 4x4 encoding `P1..P3` (paper 1's readback),
//! each level beside the CPU encoding of the `P0` below it.

use crate::collide::reduction::encode4;
use crate::collide::reduction_gpu::Reduction;
use crate::gl::picture::{Panel, Scale};
use crate::gl::Texture;

/// One buffer as a panel, with the raw texels and a CPU reference where there is one (the
/// viewer's probe shows them side by side).
pub struct BufferPanel {
    pub panel: Panel,
    /// The texels as stored (the masks of a level), when the panel shows something derived.
    pub raw: Option<Vec<f32>>,
    /// The CPU's value of every texel, computed from the GPU's `P0`.
    pub reference: Option<Vec<f32>>,
}

/// `P0` and its levels. `what` says what a row and a column of `P0` are
/// ("triangle i of A (row), triangle j of B (column)"); `short` titles for small insets.
pub fn pair_buffers(
    p0: &Texture,
    reduction: &Reduction,
    what: &str,
    short: bool,
) -> anyhow::Result<Vec<BufferPanel>> {
    let (w, h) = (p0.width() as usize, p0.height() as usize);
    let p0_values = p0.download_f32()?;
    let title = |short_name: String, long: String| if short { short_name } else { long };
    let mut out = vec![BufferPanel {
        panel: Panel {
            title: title(
                "P0".into(),
                format!("P0 ({w}x{h}): 1 where the pair {what} may intersect"),
            ),
            values: p0_values.clone(),
            width: w as u32,
            height: h as u32,
            scale: Scale::fixed(0.0, 1.0),
        },
        raw: None,
        reference: None,
    }];
    // Each level's texel is a 16-bit mask of a 4x4 block below; shown by its set bits.
    let bits = |v: f32| (v as u32).count_ones() as f32;
    let (mut below, mut bw, mut bh) = (p0_values, w, h);
    for (i, t) in reduction.level_textures().into_iter().enumerate() {
        let masks = t.download_f32()?;
        let (cpu, cw, ch) = encode4(&below, bw, bh);
        out.push(BufferPanel {
            panel: Panel {
                title: title(
                    format!("P{}", i + 1),
                    format!(
                        "P{} ({cw}x{ch}): set bits of the mask of a 4x4 block of P{i}",
                        i + 1
                    ),
                ),
                values: masks.iter().map(|&m| bits(m)).collect(),
                width: t.width(),
                height: t.height(),
                scale: Scale::fixed(0.0, 16.0),
            },
            raw: Some(masks),
            reference: Some(cpu.clone()),
        });
        (below, bw, bh) = (cpu, cw, ch);
    }
    Ok(out)
}
