//! Shaders edited while the viewer runs (`view <demo> --glsl-dir DIR`): the window polls the
//! modification times of the shader files in DIR ten times a second ([`ShaderWatch`]); when
//! one changes, [`LiveDemo::reload`] builds the demo again from its [`DemoSpec`] on the same
//! context (which reads DIR), presses the same keys (`--keys`, then those pressed since, each
//! at its step) and replays as many steps as the running one has taken, at once between the
//! keys ([`Demo::advance`]: a lesson that iterates runs its passes and reads back once). If
//! any of that fails, the running demo is kept and the overlay shows why: the file and line,
//! and the driver's first message. Each reload is kept ([`LiveDemo::take_reload`]) for the
//! window to log how long after the save its frame was shown. Nothing here knows about
//! windows, so the headless tests drive it the same way the window does.

use super::{draw_frame, overlay, press_keys, Canvas, Demo, DemoSpec, ViewState};
use crate::gl::{shaders, Context, GlError};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

/// How often the window looks at the files: a saved shader shows within this and the
/// rebuild. A look is one `stat` per project shader, a fraction of a millisecond.
pub const POLL_INTERVAL: Duration = Duration::from_millis(100);

/// A file's modification time and length, or `None` when DIR does not have it.
type Stamp = Option<(SystemTime, u64)>;

/// The stamps of every project shader file under a folder; [`ShaderWatch::poll`] says which
/// changed (written, made, removed) since the last poll.
pub struct ShaderWatch {
    dir: PathBuf,
    stamps: Vec<Stamp>,
}

impl ShaderWatch {
    pub fn new(dir: &Path) -> ShaderWatch {
        ShaderWatch {
            dir: dir.to_path_buf(),
            stamps: stamps(dir),
        }
    }

    /// The shader files (repository paths) whose stamp changed since the last poll, and
    /// the latest modification time among those DIR still has (when they were saved).
    pub fn poll(&mut self) -> (Vec<&'static str>, Option<SystemTime>) {
        let now = stamps(&self.dir);
        let changed: Vec<(&'static str, Stamp)> = shaders::ALL
            .iter()
            .zip(self.stamps.iter().zip(&now))
            .filter(|(_, (before, after))| before != after)
            .map(|(s, (_, after))| (s.name, *after))
            .collect();
        self.stamps = now;
        let saved = changed.iter().filter_map(|(_, s)| s.map(|s| s.0)).max();
        (changed.into_iter().map(|(name, _)| name).collect(), saved)
    }
}

fn stamps(dir: &Path) -> Vec<Stamp> {
    shaders::ALL
        .iter()
        .map(|s| {
            let meta = std::fs::metadata(dir.join(s.name)).ok()?;
            Some((meta.modified().ok()?, meta.len()))
        })
        .collect()
}

/// A demo that can be rebuilt from its spec when its shaders change, keeping the last good one.
pub struct LiveDemo {
    spec: DemoSpec,
    size: (u32, u32),
    keys: String,
    /// The demo's keys pressed since (at which step, which key), replayed in that order.
    pressed: Vec<(usize, String)>,
    demo: Box<dyn Demo>,
    steps: usize,
    /// Why the last reload failed (cleared by one that works).
    error: Option<String>,
    watch: Option<ShaderWatch>,
    /// The last reload, until the window takes it to log.
    reload: Option<Reload>,
}

/// A reload as the window logs it once its frame is shown.
#[derive(Clone, Debug)]
pub struct Reload {
    /// The shader files that changed.
    pub files: Vec<&'static str>,
    /// When the last of them was saved (its modification time).
    pub saved: Option<SystemTime>,
    /// How long building the demo again and replaying its steps took.
    pub rebuild: Duration,
    /// The frame it was rebuilt at (the steps replayed; a lesson that iterates runs no more
    /// iterations than it has).
    pub steps: usize,
    /// Whether it worked (else the last good demo runs on, its error drawn).
    pub worked: bool,
}

impl Reload {
    /// The line the window logs once the frame after the reload is shown: how long after
    /// the save (the file's modification time; unknown when that is ahead of the clock).
    pub fn shown_line(&self) -> String {
        let after = self
            .saved
            .and_then(|saved| SystemTime::now().duration_since(saved).ok())
            .map_or("an unknown time".to_string(), |d| {
                format!("{:.0} ms", d.as_secs_f64() * 1e3)
            });
        format!(
            "reload shown: {} saved {after} before this frame ({}; rebuilt at frame {} in \
             {:.0} ms)",
            self.files.join(", "),
            if self.worked {
                "the new shaders run"
            } else {
                "it failed, its error is drawn"
            },
            self.steps,
            self.rebuild.as_secs_f64() * 1e3
        )
    }
}

impl LiveDemo {
    /// Build `spec` on `ctx`, press `keys`; with a `--glsl-dir` on `ctx`, watch its files.
    pub fn new(
        spec: &DemoSpec,
        ctx: &Context,
        size: (u32, u32),
        keys: &str,
    ) -> anyhow::Result<LiveDemo> {
        let watch = ctx.glsl_dir().map(|dir| ShaderWatch::new(&dir));
        let demo = build(spec, ctx, size, keys, &[], 0)?;
        Ok(LiveDemo {
            spec: spec.clone(),
            size,
            keys: keys.to_string(),
            pressed: Vec::new(),
            demo,
            steps: 0,
            error: None,
            watch,
            reload: None,
        })
    }

    pub fn demo(&mut self) -> &mut dyn Demo {
        self.demo.as_mut()
    }

    /// Steps taken (the frame number).
    pub fn steps(&self) -> usize {
        self.steps
    }

    pub fn step(&mut self) -> anyhow::Result<()> {
        self.demo.step()?;
        self.steps += 1;
        Ok(())
    }

    /// A key of the demo's own pressed in the window (remembered for reloads); whether the
    /// demo used it.
    pub fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        let used = self.demo.key(key)?;
        if used {
            self.pressed.push((self.steps, key.to_string()));
        }
        Ok(used)
    }

    /// Whether shader files are watched (a `--glsl-dir` was set).
    pub fn watching(&self) -> bool {
        self.watch.is_some()
    }

    /// Why the last reload failed, as drawn in the overlay; `None` after one that worked.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Look at the files (the window calls this every [`POLL_INTERVAL`]); reload when one
    /// changed. `Some(worked)` when a reload ran.
    pub fn poll(&mut self, ctx: &Context) -> Option<bool> {
        let (files, saved) = self.watch.as_mut()?.poll();
        if files.is_empty() {
            return None;
        }
        eprintln!("shader files changed: {}; reloading", files.join(", "));
        let started = Instant::now();
        let worked = self.reload(ctx);
        self.reload = Some(Reload {
            files,
            saved,
            rebuild: started.elapsed(),
            steps: self.steps,
            worked,
        });
        Some(worked)
    }

    /// The last reload [`LiveDemo::poll`] ran, once: the window logs it when its frame is
    /// shown.
    pub fn take_reload(&mut self) -> Option<Reload> {
        self.reload.take()
    }

    /// Build the demo again on `ctx` (its shaders read afresh), press the keys and replay the
    /// steps taken. On success it replaces the running demo; on failure the running demo stays
    /// and [`LiveDemo::error`] says why. Whether it worked.
    pub fn reload(&mut self, ctx: &Context) -> bool {
        match build(
            &self.spec,
            ctx,
            self.size,
            &self.keys,
            &self.pressed,
            self.steps,
        ) {
            Ok(demo) => {
                self.demo = demo;
                self.error = None;
                true
            }
            Err(e) => {
                let message = describe(&e);
                eprintln!("reload failed, the last good demo keeps running:\n{e:#}");
                self.error = Some(message);
                false
            }
        }
    }

    /// Draw the frame (as [`draw_frame`]) and, after a failed reload, its error at the bottom,
    /// wrapped to the canvas' width.
    pub fn draw(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        draw_frame(self.demo.as_mut(), canvas, view, self.steps)?;
        if let Some(error) = &self.error {
            let columns = overlay::columns(canvas.width());
            let mut lines = vec!["reload failed; still running the last good shaders:".to_string()];
            for line in error.lines() {
                lines.extend(crate::gl::picture::wrap(line, columns));
            }
            overlay::draw_text(canvas, &lines, overlay::Corner::BottomLeft)?;
        }
        Ok(())
    }
}

/// `spec` built on `ctx` with `keys` pressed, at frame `steps`: the keys pressed since at
/// their frames, the frames between them taken at once ([`Demo::advance`]).
fn build(
    spec: &DemoSpec,
    ctx: &Context,
    size: (u32, u32),
    keys: &str,
    pressed: &[(usize, String)],
    steps: usize,
) -> anyhow::Result<Box<dyn Demo>> {
    let mut demo = spec.build(ctx, size)?;
    press_keys(demo.as_mut(), keys)?;
    // The steps taken, at once between the keys pressed since (in the order of their steps).
    let mut at = 0;
    for (step, key) in pressed {
        demo.advance(step - at)?;
        demo.key(key)?;
        at = *step;
    }
    demo.advance(steps - at)?;
    Ok(demo)
}

/// A failed reload in a few words: for a shader that does not compile, `file:line: ` and the
/// driver's first message; otherwise the error's first line.
pub fn describe(e: &anyhow::Error) -> String {
    let shader = e.chain().find_map(|cause| match cause.downcast_ref() {
        Some(GlError::Shader(s)) => Some(s),
        _ => None,
    });
    match shader {
        Some(s) => {
            let place = match s.line {
                Some(line) => format!("{}:{line}", s.file),
                None => s.file.clone(),
            };
            let first = s
                .log
                .lines()
                .map(str::trim)
                .find(|l| !l.is_empty())
                .unwrap_or("(the driver gave no message)");
            let first = first
                .strip_prefix(&format!("{place}:"))
                .unwrap_or(first)
                .trim();
            format!("{place}: {first}")
        }
        None => format!("{e:#}")
            .lines()
            .next()
            .unwrap_or_default()
            .to_string(),
    }
}
