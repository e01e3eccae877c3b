//! Framebuffer objects: render targets made of textures, with several colour attachments
//! (multiple render targets) and a depth or depth-stencil attachment.

use super::{Buffer, Context, GlError, Pass, Program, Texture, TextureFormat};

/// A pixel rectangle: `w x h` pixels from (`x`, `y`), the origin at the bottom left as in GL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Rect {
    pub x: u32,
    pub y: u32,
    pub w: u32,
    pub h: u32,
}

impl Rect {
    pub fn new(x: u32, y: u32, w: u32, h: u32) -> Rect {
        Rect { x, y, w, h }
    }
    /// The `w x h` rectangle at the origin.
    pub fn sized(w: u32, h: u32) -> Rect {
        Rect { x: 0, y: 0, w, h }
    }
    pub fn area(&self) -> usize {
        self.w as usize * self.h as usize
    }
}

/// A framebuffer object over textures it keeps alive. All attachments have one size.
pub struct Framebuffer {
    ctx: Context,
    id: glow::Framebuffer,
    name: String,
    colors: Vec<Texture>,
    depth: Option<Texture>,
    width: u32,
    height: u32,
}

impl Drop for Framebuffer {
    fn drop(&mut self) {
        unsafe { self.ctx.gl().delete_framebuffer(self.id) };
    }
}

impl Framebuffer {
    /// A framebuffer named `name` (for error messages) drawing into `colors` (attachment i is
    /// fragment output location i) and testing against `depth` (a depth or depth-stencil
    /// texture). Completeness is checked here.
    pub fn new(
        ctx: &Context,
        name: &str,
        colors: &[&Texture],
        depth: Option<&Texture>,
    ) -> Result<Framebuffer, GlError> {
        Self::new_at_level(ctx, name, colors, depth, 0)
    }

    /// A framebuffer drawing into mipmap level `level` of each attachment (one level of an
    /// image pyramid); its size is that level's size. See [`Framebuffer::new`].
    pub fn new_at_level(
        ctx: &Context,
        name: &str,
        colors: &[&Texture],
        depth: Option<&Texture>,
        level: u32,
    ) -> Result<Framebuffer, GlError> {
        let first = colors
            .first()
            .copied()
            .or(depth)
            .ok_or_else(|| GlError::Invalid(format!("framebuffer {name} has no attachment")))?;
        if let Some(t) = colors
            .iter()
            .copied()
            .chain(depth)
            .find(|t| level >= t.levels())
        {
            return Err(GlError::Invalid(format!(
                "framebuffer {name}: level {level} of a texture with {} levels",
                t.levels()
            )));
        }
        let (width, height) = first.level_size(level);
        if let Some(gpu) = ctx.period() {
            gpu.check_draw_buffers(name, colors.len())?;
        }
        let max = ctx
            .info()
            .limits
            .max_draw_buffers
            .min(ctx.info().limits.max_color_attachments);
        if colors.len() > max as usize {
            return Err(GlError::Limit(format!(
                "framebuffer {name} asks for {} colour attachments; this renderer allows {max}",
                colors.len()
            )));
        }
        for t in colors.iter().copied().chain(depth) {
            let (w, h) = t.level_size(level);
            if (w, h) != (width, height) {
                return Err(GlError::Invalid(format!(
                    "framebuffer {name}: attachments differ in size ({w}x{h} and {width}x{height})"
                )));
            }
        }
        if let Some(t) = colors.iter().find(|t| t.format().is_depth()) {
            return Err(GlError::Invalid(format!(
                "framebuffer {name}: a {} texture cannot be a colour attachment",
                t.format().name()
            )));
        }
        if let Some(d) = depth.filter(|d| !d.format().is_depth()) {
            return Err(GlError::Invalid(format!(
                "framebuffer {name}: a {} texture cannot be the depth attachment",
                d.format().name()
            )));
        }
        let gl = ctx.gl();
        let id = unsafe { gl.create_framebuffer() }.map_err(GlError::Invalid)?;
        let fb = Framebuffer {
            ctx: ctx.clone(),
            id,
            name: name.to_string(),
            colors: colors.iter().map(|&t| t.clone()).collect(),
            depth: depth.cloned(),
            width,
            height,
        };
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(id));
            for (i, t) in colors.iter().enumerate() {
                gl.framebuffer_texture(
                    glow::FRAMEBUFFER,
                    glow::COLOR_ATTACHMENT0 + i as u32,
                    Some(t.id()),
                    level as i32,
                );
            }
            if let Some(d) = depth {
                let attachment = if d.format().has_stencil() {
                    glow::DEPTH_STENCIL_ATTACHMENT
                } else {
                    glow::DEPTH_ATTACHMENT
                };
                gl.framebuffer_texture(glow::FRAMEBUFFER, attachment, Some(d.id()), level as i32);
            }
        }
        fb.bind();
        fb.check_complete()?;
        ctx.check_now(&format!("creating framebuffer {name}"))?;
        Ok(fb)
    }

    pub fn name(&self) -> &str {
        &self.name
    }
    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    /// The whole framebuffer as a rectangle.
    pub fn rect(&self) -> Rect {
        Rect::sized(self.width, self.height)
    }
    pub fn colors(&self) -> &[Texture] {
        &self.colors
    }
    pub fn color(&self, index: usize) -> &Texture {
        &self.colors[index]
    }
    pub fn depth(&self) -> Option<&Texture> {
        self.depth.as_ref()
    }
    pub fn context(&self) -> &Context {
        &self.ctx
    }
    pub(super) fn id(&self) -> glow::Framebuffer {
        self.id
    }

    /// Bind for drawing into every colour attachment, with the whole framebuffer as viewport.
    pub(super) fn bind(&self) {
        let gl = self.ctx.gl();
        let buffers: Vec<u32> = (0..self.colors.len() as u32)
            .map(|i| glow::COLOR_ATTACHMENT0 + i)
            .collect();
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.id));
            if buffers.is_empty() {
                gl.draw_buffer(glow::NONE);
                gl.read_buffer(glow::NONE);
            } else {
                gl.draw_buffers(&buffers);
            }
            gl.viewport(0, 0, self.width as i32, self.height as i32);
        }
    }

    /// GL's completeness status, as an error naming this framebuffer and the status.
    pub fn check_complete(&self) -> Result<(), GlError> {
        let gl = self.ctx.gl();
        let status = unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.id));
            gl.check_framebuffer_status(glow::FRAMEBUFFER)
        };
        let status = match status {
            glow::FRAMEBUFFER_COMPLETE => return Ok(()),
            glow::FRAMEBUFFER_UNDEFINED => "GL_FRAMEBUFFER_UNDEFINED",
            glow::FRAMEBUFFER_INCOMPLETE_ATTACHMENT => "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT",
            glow::FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT => {
                "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT"
            }
            glow::FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER => "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER",
            glow::FRAMEBUFFER_INCOMPLETE_READ_BUFFER => "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER",
            glow::FRAMEBUFFER_UNSUPPORTED => "GL_FRAMEBUFFER_UNSUPPORTED",
            glow::FRAMEBUFFER_INCOMPLETE_MULTISAMPLE => "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE",
            glow::FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS => "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS",
            _ => "an unknown status",
        };
        Err(GlError::Incomplete {
            name: self.name.clone(),
            status,
        })
    }

    /// Start a pass drawing with `program` into this framebuffer (see [`Pass`]).
    pub fn pass<'a>(&'a self, program: &'a Program, name: &'a str) -> Result<Pass<'a>, GlError> {
        Pass::begin(self, program, name)
    }

    /// Copy `from` (a rectangle of `source`'s colour attachment 0) into `to` of this
    /// framebuffer's colour attachment 0, scaled with nearest-texel sampling (a picture in a
    /// picture: the viewer's insets).
    pub fn blit_from(&self, source: &Framebuffer, from: Rect, to: Rect) -> Result<(), GlError> {
        let gl = self.ctx.gl();
        let corners = |r: Rect| {
            (
                r.x as i32,
                r.y as i32,
                (r.x + r.w) as i32,
                (r.y + r.h) as i32,
            )
        };
        let (a, b) = (corners(from), corners(to));
        self.bind();
        unsafe {
            gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(source.id));
            gl.read_buffer(glow::COLOR_ATTACHMENT0);
            gl.bind_framebuffer(glow::DRAW_FRAMEBUFFER, Some(self.id));
            gl.draw_buffers(&[glow::COLOR_ATTACHMENT0]);
            gl.blit_framebuffer(
                a.0,
                a.1,
                a.2,
                a.3,
                b.0,
                b.1,
                b.2,
                b.3,
                glow::COLOR_BUFFER_BIT,
                glow::NEAREST,
            );
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.id));
        }
        self.ctx
            .check(&format!("copying {} into {}", source.name, self.name))
    }

    /// Clear colour attachment `index` to `value` (float formats; bytes are normalised).
    pub fn clear_color(&self, index: usize, value: [f32; 4]) -> Result<(), GlError> {
        let name = super::profile::is_on(&self.ctx).then(|| format!("clear {}", self.name));
        let _scope = name.as_deref().map(|n| super::profile::scope(&self.ctx, n));
        self.bind();
        unsafe {
            self.ctx.gl().color_mask(true, true, true, true);
            self.ctx
                .gl()
                .clear_buffer_f32_slice(glow::COLOR, index as u32, &value)
        };
        self.ctx
            .check(&format!("clearing colour {index} of {}", self.name))
    }

    /// Clear every colour attachment to `value`.
    pub fn clear_colors(&self, value: [f32; 4]) -> Result<(), GlError> {
        (0..self.colors.len()).try_for_each(|i| self.clear_color(i, value))
    }

    /// Clear the depth attachment (and the stencil, if there is one) to `depth` and `stencil`.
    pub fn clear_depth_stencil(&self, depth: f32, stencil: i32) -> Result<(), GlError> {
        let name = super::profile::is_on(&self.ctx).then(|| format!("clear {}", self.name));
        let _scope = name.as_deref().map(|n| super::profile::scope(&self.ctx, n));
        self.bind();
        let gl = self.ctx.gl();
        unsafe {
            gl.depth_mask(true);
            gl.stencil_mask(0xff);
            match self.depth.as_ref().map(|d| d.format()) {
                Some(f) if f.has_stencil() => {
                    gl.clear_buffer_depth_stencil(glow::DEPTH_STENCIL, 0, depth, stencil)
                }
                Some(_) => gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[depth]),
                None => {
                    return Err(GlError::Invalid(format!(
                        "framebuffer {} has no depth attachment to clear",
                        self.name
                    )))
                }
            }
        }
        self.ctx
            .check(&format!("clearing depth/stencil of {}", self.name))
    }

    /// Read a rectangle of colour attachment `index` as floats (RGBA32F: 4 per texel; R32F: 1).
    pub fn read_f32(&self, index: usize, rect: Rect) -> Result<Vec<f32>, GlError> {
        let format = self.color_format(index)?;
        if !format.is_float() {
            return Err(GlError::Invalid(format!(
                "read_f32 of a {} attachment of {}",
                format.name(),
                self.name
            )));
        }
        let mut out = vec![0f32; rect.area() * format.components()];
        self.read_color(
            index,
            rect,
            glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut out))),
        )?;
        Ok(out)
    }

    /// Read a rectangle of colour attachment `index` as bytes (R8: 1 per texel; RGBA8: 4).
    pub fn read_u8(&self, index: usize, rect: Rect) -> Result<Vec<u8>, GlError> {
        let format = self.color_format(index)?;
        if !matches!(format, TextureFormat::R8 | TextureFormat::Rgba8) {
            return Err(GlError::Invalid(format!(
                "read_u8 of a {} attachment of {}",
                format.name(),
                self.name
            )));
        }
        let mut out = vec![0u8; rect.area() * format.components()];
        self.read_color(index, rect, glow::PixelPackData::Slice(Some(&mut out)))?;
        Ok(out)
    }

    /// Read a rectangle of colour attachment `index` as unsigned integers (RGBA32UI: 4 per
    /// texel).
    pub fn read_u32(&self, index: usize, rect: Rect) -> Result<Vec<u32>, GlError> {
        let format = self.color_format(index)?;
        if format != TextureFormat::Rgba32Ui {
            return Err(GlError::Invalid(format!(
                "read_u32 of a {} attachment of {}",
                format.name(),
                self.name
            )));
        }
        let mut out = vec![0u32; rect.area() * format.components()];
        self.read_color(
            index,
            rect,
            glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut out))),
        )?;
        Ok(out)
    }

    /// Read a rectangle of colour attachment `index` into `buffer` at `offset` bytes, as a
    /// pixel pack buffer (PBO). The data never leaves the GPU: the same buffer can then feed
    /// a draw as a vertex buffer (paper 2's render-to-vertex-buffer).
    pub fn read_into_buffer(
        &self,
        index: usize,
        rect: Rect,
        buffer: &Buffer,
        offset: usize,
    ) -> Result<(), GlError> {
        let format = self.color_format(index)?;
        let bytes = rect.area() * format.bytes_per_texel();
        if offset + bytes > buffer.len_bytes() {
            return Err(GlError::Invalid(format!(
                "reading {bytes} bytes of {} at offset {offset} overflows a {}-byte buffer",
                self.name,
                buffer.len_bytes()
            )));
        }
        unsafe {
            self.ctx
                .gl()
                .bind_buffer(glow::PIXEL_PACK_BUFFER, Some(buffer.id()))
        };
        let result = self.read_color(
            index,
            rect,
            glow::PixelPackData::BufferOffset(offset as u32),
        );
        unsafe { self.ctx.gl().bind_buffer(glow::PIXEL_PACK_BUFFER, None) };
        result
    }

    /// Read a rectangle of the depth attachment as floats in [0, 1].
    pub fn read_depth(&self, rect: Rect) -> Result<Vec<f32>, GlError> {
        self.require_depth()?;
        let mut out = vec![0f32; rect.area()];
        self.read_raw(
            rect,
            glow::DEPTH_COMPONENT,
            glow::FLOAT,
            glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut out))),
        )?;
        Ok(out)
    }

    /// Read a rectangle of the stencil buffer (a DEPTH24_STENCIL8 or DEPTH32F_STENCIL8
    /// attachment).
    pub fn read_stencil(&self, rect: Rect) -> Result<Vec<u8>, GlError> {
        if !self.require_depth()?.has_stencil() {
            return Err(GlError::Invalid(format!(
                "framebuffer {} has no stencil",
                self.name
            )));
        }
        let mut out = vec![0u8; rect.area()];
        self.read_raw(
            rect,
            glow::STENCIL_INDEX,
            glow::UNSIGNED_BYTE,
            glow::PixelPackData::Slice(Some(&mut out)),
        )?;
        Ok(out)
    }

    fn require_depth(&self) -> Result<TextureFormat, GlError> {
        self.depth.as_ref().map(|d| d.format()).ok_or_else(|| {
            GlError::Invalid(format!("framebuffer {} has no depth attachment", self.name))
        })
    }

    fn color_format(&self, index: usize) -> Result<TextureFormat, GlError> {
        self.colors.get(index).map(|t| t.format()).ok_or_else(|| {
            GlError::Invalid(format!(
                "framebuffer {} has {} colour attachments, not {}",
                self.name,
                self.colors.len(),
                index + 1
            ))
        })
    }

    fn read_color(
        &self,
        index: usize,
        rect: Rect,
        data: glow::PixelPackData,
    ) -> Result<(), GlError> {
        let (_, format, ty) = self.colors[index].format().gl();
        unsafe {
            self.ctx
                .gl()
                .bind_framebuffer(glow::FRAMEBUFFER, Some(self.id));
            self.ctx
                .gl()
                .read_buffer(glow::COLOR_ATTACHMENT0 + index as u32);
        }
        self.read_raw(rect, format, ty, data)
    }

    fn read_raw(
        &self,
        rect: Rect,
        format: u32,
        ty: u32,
        data: glow::PixelPackData,
    ) -> Result<(), GlError> {
        if rect.x + rect.w > self.width || rect.y + rect.h > self.height {
            return Err(GlError::Invalid(format!(
                "reading {}x{} at ({}, {}) outside the {}x{} framebuffer {}",
                rect.w, rect.h, rect.x, rect.y, self.width, self.height, self.name
            )));
        }
        let gl = self.ctx.gl();
        super::profile::wait(&self.ctx, "glReadPixels", || unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.id));
            gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            gl.read_pixels(
                rect.x as i32,
                rect.y as i32,
                rect.w as i32,
                rect.h as i32,
                format,
                ty,
                data,
            );
        });
        self.ctx.check(&format!("reading back {}", self.name))
    }
}

impl std::fmt::Debug for Framebuffer {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(
            f,
            "Framebuffer({} {}x{}, {} colour)",
            self.name,
            self.width,
            self.height,
            self.colors.len()
        )
    }
}
