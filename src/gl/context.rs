//! A headless OpenGL context: EGL (device or surfaceless platform) or OSMesa, all loaded at
//! run time, so that a machine without them gets a clear error instead of a link failure.

use super::GlError;
use glow::HasContext;
use khronos_egl as egl;
use serde::Serialize;
use std::cell::Cell;
use std::ffi::{c_void, CStr, CString};
use std::fmt;
use std::rc::Rc;
use std::str::FromStr;
use std::sync::OnceLock;

/// The environment variable that selects the renderer (tests and library users).
pub const RENDERER_ENV: &str = "CLASSIC_GPGPU_RENDERER";
/// Set to `1` to check GL errors after every pass in release builds too.
pub const CHECKS_ENV: &str = "CLASSIC_GPGPU_GL_CHECKS";

/// The Debian packages that provide the default renderer.
const MESA_PACKAGES: &str = "libegl1 libegl-mesa0 libgl1-mesa-dri";

/// OpenGL versions asked for, newest first; 3.3 core is the floor of the faithful paths.
const GL_VERSIONS: [(i32, i32); 4] = [(4, 5), (4, 3), (4, 1), (3, 3)];

/// Mesa's Vulkan layer that picks a device (`VK_LAYER_MESA_device_select`, loaded implicitly
/// with `mesa-vulkan-drivers`) looks for a Wayland and an X display when zink enumerates the
/// Vulkan devices; with `XDG_RUNTIME_DIR` unset, libwayland-client prints "error:
/// XDG_RUNTIME_DIR is invalid or not set in the environment." to stderr on each probe, although
/// nothing failed. A headless context has no display to choose a device by, so the layer is
/// switched off with its own switch (`NODEVICE_SELECT=1`) in exactly that case: no
/// `XDG_RUNTIME_DIR`, and no device chosen by the user (`MESA_VK_DEVICE_SELECT`, `DRI_PRIME`,
/// `NODEVICE_SELECT` already set). Call it first thing in `main`, before any thread starts
/// (it sets a variable of the process's environment).
pub fn quiet_display_probes() {
    let unset = |name: &str| std::env::var_os(name).is_none_or(|v| v.is_empty());
    let user_chose = ["MESA_VK_DEVICE_SELECT", "DRI_PRIME", "NODEVICE_SELECT"]
        .iter()
        .any(|name| !unset(name));
    if unset("XDG_RUNTIME_DIR") && !user_chose {
        std::env::set_var("NODEVICE_SELECT", "1");
    }
}

/// Which platform provides the context.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Renderer {
    /// EGL device, then EGL surfaceless, then OSMesa.
    Auto,
    /// `EGL_EXT_platform_device`: a GPU without a display (NVIDIA).
    EglDevice,
    /// `EGL_MESA_platform_surfaceless`: Mesa, usually llvmpipe.
    EglSurfaceless,
    /// Mesa's off-screen library, for systems without EGL.
    Osmesa,
    /// A window's context, made by glutin for the viewer (`view`); not a `--renderer` choice.
    Window,
}

impl Renderer {
    /// Every choice, as a user names it: `auto` first, then the order `auto` tries.
    pub const ALL: [Renderer; 4] = [
        Renderer::Auto,
        Renderer::EglDevice,
        Renderer::EglSurfaceless,
        Renderer::Osmesa,
    ];

    /// The name a user types (`--renderer`, `CLASSIC_GPGPU_RENDERER`).
    pub fn name(self) -> &'static str {
        match self {
            Renderer::Auto => "auto",
            Renderer::EglDevice => "egl-device",
            Renderer::EglSurfaceless => "egl-surfaceless",
            Renderer::Osmesa => "osmesa",
            Renderer::Window => "window",
        }
    }

    /// What the choice means, in one line (for help texts).
    pub fn description(self) -> &'static str {
        match self {
            Renderer::Auto => "EGL device, then EGL surfaceless, then OSMesa",
            Renderer::EglDevice => "`EGL_EXT_platform_device`: a GPU without a display (NVIDIA)",
            Renderer::EglSurfaceless => "`EGL_MESA_platform_surfaceless`: Mesa, usually llvmpipe",
            Renderer::Osmesa => "Mesa's off-screen library, for systems without EGL",
            Renderer::Window => "a window's context (glutin), made by `view`",
        }
    }
}

impl FromStr for Renderer {
    type Err = GlError;
    fn from_str(s: &str) -> Result<Self, GlError> {
        let s = s.trim();
        if s.is_empty() {
            return Ok(Renderer::Auto);
        }
        Renderer::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| {
                GlError::Context(format!(
                    "unknown renderer '{s}': expected auto, egl-device, egl-surfaceless or osmesa"
                ))
            })
    }
}

impl fmt::Display for Renderer {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The limits the papers depend on.
#[derive(Clone, Debug, Serialize)]
pub struct Limits {
    pub max_texture_size: u32,
    pub max_draw_buffers: u32,
    pub max_color_attachments: u32,
    pub max_viewport_dims: [u32; 2],
    pub max_texture_image_units: u32,
    pub max_vertex_texture_image_units: u32,
    pub max_vertex_uniform_components: u32,
    pub max_fragment_uniform_components: u32,
    /// The largest vertex attribute stride in bytes (GL 4.4; 2048, the 4.4 minimum, before).
    pub max_vertex_attrib_stride: u32,
    pub stencil_bits: u32,
    pub samples_passed_counter_bits: u32,
    pub time_elapsed_counter_bits: u32,
}

/// What `info` prints: which renderer, why, and its limits.
#[derive(Clone, Debug, Serialize)]
pub struct ContextInfo {
    /// The platform that made the context (`egl-device`, `egl-surfaceless`, `osmesa`).
    pub platform: Renderer,
    /// Why this platform: what was asked for and what was tried before it.
    pub why: String,
    pub vendor: String,
    pub renderer: String,
    pub version: String,
    pub glsl_version: String,
    /// The (major, minor) of the context actually made.
    pub gl_version: (i32, i32),
    pub limits: Limits,
}

impl ContextInfo {
    /// Whether the renderer rasterizes on the CPU (llvmpipe, softpipe, swrast, SwiftShader):
    /// there, every fragment costs CPU time that the CPU baselines also need.
    pub fn is_software(&self) -> bool {
        let renderer = self.renderer.to_lowercase();
        ["llvmpipe", "softpipe", "swrast", "swiftshader"]
            .iter()
            .any(|name| renderer.contains(name))
    }

    /// One line naming the renderer, for every printed figure: "llvmpipe (...) via egl-surfaceless".
    pub fn renderer_line(&self) -> String {
        format!(
            "{} via {}, OpenGL {}",
            self.renderer, self.platform, self.version
        )
    }
}

/// A headless OpenGL context, current on the thread that made it. Every GL object holds a
/// clone of it, so the context outlives them.
#[derive(Clone)]
pub struct Context {
    pub(super) inner: Rc<Inner>,
}

pub(super) struct Inner {
    pub(super) gl: super::trace::Gl,
    info: ContextInfo,
    checks: Cell<bool>,
    /// A lower limit on work groups per dispatch axis (a test hook), if set.
    work_group_limit: Cell<Option<u32>>,
    /// The period GPU whose limits are checked ([`Context::set_period`]), if any.
    pub(super) period: Cell<Option<&'static super::period::PeriodGpu>>,
    /// A lower limit on the bytes of one storage buffer (a test hook), if set.
    storage_buffer_limit: Cell<Option<usize>>,
    /// The empty vertex array that attribute-less draws (rectangles) bind.
    pub(super) empty_vao: glow::VertexArray,
    pub(super) extra: ExtraEntryPoints,
    /// The running per-pass profile, if any ([`super::profile`]).
    pub(super) profile: std::cell::RefCell<Option<Box<super::profile::State>>>,
    /// `--glsl-dir`: shader files found here replace the compiled-in ones ([`Context::set_glsl_dir`]).
    glsl_dir: std::cell::RefCell<Option<std::path::PathBuf>>,
    /// What `gl_FrontFacing` says here, once probed ([`Context::fragment_facing`]).
    pub(super) facing: Cell<Option<super::facing::FragmentFacing>>,
    platform: Platform,
}

/// Entry points glow does not bind, looked up by name.
pub(super) struct ExtraEntryPoints {
    pub(super) get_query_iv: Option<unsafe extern "system" fn(u32, u32, *mut i32)>,
    /// glGetProgramiv, for parameters of several values (a compute shader's work group size).
    pub(super) get_program_iv: Option<unsafe extern "system" fn(u32, u32, *mut i32)>,
    #[allow(clippy::type_complexity)]
    pub(super) tex_sub_image_1d:
        Option<unsafe extern "system" fn(u32, i32, i32, i32, u32, u32, *const c_void)>,
}

impl ExtraEntryPoints {
    unsafe fn load(platform: &Platform) -> Self {
        let get_query_iv = platform.proc_address("glGetQueryiv");
        let tex_sub_image_1d = platform.proc_address("glTexSubImage1D");
        let get_program_iv = platform.proc_address("glGetProgramiv");
        ExtraEntryPoints {
            get_program_iv: (!get_program_iv.is_null())
                .then(|| std::mem::transmute(get_program_iv)),
            get_query_iv: (!get_query_iv.is_null()).then(|| std::mem::transmute(get_query_iv)),
            tex_sub_image_1d: (!tex_sub_image_1d.is_null())
                .then(|| std::mem::transmute(tex_sub_image_1d)),
        }
    }
}

enum Platform {
    Egl {
        egl: &'static EglInstance,
        display: egl::Display,
        context: egl::Context,
    },
    OsMesa {
        lib: &'static OsMesa,
        context: *mut c_void,
        _buffer: Vec<u8>,
    },
    /// A context made elsewhere (a window's, by glutin): its loader, and a guard that keeps
    /// the context and its surface alive until the last GL object is gone.
    External {
        loader: Box<dyn Fn(&str) -> *const c_void>,
        _guard: Box<dyn std::any::Any>,
    },
}

impl Platform {
    fn proc_address(&self, name: &str) -> *const c_void {
        match self {
            Platform::Egl { egl, .. } => egl
                .get_proc_address(name)
                .map_or(std::ptr::null(), |f| f as *const c_void),
            Platform::OsMesa { lib, .. } => {
                let name = CString::new(name).expect("GL names have no NUL");
                unsafe { (lib.get_proc_address)(name.as_ptr()) }
            }
            Platform::External { loader, .. } => loader(name),
        }
    }
}

impl Drop for Inner {
    fn drop(&mut self) {
        // SAFETY: the context is current on this thread (it is not Send) and no object
        // outlives it, since each holds an Rc to it.
        unsafe { self.gl.delete_vertex_array(self.empty_vao) };
        match &self.platform {
            Platform::Egl {
                egl,
                display,
                context,
            } => {
                // The display is shared by every context of the process: never terminate it.
                let _ = egl.make_current(*display, None, None, None);
                let _ = egl.destroy_context(*display, *context);
            }
            Platform::OsMesa { lib, context, .. } => unsafe { (lib.destroy)(*context) },
            // The guard drops the context after this.
            Platform::External { .. } => {}
        }
    }
}

impl Context {
    /// A context from the renderer named in `CLASSIC_GPGPU_RENDERER` (default `auto`).
    pub fn from_env() -> Result<Context, GlError> {
        let choice = std::env::var(RENDERER_ENV).unwrap_or_default();
        let renderer: Renderer = choice.parse()?;
        let why = if choice.trim().is_empty() {
            "default".to_string()
        } else {
            format!("{RENDERER_ENV}={choice}")
        };
        Self::with_reason(renderer, &why)
    }

    /// A context from the given platform (`Auto` tries them in order).
    pub fn new(renderer: Renderer) -> Result<Context, GlError> {
        Self::with_reason(renderer, "asked for")
    }

    fn with_reason(renderer: Renderer, asked: &str) -> Result<Context, GlError> {
        let attempts: &[Renderer] = match renderer {
            Renderer::Auto => &[
                Renderer::EglDevice,
                Renderer::EglSurfaceless,
                Renderer::Osmesa,
            ],
            Renderer::EglDevice => &[Renderer::EglDevice],
            Renderer::EglSurfaceless => &[Renderer::EglSurfaceless],
            Renderer::Osmesa => &[Renderer::Osmesa],
            Renderer::Window => {
                return Err(GlError::Context(
                    "a window's context is made by the viewer (`classic-gpgpu view`), not by \
                     --renderer"
                        .into(),
                ))
            }
        };
        let mut failures = Vec::new();
        for &platform in attempts {
            let made = match platform {
                Renderer::EglDevice => egl_device_context(),
                Renderer::EglSurfaceless => egl_surfaceless_context(),
                _ => osmesa_context(),
            };
            match made {
                Ok((gl, platform_state)) => {
                    let mut why = format!("{renderer} ({asked})");
                    if !failures.is_empty() {
                        why.push_str("; skipped: ");
                        why.push_str(&failures.join("; "));
                    }
                    return Context::finish(gl, platform_state, platform, why);
                }
                Err(e) => failures.push(format!("{platform}: {e}")),
            }
        }
        Err(GlError::Context(format!(
            "no OpenGL context could be made ({}). On Debian the default renderer needs the \
             packages {MESA_PACKAGES} (apt-get install {MESA_PACKAGES}); OSMesa needs libosmesa6",
            failures.join("; ")
        )))
    }

    /// Wrap a context made elsewhere and current on this thread (a window's, made by glutin in
    /// [`super::window`]): `gl` loaded from it, `loader` its entry points by name, `guard` what
    /// keeps it alive (dropped after every GL object), `why` how it was made.
    pub(super) fn from_current(
        gl: glow::Context,
        loader: impl Fn(&str) -> *const c_void + 'static,
        guard: Box<dyn std::any::Any>,
        platform: Renderer,
        why: String,
    ) -> Result<Context, GlError> {
        let state = Platform::External {
            loader: Box::new(loader),
            _guard: guard,
        };
        Context::finish(gl, state, platform, why)
    }

    fn finish(
        gl: glow::Context,
        platform_state: Platform,
        platform: Renderer,
        why: String,
    ) -> Result<Context, GlError> {
        // SAFETY: the context was just made current on this thread.
        let (version, empty_vao) = unsafe {
            let version = (
                gl.get_parameter_i32(glow::MAJOR_VERSION),
                gl.get_parameter_i32(glow::MINOR_VERSION),
            );
            let vao = gl.create_vertex_array().map_err(GlError::Context)?;
            (version, vao)
        };
        let extra = unsafe { ExtraEntryPoints::load(&platform_state) };
        let info = unsafe { read_info(&gl, &extra, platform, why, version) };
        let checks = cfg!(debug_assertions)
            || std::env::var(CHECKS_ENV).is_ok_and(|v| v == "1" || v == "true");
        let ctx = Context {
            inner: Rc::new(Inner {
                gl: super::trace::Gl::new(gl),
                info,
                checks: Cell::new(checks),
                work_group_limit: Cell::new(None),
                period: Cell::new(None),
                storage_buffer_limit: Cell::new(None),
                empty_vao,
                extra,
                profile: std::cell::RefCell::new(None),
                glsl_dir: std::cell::RefCell::new(None),
                facing: Cell::new(None),
                platform: platform_state,
            }),
        };
        if version >= (3, 3) {
            ctx.warm_up_timer_queries()?;
        }
        if ctx.info().is_software() {
            keep_freed_memory_in_the_process();
        }
        if version < (3, 3) {
            return Err(GlError::Context(format!(
                "OpenGL {}.{} is too old: classic-gpgpu needs OpenGL 3.3 core ({}). \
                 Install a newer Mesa ({MESA_PACKAGES}) or a GPU driver",
                version.0,
                version.1,
                ctx.info().renderer
            )));
        }
        Ok(ctx)
    }

    /// llvmpipe answers the first TIME_ELAPSED query of a context that has drawn nothing
    /// with its uptime. One throw-away query around a clear takes that answer.
    fn warm_up_timer_queries(&self) -> Result<(), GlError> {
        let target = super::Texture::new_2d(self, 1, 1, super::TextureFormat::R8)?;
        let framebuffer = super::Framebuffer::new(self, "timer warm-up", &[&target], None)?;
        let query = super::TimerQuery::new(self)?;
        query.begin();
        framebuffer.clear_colors([0.0; 4])?;
        query.end();
        query.nanoseconds().map(|_| ())
    }

    /// Vendor, renderer, version, platform and limits.
    pub fn info(&self) -> &ContextInfo {
        &self.inner.info
    }

    /// Whether GL errors and framebuffer completeness are checked after every pass.
    pub fn checks(&self) -> bool {
        self.inner.checks.get()
    }

    /// Turn the per-pass checks on (tests) or off (timed benchmark loops).
    pub fn set_checks(&self, on: bool) {
        self.inner.checks.set(on);
    }

    /// Test hook: compute dispatches may use at most `limit` work groups along each axis
    /// (when below the renderer's own limit), so that code which splits dispatches larger than
    /// the limit is tested on small inputs. `None` restores the renderer's limit.
    pub fn set_work_group_limit(&self, limit: Option<u32>) {
        self.inner.work_group_limit.set(limit);
    }

    /// Test hook: storage buffers may hold at most `bytes` (when below the renderer's own
    /// limit), so that code which splits work too large for one buffer is tested on small
    /// inputs. `None` restores the renderer's limit.
    pub fn set_storage_buffer_limit(&self, bytes: Option<usize>) {
        self.inner.storage_buffer_limit.set(bytes);
    }

    /// The most bytes one storage buffer may hold here: what one shader storage block may
    /// see (`GL_MAX_SHADER_STORAGE_BLOCK_SIZE`, OpenGL 4.3) and what a buffer's size can say
    /// (the binding passes sizes as 32-bit signed integers).
    pub fn max_storage_buffer_bytes(&self) -> usize {
        let block = unsafe {
            self.gl()
                .get_parameter_i64(glow::MAX_SHADER_STORAGE_BLOCK_SIZE)
        }
        .max(0) as u64;
        let renderer = block.min(i32::MAX as u64) as usize;
        self.inner
            .storage_buffer_limit
            .get()
            .map_or(renderer, |limit| limit.min(renderer))
    }

    /// The bits of sub-pixel precision the rasterizer snaps vertex positions to
    /// (`GL_SUBPIXEL_BITS`; OpenGL asks for at least 4): whether a pixel centre within
    /// `2^-bits` of a triangle's edge is covered is the rasterizer's choice.
    pub fn subpixel_bits(&self) -> u32 {
        let bits = unsafe { self.gl().get_parameter_i32(glow::SUBPIXEL_BITS) };
        (bits.max(0) as u32).max(4)
    }

    /// The most work groups one dispatch may have along `axis` (0, 1, 2).
    pub fn max_work_groups(&self, axis: u32) -> u32 {
        let renderer = unsafe {
            self.gl()
                .get_parameter_indexed_i32(glow::MAX_COMPUTE_WORK_GROUP_COUNT, axis)
        }
        .max(0) as u32;
        self.inner
            .work_group_limit
            .get()
            .map_or(renderer, |limit| limit.min(renderer))
    }

    /// Load shaders from `dir` where it has them: a program built from `glsl/x.frag` reads
    /// `dir/glsl/x.frag` if that file exists, and the compiled-in copy otherwise (a learner's
    /// edit without a rebuild). `None` goes back to the compiled-in shaders only.
    pub fn set_glsl_dir(&self, dir: Option<std::path::PathBuf>) {
        *self.inner.glsl_dir.borrow_mut() = dir;
    }

    /// The folder set by [`Context::set_glsl_dir`], if any.
    pub fn glsl_dir(&self) -> Option<std::path::PathBuf> {
        self.inner.glsl_dir.borrow().clone()
    }

    pub(super) fn gl(&self) -> &super::trace::Gl {
        &self.inner.gl
    }

    /// Start recording every GL call this context makes ([`super::trace`]); an earlier
    /// recording is dropped.
    pub fn trace_start(&self) {
        self.inner.gl.start();
    }

    /// Stop recording: the calls made since [`Context::trace_start`], in order.
    pub fn trace_stop(&self) -> Vec<super::trace::TracedCall> {
        self.inner.gl.stop()
    }

    /// Whether GL calls are being recorded.
    pub fn tracing(&self) -> bool {
        self.inner.gl.is_on()
    }

    /// If checks are on: the first pending GL error, named, with what was being done.
    pub fn check(&self, what: &str) -> Result<(), GlError> {
        if self.checks() {
            self.check_now(what)
        } else {
            Ok(())
        }
    }

    /// The first pending GL error, whatever the checks setting.
    pub fn check_now(&self, what: &str) -> Result<(), GlError> {
        // SAFETY: glGetError has no preconditions.
        let code = unsafe { self.gl().get_error() };
        if code == glow::NO_ERROR {
            Ok(())
        } else {
            // Drain the rest so the next check starts clean.
            unsafe { while self.gl().get_error() != glow::NO_ERROR {} }
            Err(GlError::Gl {
                what: what.to_string(),
                error: gl_error_name(code),
            })
        }
    }

    /// Wait for every queued command (wall-clock timing of whole frames).
    pub fn finish_all(&self) {
        super::profile::wait(self, "glFinish", || unsafe { self.gl().finish() });
    }

    /// The bits of the `GL_TIMESTAMP` counter (0: no timestamps).
    pub(super) fn timestamp_bits(&self) -> u32 {
        let Some(get_query_iv) = self.inner.extra.get_query_iv else {
            return 0;
        };
        let mut bits = 0;
        // SAFETY: the entry point was looked up by its name; one i32 is written.
        unsafe { get_query_iv(glow::TIMESTAMP, glow::QUERY_COUNTER_BITS, &mut bits) };
        self.check_now("reading the timestamp counter bits").ok();
        bits.max(0) as u32
    }

    /// Push queued commands to the GPU without waiting.
    pub fn flush(&self) {
        unsafe { self.gl().flush() };
    }
}

/// A software renderer allocates and frees large buffers on every draw; glibc hands each
/// freed top-of-heap block back to the kernel (trim) and maps big ones afresh (mmap), which
/// made paper 4's 50-body buoyancy step spend most of its time in the kernel. Raising both
/// thresholds keeps those pages in the process: 30 -> 41 steps/s measured on llvmpipe, 2 cores.
fn keep_freed_memory_in_the_process() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes allocator parameters; both values are within glibc's bounds.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, 256 << 20);
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
    }
}

fn gl_error_name(code: u32) -> &'static str {
    match code {
        glow::INVALID_ENUM => "GL_INVALID_ENUM",
        glow::INVALID_VALUE => "GL_INVALID_VALUE",
        glow::INVALID_OPERATION => "GL_INVALID_OPERATION",
        glow::INVALID_FRAMEBUFFER_OPERATION => "GL_INVALID_FRAMEBUFFER_OPERATION",
        glow::OUT_OF_MEMORY => "GL_OUT_OF_MEMORY",
        glow::STACK_OVERFLOW => "GL_STACK_OVERFLOW",
        glow::STACK_UNDERFLOW => "GL_STACK_UNDERFLOW",
        _ => "unknown GL error",
    }
}

unsafe fn read_info(
    gl: &glow::Context,
    extra: &ExtraEntryPoints,
    platform: Renderer,
    why: String,
    gl_version: (i32, i32),
) -> ContextInfo {
    let int = |p| gl.get_parameter_i32(p).max(0) as u32;
    let mut viewport = [0i32; 2];
    gl.get_parameter_i32_slice(glow::MAX_VIEWPORT_DIMS, &mut viewport);
    let counter_bits = |target| {
        let Some(get_query_iv) = extra.get_query_iv else {
            return 0;
        };
        let mut bits = 0i32;
        get_query_iv(target, glow::QUERY_COUNTER_BITS, &mut bits);
        bits.max(0) as u32
    };
    let limits = Limits {
        max_texture_size: int(glow::MAX_TEXTURE_SIZE),
        max_draw_buffers: int(glow::MAX_DRAW_BUFFERS),
        max_color_attachments: int(glow::MAX_COLOR_ATTACHMENTS),
        max_viewport_dims: [viewport[0].max(0) as u32, viewport[1].max(0) as u32],
        max_texture_image_units: int(glow::MAX_TEXTURE_IMAGE_UNITS),
        max_vertex_texture_image_units: int(glow::MAX_VERTEX_TEXTURE_IMAGE_UNITS),
        max_vertex_uniform_components: int(glow::MAX_VERTEX_UNIFORM_COMPONENTS),
        max_fragment_uniform_components: int(glow::MAX_FRAGMENT_UNIFORM_COMPONENTS),
        max_vertex_attrib_stride: if gl_version >= (4, 4) {
            int(glow::MAX_VERTEX_ATTRIB_STRIDE)
        } else {
            2048
        },
        stencil_bits: stencil_bits(gl),
        samples_passed_counter_bits: counter_bits(glow::SAMPLES_PASSED),
        time_elapsed_counter_bits: counter_bits(glow::TIME_ELAPSED),
    };
    // Reading the limits must not leave an error behind for the first pass to report.
    while gl.get_error() != glow::NO_ERROR {}
    ContextInfo {
        platform,
        why,
        vendor: gl.get_parameter_string(glow::VENDOR),
        renderer: gl.get_parameter_string(glow::RENDERER),
        version: gl.get_parameter_string(glow::VERSION),
        glsl_version: gl.get_parameter_string(glow::SHADING_LANGUAGE_VERSION),
        gl_version,
        limits,
    }
}

/// Stencil bits of a DEPTH24_STENCIL8 attachment (a core context has no default framebuffer
/// to ask, so ask a small framebuffer object).
unsafe fn stencil_bits(gl: &glow::Context) -> u32 {
    let (Ok(fbo), Ok(rb)) = (gl.create_framebuffer(), gl.create_renderbuffer()) else {
        return 0;
    };
    gl.bind_renderbuffer(glow::RENDERBUFFER, Some(rb));
    gl.renderbuffer_storage(glow::RENDERBUFFER, glow::DEPTH24_STENCIL8, 1, 1);
    gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
    gl.framebuffer_renderbuffer(
        glow::FRAMEBUFFER,
        glow::DEPTH_STENCIL_ATTACHMENT,
        glow::RENDERBUFFER,
        Some(rb),
    );
    let bits = gl.get_framebuffer_attachment_parameter_i32(
        glow::FRAMEBUFFER,
        glow::STENCIL_ATTACHMENT,
        glow::FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE,
    );
    gl.bind_framebuffer(glow::FRAMEBUFFER, None);
    gl.delete_framebuffer(fbo);
    gl.delete_renderbuffer(rb);
    bits.max(0) as u32
}

// ---------------------------------------------------------------------------------------------
// EGL

type EglInstance = egl::DynamicInstance<egl::EGL1_5>;

const PLATFORM_DEVICE_EXT: egl::Enum = 0x313F;
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;
const DEVICE_EXTENSIONS: egl::Int = egl::EXTENSIONS;
const DRM_DEVICE_FILE_EXT: egl::Int = 0x3233;
const CONTEXT_MAJOR_VERSION: egl::Int = 0x3098;
const CONTEXT_MINOR_VERSION: egl::Int = 0x30FB;
const CONTEXT_OPENGL_PROFILE_MASK: egl::Int = 0x30FD;
const CONTEXT_OPENGL_CORE_PROFILE_BIT: egl::Int = 0x1;

type QueryDevicesExt = unsafe extern "system" fn(
    max_devices: egl::Int,
    devices: *mut *mut c_void,
    num_devices: *mut egl::Int,
) -> egl::Boolean;
type QueryDeviceStringExt =
    unsafe extern "system" fn(device: *mut c_void, name: egl::Int) -> *const std::ffi::c_char;

/// libEGL, loaded once per process.
fn egl_instance() -> Result<&'static EglInstance, String> {
    static EGL: OnceLock<Result<EglInstance, String>> = OnceLock::new();
    EGL.get_or_init(|| {
        // SAFETY: loading libEGL runs its initialisers, which have no preconditions.
        unsafe { EglInstance::load_required() }.map_err(|e| {
            format!(
                "libEGL could not be loaded ({e}); on Debian it is in the packages {MESA_PACKAGES}"
            )
        })
    })
    .as_ref()
    .map_err(Clone::clone)
}

fn client_extensions(egl: &EglInstance) -> String {
    egl.query_string(None, egl::EXTENSIONS)
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn egl_device_context() -> Result<(glow::Context, Platform), String> {
    let egl = egl_instance()?;
    let extensions = client_extensions(egl);
    if !extensions.contains("EGL_EXT_platform_device") {
        return Err("EGL_EXT_platform_device is not offered".into());
    }
    // NVIDIA offers EGL_EXT_device_base, which includes device enumeration.
    if !extensions.contains("EGL_EXT_device_enumeration")
        && !extensions.contains("EGL_EXT_device_base")
    {
        return Err("neither EGL_EXT_device_enumeration nor EGL_EXT_device_base is offered".into());
    }
    let query_devices: QueryDevicesExt = unsafe {
        std::mem::transmute(
            egl.get_proc_address("eglQueryDevicesEXT")
                .ok_or("eglQueryDevicesEXT is missing")?,
        )
    };
    let query_string: Option<QueryDeviceStringExt> = egl
        .get_proc_address("eglQueryDeviceStringEXT")
        .map(|f| unsafe { std::mem::transmute(f) });
    let mut devices = [std::ptr::null_mut::<c_void>(); 16];
    let mut count = 0;
    let ok = unsafe { query_devices(devices.len() as egl::Int, devices.as_mut_ptr(), &mut count) };
    if ok == egl::FALSE || count <= 0 {
        return Err("no EGL device found".into());
    }
    let mut skipped = Vec::new();
    for &device in &devices[..count as usize] {
        let device_extensions = query_string
            .map(|q| unsafe { cstr_or_empty(q(device, DEVICE_EXTENSIONS)) })
            .unwrap_or_default();
        // A software device is what the surfaceless platform gives too; a GPU is the point here.
        if device_extensions.contains("EGL_MESA_device_software") {
            skipped.push("a software device".to_string());
            continue;
        }
        let display =
            unsafe { egl.get_platform_display(PLATFORM_DEVICE_EXT, device, &[egl::ATTRIB_NONE]) };
        match display
            .map_err(|e| e.to_string())
            .and_then(|d| egl_context_on(egl, d))
        {
            Ok(made) => return Ok(made),
            Err(e) => {
                let name = query_string
                    .map(|q| unsafe { cstr_or_empty(q(device, DRM_DEVICE_FILE_EXT)) })
                    .unwrap_or_default();
                skipped.push(format!("device {name}: {e}"));
            }
        }
    }
    Err(format!(
        "no GPU device gave a context ({})",
        skipped.join(", ")
    ))
}

unsafe fn cstr_or_empty(p: *const std::ffi::c_char) -> String {
    if p.is_null() {
        String::new()
    } else {
        CStr::from_ptr(p).to_string_lossy().into_owned()
    }
}

fn egl_surfaceless_context() -> Result<(glow::Context, Platform), String> {
    let egl = egl_instance()?;
    if !client_extensions(egl).contains("EGL_MESA_platform_surfaceless") {
        return Err("EGL_MESA_platform_surfaceless is not offered".into());
    }
    let display = unsafe {
        egl.get_platform_display(
            PLATFORM_SURFACELESS_MESA,
            egl::DEFAULT_DISPLAY,
            &[egl::ATTRIB_NONE],
        )
    }
    .map_err(|e| e.to_string())?;
    egl_context_on(egl, display)
}

/// Initialise the display, pick a config, make a core context (newest version first) and
/// make it current without a surface.
fn egl_context_on(
    egl: &'static EglInstance,
    display: egl::Display,
) -> Result<(glow::Context, Platform), String> {
    egl.initialize(display)
        .map_err(|e| format!("eglInitialize: {e}"))?;
    let display_extensions = egl
        .query_string(Some(display), egl::EXTENSIONS)
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    if !display_extensions.contains("EGL_KHR_surfaceless_context") {
        return Err("EGL_KHR_surfaceless_context is not offered".into());
    }
    // Mesa's surfaceless platform finds no config without PBUFFER_BIT.
    let config_attribs = [
        egl::SURFACE_TYPE,
        egl::PBUFFER_BIT,
        egl::RENDERABLE_TYPE,
        egl::OPENGL_BIT,
        egl::NONE,
    ];
    let config = egl
        .choose_first_config(display, &config_attribs)
        .map_err(|e| format!("eglChooseConfig: {e}"))?
        .ok_or("no EGL config with PBUFFER_BIT and OPENGL_BIT")?;
    egl.bind_api(egl::OPENGL_API)
        .map_err(|e| format!("eglBindAPI(OpenGL): {e}"))?;
    let mut last_error = String::new();
    for (major, minor) in GL_VERSIONS {
        let attribs = [
            CONTEXT_MAJOR_VERSION,
            major,
            CONTEXT_MINOR_VERSION,
            minor,
            CONTEXT_OPENGL_PROFILE_MASK,
            CONTEXT_OPENGL_CORE_PROFILE_BIT,
            egl::NONE,
        ];
        match egl.create_context(display, config, None, &attribs) {
            Ok(context) => {
                egl.make_current(display, None, None, Some(context))
                    .map_err(|e| format!("eglMakeCurrent: {e}"))?;
                // SAFETY: the context is current; the loader returns its entry points.
                let gl = unsafe {
                    glow::Context::from_loader_function(|name| {
                        egl.get_proc_address(name)
                            .map_or(std::ptr::null(), |f| f as *const c_void)
                    })
                };
                return Ok((
                    gl,
                    Platform::Egl {
                        egl,
                        display,
                        context,
                    },
                ));
            }
            Err(e) => last_error = format!("OpenGL {major}.{minor} core: {e}"),
        }
    }
    Err(format!(
        "no OpenGL core context of version 3.3 or newer ({last_error})"
    ))
}

// ---------------------------------------------------------------------------------------------
// OSMesa

type OsCreate = unsafe extern "C" fn(*const i32, *mut c_void) -> *mut c_void;
type OsMakeCurrent = unsafe extern "C" fn(*mut c_void, *mut c_void, u32, i32, i32) -> u8;
type OsGetProcAddress = unsafe extern "C" fn(*const std::ffi::c_char) -> *const c_void;
type OsDestroy = unsafe extern "C" fn(*mut c_void);

struct OsMesa {
    _lib: libloading::Library,
    create: OsCreate,
    make_current: OsMakeCurrent,
    get_proc_address: OsGetProcAddress,
    destroy: OsDestroy,
}

// SAFETY: the function pointers are plain C entry points of a library that is never unloaded.
unsafe impl Send for OsMesa {}
unsafe impl Sync for OsMesa {}

const OSMESA_FORMAT: i32 = 0x22;
const OSMESA_RGBA: i32 = 0x1908;
const OSMESA_DEPTH_BITS: i32 = 0x30;
const OSMESA_STENCIL_BITS: i32 = 0x31;
const OSMESA_PROFILE: i32 = 0x33;
const OSMESA_CORE_PROFILE: i32 = 0x34;
const OSMESA_CONTEXT_MAJOR_VERSION: i32 = 0x36;
const OSMESA_CONTEXT_MINOR_VERSION: i32 = 0x37;

fn osmesa_library() -> Result<&'static OsMesa, String> {
    static OSMESA: OnceLock<Result<OsMesa, String>> = OnceLock::new();
    OSMESA
        .get_or_init(|| unsafe {
            let lib = ["libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"]
                .iter()
                .find_map(|name| libloading::Library::new(name).ok())
                .ok_or(
                    "libOSMesa could not be loaded; on Debian it is in the package libosmesa6",
                )?;
            let symbol = |name: &[u8]| -> Result<*const c_void, String> {
                lib.get::<*const c_void>(name)
                    .map(|s| *s)
                    .map_err(|e| format!("libOSMesa lacks {}: {e}", String::from_utf8_lossy(name)))
            };
            Ok(OsMesa {
                create: std::mem::transmute::<*const c_void, OsCreate>(symbol(
                    b"OSMesaCreateContextAttribs\0",
                )?),
                make_current: std::mem::transmute::<*const c_void, OsMakeCurrent>(symbol(
                    b"OSMesaMakeCurrent\0",
                )?),
                get_proc_address: std::mem::transmute::<*const c_void, OsGetProcAddress>(symbol(
                    b"OSMesaGetProcAddress\0",
                )?),
                destroy: std::mem::transmute::<*const c_void, OsDestroy>(symbol(
                    b"OSMesaDestroyContext\0",
                )?),
                _lib: lib,
            })
        })
        .as_ref()
        .map_err(Clone::clone)
}

fn osmesa_context() -> Result<(glow::Context, Platform), String> {
    let lib = osmesa_library()?;
    for (major, minor) in GL_VERSIONS {
        let attribs = [
            OSMESA_FORMAT,
            OSMESA_RGBA,
            OSMESA_DEPTH_BITS,
            24,
            OSMESA_STENCIL_BITS,
            8,
            OSMESA_PROFILE,
            OSMESA_CORE_PROFILE,
            OSMESA_CONTEXT_MAJOR_VERSION,
            major,
            OSMESA_CONTEXT_MINOR_VERSION,
            minor,
            0,
        ];
        // SAFETY: a zero-terminated attribute list and no share context.
        let context = unsafe { (lib.create)(attribs.as_ptr(), std::ptr::null_mut()) };
        if context.is_null() {
            continue;
        }
        // OSMesa needs a colour buffer to be current; everything here draws into FBOs.
        let mut buffer = vec![0u8; 4];
        let ok = unsafe {
            (lib.make_current)(
                context,
                buffer.as_mut_ptr().cast(),
                glow::UNSIGNED_BYTE,
                1,
                1,
            )
        };
        if ok == 0 {
            unsafe { (lib.destroy)(context) };
            return Err("OSMesaMakeCurrent failed".into());
        }
        let gl = unsafe {
            glow::Context::from_loader_function(|name| {
                let name = CString::new(name).expect("GL names have no NUL");
                (lib.get_proc_address)(name.as_ptr())
            })
        };
        return Ok((
            gl,
            Platform::OsMesa {
                lib,
                context,
                _buffer: buffer,
            },
        ));
    }
    Err("no OpenGL core context of version 3.3 or newer".into())
}
