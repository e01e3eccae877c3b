//! What each written figure shows, told by the code that drew it: a plot's axis titles, tick
//! labels and legend; a picture's panel titles, colour keys and texel scale; or that it is a
//! rendered frame. The report keeps one [`Drawn`] per figure (in `results.json`), and
//! [`Drawn::problems`] names what would keep a reader from reading the figure without the code:
//! the figure test fails on any.

use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// One written figure, as drawn.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Drawn {
    /// A line or point plot ([`crate::page::plot`]).
    Plot(PlotDrawn),
    /// Float buffers as panels through the colour map ([`super::picture::picture`]).
    Picture(PictureDrawn),
    /// Rendered frames side by side, each titled, with a legend of the colours that mean
    /// something ([`super::picture::frames_picture`]).
    Frames(FramesDrawn),
    /// Float data mapped to colours with no key (a bare dump): never readable on its own.
    BareFloats { what: String },
    /// A rendered frame or a photograph: colours are the scene's, no key to give.
    Image { what: String },
}

/// A plot's readable parts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PlotDrawn {
    pub title: String,
    pub x_title: String,
    pub y_title: String,
    /// The tick labels drawn on each axis, in order.
    pub x_ticks: Vec<String>,
    pub y_ticks: Vec<String>,
    /// The legend's entries (identical series share one: "A = B").
    pub legend: Vec<String>,
    /// Data curves drawn (reference lines not counted).
    pub curves: usize,
    /// Lines under the legend: off-scale and zero marks, reference lines.
    pub notes: Vec<String>,
    /// The height of its smallest text (tick labels, legend), pixels (0: not recorded).
    #[serde(default)]
    pub text_px: u32,
}

/// One panel of a picture.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PanelDrawn {
    pub title: String,
    /// Lines the title took.
    pub title_lines: usize,
    /// The colour key's range, as printed under the panel.
    pub key: (String, String),
    /// The buffer's size in texels and the image's size in pixels.
    pub texels: (u32, u32),
    pub pixels: (u32, u32),
    /// The share of its texels that are not zero (drawn in a colour other than zero's grey).
    #[serde(default = "all_filled")]
    pub filled: f32,
}

fn all_filled() -> f32 {
    1.0
}

/// A panel with fewer than one texel in a thousand not zero shows almost nothing: such data
/// is better said in numbers or drawn with the others (the figure test refuses it).
pub const MOSTLY_EMPTY: f32 = 0.001;

impl PanelDrawn {
    /// Every texel a whole block of pixels (integer magnification, none dropped).
    pub fn whole_texels(&self) -> bool {
        let whole = |t: u32, p: u32| t > 0 && p >= t && p.is_multiple_of(t);
        whole(self.texels.0, self.pixels.0) && whole(self.texels.1, self.pixels.1)
    }
}

/// A picture's panels.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PictureDrawn {
    pub panels: Vec<PanelDrawn>,
    /// The height of its smallest text (titles, key numbers), pixels (0: not recorded).
    #[serde(default)]
    pub text_px: u32,
}

/// One rendered frame of a [`FramesDrawn`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FrameDrawn {
    pub title: String,
    pub title_lines: usize,
    /// The frame's size and its size in the picture, pixels.
    pub pixels: (u32, u32),
    pub shown: (u32, u32),
}

/// Frames and their colour legend.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FramesDrawn {
    pub frames: Vec<FrameDrawn>,
    pub legend: Vec<String>,
    /// The height of its smallest text (titles, legend), pixels (0: not recorded).
    #[serde(default)]
    pub text_px: u32,
}

/// The most lines a panel title may wrap to.
pub const MAX_TITLE_LINES: usize = 3;

/// The least height, pixels, of any text as a reader sees it on the page.
pub const MIN_TEXT_SHOWN_PX: f64 = 12.0;

impl Drawn {
    /// The height of the figure's smallest text in its own pixels, where it has text (`None`
    /// for a rendered frame or bare data, which carry none).
    pub fn text_px(&self) -> Option<u32> {
        match self {
            Drawn::Plot(p) => Some(p.text_px),
            Drawn::Picture(p) => Some(p.text_px),
            Drawn::Frames(f) => Some(f.text_px),
            Drawn::BareFloats { .. } | Drawn::Image { .. } => None,
        }
    }

    /// What keeps the figure from being read where it is shown at `scale` of its size (1 at
    /// full size): its [`Drawn::problems`], and text smaller than [`MIN_TEXT_SHOWN_PX`] there.
    pub fn problems_shown_at(&self, scale: f64) -> Vec<String> {
        let mut out = self.problems();
        if let Some(px) = self.text_px() {
            let shown = px as f64 * scale;
            if shown < MIN_TEXT_SHOWN_PX {
                out.push(format!(
                    "its smallest text is {px} px, {shown:.1} px as shown at {:.0}% (at least \
                     {MIN_TEXT_SHOWN_PX} px)",
                    100.0 * scale
                ));
            }
        }
        out
    }

    /// What keeps the figure from being read without the code; empty when nothing does.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        match self {
            Drawn::Plot(p) => {
                for (what, text) in [
                    ("title", &p.title),
                    ("x axis title", &p.x_title),
                    ("y axis title", &p.y_title),
                ] {
                    if text.trim().is_empty() {
                        out.push(format!("no {what}"));
                    }
                }
                for (axis, ticks) in [("x", &p.x_ticks), ("y", &p.y_ticks)] {
                    let labelled = ticks.iter().filter(|t| !t.trim().is_empty()).count();
                    if labelled < 2 {
                        out.push(format!("{labelled} labelled tick(s) on the {axis} axis"));
                    }
                }
                if p.curves == 0 {
                    out.push("no curve".into());
                }
                if p.curves >= 2 && p.legend.len() < p.curves {
                    out.push(format!(
                        "{} curves but {} legend entries",
                        p.curves,
                        p.legend.len()
                    ));
                }
                if p.legend.iter().any(|l| l.trim().is_empty()) {
                    out.push("a legend entry without a name".into());
                }
            }
            Drawn::Picture(p) => {
                if p.panels.is_empty() {
                    out.push("no panel".into());
                }
                for (i, panel) in p.panels.iter().enumerate() {
                    let name = format!("panel {} '{}'", i + 1, panel.title);
                    if panel.title.trim().is_empty() {
                        out.push(format!("panel {} has no title", i + 1));
                    }
                    if panel.title_lines > MAX_TITLE_LINES {
                        out.push(format!(
                            "{name}: title wraps {} lines (at most {MAX_TITLE_LINES})",
                            panel.title_lines
                        ));
                    }
                    if panel.key.0.is_empty() || panel.key.1.is_empty() {
                        out.push(format!("{name}: no colour key"));
                    }
                    if panel.filled < MOSTLY_EMPTY {
                        out.push(format!(
                            "{name}: mostly empty ({:.2}% of its texels not zero)",
                            100.0 * panel.filled
                        ));
                    }
                    if !panel.whole_texels() {
                        out.push(format!(
                            "{name}: {}x{} texels drawn in {}x{} pixels (not whole texels)",
                            panel.texels.0, panel.texels.1, panel.pixels.0, panel.pixels.1
                        ));
                    }
                }
                let mut titles: Vec<&str> = p.panels.iter().map(|q| q.title.as_str()).collect();
                titles.sort_unstable();
                titles.dedup();
                if titles.len() < p.panels.len() {
                    out.push("two panels with the same title".into());
                }
            }
            Drawn::Frames(f) => {
                if f.frames.is_empty() {
                    out.push("no frame".into());
                }
                for (i, frame) in f.frames.iter().enumerate() {
                    let name = format!("frame {} '{}'", i + 1, frame.title);
                    if f.frames.len() > 1 && frame.title.trim().is_empty() {
                        out.push(format!(
                            "frame {} of {} has no title",
                            i + 1,
                            f.frames.len()
                        ));
                    }
                    if frame.title_lines > MAX_TITLE_LINES {
                        out.push(format!("{name}: title wraps {} lines", frame.title_lines));
                    }
                    let whole = |p: u32, s: u32| p > 0 && s >= p && s.is_multiple_of(p);
                    if !(whole(frame.pixels.0, frame.shown.0)
                        && whole(frame.pixels.1, frame.shown.1))
                    {
                        out.push(format!(
                            "{name}: {}x{} pixels shown at {}x{} (not a whole factor)",
                            frame.pixels.0, frame.pixels.1, frame.shown.0, frame.shown.1
                        ));
                    }
                }
            }
            Drawn::BareFloats { what } => {
                out.push(format!("float data ({what}) drawn without a colour key"));
            }
            Drawn::Image { what } => {
                if what.trim().is_empty() {
                    out.push("an image that does not say what it shows".into());
                }
            }
        }
        out
    }
}

/// Every figure written by this process, by path.
static DRAWN: Mutex<Option<HashMap<PathBuf, Drawn>>> = Mutex::new(None);

/// Note that the PNG at `path` shows `drawn` (the last write of a path wins).
pub fn record(path: &Path, drawn: Drawn) {
    let mut map = DRAWN.lock().unwrap_or_else(|e| e.into_inner());
    map.get_or_insert_with(HashMap::new)
        .insert(path.to_path_buf(), drawn);
}

/// What the PNG at `path` shows, if this process wrote it.
pub fn recorded(path: &Path) -> Option<Drawn> {
    let map = DRAWN.lock().unwrap_or_else(|e| e.into_inner());
    map.as_ref().and_then(|m| m.get(path).cloned())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plot() -> PlotDrawn {
        PlotDrawn {
            title: "t".into(),
            x_title: "n".into(),
            y_title: "ms".into(),
            x_ticks: vec!["1".into(), "10".into()],
            y_ticks: vec!["0".into(), "5".into()],
            legend: vec!["a".into(), "b".into()],
            curves: 2,
            notes: vec![],
            text_px: 14,
        }
    }

    #[test]
    fn a_readable_plot_has_no_problems_and_each_missing_part_is_named() {
        assert!(Drawn::Plot(plot()).problems().is_empty());
        let one_tick = Drawn::Plot(PlotDrawn {
            y_ticks: vec!["1".into(), String::new()],
            ..plot()
        });
        assert_eq!(
            one_tick.problems(),
            ["1 labelled tick(s) on the y axis".to_string()]
        );
        let no_title = Drawn::Plot(PlotDrawn {
            x_title: " ".into(),
            legend: vec!["a".into()],
            ..plot()
        });
        assert_eq!(no_title.problems().len(), 2, "{:?}", no_title.problems());
    }

    #[test]
    fn pictures_need_titles_keys_and_whole_texels() {
        let panel = PanelDrawn {
            title: "P0".into(),
            title_lines: 1,
            key: ("0".into(), "1".into()),
            texels: (64, 8),
            pixels: (256, 32),
            filled: 0.5,
        };
        let good = Drawn::Picture(PictureDrawn {
            panels: vec![panel.clone()],
            text_px: 16,
        });
        assert!(good.problems().is_empty());
        let shrunk = PanelDrawn {
            pixels: (48, 6),
            ..panel.clone()
        };
        let wrapped = PanelDrawn {
            title: "P1".into(),
            title_lines: 6,
            ..panel.clone()
        };
        let empty = PanelDrawn {
            title: "peel 5".into(),
            filled: 0.0003,
            ..panel.clone()
        };
        let bad = Drawn::Picture(PictureDrawn {
            panels: vec![panel, shrunk, wrapped, empty],
            text_px: 16,
        });
        let problems = bad.problems();
        assert_eq!(problems.len(), 4, "{problems:?}");
        assert!(
            problems
                .iter()
                .any(|p| p.contains("'peel 5': mostly empty")),
            "{problems:?}"
        );
        // 16-pixel text reads at full size and at 75%, not at half.
        assert!(good.problems_shown_at(1.0).is_empty());
        assert!(good.problems_shown_at(0.75).is_empty());
        assert_eq!(good.problems_shown_at(0.5).len(), 1);
        assert_eq!(
            Drawn::Image {
                what: "a frame".into()
            }
            .text_px(),
            None
        );
        assert!(!Drawn::BareFloats { what: "x".into() }.problems().is_empty());
    }

    #[test]
    fn the_record_keeps_the_last_write_of_a_path() {
        let path = Path::new("/nowhere/drawn-test.png");
        record(path, Drawn::BareFloats { what: "a".into() });
        record(path, Drawn::Image { what: "b".into() });
        assert_eq!(recorded(path), Some(Drawn::Image { what: "b".into() }));
    }
}
