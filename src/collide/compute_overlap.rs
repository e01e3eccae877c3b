//! The AABB overlap test over all leaf pairs as a compute pass with stream compaction
//! (OpenGL 4.3; the "then and now" of Sec. 5.2-5.3): each overlapping pair is appended to a
//! list through an atomic counter, and the CPU reads the count and exactly that many pairs.
//! It replaces the occlusion-counted `P0` render target, the stencil mask that keeps one
//! slot per leaf, and the hierarchical readback that locates the set pixels.

use super::compute_update::LeafBoxes;
use crate::gl::{
    memory_barrier, AtomicCounters, Barrier, Buffer, BufferUsage, ComputeProgram, Context, GlError,
};
use crate::shader;

/// The overlap program, its counter and its pair list (grown when a frame needs more).
pub struct ComputeOverlap {
    ctx: Context,
    program: ComputeProgram,
    counter: AtomicCounters,
    pairs: Buffer,
    capacity: u32,
}

/// What one overlap pass read back.
#[derive(Clone, Debug, Default)]
pub struct OverlapPairs {
    /// Colliding leaf pairs `(leaf of X, leaf of Y)`, sorted.
    pub caps: Vec<(u32, u32)>,
    /// Bytes read back: the counter and the pairs.
    pub bytes: u64,
    /// Whether the list overflowed and the pass ran again with a larger one.
    pub reran: bool,
}

/// Pairs the list holds at first.
const INITIAL_CAPACITY: u32 = 4096;

impl ComputeOverlap {
    pub fn new(ctx: &Context) -> Result<ComputeOverlap, GlError> {
        let program =
            ComputeProgram::new(ctx, &[shader!("glsl/collide/compute/overlap_pairs.comp")])?;
        Ok(ComputeOverlap {
            ctx: ctx.clone(),
            program,
            counter: AtomicCounters::new(ctx, 1)?,
            pairs: Buffer::new(ctx, INITIAL_CAPACITY as usize * 8, BufferUsage::GpuCopy)?,
            capacity: INITIAL_CAPACITY,
        })
    }

    /// Dispatch the test; the pair count is left in the counter.
    pub fn dispatch(&self, x: &LeafBoxes, y: &LeafBoxes) -> Result<(), GlError> {
        self.counter.reset()?;
        let [gx, gy, _] = self.program.local_size();
        self.program
            .dispatch("leaf-pair overlap (compute)")
            .storage(0, &x.boxes)
            .storage(1, &y.boxes)
            .storage(2, &self.pairs)
            .counters(0, self.counter.buffer())
            .uniform("u_leaves_x", x.leaves)
            .uniform("u_leaves_y", y.leaves)
            .uniform("u_capacity", self.capacity)
            .run([y.leaves.div_ceil(gx), x.leaves.div_ceil(gy), 1])?;
        memory_barrier(&self.ctx, &[Barrier::BufferUpdate, Barrier::AtomicCounter]);
        Ok(())
    }

    /// Read the count, then that many pairs; if the list was too short, grow it and test again.
    pub fn read(&mut self, x: &LeafBoxes, y: &LeafBoxes) -> Result<OverlapPairs, GlError> {
        let mut out = OverlapPairs::default();
        let mut count = self.counter.read()?[0];
        out.bytes += 4;
        if count > self.capacity {
            self.capacity = count.next_power_of_two();
            self.pairs = Buffer::new(&self.ctx, self.capacity as usize * 8, BufferUsage::GpuCopy)?;
            self.dispatch(x, y)?;
            count = self.counter.read()?[0];
            out.bytes += 4;
            out.reran = true;
        }
        let pairs: Vec<[u32; 2]> = self.pairs.read_prefix(count as usize)?;
        out.bytes += count as u64 * 8;
        out.caps = pairs.into_iter().map(|[a, b]| (a, b)).collect();
        out.caps.sort_unstable();
        Ok(out)
    }
}
