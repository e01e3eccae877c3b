//! 1D and 2D textures: the GPGPU programmer's arrays.

use super::{Buffer, Context, GlError};
use std::rc::Rc;

/// The texel formats the papers use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TextureFormat {
    /// Four 32-bit floats: the workhorse of every paper.
    Rgba32F,
    /// Two 32-bit floats.
    Rg32F,
    /// One 32-bit float.
    R32F,
    /// One 16-bit (half) float: 11 significant bits, largest finite 65504. Uploaded and read
    /// back as 32-bit floats (the driver converts).
    R16F,
    /// Four 16-bit (half) floats: the float format the GeForce 7800 could blend and filter.
    Rgba16F,
    /// One normalised byte.
    R8,
    /// Four normalised bytes (images).
    Rgba8,
    /// 32-bit float depth (depth peeling).
    Depth32F,
    /// 24-bit depth and an 8-bit stencil (paper 1's stencil mask, paper 4's stencil bit).
    Depth24Stencil8,
    /// 32-bit float depth and an 8-bit stencil: depth peeling that keeps a stencil bit
    /// (paper 4, section 5.2) without rounding the peel depths to 24 bits.
    Depth32FStencil8,
    /// Four unsigned 32-bit integers (`usampler2D`, `uvec4` outputs): generator states.
    Rgba32Ui,
}

impl TextureFormat {
    /// (internal format, pixel format, pixel type).
    pub(super) fn gl(self) -> (u32, u32, u32) {
        match self {
            TextureFormat::Rgba32F => (glow::RGBA32F, glow::RGBA, glow::FLOAT),
            TextureFormat::Rg32F => (glow::RG32F, glow::RG, glow::FLOAT),
            TextureFormat::R32F => (glow::R32F, glow::RED, glow::FLOAT),
            TextureFormat::R16F => (glow::R16F, glow::RED, glow::FLOAT),
            TextureFormat::Rgba16F => (glow::RGBA16F, glow::RGBA, glow::FLOAT),
            TextureFormat::R8 => (glow::R8, glow::RED, glow::UNSIGNED_BYTE),
            TextureFormat::Rgba8 => (glow::RGBA8, glow::RGBA, glow::UNSIGNED_BYTE),
            TextureFormat::Depth32F => {
                (glow::DEPTH_COMPONENT32F, glow::DEPTH_COMPONENT, glow::FLOAT)
            }
            TextureFormat::Depth24Stencil8 => (
                glow::DEPTH24_STENCIL8,
                glow::DEPTH_STENCIL,
                glow::UNSIGNED_INT_24_8,
            ),
            TextureFormat::Depth32FStencil8 => (
                glow::DEPTH32F_STENCIL8,
                glow::DEPTH_STENCIL,
                glow::FLOAT_32_UNSIGNED_INT_24_8_REV,
            ),
            TextureFormat::Rgba32Ui => (glow::RGBA32UI, glow::RGBA_INTEGER, glow::UNSIGNED_INT),
        }
    }

    /// Values per texel in the upload/download arrays.
    pub fn components(self) -> usize {
        match self {
            TextureFormat::Rgba32F
            | TextureFormat::Rgba16F
            | TextureFormat::Rgba8
            | TextureFormat::Rgba32Ui => 4,
            TextureFormat::Rg32F => 2,
            _ => 1,
        }
    }

    /// Bytes per texel in the upload/download arrays.
    pub fn bytes_per_texel(self) -> usize {
        match self {
            TextureFormat::Rgba32F | TextureFormat::Rgba16F | TextureFormat::Rgba32Ui => 16,
            TextureFormat::R8 => 1,
            TextureFormat::Depth32FStencil8 | TextureFormat::Rg32F => 8,
            _ => 4,
        }
    }

    /// The scalar type of the upload/download arrays.
    pub fn is_float(self) -> bool {
        matches!(
            self,
            TextureFormat::Rgba32F
                | TextureFormat::Rg32F
                | TextureFormat::R32F
                | TextureFormat::R16F
                | TextureFormat::Rgba16F
                | TextureFormat::Depth32F
        )
    }

    /// Bits of each stored float (16 or 32), 0 for a format that is not float.
    pub fn float_bits(self) -> u32 {
        match self {
            TextureFormat::R16F | TextureFormat::Rgba16F => 16,
            f if f.is_float() => 32,
            _ => 0,
        }
    }

    pub fn is_depth(self) -> bool {
        matches!(
            self,
            TextureFormat::Depth32F
                | TextureFormat::Depth24Stencil8
                | TextureFormat::Depth32FStencil8
        )
    }

    /// A packed depth-stencil format (attached as `DEPTH_STENCIL_ATTACHMENT`).
    pub fn has_stencil(self) -> bool {
        matches!(
            self,
            TextureFormat::Depth24Stencil8 | TextureFormat::Depth32FStencil8
        )
    }

    pub fn name(self) -> &'static str {
        match self {
            TextureFormat::Rgba32F => "RGBA32F",
            TextureFormat::Rg32F => "RG32F",
            TextureFormat::R32F => "R32F",
            TextureFormat::R16F => "R16F",
            TextureFormat::Rgba16F => "RGBA16F",
            TextureFormat::R8 => "R8",
            TextureFormat::Rgba8 => "RGBA8",
            TextureFormat::Depth32F => "DEPTH_COMPONENT32F",
            TextureFormat::Depth24Stencil8 => "DEPTH24_STENCIL8",
            TextureFormat::Depth32FStencil8 => "DEPTH32F_STENCIL8",
            TextureFormat::Rgba32Ui => "RGBA32UI",
        }
    }
}

/// Texture coordinate wrapping. Paper 1 reads its AABB textures periodically (`Repeat`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    ClampToEdge,
    Repeat,
}

/// How texture lookups between texels are filtered (both minification and magnification).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// The nearest texel (the GPGPU default: read values, never blend them).
    Nearest,
    /// Linear interpolation between the nearest texels (a function stored in a texture).
    Linear,
}

/// A 1D or 2D texture with nearest filtering (GPGPU reads texels, never blends them).
/// Cloning is cheap and shares the GL object, which is freed when the last clone drops.
#[derive(Clone)]
pub struct Texture {
    obj: Rc<TextureObject>,
}

struct TextureObject {
    ctx: Context,
    id: glow::Texture,
    target: u32,
    width: u32,
    height: u32,
    format: TextureFormat,
    /// Mipmap levels allocated (1 for a plain texture).
    levels: u32,
    /// The filter last set ([`Texture::set_filter`]), checked against a period GPU's limits.
    filter: std::cell::Cell<Filter>,
}

impl Drop for TextureObject {
    fn drop(&mut self) {
        unsafe { self.ctx.gl().delete_texture(self.id) };
    }
}

impl Texture {
    /// A 1D texture of `width` texels, all zero.
    pub fn new_1d(ctx: &Context, width: u32, format: TextureFormat) -> Result<Texture, GlError> {
        Self::create(ctx, glow::TEXTURE_1D, width, 1, format, 1)
    }

    /// A 2D texture of `width x height` texels, all zero (depth and stencil too).
    pub fn new_2d(
        ctx: &Context,
        width: u32,
        height: u32,
        format: TextureFormat,
    ) -> Result<Texture, GlError> {
        Self::create(ctx, glow::TEXTURE_2D, width, height, format, 1)
    }

    /// A 2D texture with `levels` mipmap levels (level k is `max(1, width >> k)` by
    /// `max(1, height >> k)`), contents undefined until uploaded or drawn: an image pyramid.
    /// Lookups take the nearest texel of the nearest level; `texelFetch` reads any level.
    pub fn new_2d_mipmapped(
        ctx: &Context,
        width: u32,
        height: u32,
        format: TextureFormat,
        levels: u32,
    ) -> Result<Texture, GlError> {
        let possible = 32 - width.max(height).max(1).leading_zeros();
        if levels == 0 || levels > possible {
            return Err(GlError::Invalid(format!(
                "a {width}x{height} texture has 1 to {possible} mipmap levels, not {levels}"
            )));
        }
        Self::create(ctx, glow::TEXTURE_2D, width, height, format, levels)
    }

    /// A 2D RGBA32F or R32F texture holding `data` (row by row from the bottom).
    pub fn from_f32(
        ctx: &Context,
        width: u32,
        height: u32,
        format: TextureFormat,
        data: &[f32],
    ) -> Result<Texture, GlError> {
        let t = Self::new_2d(ctx, width, height, format)?;
        t.upload_f32(data)?;
        Ok(t)
    }

    fn create(
        ctx: &Context,
        target: u32,
        width: u32,
        height: u32,
        format: TextureFormat,
        levels: u32,
    ) -> Result<Texture, GlError> {
        if let Some(gpu) = ctx.period() {
            gpu.check_texture(width, height, format)?;
        }
        let max = ctx.info().limits.max_texture_size;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(GlError::Limit(format!(
                "a {width}x{height} {} texture does not fit this renderer: each side must be \
                 between 1 and GL_MAX_TEXTURE_SIZE = {max}",
                format.name()
            )));
        }
        let gl = ctx.gl();
        let (internal, pixel_format, pixel_type) = format.gl();
        let id = unsafe { gl.create_texture() }.map_err(GlError::Invalid)?;
        let texture = Texture {
            obj: Rc::new(TextureObject {
                ctx: ctx.clone(),
                id,
                target,
                width,
                height,
                format,
                levels,
                filter: std::cell::Cell::new(Filter::Nearest),
            }),
        };
        unsafe {
            gl.bind_texture(target, Some(id));
            for level in 0..levels {
                let (w, h) = texture.level_size(level);
                let empty = glow::PixelUnpackData::Slice(None);
                if target == glow::TEXTURE_1D {
                    gl.tex_image_1d(
                        target,
                        level as i32,
                        internal as i32,
                        w as i32,
                        0,
                        pixel_format,
                        pixel_type,
                        empty,
                    );
                } else {
                    gl.tex_image_2d(
                        target,
                        level as i32,
                        internal as i32,
                        w as i32,
                        h as i32,
                        0,
                        pixel_format,
                        pixel_type,
                        empty,
                    );
                }
            }
            gl.tex_parameter_i32(target, glow::TEXTURE_MAG_FILTER, glow::NEAREST as i32);
        }
        texture.set_filter(Filter::Nearest);
        texture.set_level_range(0, levels - 1)?;
        texture.set_wrap(Wrap::ClampToEdge);
        texture.clear_to_zero()?;
        // Out of memory shows up here, whatever the checks setting.
        ctx.check_now(&format!(
            "creating a {width}x{height} {} texture",
            format.name()
        ))?;
        Ok(texture)
    }

    /// GL leaves a new texture's texels undefined, and softpipe really leaves whatever its
    /// allocator hands back (a freed texture's NaNs, say), so a pass that reads a texel it
    /// never drew sees garbage there and zeros on llvmpipe. Every new texture is therefore
    /// cleared to zero through a throwaway framebuffer: the same start on every renderer,
    /// at the cost of one clear on the GPU.
    fn clear_to_zero(&self) -> Result<(), GlError> {
        let gl = self.obj.ctx.gl();
        let fbo = unsafe { gl.create_framebuffer() }.map_err(GlError::Invalid)?;
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
            // Every mipmap level: a level drawn later from the one below may still be read
            // before it is drawn.
            for level in 0..self.obj.levels as i32 {
                match self.format() {
                    TextureFormat::Depth24Stencil8
                    | TextureFormat::Depth32FStencil8
                    | TextureFormat::Depth32F => {
                        let stencil = self.format().has_stencil();
                        let attachment = if stencil {
                            glow::DEPTH_STENCIL_ATTACHMENT
                        } else {
                            glow::DEPTH_ATTACHMENT
                        };
                        gl.framebuffer_texture(
                            glow::FRAMEBUFFER,
                            attachment,
                            Some(self.id()),
                            level,
                        );
                        gl.draw_buffer(glow::NONE);
                        gl.read_buffer(glow::NONE);
                        gl.depth_mask(true);
                        gl.stencil_mask(0xff);
                        if stencil {
                            gl.clear_buffer_depth_stencil(glow::DEPTH_STENCIL, 0, 0.0, 0);
                        } else {
                            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[0.0]);
                        }
                    }
                    format => {
                        let attachment = glow::COLOR_ATTACHMENT0;
                        gl.framebuffer_texture(
                            glow::FRAMEBUFFER,
                            attachment,
                            Some(self.id()),
                            level,
                        );
                        gl.draw_buffer(attachment);
                        gl.color_mask(true, true, true, true);
                        // An integer target is cleared with integers (a float clear of it is
                        // undefined).
                        if format == TextureFormat::Rgba32Ui {
                            gl.clear_buffer_u32_slice(glow::COLOR, 0, &[0; 4]);
                        } else {
                            gl.clear_buffer_f32_slice(glow::COLOR, 0, &[0.0; 4]);
                        }
                    }
                }
            }
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
            gl.delete_framebuffer(fbo);
        }
        Ok(())
    }

    pub fn width(&self) -> u32 {
        self.obj.width
    }
    pub fn height(&self) -> u32 {
        self.obj.height
    }
    pub fn format(&self) -> TextureFormat {
        self.obj.format
    }
    /// How lookups filter ([`Texture::set_filter`]).
    pub fn filter(&self) -> Filter {
        self.obj.filter.get()
    }
    pub fn is_1d(&self) -> bool {
        self.obj.target == glow::TEXTURE_1D
    }
    /// Mipmap levels (1 unless made by [`Texture::new_2d_mipmapped`]).
    pub fn levels(&self) -> u32 {
        self.obj.levels
    }
    /// The size of mipmap level `level`.
    pub fn level_size(&self, level: u32) -> (u32, u32) {
        (
            (self.obj.width >> level).max(1),
            (self.obj.height >> level).max(1),
        )
    }
    pub(super) fn id(&self) -> glow::Texture {
        self.obj.id
    }
    pub(super) fn target(&self) -> u32 {
        self.obj.target
    }
    pub fn context(&self) -> &Context {
        &self.obj.ctx
    }
    /// Texel count.
    pub fn len(&self) -> usize {
        self.obj.width as usize * self.obj.height as usize
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// How texture coordinates outside [0, 1] wrap (both axes).
    pub fn set_wrap(&self, wrap: Wrap) {
        let mode = match wrap {
            Wrap::ClampToEdge => glow::CLAMP_TO_EDGE,
            Wrap::Repeat => glow::REPEAT,
        } as i32;
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.bind_texture(self.obj.target, Some(self.obj.id));
            gl.tex_parameter_i32(self.obj.target, glow::TEXTURE_WRAP_S, mode);
            gl.tex_parameter_i32(self.obj.target, glow::TEXTURE_WRAP_T, mode);
        }
    }

    /// How lookups filter. Mipmapped textures filter within the nearest level, never between
    /// levels.
    pub fn set_filter(&self, filter: Filter) {
        let (min, mag) = match (filter, self.obj.levels > 1) {
            (Filter::Nearest, false) => (glow::NEAREST, glow::NEAREST),
            (Filter::Nearest, true) => (glow::NEAREST_MIPMAP_NEAREST, glow::NEAREST),
            (Filter::Linear, false) => (glow::LINEAR, glow::LINEAR),
            (Filter::Linear, true) => (glow::LINEAR_MIPMAP_NEAREST, glow::LINEAR),
        };
        self.obj.filter.set(filter);
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.bind_texture(self.obj.target, Some(self.obj.id));
            gl.tex_parameter_i32(self.obj.target, glow::TEXTURE_MIN_FILTER, min as i32);
            gl.tex_parameter_i32(self.obj.target, glow::TEXTURE_MAG_FILTER, mag as i32);
        }
    }

    /// Which mipmap levels lookups may read: `base..=max` (`texelFetch` level 0 is `base`).
    /// A pass that renders level k from level k - 1 of the same texture restricts the range
    /// to `k - 1..=k - 1`, so that the level it writes is not one it can read (no feedback
    /// loop, GL 4.5 section 9.3.1); [`Texture::new_2d_mipmapped`] leaves every level readable.
    pub fn set_level_range(&self, base: u32, max: u32) -> Result<(), GlError> {
        if base > max || max >= self.obj.levels {
            return Err(GlError::Invalid(format!(
                "levels {base}..={max} of a texture with {} levels",
                self.obj.levels
            )));
        }
        let gl = self.obj.ctx.gl();
        unsafe {
            gl.bind_texture(self.obj.target, Some(self.obj.id));
            gl.tex_parameter_i32(self.obj.target, glow::TEXTURE_BASE_LEVEL, base as i32);
            gl.tex_parameter_i32(self.obj.target, glow::TEXTURE_MAX_LEVEL, max as i32);
        }
        Ok(())
    }

    /// Replace the whole texture with float data (RGBA32F, R32F, DEPTH32F).
    pub fn upload_f32(&self, data: &[f32]) -> Result<(), GlError> {
        self.upload_region_f32(0, 0, self.width(), self.height(), data)
    }

    /// Replace a `w x h` region at (`x`, `y`) with float data.
    pub fn upload_region_f32(
        &self,
        x: u32,
        y: u32,
        w: u32,
        h: u32,
        data: &[f32],
    ) -> Result<(), GlError> {
        self.expect_kind(true, "upload_f32")?;
        self.upload_bytes(x, y, w, h, bytemuck::cast_slice(data))
    }

    /// Replace mipmap level `level` with float data (RGBA32F, R32F), row by row from the
    /// bottom.
    pub fn upload_level_f32(&self, level: u32, data: &[f32]) -> Result<(), GlError> {
        self.expect_kind(true, "upload_level_f32")?;
        if level >= self.levels() {
            return Err(GlError::Invalid(format!(
                "level {level} of a texture with {} levels",
                self.levels()
            )));
        }
        let (w, h) = self.level_size(level);
        self.upload_level_bytes(level, 0, 0, w, h, bytemuck::cast_slice(data))
    }

    /// Replace the whole texture with byte data (R8, RGBA8).
    pub fn upload_u8(&self, data: &[u8]) -> Result<(), GlError> {
        if !matches!(self.format(), TextureFormat::R8 | TextureFormat::Rgba8) {
            return Err(self.wrong_kind("upload_u8"));
        }
        self.upload_bytes(0, 0, self.width(), self.height(), data)
    }

    /// Replace the whole texture with 32-bit words (DEPTH24_STENCIL8: depth << 8 | stencil;
    /// RGBA32UI: four per texel).
    pub fn upload_u32(&self, data: &[u32]) -> Result<(), GlError> {
        if !matches!(
            self.format(),
            TextureFormat::Depth24Stencil8 | TextureFormat::Rgba32Ui
        ) {
            return Err(self.wrong_kind("upload_u32"));
        }
        self.upload_bytes(
            0,
            0,
            self.width(),
            self.height(),
            bytemuck::cast_slice(data),
        )
    }

    /// Upload the whole texture from `buffer` at byte `offset`, bound as the pixel unpack
    /// buffer (PBO): the copy is queued on the GPU and the call returns at once, where an
    /// upload from client memory must copy the data before it returns.
    pub fn upload_from_buffer(&self, buffer: &Buffer, offset: usize) -> Result<(), GlError> {
        let bytes = self.len() * self.format().bytes_per_texel();
        if self.is_1d() || offset + bytes > buffer.len_bytes() {
            return Err(GlError::Invalid(format!(
                "uploading a {}x{} {} texture ({bytes} bytes, 2D only) from byte {offset} of a \
                 {}-byte buffer",
                self.width(),
                self.height(),
                self.format().name(),
                buffer.len_bytes()
            )));
        }
        let gl = self.obj.ctx.gl();
        let (_, pixel_format, pixel_type) = self.format().gl();
        unsafe {
            gl.bind_buffer(glow::PIXEL_UNPACK_BUFFER, Some(buffer.id()));
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            gl.bind_texture(self.obj.target, Some(self.obj.id));
            gl.tex_sub_image_2d(
                self.obj.target,
                0,
                0,
                0,
                self.width() as i32,
                self.height() as i32,
                pixel_format,
                pixel_type,
                glow::PixelUnpackData::BufferOffset(offset as u32),
            );
            gl.bind_buffer(glow::PIXEL_UNPACK_BUFFER, None);
        }
        self.obj.ctx.check("texture upload from a pixel buffer")
    }

    fn upload_bytes(&self, x: u32, y: u32, w: u32, h: u32, bytes: &[u8]) -> Result<(), GlError> {
        self.upload_level_bytes(0, x, y, w, h, bytes)
    }

    fn upload_level_bytes(
        &self,
        level: u32,
        x: u32,
        y: u32,
        w: u32,
        h: u32,
        bytes: &[u8],
    ) -> Result<(), GlError> {
        let (level_w, level_h) = self.level_size(level);
        if x + w > level_w || y + h > level_h {
            return Err(GlError::Invalid(format!(
                "region {w}x{h} at ({x}, {y}) lies outside a {level_w}x{level_h} texture"
            )));
        }
        let expected = w as usize * h as usize * self.format().bytes_per_texel();
        if bytes.len() != expected {
            return Err(GlError::Invalid(format!(
                "{} bytes given for a {w}x{h} {} region, which needs {expected}",
                bytes.len(),
                self.format().name()
            )));
        }
        let gl = self.obj.ctx.gl();
        let (_, pixel_format, pixel_type) = self.format().gl();
        unsafe {
            gl.bind_buffer(glow::PIXEL_UNPACK_BUFFER, None);
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            gl.bind_texture(self.obj.target, Some(self.obj.id));
            if self.is_1d() {
                let sub_image_1d =
                    self.obj.ctx.inner.extra.tex_sub_image_1d.ok_or_else(|| {
                        GlError::Context("this OpenGL has no glTexSubImage1D".into())
                    })?;
                sub_image_1d(
                    self.obj.target,
                    level as i32,
                    x as i32,
                    w as i32,
                    pixel_format,
                    pixel_type,
                    bytes.as_ptr().cast(),
                );
            } else {
                gl.tex_sub_image_2d(
                    self.obj.target,
                    level as i32,
                    x as i32,
                    y as i32,
                    w as i32,
                    h as i32,
                    pixel_format,
                    pixel_type,
                    glow::PixelUnpackData::Slice(Some(bytes)),
                );
            }
        }
        self.obj.ctx.check("texture upload")
    }

    /// The whole texture as floats (RGBA32F, R32F, DEPTH32F), row by row from the bottom.
    pub fn download_f32(&self) -> Result<Vec<f32>, GlError> {
        self.expect_kind(true, "download_f32")?;
        let mut out = vec![0f32; self.len() * self.format().components()];
        self.download_bytes(bytemuck::cast_slice_mut(&mut out))?;
        Ok(out)
    }

    /// The whole texture as bytes (R8, RGBA8).
    pub fn download_u8(&self) -> Result<Vec<u8>, GlError> {
        if !matches!(self.format(), TextureFormat::R8 | TextureFormat::Rgba8) {
            return Err(self.wrong_kind("download_u8"));
        }
        let mut out = vec![0u8; self.len() * self.format().components()];
        self.download_bytes(&mut out)?;
        Ok(out)
    }

    /// The whole texture as words (DEPTH24_STENCIL8: depth << 8 | stencil; RGBA32UI: four
    /// per texel).
    pub fn download_u32(&self) -> Result<Vec<u32>, GlError> {
        if !matches!(
            self.format(),
            TextureFormat::Depth24Stencil8 | TextureFormat::Rgba32Ui
        ) {
            return Err(self.wrong_kind("download_u32"));
        }
        let mut out = vec![0u32; self.len() * self.format().components()];
        self.download_bytes(bytemuck::cast_slice_mut(&mut out))?;
        Ok(out)
    }

    /// Mipmap level `level` as floats (RGBA32F, R32F), row by row from the bottom.
    pub fn download_level_f32(&self, level: u32) -> Result<Vec<f32>, GlError> {
        self.expect_kind(true, "download_level_f32")?;
        if level >= self.levels() {
            return Err(GlError::Invalid(format!(
                "level {level} of a texture with {} levels",
                self.levels()
            )));
        }
        let (w, h) = self.level_size(level);
        let mut out = vec![0f32; (w * h) as usize * self.format().components()];
        self.download_level_bytes(level, bytemuck::cast_slice_mut(&mut out))?;
        Ok(out)
    }

    fn download_bytes(&self, out: &mut [u8]) -> Result<(), GlError> {
        self.download_level_bytes(0, out)
    }

    fn download_level_bytes(&self, level: u32, out: &mut [u8]) -> Result<(), GlError> {
        let gl = self.obj.ctx.gl();
        let (_, pixel_format, pixel_type) = self.format().gl();
        super::profile::wait(&self.obj.ctx, "glGetTexImage", || unsafe {
            gl.bind_buffer(glow::PIXEL_PACK_BUFFER, None);
            gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            gl.bind_texture(self.obj.target, Some(self.obj.id));
            gl.get_tex_image(
                self.obj.target,
                level as i32,
                pixel_format,
                pixel_type,
                glow::PixelPackData::Slice(Some(out)),
            );
        });
        self.obj.ctx.check("texture download")
    }

    fn expect_kind(&self, float: bool, what: &str) -> Result<(), GlError> {
        if self.format().is_float() == float {
            Ok(())
        } else {
            Err(self.wrong_kind(what))
        }
    }

    fn wrong_kind(&self, what: &str) -> GlError {
        GlError::Invalid(format!(
            "{what} does not apply to a {} texture",
            self.format().name()
        ))
    }
}

impl std::fmt::Debug for Texture {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let dims = if self.is_1d() { "1D" } else { "2D" };
        write!(
            f,
            "Texture({dims} {}x{} {})",
            self.width(),
            self.height(),
            self.format().name()
        )
    }
}
