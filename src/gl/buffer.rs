//! Buffer objects and vertex arrays. One GL buffer object serves as vertex, index, pixel
//! pack or pixel unpack buffer depending on where it is bound, which is what makes paper 2's
//! render-to-vertex-buffer possible without a trip through the CPU.

use super::{Context, GlError};
use std::rc::Rc;

/// How often the contents change (a hint to the driver).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BufferUsage {
    /// Written once.
    Static,
    /// Rewritten every frame from the CPU.
    Dynamic,
    /// Written by the GPU (pixel pack / render-to-vertex-buffer), read by the GPU.
    GpuCopy,
}

impl BufferUsage {
    fn gl(self) -> u32 {
        match self {
            BufferUsage::Static => glow::STATIC_DRAW,
            BufferUsage::Dynamic => glow::DYNAMIC_DRAW,
            BufferUsage::GpuCopy => glow::STREAM_COPY,
        }
    }
}

/// A GL buffer object. Cloning shares it; the last clone frees it.
#[derive(Clone)]
pub struct Buffer {
    obj: Rc<BufferObject>,
}

struct BufferObject {
    ctx: Context,
    id: glow::Buffer,
    len: std::cell::Cell<usize>,
    usage: BufferUsage,
}

impl Drop for BufferObject {
    fn drop(&mut self) {
        unsafe { self.ctx.gl().delete_buffer(self.id) };
    }
}

/// Where buffers are bound while their data is set: a target no draw reads.
const SCRATCH_TARGET: u32 = glow::COPY_WRITE_BUFFER;

impl Buffer {
    /// A buffer of `len` bytes, contents undefined.
    pub fn new(ctx: &Context, len: usize, usage: BufferUsage) -> Result<Buffer, GlError> {
        if len > i32::MAX as usize {
            return Err(GlError::Limit(format!(
                "a buffer of {len} bytes: buffer sizes here are 32-bit (at most {} bytes)",
                i32::MAX
            )));
        }
        let id = unsafe { ctx.gl().create_buffer() }.map_err(GlError::Invalid)?;
        let buffer = Buffer {
            obj: Rc::new(BufferObject {
                ctx: ctx.clone(),
                id,
                len: std::cell::Cell::new(len),
                usage,
            }),
        };
        unsafe {
            ctx.gl().bind_buffer(SCRATCH_TARGET, Some(id));
            ctx.gl()
                .buffer_data_size(SCRATCH_TARGET, len as i32, usage.gl());
        }
        ctx.check_now(&format!("allocating a {len}-byte buffer"))?;
        Ok(buffer)
    }

    /// A buffer holding `data`.
    pub fn from_slice<T: bytemuck::Pod>(
        ctx: &Context,
        data: &[T],
        usage: BufferUsage,
    ) -> Result<Buffer, GlError> {
        let buffer = Buffer::new(ctx, std::mem::size_of_val(data), usage)?;
        buffer.write(0, data)?;
        Ok(buffer)
    }

    pub fn len_bytes(&self) -> usize {
        self.obj.len.get()
    }
    pub(super) fn id(&self) -> glow::Buffer {
        self.obj.id
    }
    pub(super) fn context(&self) -> &Context {
        &self.obj.ctx
    }

    /// Write `data` at `offset` bytes.
    pub fn write<T: bytemuck::Pod>(&self, offset: usize, data: &[T]) -> Result<(), GlError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        if offset + bytes.len() > self.len_bytes() {
            return Err(GlError::Invalid(format!(
                "writing {} bytes at {offset} overflows a {}-byte buffer",
                bytes.len(),
                self.len_bytes()
            )));
        }
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.bind_buffer(SCRATCH_TARGET, Some(self.obj.id));
            gl.buffer_sub_data_u8_slice(SCRATCH_TARGET, offset as i32, bytes);
        }
        self.obj.ctx.check("buffer write")
    }

    /// Replace the contents with `data`, growing the buffer if needed.
    pub fn replace<T: bytemuck::Pod>(&self, data: &[T]) -> Result<(), GlError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.bind_buffer(SCRATCH_TARGET, Some(self.obj.id));
            gl.buffer_data_u8_slice(SCRATCH_TARGET, bytes, self.obj.usage.gl());
        }
        self.obj.len.set(bytes.len());
        self.obj.ctx.check("buffer replace")
    }

    /// The whole contents, read back to the CPU. Waits for every queued command first:
    /// GL promises that the read sees them, but zink on lavapipe (Mesa 22.3) returned a
    /// buffer that a pixel-pack read (paper 2's render-to-VBO) had only partly filled, the
    /// first time in a process (crowd_gpu's 300-character check, 3 runs of 3). The CPU
    /// waits for the data anyway, so the explicit wait costs nothing.
    pub fn read<T: bytemuck::Pod + Default>(&self) -> Result<Vec<T>, GlError> {
        let n = self.len_bytes() / std::mem::size_of::<T>();
        let mut out = vec![T::default(); n];
        let gl = self.obj.ctx.gl();
        super::profile::wait(&self.obj.ctx, "buffer read", || unsafe {
            gl.finish();
            gl.bind_buffer(SCRATCH_TARGET, Some(self.obj.id));
            gl.get_buffer_sub_data(SCRATCH_TARGET, 0, bytemuck::cast_slice_mut(&mut out));
        });
        self.obj.ctx.check("buffer read")?;
        Ok(out)
    }

    /// The first `out.len()` bytes, read back to the CPU (waits like [`Buffer::read`]).
    pub(super) fn read_into(&self, out: &mut [u8]) -> Result<(), GlError> {
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.finish();
            gl.bind_buffer(SCRATCH_TARGET, Some(self.obj.id));
            gl.get_buffer_sub_data(SCRATCH_TARGET, 0, out);
        }
        self.obj.ctx.check("buffer read")
    }

    /// Copy `len` bytes from `src` at `src_offset` to this buffer at `dst_offset`, on the GPU.
    pub fn copy_from(
        &self,
        src: &Buffer,
        src_offset: usize,
        dst_offset: usize,
        len: usize,
    ) -> Result<(), GlError> {
        if src_offset + len > src.len_bytes() || dst_offset + len > self.len_bytes() {
            return Err(GlError::Invalid(format!(
                "copying {len} bytes from {src_offset} of a {}-byte buffer to {dst_offset} of a \
                 {}-byte buffer",
                src.len_bytes(),
                self.len_bytes()
            )));
        }
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.bind_buffer(glow::COPY_READ_BUFFER, Some(src.id()));
            gl.bind_buffer(glow::COPY_WRITE_BUFFER, Some(self.obj.id));
            gl.copy_buffer_sub_data(
                glow::COPY_READ_BUFFER,
                glow::COPY_WRITE_BUFFER,
                src_offset as i32,
                dst_offset as i32,
                len as i32,
            );
        }
        self.obj.ctx.check("buffer copy")
    }
}

/// The scalar type of a vertex attribute in its buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttribType {
    F32,
    /// Integer attribute read as `int`/`ivec` in the shader.
    I32,
    /// Integer attribute read as `uint`/`uvec` in the shader.
    U32,
}

/// A vertex array object: which buffers feed which attribute locations, and the index buffer.
pub struct VertexArray {
    ctx: Context,
    id: glow::VertexArray,
    /// The buffer feeding each attribute location, kept alive while it is in use.
    buffers: std::collections::HashMap<u32, Buffer>,
    index_buffer: Option<Buffer>,
}

impl Drop for VertexArray {
    fn drop(&mut self) {
        unsafe { self.ctx.gl().delete_vertex_array(self.id) };
    }
}

impl VertexArray {
    pub fn new(ctx: &Context) -> Result<VertexArray, GlError> {
        let id = unsafe { ctx.gl().create_vertex_array() }.map_err(GlError::Invalid)?;
        Ok(VertexArray {
            ctx: ctx.clone(),
            id,
            buffers: std::collections::HashMap::new(),
            index_buffer: None,
        })
    }

    pub(super) fn id(&self) -> glow::VertexArray {
        self.id
    }

    pub fn has_indices(&self) -> bool {
        self.index_buffer.is_some()
    }

    /// Feed float attribute `location` with `components` floats per vertex from `buffer`,
    /// `stride` and `offset` in bytes. `divisor` 0 is per vertex, n > 0 per n instances.
    pub fn float_attribute(
        &mut self,
        location: u32,
        buffer: &Buffer,
        components: i32,
        stride: usize,
        offset: usize,
        divisor: u32,
    ) -> Result<(), GlError> {
        self.attribute(
            location,
            buffer,
            components,
            AttribType::F32,
            stride,
            offset,
            divisor,
        )
    }

    /// Feed attribute `location` from `buffer`; see [`VertexArray::float_attribute`].
    #[allow(clippy::too_many_arguments)]
    pub fn attribute(
        &mut self,
        location: u32,
        buffer: &Buffer,
        components: i32,
        ty: AttribType,
        stride: usize,
        offset: usize,
        divisor: u32,
    ) -> Result<(), GlError> {
        let gl = self.ctx.gl();
        unsafe {
            gl.bind_vertex_array(Some(self.id));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(buffer.id()));
            gl.enable_vertex_attrib_array(location);
            match ty {
                AttribType::F32 => gl.vertex_attrib_pointer_f32(
                    location,
                    components,
                    glow::FLOAT,
                    false,
                    stride as i32,
                    offset as i32,
                ),
                AttribType::I32 | AttribType::U32 => gl.vertex_attrib_pointer_i32(
                    location,
                    components,
                    if ty == AttribType::I32 {
                        glow::INT
                    } else {
                        glow::UNSIGNED_INT
                    },
                    stride as i32,
                    offset as i32,
                ),
            }
            gl.vertex_attrib_divisor(location, divisor);
            gl.bind_vertex_array(None);
        }
        self.buffers.insert(location, buffer.clone());
        self.ctx
            .check(&format!("setting vertex attribute {location}"))
    }

    /// Draw with `u32` indices from `buffer`.
    pub fn set_index_buffer(&mut self, buffer: &Buffer) -> Result<(), GlError> {
        let gl = self.ctx.gl();
        unsafe {
            gl.bind_vertex_array(Some(self.id));
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(buffer.id()));
            gl.bind_vertex_array(None);
        }
        self.index_buffer = Some(buffer.clone());
        self.ctx.check("setting the index buffer")
    }
}

impl std::fmt::Debug for Buffer {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "Buffer({} bytes)", self.len_bytes())
    }
}
