//! The live viewer: each paper's technique running in a window, its intermediate buffers one
//! key away (the tutorial's first debugging tip: draw the intermediate data to the screen).
//!
//! A demo ([`Demo`]) steps the same paper code the headless commands run and draws a frame into
//! a [`Canvas`], a framebuffer of the window's size. The window ([`window::run`]) copies the
//! canvas to its default framebuffer; [`headless`] draws the very same frame on a headless
//! context and writes it as PNG. So `view <demo> --frames N --screenshot FILE` (the window's
//! back buffer after frame N) can be compared with `view <demo> --headless --frames N
//! --screenshot FILE`, which is how the tests check the window.
//!
//! Only the window knows it is a window: the paper modules get a [`crate::gl::Context`] and
//! cannot tell a glutin one from a headless one.

pub mod canvas;
pub mod demos;
pub mod inset;
pub mod live;
pub mod overlay;
pub mod window;

pub use canvas::Canvas;
pub use demos::DemoSpec;

use crate::gl::Context;

/// What the user controls that changes a frame: the buffer shown, the camera, the help text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewState {
    /// Which of [`Demo::buffers`] is shown (Tab cycles); at the start `--buffer`'s, or the
    /// demo's [`Demo::first_buffer`] (see [`first_shown`]).
    pub shown: usize,
    /// Orbit angles in radians (mouse drag) and zoom factor (wheel), for 3D demos.
    pub yaw: f32,
    pub pitch: f32,
    pub zoom: f32,
    /// The help text is drawn over the frame (`h`).
    pub help: bool,
    /// The texel probe: the canvas pixel (top-left origin) under the mouse, or `--probe X,Y`.
    pub probe: Option<(u32, u32)>,
}

impl Default for ViewState {
    fn default() -> Self {
        ViewState {
            shown: 0,
            yaw: 0.0,
            pitch: 0.0,
            zoom: 1.0,
            help: false,
            probe: None,
        }
    }
}

/// One technique as a live demo. A demo's frame depends only on how many steps it has taken and
/// on the [`ViewState`], never on the wall clock, so that a window and a headless run of the
/// same frame give the same picture.
pub trait Demo {
    /// Advance by one frame (one step of the paper's technique).
    fn step(&mut self) -> anyhow::Result<()>;
    /// Advance by `steps` frames at once, to the state as many [`Demo::step`]s reach (a
    /// reload replays the frames taken so): a demo that reads back or checks at each step
    /// does it once at the end.
    fn advance(&mut self, steps: usize) -> anyhow::Result<()> {
        for _ in 0..steps {
            self.step()?;
        }
        Ok(())
    }
    /// Draw the current frame into `canvas`; `view.shown` picks the buffer.
    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()>;
    /// The names of the buffers Tab cycles through; the first is the scene. Every buffer the
    /// demo makes, from the first frame on, each keeping its number at every step.
    fn buffers(&self) -> Vec<String>;
    /// Lines of text drawn in the frame's top-left corner (no timings: they differ per run).
    fn overlay(&self) -> Vec<String>;
    /// The last step's per-pass timings, for the window title.
    fn timings(&self) -> String;
    /// The demo's own keys and what they do, for the help text.
    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }
    /// A key press (`winit`'s logical key text, e.g. "l", "+"); whether the demo used it.
    fn key(&mut self, _key: &str) -> anyhow::Result<bool> {
        Ok(false)
    }
    /// The buffer `view.shown` picks, told before the overlay is measured, for a demo whose
    /// overlay describes the buffer shown.
    fn show(&mut self, _shown: usize) {}
    /// The buffer shown first when `--buffer` does not say: one that changes as the demo
    /// steps (the scene, the latest iterate).
    fn first_buffer(&self) -> usize {
        0
    }
}

/// The keys every demo has, for the help text.
pub const COMMON_KEYS: [(&str, &str); 9] = [
    ("space", "pause / run"),
    ("right", "one step"),
    ("tab", "next buffer"),
    ("drag", "orbit (3D)"),
    ("wheel", "zoom in / out (3D)"),
    ("mouse", "probe a buffer's texel"),
    ("s", "save a PNG"),
    ("h", "this help"),
    ("esc", "quit"),
];

/// The buffer shown first: `buffer` (`--buffer`) when given, else the demo's own
/// [`Demo::first_buffer`]. Refuses a buffer the demo does not make, naming those it makes.
pub fn first_shown(demo: &dyn Demo, buffer: Option<usize>) -> anyhow::Result<usize> {
    let Some(shown) = buffer else {
        return Ok(demo.first_buffer());
    };
    let buffers = demo.buffers();
    if shown >= buffers.len() {
        anyhow::bail!(
            "--buffer {shown}: this demo has {} buffers, 0 to {}: {}",
            buffers.len(),
            buffers.len().saturating_sub(1),
            buffers
                .iter()
                .enumerate()
                .map(|(i, b)| format!("{i} {b}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(shown)
}

/// Draw frame `frames` of `demo` (after that many steps) on `canvas`, with the overlay text,
/// the probe's readout when `view.probe` points somewhere and, if `view.help`, the help, as
/// the window shows it. The probe's lines (empty without a probe).
pub fn draw_frame(
    demo: &mut dyn Demo,
    canvas: &Canvas,
    view: &ViewState,
    frame: usize,
) -> anyhow::Result<Vec<String>> {
    let text = |demo: &dyn Demo| {
        let buffers = demo.buffers();
        let shown = buffers
            .get(view.shown % buffers.len().max(1))
            .cloned()
            .unwrap_or_default();
        let mut lines = vec![format!("frame {frame}  [tab] {shown}  [h] help")];
        lines.extend(demo.overlay());
        lines
    };
    // The demo draws its buffers below the text (measured before, drawn after it). Where
    // drawing changed the text so that it needs more room (a figure the frame measured, a
    // line that now wraps), the frame is drawn again below the taller text, so that the text
    // never covers a panel's title.
    demo.show(view.shown);
    let height = |lines: &[String]| overlay::text_height(lines, canvas.width(), canvas.height());
    let mut measured = height(&text(demo));
    loop {
        canvas.set_text_height(measured);
        canvas.clear_probed();
        demo.render(canvas, view)?;
        let needed = height(&text(demo));
        if needed <= measured {
            break;
        }
        measured = needed;
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
    }
    overlay::draw_text(canvas, &text(demo), overlay::Corner::TopLeft)?;
    if view.help {
        let mut help = vec!["keys".to_string()];
        for (key, what) in COMMON_KEYS.iter().chain(demo.keys().iter()) {
            help.push(format!("{key:>6}  {what}"));
        }
        overlay::draw_text(canvas, &help, overlay::Corner::Centre)?;
    }
    let Some((x, y)) = view.probe else {
        return Ok(Vec::new());
    };
    // Only over a buffer is a readout drawn; elsewhere (the text, the background) nothing is,
    // so no label is left standing where no texel is, and the line comes back for `--probe`.
    let Some(probe) = canvas.probe_buffer((x, y)) else {
        return Ok(canvas.probe((x, y)));
    };
    // Beside the pointer (below and right of it, moved inside the frame where it must be).
    let below = canvas.height().saturating_sub(y + 12);
    overlay::draw_text(canvas, &probe, overlay::Corner::Probe(x + 12, below))?;
    Ok(probe)
}

/// Press the demo's own keys `keys` (one character each) in order: a demo's settings as a
/// command line gives them (`--keys mc`), the same in the window and headless.
pub fn press_keys(demo: &mut dyn Demo, keys: &str) -> anyhow::Result<()> {
    for c in keys.chars() {
        if !demo.key(&c.to_string())? {
            let known: Vec<&str> = demo.keys().iter().map(|(k, _)| *k).collect();
            anyhow::bail!(
                "--keys: '{c}' is not a key of this demo (its keys: {})",
                if known.is_empty() {
                    "none".to_string()
                } else {
                    known.join(", ")
                }
            );
        }
    }
    Ok(())
}

/// The headless path: build `spec` on `ctx`, press `keys`, take `frames` steps and draw the
/// last frame into a `width x height` canvas; the RGBA pixels, rows from the bottom (as the
/// window reads them).
pub fn headless(
    spec: &DemoSpec,
    ctx: &Context,
    size: (u32, u32),
    frames: usize,
    view: &ViewState,
    keys: &str,
) -> anyhow::Result<Vec<u8>> {
    Ok(headless_frame(spec, ctx, size, frames, view, keys)?.0)
}

/// [`headless`], and the probe's lines (empty without `view.probe`).
pub fn headless_frame(
    spec: &DemoSpec,
    ctx: &Context,
    size: (u32, u32),
    frames: usize,
    view: &ViewState,
    keys: &str,
) -> anyhow::Result<(Vec<u8>, Vec<String>)> {
    headless_opening(spec, ctx, size, frames, view, keys, Some(view.shown))
}

/// [`headless_frame`] showing `buffer` (`--buffer`) when given, else the demo's own first
/// buffer ([`first_shown`]), as `view --headless` does.
pub fn headless_opening(
    spec: &DemoSpec,
    ctx: &Context,
    (width, height): (u32, u32),
    frames: usize,
    view: &ViewState,
    keys: &str,
    buffer: Option<usize>,
) -> anyhow::Result<(Vec<u8>, Vec<String>)> {
    let mut demo = spec.build(ctx, (width, height))?;
    let view = ViewState {
        shown: first_shown(demo.as_ref(), buffer)?,
        ..*view
    };
    press_keys(demo.as_mut(), keys)?;
    for _ in 0..frames {
        demo.step()?;
    }
    let canvas = Canvas::new(ctx, width, height)?;
    let probe = draw_frame(demo.as_mut(), &canvas, &view, frames)?;
    Ok((canvas.pixels()?, probe))
}

/// Write RGBA pixels (rows from the bottom) as a PNG.
pub fn write_png(
    pixels: &[u8],
    (width, height): (u32, u32),
    path: &std::path::Path,
) -> anyhow::Result<()> {
    // The folder is made by the write (`files::write`), which names a part that is a file.
    Ok(crate::gl::dump::rgba_png(pixels, (width, height), path)?)
}
