//! Lesson 8's compaction on the GPU, after Ziegler, Tevs, Theobalt and Seidel, "GPU point list
//! generation through histogram pyramids" (2006): the flags of the blocks that hold data are
//! summed into a pyramid (each level 2x2 sums of the one below, the 1x1 top the count), the CPU
//! reads the count, and each slot of an output list walks down the pyramid to the flagged block
//! it stands for. A gather pass then copies those blocks' texels into one small texture, so that
//! the CPU reads the count, the list and the flagged blocks in three glReadPixels calls however
//! many blocks are flagged.
//!
//! The pyramid is one mipmapped R32F texture, square and a power of two on a side, its level 0
//! the flags (zero outside the array's blocks). The list and the gathered blocks share one
//! layout, as square as it goes: slot k at (k % width, k / width), its block's tile at the same
//! place in units of a block. The list's order is the walk's, the quadtree (Morton) order of
//! the blocks, which [`cpu_list`] reproduces.

use crate::gl::{Context, Framebuffer, Program, Rect, Texture, TextureFormat};
use crate::shader;

/// The pyramid over a grid of block flags, with the programs that build and walk it.
pub struct HistogramPyramid {
    texture: Texture,
    /// A target per level, level 0 (the flags) first.
    targets: Vec<Framebuffer>,
    /// The flags' grid: blocks across and up.
    blocks: (u32, u32),
    level_program: Program,
    list_program: Program,
    gather_program: Program,
}

/// The side of the pyramid over `blocks` (across, up): the power of two that holds both.
pub fn pyramid_side(blocks: (u32, u32)) -> u32 {
    blocks.0.max(blocks.1).max(1).next_power_of_two()
}

impl HistogramPyramid {
    /// An empty pyramid over a `blocks.0 x blocks.1` grid of flags.
    pub fn new(ctx: &Context, blocks: (u32, u32)) -> anyhow::Result<HistogramPyramid> {
        let side = pyramid_side(blocks);
        let levels = side.trailing_zeros() + 1;
        let texture = Texture::new_2d_mipmapped(ctx, side, side, TextureFormat::R32F, levels)?;
        let targets = (0..levels)
            .map(|level| {
                Framebuffer::new_at_level(ctx, "histogram pyramid level", &[&texture], None, level)
            })
            .collect::<Result<_, _>>()?;
        let program = |path| Program::rect(ctx, &[path]);
        Ok(HistogramPyramid {
            texture,
            targets,
            blocks,
            level_program: program(shader!("glsl/learn/readback-and-upload/pyramid_level.frag"))?,
            list_program: program(shader!("glsl/learn/readback-and-upload/pyramid_list.frag"))?,
            gather_program: program(shader!("glsl/learn/readback-and-upload/gather_blocks.frag"))?,
        })
    }

    /// Level 0, cleared to zero: the target the flags pass draws into, over [`Self::flags_rect`].
    pub fn base(&self) -> anyhow::Result<&Framebuffer> {
        self.targets[0].clear_colors([0.0; 4])?;
        Ok(&self.targets[0])
    }

    /// Where the flags lie in level 0: one texel per block, from the corner.
    pub fn flags_rect(&self) -> Rect {
        Rect::sized(self.blocks.0, self.blocks.1)
    }

    /// The number of levels, the flags included.
    pub fn levels(&self) -> u32 {
        self.targets.len() as u32
    }

    /// Levels 1 to the top from the flags: a pass per level, each reading only the level below
    /// (the texture's readable levels narrowed to it while the next is drawn).
    pub fn build(&self) -> anyhow::Result<()> {
        let texture = &self.texture;
        // region: pyramid-levels
        let built = (1..self.levels()).try_for_each(|level| {
            texture.set_level_range(level - 1, level - 1)?;
            self.targets[level as usize]
                .pass(&self.level_program, "histogram pyramid level")?
                .texture("u_below", texture)
                .draw_full()
        });
        // endregion
        texture.set_level_range(0, self.levels() - 1)?;
        Ok(built?)
    }

    /// Level `level` read back (for its picture and its check): its side squared counts, rows
    /// from the bottom.
    pub fn level(&self, level: u32) -> anyhow::Result<Vec<f32>> {
        let target = &self.targets[level as usize];
        Ok(target.read_f32(0, target.rect())?)
    }

    /// The flagged blocks counted: the top's one texel, read back.
    pub fn count(&self) -> anyhow::Result<u32> {
        let top = self.targets.last().expect("at least level 0");
        let count = top.read_f32(0, Rect::sized(1, 1))?[0];
        anyhow::ensure!(
            count.is_finite() && count >= 0.0 && count.fract() == 0.0,
            "the histogram pyramid's top holds {count}, not a count of blocks"
        );
        Ok(count as u32)
    }
}

/// The list and the gathered blocks for `count` flagged blocks: their targets, made once.
pub struct Compaction {
    count: u32,
    /// Slots per row; the rows are `count / width` rounded up.
    width: u32,
    list: Framebuffer,
    gathered: Framebuffer,
    block: u32,
}

impl Compaction {
    /// Targets for `count` (at least one) flagged blocks of `block x block` texels.
    pub fn new(ctx: &Context, count: u32, block: u32) -> anyhow::Result<Compaction> {
        anyhow::ensure!(count > 0, "a compaction of no blocks has nothing to draw");
        let (width, rows) = super::ladder::shape(count);
        let list = Texture::new_2d(ctx, width, rows, TextureFormat::R32F)?;
        let tiles = Texture::new_2d(ctx, width * block, rows * block, TextureFormat::Rgba32F)?;
        Ok(Compaction {
            count,
            width,
            list: Framebuffer::new(ctx, "histogram pyramid list", &[&list], None)?,
            gathered: Framebuffer::new(ctx, "gathered blocks", &[&tiles], None)?,
            block,
        })
    }

    pub fn count(&self) -> u32 {
        self.count
    }

    /// The list's slots across and up.
    pub fn list_size(&self) -> (u32, u32) {
        (self.list.width(), self.list.height())
    }

    /// The two passes: every slot walks the pyramid to its block, then every texel of the
    /// gathered texture copies its block's texel from `data`.
    pub fn draw(&self, pyramid: &HistogramPyramid, data: &Texture) -> anyhow::Result<()> {
        let blocks_across = pyramid.blocks.0 as i32;
        // region: pyramid-list
        self.list
            .pass(&pyramid.list_program, "histogram pyramid list")?
            .texture("u_pyramid", &pyramid.texture)
            .uniform("u_top", pyramid.levels() as i32 - 1)
            .uniform("u_count", self.count as i32)
            .uniform("u_width", self.width as i32)
            .uniform("u_blocks_across", blocks_across)
            .draw_full()?;
        // endregion
        // region: pyramid-gather
        self.gathered
            .pass(&pyramid.gather_program, "gather the flagged blocks")?
            .texture("u_data", data)
            .texture("u_list", self.list.color(0))
            .uniform("u_block", self.block as i32)
            .uniform("u_blocks_across", blocks_across)
            .draw_full()?;
        // endregion
        Ok(())
    }

    /// The list read back: one block index per slot, -1 in the slots past the count.
    pub fn read_list(&self) -> anyhow::Result<Vec<f32>> {
        Ok(self.list.read_f32(0, self.list.rect())?)
    }

    /// The gathered blocks read back, in one call: RGBA texels, rows from the bottom.
    pub fn read_blocks(&self) -> anyhow::Result<Vec<f32>> {
        Ok(self.gathered.read_f32(0, self.gathered.rect())?)
    }

    /// Bytes the three reads move: the count, the list, the gathered blocks.
    pub fn bytes_read(&self) -> usize {
        let (w, h) = self.list_size();
        4 + (w * h) as usize * 4 + (w * h * self.block * self.block) as usize * 16
    }

    /// The whole `side x side` RGBA array put together on the CPU from the list and the
    /// gathered blocks (zero elsewhere), with the blocks `blocks_across` to a row.
    pub fn place(&self, list: &[f32], gathered: &[f32], side: u32) -> Vec<f32> {
        let b = self.block as usize;
        let blocks_across = side as usize / b;
        let row_texels = self.width as usize * b;
        let mut out = vec![0f32; side as usize * side as usize * 4];
        for (slot, &block) in list.iter().enumerate().take(self.count as usize) {
            if block < 0.0 {
                continue;
            }
            let block = block as usize;
            let (bx, by) = (block % blocks_across * b, block / blocks_across * b);
            let (tx, ty) = (
                slot % self.width as usize * b,
                slot / self.width as usize * b,
            );
            for row in 0..b {
                let from = ((ty + row) * row_texels + tx) * 4;
                let to = ((by + row) * side as usize + bx) * 4;
                if let (Some(src), Some(dst)) = (
                    gathered.get(from..from + b * 4),
                    out.get_mut(to..to + b * 4),
                ) {
                    dst.copy_from_slice(src);
                }
            }
        }
        out
    }
}

/// The walk's order of two blocks: their Morton code, x's bits in the even places.
pub fn morton(x: u32, y: u32) -> u64 {
    (0..32).fold(0u64, |code, bit| {
        code | (((x as u64 >> bit) & 1) << (2 * bit)) | (((y as u64 >> bit) & 1) << (2 * bit + 1))
    })
}

/// The CPU's compaction: the flagged blocks of a `blocks.0 x blocks.1` grid of flags (rows from
/// the bottom, flagged when above one half), in the order the pyramid's walk lists them.
pub fn cpu_list(flags: &[f32], blocks: (u32, u32)) -> Vec<u32> {
    let mut list: Vec<u32> = (0..blocks.0 * blocks.1)
        .filter(|&b| flags.get(b as usize).is_some_and(|&f| f > 0.5))
        .collect();
    list.sort_by_key(|&b| morton(b % blocks.0, b / blocks.0));
    list
}

/// The CPU's pyramid over the same flags: level 0 the flags in the pyramid's square (zero
/// outside the grid), each level above the 2x2 sums of the one below, up to the 1x1 top.
pub fn cpu_levels(flags: &[f32], blocks: (u32, u32)) -> Vec<Vec<f32>> {
    let side = pyramid_side(blocks) as usize;
    let mut level = vec![0f32; side * side];
    for y in 0..blocks.1 as usize {
        for x in 0..blocks.0 as usize {
            level[y * side + x] = flags[y * blocks.0 as usize + x];
        }
    }
    let mut levels = vec![level];
    let mut n = side;
    while n > 1 {
        let below = levels.last().expect("level 0 is there");
        let half = n / 2;
        let next = (0..half * half)
            .map(|k| {
                let (x, y) = (k % half * 2, k / half * 2);
                (below[y * n + x] + below[y * n + x + 1])
                    + (below[(y + 1) * n + x] + below[(y + 1) * n + x + 1])
            })
            .collect();
        levels.push(next);
        n = half;
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_walk_order_is_the_quadtree_order() {
        assert_eq!(morton(0, 0), 0);
        assert_eq!(morton(1, 0), 1);
        assert_eq!(morton(0, 1), 2);
        assert_eq!(morton(1, 1), 3);
        assert_eq!(morton(2, 0), 4);
        // A 3x2 grid: blocks 0 (0,0), 2 (2,0), 4 (1,1) flagged.
        let flags = [1.0, 0.0, 1.0, 0.0, 1.0, 0.0];
        assert_eq!(cpu_list(&flags, (3, 2)), vec![0, 4, 2]);
        let levels = cpu_levels(&flags, (3, 2));
        assert_eq!(levels.len(), 3);
        assert_eq!(levels[1], vec![2.0, 1.0, 0.0, 0.0]);
        assert_eq!(levels[2], vec![3.0]);
        assert_eq!(pyramid_side((3, 2)), 4);
        assert_eq!(pyramid_side((16, 16)), 16);
    }
}
