//! The image pyramid of the displacement map (technique 1 applied): level 0 holds, for each
//! bilinear patch, the maximum of its four corners (a bilinear patch is bounded by its
//! corners), drawn by one pass from the height texture; the levels above are the max pyramid
//! of that ([`crate::lecture3::pyramid`]). Node (i, j) of level k then bounds every patch in
//! `[i 2^k, (i+1) 2^k) x [j 2^k, (j+1) 2^k)`, which is what makes skipping a node safe.

use crate::gl::{Context, GlError, Program, Texture};
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, Level, Pyramid, PyramidBuilder};
use crate::lecture3::HeightMap;
use crate::shader;

/// The extreme of each patch's four corners, `(width - 1) x (height - 1)`, on the CPU.
pub fn patch_bounds(map: &HeightMap, extreme: Extreme) -> Vec<f32> {
    let (wp, hp) = map.patches();
    (0..hp)
        .flat_map(|j| (0..wp).map(move |i| (i, j)))
        .map(|(i, j)| {
            let a = extreme.combine(map.at(i, j), map.at(i + 1, j));
            let b = extreme.combine(map.at(i, j + 1), map.at(i + 1, j + 1));
            extreme.combine(a, b)
        })
        .collect()
}

/// The whole bound pyramid on the CPU.
pub fn cpu_bound_pyramid(map: &HeightMap, extreme: Extreme) -> Vec<Level> {
    let (wp, hp) = map.patches();
    cpu_pyramid(wp, hp, &patch_bounds(map, extreme), extreme)
}

/// Draws bound pyramids on the GPU.
pub struct BoundPyramidBuilder {
    pyramids: PyramidBuilder,
    bounds_program: Program,
}

impl BoundPyramidBuilder {
    pub fn new(ctx: &Context) -> Result<BoundPyramidBuilder, GlError> {
        Ok(BoundPyramidBuilder {
            pyramids: PyramidBuilder::new(ctx)?,
            bounds_program: Program::rect(ctx, &[shader!("glsl/lecture3/patch_bounds.frag")])?,
        })
    }

    /// The pyramid of `heights` (the height map's texture, `patches` + 1 samples a side):
    /// level 0 by the patch-bounds pass, then one pass per level.
    pub fn build(
        &self,
        heights: &Texture,
        patches: (u32, u32),
        extreme: Extreme,
    ) -> Result<Pyramid, GlError> {
        let op = match extreme {
            Extreme::Max => 0,
            Extreme::Min => 1,
            Extreme::Mean => {
                return Err(GlError::Invalid(
                    "a bound pyramid keeps maxima or minima of the patches, not means".into(),
                ))
            }
        };
        let pyramid = self.pyramids.allocate(patches.0, patches.1, extreme)?;
        pyramid
            .target(0)
            .pass(&self.bounds_program, "patch bounds")?
            .texture("u_heights", heights)
            .uniform(
                "u_patches",
                glam::IVec2::new(patches.0 as i32, patches.1 as i32),
            )
            .uniform("u_op", op)
            .draw_full()?;
        self.pyramids.build_levels(&pyramid)?;
        Ok(pyramid)
    }
}
