//! Buffers as compute shaders use them: shader storage blocks (any [`Buffer`]; a compute pass
//! binds it with [`super::Dispatch::storage`]) and atomic counters, the scatter and the
//! "append here" that fragment programs of 2007 did not have.

use super::{Buffer, BufferUsage, Context, GlError};

/// `count` 32-bit atomic counters in one buffer (`layout(binding = b, offset = 4 * i)
/// uniform atomic_uint ...` in GLSL, or `atomicAdd` on a storage block).
pub struct AtomicCounters {
    buffer: Buffer,
    count: usize,
}

impl AtomicCounters {
    /// `count` counters, all zero.
    pub fn new(ctx: &Context, count: usize) -> Result<AtomicCounters, GlError> {
        ctx.require_compute("atomic counters")?;
        let buffer = Buffer::from_slice(ctx, &vec![0u32; count.max(1)], BufferUsage::Dynamic)?;
        Ok(AtomicCounters { buffer, count })
    }

    /// Set every counter back to zero.
    pub fn reset(&self) -> Result<(), GlError> {
        self.buffer.write(0, &vec![0u32; self.count.max(1)])
    }

    /// The counters' values (waits for the passes that count).
    pub fn read(&self) -> Result<Vec<u32>, GlError> {
        let mut values: Vec<u32> = self.buffer.read()?;
        values.truncate(self.count);
        Ok(values)
    }

    /// Binds the counters to atomic-counter binding `binding` for the draws that follow (a
    /// fragment shader counting its runs); compute passes bind theirs through
    /// [`super::Dispatch::counters`].
    pub fn bind_for_draws(&self, binding: u32) -> Result<(), GlError> {
        let ctx = self.buffer.context();
        unsafe {
            ctx.gl()
                .bind_buffer_base(glow::ATOMIC_COUNTER_BUFFER, binding, Some(self.buffer.id()))
        };
        ctx.check("binding atomic counters")
    }

    /// The buffer to bind ([`super::Dispatch::counters`]).
    pub fn buffer(&self) -> &Buffer {
        &self.buffer
    }
}

impl Buffer {
    /// Bind this buffer to storage-block binding `binding` for the draws that follow (a
    /// vertex shader reading what a compute pass wrote); compute passes bind their own
    /// through [`super::Dispatch::storage`].
    pub fn bind_storage(&self, binding: u32) -> Result<(), GlError> {
        let ctx = self.context();
        ctx.require_compute("a shader storage buffer")?;
        unsafe {
            ctx.gl()
                .bind_buffer_base(glow::SHADER_STORAGE_BUFFER, binding, Some(self.id()))
        };
        ctx.check("binding a storage buffer")
    }

    /// The first `count` values of type `T`, read back to the CPU: what a compacting pass
    /// wrote, without reading the rest of its worst-case-sized buffer.
    pub fn read_prefix<T: bytemuck::Pod + Default>(&self, count: usize) -> Result<Vec<T>, GlError> {
        let size = std::mem::size_of::<T>();
        if count * size > self.len_bytes() {
            return Err(GlError::Invalid(format!(
                "reading {count} values of {size} bytes from a {}-byte buffer",
                self.len_bytes()
            )));
        }
        let mut out = vec![T::default(); count];
        if count > 0 {
            self.read_into(bytemuck::cast_slice_mut(&mut out))?;
        }
        Ok(out)
    }
}
