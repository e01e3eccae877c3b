//! What the two paper-4 demos share: a strip of depth-peel insets, and the full view of one
//! peel's integrand target, cycled with `l` (layer), `t` (target) and `c` (the channel of the
//! strip). Every channel is on one scale for all the peels of the step, as `gl::dump` says.

use crate::mass::integrands::CHANNELS;
use crate::mass::peel::CapturedPeel;
use crate::view::inset::{self, Shown};
use crate::view::Canvas;

/// Which captured peel and which of its integrand targets (and, in the strip, channel) is
/// shown.
#[derive(Clone, Copy, Debug, Default)]
pub struct PeelChoice {
    pub layer: usize,
    pub target: usize,
    /// Counted from the last channel of the target (0: `V` of target 0, the volume).
    pub channel: usize,
}

impl PeelChoice {
    /// `l`: next layer; `t`: next integrand target; `c`: next channel. Whether the key was used.
    pub fn key(&mut self, key: &str, peels: &[CapturedPeel]) -> bool {
        match key {
            "l" => self.layer = (self.layer + 1) % peels.len().max(1),
            "t" => self.target = (self.target + 1) % CHANNELS.len(),
            "c" => self.channel += 1,
            _ => return false,
        }
        true
    }

    pub const KEYS: [(&'static str, &'static str); 3] = [
        ("l", "next peel layer"),
        ("t", "next integrand target"),
        ("c", "next channel (strip)"),
    ];

    fn target(&self) -> usize {
        self.target % CHANNELS.len()
    }

    /// The strip's channel of the chosen target.
    fn channel(&self) -> usize {
        let n = CHANNELS[self.target()].len();
        n - 1 - self.channel % n
    }

    /// The chosen peel's target filling `canvas`, one panel per channel.
    pub fn draw_full(&self, canvas: &Canvas, peels: &[CapturedPeel]) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        if peels.is_empty() {
            return Ok(());
        }
        let layer = self.layer % peels.len();
        let target = self.target();
        let shown: Vec<Shown> = CHANNELS[target]
            .iter()
            .enumerate()
            .map(|(c, name)| {
                let title = format!("peel {} of {}, {name}", layer + 1, peels.len());
                let scale = CapturedPeel::scale(peels, target, c);
                peels[layer].panel(target, c, &title, scale).into()
            })
            .collect();
        let rect = canvas.below_text();
        inset::draw_picture(canvas, shown, rect)?;
        Ok(())
    }

    /// Every peel's chosen channel along the bottom of `canvas`, on one scale.
    pub fn draw_strip(&self, canvas: &Canvas, peels: &[CapturedPeel]) -> anyhow::Result<()> {
        if peels.is_empty() {
            return Ok(());
        }
        let shown = peels.len().min(6);
        let (target, c) = (self.target(), self.channel());
        let scale = CapturedPeel::scale(&peels[..shown], target, c);
        let name = CHANNELS[target][c];
        let panels: Vec<Shown> = peels[..shown]
            .iter()
            .enumerate()
            .map(|(k, p)| -> Shown {
                p.panel(target, c, &format!("peel {} {name}", k + 1), scale)
                    .into()
            })
            .collect();
        let rect = inset::strip_rect(canvas, shown);
        inset::draw_picture(canvas, panels, rect)?;
        Ok(())
    }
}
