//! The window: a winit event loop around a demo. Each tick steps the demo, draws the frame
//! into the canvas and copies the canvas to the window; keys and the mouse change the
//! [`ViewState`]; the title shows the frame time and the demo's per-pass timings.

use super::live::{LiveDemo, POLL_INTERVAL};
use super::{write_png, Canvas, DemoSpec, ViewState};
use crate::gl::GlWindow;
use anyhow::anyhow;
use std::path::{Path, PathBuf};
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{WindowAttributes, WindowId};

/// How the window runs.
#[derive(Clone, Debug)]
pub struct WindowOptions {
    /// The window's inner size in pixels.
    pub size: (u32, u32),
    /// Run this many frames, then (with `screenshot`) save the window and quit.
    pub frames: Option<usize>,
    /// Where `--frames` writes the window's contents.
    pub screenshot: Option<PathBuf>,
    /// Start paused.
    pub paused: bool,
    /// The first view (help, probe); the buffer it shows is `buffer`'s.
    pub view: ViewState,
    /// `--buffer`: the buffer shown first; `None`: the demo's own ([`super::first_shown`]).
    pub buffer: Option<usize>,
    /// The demo's own keys pressed before the first frame.
    pub keys: String,
    /// `--glsl-dir`: shaders read from this folder, and reloaded when saved there.
    pub glsl_dir: Option<PathBuf>,
}

/// Open the window and run `spec` until Esc, or for `options.frames` frames. Without a
/// display, or without an OpenGL 3.3 context, a one-line error naming what is missing and the
/// headless command that does the same work.
pub fn run(spec: &DemoSpec, options: WindowOptions) -> anyhow::Result<()> {
    let hint = spec.headless_hint();
    let display_unset = |name: &str| std::env::var_os(name).is_none_or(|v| v.is_empty());
    if display_unset("DISPLAY") {
        let wayland = if display_unset("WAYLAND_DISPLAY") {
            "nor WAYLAND_DISPLAY is set"
        } else {
            "is set (the viewer opens X11 windows; under Wayland it needs XWayland)"
        };
        return Err(anyhow!(
            "no display: neither DISPLAY {wayland}; the headless command {hint} does the same \
             work without one"
        ));
    }
    let event_loop = EventLoop::new().map_err(|e| {
        let e = without_source_path(&e.to_string());
        anyhow!("no display ({e}); the headless command {hint} does the same work")
    })?;
    let mut app = App {
        spec,
        options,
        running: None,
        error: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| anyhow!("the window's event loop failed: {e}"))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct App<'a> {
    spec: &'a DemoSpec,
    options: WindowOptions,
    running: Option<Running>,
    error: Option<anyhow::Error>,
}

/// A window with its demo.
struct Running {
    // Dropped in this order: the demo's and the canvas' GL objects before the window.
    demo: LiveDemo,
    canvas: Canvas,
    window: GlWindow,
    view: ViewState,
    paused: bool,
    step_once: bool,
    redraw: bool,
    drag: Option<(f64, f64)>,
    cursor: (f64, f64),
    frame_ms: f64,
    /// When the shader files were last looked at (`--glsl-dir`).
    polled: Instant,
}

impl App<'_> {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<Running> {
        let (w, h) = self.options.size;
        let attributes = WindowAttributes::default()
            .with_title(format!("classic-gpgpu view {}", self.spec.name()))
            .with_inner_size(PhysicalSize::new(w, h))
            .with_resizable(self.options.frames.is_none());
        let window =
            GlWindow::new(event_loop, attributes, self.options.frames.is_none()).map_err(|e| {
                anyhow!(
                    "{}; the headless command {} does the same work",
                    without_source_path(&e.to_string()),
                    self.spec.headless_hint()
                )
            })?;
        let size = window.window().inner_size();
        let size = (size.width.max(1), size.height.max(1));
        let ctx = window.context().clone();
        let info = ctx.info();
        eprintln!("window: {} ({})", info.renderer_line(), info.why);
        ctx.set_glsl_dir(self.options.glsl_dir.clone());
        let mut demo = LiveDemo::new(self.spec, &ctx, size, &self.options.keys)?;
        let shown = super::first_shown(demo.demo(), self.options.buffer)?;
        let canvas = Canvas::new(&ctx, size.0, size.1)?;
        Ok(Running {
            demo,
            canvas,
            window,
            view: ViewState {
                shown,
                ..self.options.view
            },
            paused: self.options.paused,
            step_once: false,
            redraw: true,
            drag: None,
            cursor: (0.0, 0.0),
            frame_ms: 0.0,
            polled: Instant::now(),
        })
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }

    /// Step (unless paused), draw, show; after `--frames` frames save and quit.
    fn tick(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        if r.polled.elapsed() >= POLL_INTERVAL {
            r.polled = Instant::now();
            let ctx = r.window.context().clone();
            if r.demo.poll(&ctx).is_some() {
                r.redraw = true;
            }
        }
        let advance = !r.paused || r.step_once;
        if !advance && !r.redraw {
            return Ok(());
        }
        let started = Instant::now();
        if advance {
            r.demo.step()?;
            r.step_once = false;
        }
        r.demo.draw(&r.canvas, &r.view)?;
        r.window.present(r.canvas.target())?;
        r.redraw = false;
        if self.options.frames == Some(r.demo.steps()) {
            if let Some(path) = &self.options.screenshot {
                let size = (r.canvas.width(), r.canvas.height());
                let pixels = r.window.read_pixels(size.0, size.1)?;
                write_png(&pixels, size, path)?;
            }
            event_loop.exit();
            return Ok(());
        }
        r.window.swap()?;
        // A reload's frame is on the screen now: how long after the save.
        if let Some(reload) = r.demo.take_reload() {
            eprintln!("{}", reload.shown_line());
        }
        if advance {
            r.frame_ms = started.elapsed().as_secs_f64() * 1e3;
        }
        let state = if r.paused { "paused" } else { "running" };
        r.window.window().set_title(&format!(
            "classic-gpgpu view {} | frame {} {state} | {:.1} ms/frame | {}",
            self.spec.name(),
            r.demo.steps(),
            r.frame_ms,
            r.demo.demo().timings()
        ));
        Ok(())
    }

    fn key(&mut self, event_loop: &ActiveEventLoop, key: &Key) -> anyhow::Result<()> {
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        match key {
            Key::Named(NamedKey::Escape) => event_loop.exit(),
            // Some keyboard layouts report the space bar as the text " ".
            Key::Named(NamedKey::Space) => r.paused = !r.paused,
            Key::Character(c) if c.as_str() == " " => r.paused = !r.paused,
            Key::Named(NamedKey::ArrowRight) => r.step_once = true,
            Key::Named(NamedKey::Tab) => {
                r.view.shown = (r.view.shown + 1) % r.demo.demo().buffers().len().max(1);
            }
            Key::Character(c) if c.as_str() == "h" => r.view.help = !r.view.help,
            Key::Character(c) if c.as_str() == "s" => {
                let path = free_path(&format!(
                    "classic-gpgpu-{}-frame{}",
                    self.spec.name().replace(' ', "-"),
                    r.demo.steps()
                ));
                let pixels = r.canvas.pixels()?;
                write_png(&pixels, (r.canvas.width(), r.canvas.height()), &path)?;
                eprintln!("saved {}", path.display());
            }
            Key::Character(c) => {
                r.demo.key(c.as_str())?;
            }
            _ => return Ok(()),
        }
        r.redraw = true;
        Ok(())
    }

    fn event(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent) -> anyhow::Result<()> {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                self.key(event_loop, &event.logical_key)?;
            }
            WindowEvent::Resized(size) => {
                if let Some(r) = self.running.as_mut() {
                    let (w, h) = (size.width.max(1), size.height.max(1));
                    if (w, h) != (r.canvas.width(), r.canvas.height()) {
                        r.window.resize(w, h);
                        r.canvas = Canvas::new(r.window.context(), w, h)?;
                        r.redraw = true;
                    }
                }
            }
            WindowEvent::RedrawRequested => {
                if let Some(r) = self.running.as_mut() {
                    r.redraw = true;
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                if let Some(r) = self.running.as_mut() {
                    r.drag = (state == ElementState::Pressed).then_some(r.cursor);
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let Some(r) = self.running.as_mut() {
                    r.cursor = (position.x, position.y);
                    // The probe follows the mouse, unless the command line fixed it (a
                    // scripted run draws the frame it names, wherever the pointer is).
                    if self.options.view.probe.is_none() && self.options.frames.is_none() {
                        let (x, y) = (position.x.max(0.0) as u32, position.y.max(0.0) as u32);
                        r.view.probe = Some((x, y));
                        r.redraw = true;
                    }
                    if let Some((x, y)) = r.drag {
                        r.view.yaw += ((position.x - x) * 0.01) as f32;
                        r.view.pitch =
                            (r.view.pitch + ((position.y - y) * 0.01) as f32).clamp(-1.5, 1.5);
                        r.drag = Some(r.cursor);
                        r.redraw = true;
                    }
                }
            }
            WindowEvent::CursorLeft { .. } => {
                if let Some(r) = self.running.as_mut() {
                    if self.options.view.probe.is_none() {
                        r.view.probe = None;
                        r.redraw = true;
                    }
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                if let Some(r) = self.running.as_mut() {
                    let lines = match delta {
                        MouseScrollDelta::LineDelta(_, y) => y,
                        MouseScrollDelta::PixelDelta(p) => (p.y / 40.0) as f32,
                    };
                    // Wheel away from the user (positive lines) brings the scene closer.
                    r.view.zoom = (r.view.zoom * 1.1f32.powf(lines)).clamp(0.1, 10.0);
                    r.redraw = true;
                }
            }
            _ => {}
        }
        Ok(())
    }
}

impl ApplicationHandler for App<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() || self.error.is_some() {
            return;
        }
        match self.start(event_loop) {
            Ok(running) => self.running = Some(running),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let Err(e) = self.event(event_loop, event) {
            self.fail(event_loop, e);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Err(e) = self.tick(event_loop) {
            self.fail(event_loop, e);
            return;
        }
        let idle = self.running.as_ref().is_none_or(|r| r.paused && !r.redraw);
        let watching = self.running.as_ref().filter(|r| r.demo.watching());
        event_loop.set_control_flow(if let (true, Some(r)) = (idle, watching) {
            // Paused, but the shader files are still looked at.
            ControlFlow::WaitUntil(r.polled + POLL_INTERVAL)
        } else if idle {
            ControlFlow::Wait
        } else {
            ControlFlow::Poll
        });
    }
}

/// `stem.png`, or `stem-1.png`, `stem-2.png`, ... : the first that does not exist.
fn free_path(stem: &str) -> PathBuf {
    let mut path = PathBuf::from(format!("{stem}.png"));
    let mut n = 1;
    while Path::new(&path).exists() {
        path = PathBuf::from(format!("{stem}-{n}.png"));
        n += 1;
    }
    path
}

/// `text` without the source location winit puts in its OS errors ("os error at
/// /home/.cargo/registry/.../x11/mod.rs:123: "), which says nothing to a user.
pub fn without_source_path(text: &str) -> String {
    let Some(start) = text.find("os error at ") else {
        return text.to_string();
    };
    let rest = &text[start + "os error at ".len()..];
    let Some(rs) = rest.find(".rs:") else {
        return text.to_string();
    };
    let after = rest[rs + ".rs:".len()..].trim_start_matches(|c: char| c.is_ascii_digit());
    let after = after.strip_prefix(':').unwrap_or(after).trim_start();
    format!("{}{after}", &text[..start])
}

#[cfg(test)]
mod source_path_tests {
    #[test]
    fn the_source_location_of_an_os_error_is_dropped() {
        let text = "os error at /root/.cargo/registry/src/index.crates.io-1/winit-0.30.12/src/\
                    platform_impl/linux/mod.rs:765: failed to open display :99";
        assert_eq!(
            super::without_source_path(text),
            "failed to open display :99"
        );
        assert_eq!(super::without_source_path("no display"), "no display");
    }
}
