//! A window with an OpenGL 3.3 core context, made by glutin (GLX, then EGL, on X11) for a winit
//! event loop. Its [`Context`] is the same type the headless renderers give: the paper code
//! drawing into framebuffers cannot tell them apart. What only a window has is here: the
//! default framebuffer (drawn by [`GlWindow::present`], read by [`GlWindow::read_pixels`]),
//! resizing and buffer swaps.

use super::{Context, Framebuffer, GlError, Renderer};
use glutin::config::{Config, ConfigTemplateBuilder, GlConfig};
use glutin::context::{
    ContextApi, ContextAttributesBuilder, GlProfile, NotCurrentGlContext, PossiblyCurrentContext,
    Version,
};
use glutin::display::{GetGlDisplay, GlDisplay};
use glutin::surface::{GlSurface, Surface, SwapInterval, WindowSurface};
use glutin_winit::{DisplayBuilder, GlWindow as _};
use raw_window_handle::HasWindowHandle;
use std::ffi::CString;
use std::num::NonZeroU32;
use std::rc::Rc;
use winit::event_loop::ActiveEventLoop;
use winit::window::{Window, WindowAttributes};

/// What must outlive every GL object of a window's context: glutin's context, its surface and
/// the window, dropped in that order.
pub(super) struct WindowState {
    context: PossiblyCurrentContext,
    surface: Surface<WindowSurface>,
    window: Window,
}

/// A window and its current GL context.
pub struct GlWindow {
    ctx: Context,
    state: Rc<WindowState>,
}

impl GlWindow {
    /// Open a window with `attributes` and make an OpenGL 3.3 core context current on it.
    /// `vsync` asks the swap to wait for the display (off for `--frames` runs).
    pub fn new(
        event_loop: &ActiveEventLoop,
        attributes: WindowAttributes,
        vsync: bool,
    ) -> Result<GlWindow, GlError> {
        let err = |what: &str, e: &dyn std::fmt::Display| GlError::Context(format!("{what}: {e}"));
        let template = ConfigTemplateBuilder::new()
            .with_alpha_size(8)
            .with_depth_size(0)
            .with_stencil_size(0);
        let (window, config) = DisplayBuilder::new()
            .with_window_attributes(Some(attributes))
            .build(event_loop, template, pick_config)
            .map_err(|e| err("no OpenGL configuration for a window", &e))?;
        let window = window.ok_or_else(|| GlError::Context("no window was made".into()))?;
        let handle = window
            .window_handle()
            .map_err(|e| err("the window has no handle", &e))?
            .as_raw();
        let display = config.display();
        let attributes = ContextAttributesBuilder::new()
            .with_profile(GlProfile::Core)
            .with_context_api(ContextApi::OpenGl(Some(Version::new(3, 3))))
            .build(Some(handle));
        // SAFETY: the handle is of the live window created above for this display.
        let not_current = unsafe { display.create_context(&config, &attributes) }.map_err(|e| {
            err(
                "no OpenGL 3.3 core context (the viewer needs 3.3 or newer)",
                &e,
            )
        })?;
        let surface_attributes = window
            .build_surface_attributes(Default::default())
            .map_err(|e| err("window surface attributes", &e))?;
        // SAFETY: as above; the surface is dropped before the window (WindowState's order).
        let surface = unsafe { display.create_window_surface(&config, &surface_attributes) }
            .map_err(|e| err("no window surface", &e))?;
        let context = not_current
            .make_current(&surface)
            .map_err(|e| err("making the window's context current", &e))?;
        let interval = if vsync {
            SwapInterval::Wait(NonZeroU32::MIN)
        } else {
            SwapInterval::DontWait
        };
        // Not every platform can change it; the frames come out the same either way.
        let _ = surface.set_swap_interval(&context, interval);
        // SAFETY: the context is current on this thread; the loader returns its entry points.
        let gl = unsafe {
            glow::Context::from_loader_function(|name| {
                let name = CString::new(name).expect("GL names have no NUL");
                display.get_proc_address(&name)
            })
        };
        let api = match display {
            #[allow(unreachable_patterns)]
            glutin::display::Display::Glx(_) => "GLX",
            _ => "EGL",
        };
        let state = Rc::new(WindowState {
            context,
            surface,
            window,
        });
        let loader_display = config.display();
        let ctx = Context::from_current(
            gl,
            move |name| {
                let name = CString::new(name).expect("GL names have no NUL");
                loader_display.get_proc_address(&name)
            },
            Box::new(state.clone()),
            Renderer::Window,
            format!("a window's context through glutin ({api})"),
        )?;
        Ok(GlWindow { ctx, state })
    }

    /// The context, as every paper type takes it.
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// The winit window (size, title, redraw requests).
    pub fn window(&self) -> &Window {
        &self.state.window
    }

    /// Resize the surface to the window's new size in pixels.
    pub fn resize(&self, width: u32, height: u32) {
        if let (Some(w), Some(h)) = (NonZeroU32::new(width), NonZeroU32::new(height)) {
            self.state.surface.resize(&self.state.context, w, h);
        }
    }

    /// Copy colour attachment 0 of `canvas` to the window's back buffer, pixel for pixel from
    /// the bottom-left corner (the canvas has the window's size).
    pub fn present(&self, canvas: &Framebuffer) -> Result<(), GlError> {
        let gl = self.ctx.gl();
        let (w, h) = (canvas.width() as i32, canvas.height() as i32);
        unsafe {
            gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(canvas.id()));
            gl.read_buffer(glow::COLOR_ATTACHMENT0);
            gl.bind_framebuffer(glow::DRAW_FRAMEBUFFER, None);
            gl.draw_buffer(glow::BACK);
            gl.viewport(0, 0, w, h);
            gl.disable(glow::SCISSOR_TEST);
            gl.blit_framebuffer(
                0,
                0,
                w,
                h,
                0,
                0,
                w,
                h,
                glow::COLOR_BUFFER_BIT,
                glow::NEAREST,
            );
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        self.ctx.check_now("copying the canvas to the window")
    }

    /// The window's back buffer as RGBA bytes, `width x height` from the bottom-left corner,
    /// rows from the bottom (GL's order), alpha forced opaque.
    pub fn read_pixels(&self, width: u32, height: u32) -> Result<Vec<u8>, GlError> {
        let gl = self.ctx.gl();
        let mut out = vec![0u8; width as usize * height as usize * 4];
        unsafe {
            gl.bind_framebuffer(glow::READ_FRAMEBUFFER, None);
            gl.read_buffer(glow::BACK);
            gl.bind_buffer(glow::PIXEL_PACK_BUFFER, None);
            gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            gl.read_pixels(
                0,
                0,
                width as i32,
                height as i32,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelPackData::Slice(Some(&mut out)),
            );
        }
        self.ctx.check_now("reading the window's back buffer")?;
        for px in out.chunks_exact_mut(4) {
            px[3] = 255;
        }
        Ok(out)
    }

    /// Show the back buffer.
    pub fn swap(&self) -> Result<(), GlError> {
        self.state
            .surface
            .swap_buffers(&self.state.context)
            .map_err(|e| GlError::Context(format!("swapping the window's buffers: {e}")))
    }
}

/// The configuration with the most samples is not wanted (the canvas is copied pixel for
/// pixel); take the first one without multisampling, else the first.
fn pick_config(configs: Box<dyn Iterator<Item = Config> + '_>) -> Config {
    let mut first = None;
    for config in configs {
        if config.num_samples() == 0 {
            return config;
        }
        first.get_or_insert(config);
    }
    first.expect("glutin offers at least one configuration")
}
