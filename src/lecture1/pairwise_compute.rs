//! The compute counterpart of [`super::pairwise`] (then and now, OpenGL 4.3): the same pair
//! filter (`glsl/lecture1/pair_filter.glsl`: neighbours skipped, box reject, paper 1's exact
//! test with fp32-filtered signs) run by one compute dispatch over all pairs
//! (`glsl/lecture1/compute/pair_test.comp`), each pair that may intersect appended to a list
//! through an atomic counter. The triangles go in as storage buffers instead of textures,
//! and the list replaces the pair texture, its tiles, the occlusion count and the
//! hierarchical readback. The CPU confirms each listed pair with the exact predicate, as the
//! classic path does, so both give the same pairs.

use super::pairwise::{confirm, PairwiseResult, Sides};
use crate::collide::stream_setup::validate_mesh;
use crate::gl::{
    memory_barrier, time_finished, AtomicCounters, Barrier, Buffer, BufferUsage, ComputeProgram,
    Context, GlError,
};
use crate::mesh::Mesh;
use crate::shader;

/// Pairs the list holds at first; grown to the next power of two when a run needs more.
const INITIAL_CAPACITY: u32 = 4096;

/// One model's triangles in a storage buffer: three `vec4` per triangle, xyz a corner, w its
/// vertex id (exact as a float below 2^24).
fn triangle_buffer(ctx: &Context, mesh: &Mesh) -> anyhow::Result<Buffer> {
    anyhow::ensure!(
        mesh.positions.len() <= 1 << 24,
        "{} vertices: the triangle buffer holds vertex ids below 2^24",
        mesh.positions.len()
    );
    let mut data = Vec::with_capacity(12 * mesh.triangles.len().max(1));
    for tri in &mesh.triangles {
        for &v in tri {
            let p = mesh.positions[v as usize];
            data.extend_from_slice(&[p.x, p.y, p.z, v as f32]);
        }
    }
    if data.is_empty() {
        data.resize(4, 0.0);
    }
    Ok(Buffer::from_slice(ctx, &data, BufferUsage::Static)?)
}

/// The compute pair test: its program, counter and pair list.
pub struct ComputePairwiseTester {
    ctx: Context,
    program: ComputeProgram,
    counter: AtomicCounters,
    pairs: Buffer,
    capacity: u32,
}

impl ComputePairwiseTester {
    /// Needs OpenGL 4.3: on an older context, the error names both versions.
    pub fn new(ctx: &Context) -> Result<ComputePairwiseTester, GlError> {
        let program = ComputeProgram::new(
            ctx,
            &[
                shader!("glsl/lecture1/pair_filter.glsl"),
                shader!("glsl/lecture1/compute/pair_test.comp"),
            ],
        )?;
        Ok(ComputePairwiseTester {
            ctx: ctx.clone(),
            program,
            counter: AtomicCounters::new(ctx, 1)?,
            pairs: Buffer::new(ctx, INITIAL_CAPACITY as usize * 8, BufferUsage::GpuCopy)?,
            capacity: INITIAL_CAPACITY,
        })
    }

    /// Every intersecting pair between A and B, or (`b` = `None`) within A, as
    /// [`super::pairwise::PairwiseTester::run`] gives them. `test_ms` is the dispatch and
    /// the list's readback by wall clock between glFinish calls; `tiles` is the number of
    /// dispatches (two when the list overflowed once).
    pub fn run(&mut self, a: &Mesh, b: Option<&Mesh>) -> anyhow::Result<PairwiseResult> {
        validate_mesh(a).map_err(|e| anyhow::anyhow!("model A: {e}"))?;
        if let Some(b) = b {
            validate_mesh(b).map_err(|e| anyhow::anyhow!("model B: {e}"))?;
        }
        let sides = Sides::of(a, b);
        let (a, b, self_test) = sides.pair();
        let buf_a = triangle_buffer(&self.ctx, a)?;
        let buf_b = if self_test {
            None
        } else {
            Some(triangle_buffer(&self.ctx, b)?)
        };
        let buf_b = buf_b.as_ref().unwrap_or(&buf_a);
        let counts = (a.triangles.len() as u32, b.triangles.len() as u32);
        let mut out = PairwiseResult::default();
        let ctx = self.ctx.clone();
        let (candidates, ms) = time_finished(&ctx, || {
            let mut count = self.dispatch(&buf_a, buf_b, counts, self_test)?;
            out.tiles = 1;
            if count > self.capacity {
                self.capacity = count.next_power_of_two();
                self.pairs =
                    Buffer::new(&self.ctx, self.capacity as usize * 8, BufferUsage::GpuCopy)?;
                count = self.dispatch(&buf_a, buf_b, counts, self_test)?;
                out.tiles = 2;
            }
            let list: Vec<[u32; 2]> = self.pairs.read_prefix(count as usize)?;
            out.readback_bytes = 4 * out.tiles as u64 + 8 * count as u64;
            Ok(list)
        })?;
        out.test_ms = ms;
        let candidates: Vec<(u32, u32)> = candidates.into_iter().map(|[i, j]| (i, j)).collect();
        out.candidates = candidates.len();
        out.pairs = confirm(a, b, self_test, &candidates);
        Ok(out)
    }

    /// One dispatch over all pairs; returns the counter (pairs that may intersect, possibly
    /// more than the list holds).
    fn dispatch(
        &self,
        a: &Buffer,
        b: &Buffer,
        (na, nb): (u32, u32),
        self_test: bool,
    ) -> Result<u32, GlError> {
        self.counter.reset()?;
        let [gx, gy, _] = self.program.local_size();
        self.program
            .dispatch("pairwise triangle test (compute)")
            .storage(0, a)
            .storage(1, b)
            .storage(2, &self.pairs)
            .counters(0, self.counter.buffer())
            .uniform("u_count_a", na)
            .uniform("u_count_b", nb)
            .uniform("u_self", self_test as i32)
            .uniform("u_capacity", self.capacity)
            .run([nb.div_ceil(gx), na.div_ceil(gy), 1])?;
        memory_barrier(&self.ctx, &[Barrier::BufferUpdate, Barrier::AtomicCounter]);
        Ok(self.counter.read()?[0])
    }
}
