//! Reduction in work-group shared memory (OpenGL 4.3): the compute counterpart of the
//! ping-pong [`super::reduce`]. A work group combines 512 values in on-chip shared memory
//! with `barrier()` between its halving steps, so one pass shrinks the data 512-fold where a
//! 2x2 fragment pass shrinks it 4-fold; n values take ceil(log512 n) passes instead of
//! ceil(log4 n).

use super::compute::{memory_barrier, Barrier};
use super::reduce::ReduceOp;
use super::{Buffer, BufferUsage, ComputeProgram, Context, GlError};
use crate::shader;

/// Values one work group reduces per pass (256 invocations, two values each).
pub const PER_GROUP: u32 = 512;

/// Reduces storage buffers of `vec4` values, whole or in equal segments.
pub struct SharedReducer {
    program: ComputeProgram,
}

/// How many passes bring `n` values down to one (at least one).
pub fn passes_for(n: u32) -> u32 {
    let mut passes = 1;
    let mut n = n.div_ceil(PER_GROUP);
    while n > 1 {
        n = n.div_ceil(PER_GROUP);
        passes += 1;
    }
    passes
}

impl SharedReducer {
    pub fn new(ctx: &Context) -> Result<SharedReducer, GlError> {
        let program = ComputeProgram::new(ctx, &[shader!("glsl/gl/compute/reduce.comp")])?;
        Ok(SharedReducer { program })
    }

    /// Reduce the `n` `vec4` values at the start of `input` to one.
    pub fn reduce(&self, input: &Buffer, n: u32, op: ReduceOp) -> Result<[f32; 4], GlError> {
        Ok(self.reduce_segments(input, 1, n, op)?[0])
    }

    /// Reduce each of `segments` consecutive runs of `n` `vec4` values in `input` to one
    /// value: the many small sums of paper 4 (one per body) in the same passes.
    pub fn reduce_segments(
        &self,
        input: &Buffer,
        segments: u32,
        n: u32,
        op: ReduceOp,
    ) -> Result<Vec<[f32; 4]>, GlError> {
        let out = self.run(input, segments, n, op)?;
        let values: Vec<[f32; 4]> = out.read_prefix(segments as usize)?;
        Ok(values)
    }

    /// The passes; the buffer whose first `segments` values are the results.
    pub fn run(
        &self,
        input: &Buffer,
        segments: u32,
        n: u32,
        op: ReduceOp,
    ) -> Result<Buffer, GlError> {
        let needed = segments as usize * n as usize * 16;
        if needed > input.len_bytes() || segments == 0 {
            return Err(GlError::Invalid(format!(
                "reducing {segments} segments of {n} vec4 values needs {needed} bytes; the \
                 buffer has {}",
                input.len_bytes()
            )));
        }
        let (shader_op, nonzero) = op.shader();
        let ctx = self.program.context();
        let mut source = input.clone();
        let mut count = n;
        let mut first = true;
        loop {
            let groups = count.div_ceil(PER_GROUP).max(1);
            let out = Buffer::new(
                ctx,
                segments as usize * groups as usize * 16,
                BufferUsage::GpuCopy,
            )?;
            // In as many dispatches as the work-group limit of each axis needs.
            let most = [0, 1].map(|axis| ctx.max_work_groups(axis).max(1));
            for y in (0..segments).step_by(most[1] as usize) {
                for x in (0..groups).step_by(most[0] as usize) {
                    self.program
                        .dispatch("shared-memory reduction")
                        .storage(0, &source)
                        .storage(1, &out)
                        .uniform("u_count", count)
                        .uniform("u_op", shader_op)
                        .uniform("u_nonzero", nonzero && first)
                        .uniform("u_first_group", x)
                        .uniform("u_first_segment", y)
                        .uniform("u_groups", groups)
                        .run([most[0].min(groups - x), most[1].min(segments - y), 1])?;
                }
            }
            memory_barrier(ctx, &[Barrier::Storage, Barrier::BufferUpdate]);
            source = out;
            count = groups;
            first = false;
            if count == 1 {
                return Ok(source);
            }
        }
    }
}
