//! Newell's teapot, tessellated from its Bezier patches.

use glam::Vec3;

use super::teapot_data::{PATCHES, POINTS};
use crate::mesh::Mesh;

/// The 32 patches of the Utah teapot as 4 x 4 control points (row `r`, column `c` at
/// `[r][c]`), z up, about 3.15 units tall and 6.4 long (spout to handle).
pub fn teapot_patches() -> Vec<[[Vec3; 4]; 4]> {
    PATCHES
        .iter()
        .map(|patch| {
            std::array::from_fn(|r| {
                std::array::from_fn(|c| Vec3::from(POINTS[patch[4 * r + c] as usize - 1]))
            })
        })
        .collect()
}

/// The Utah teapot: each of the 32 patches sampled on an `(n + 1) x (n + 1)` grid
/// (`n = segments`, at least 1), points shared by neighbouring patches welded, and the
/// triangles that collapse at the lid knob and the bottom centre dropped:
/// `64 n^2 - 8 n` triangles.
///
/// Not watertight, as Newell modelled it: the lid rests on the rim with a gap, the
/// spout's tip is open, and the spout and handle pierce the body instead of joining it.
/// Its signed volume is therefore only approximately the enclosed volume. Triangles
/// face outward (counter-clockwise seen from outside). Paper 4 lists 821 vertices and
/// 1628 triangles; `teapot(5)` has exactly 821 vertices and 1560 triangles (the paper's
/// extra 68 faces are not explained; perhaps it kept some collapsed ones).
pub fn teapot(segments: usize) -> Mesh {
    let n = segments.max(1);
    let mut raw = Mesh::default();
    for patch in teapot_patches() {
        let base = raw.positions.len() as u32;
        for i in 0..=n {
            for j in 0..=n {
                raw.positions.push(bezier_patch_point(
                    &patch,
                    i as f32 / n as f32,
                    j as f32 / n as f32,
                ));
            }
        }
        let id = |i: usize, j: usize| base + (i * (n + 1) + j) as u32;
        for i in 0..n {
            for j in 0..n {
                // Rows (u) run from the top of a patch down and columns (v) clockwise
                // seen from above, so dS/dv x dS/du points out: (i,j) (i,j+1) (i+1,j+1).
                let quad = [id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)];
                super::push_quad(&mut raw.triangles, quad);
            }
        }
    }
    // Shared patch edges are evaluated twice, in different orders: weld within a
    // tolerance far below the patch sizes (the smallest control-point gap is 0.002).
    raw.welded_within(1e-4).without_degenerate()
}

/// The cubic Bernstein weights at `t`, written so that `bernstein(1 - t)` is exactly the
/// reverse of `bernstein(t)` (shared edges then agree up to summation order).
fn bernstein(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * (s * t) * s, 3.0 * (s * t) * t, t * t * t]
}

/// The patch's point at `(u, v)`: sum over rows r and columns c of `B_r(u) B_c(v) P[r][c]`.
fn bezier_patch_point(patch: &[[Vec3; 4]; 4], u: f32, v: f32) -> Vec3 {
    let (bu, bv) = (bernstein(u), bernstein(v));
    let mut p = Vec3::ZERO;
    for r in 0..4 {
        for c in 0..4 {
            p += bu[r] * bv[c] * patch[r][c];
        }
    }
    p
}
