//! What the two paper-4 demos share: a strip of depth-peel insets, and the full view of one
//! peel's integrand target, cycled with `l` (layer) and `t` (target).

use crate::gl::Rect;
use crate::mass::peel::CapturedPeel;
use crate::view::{inset, Canvas};

/// Which captured peel and which of its integrand targets is shown.
#[derive(Clone, Copy, Debug, Default)]
pub struct PeelChoice {
    pub layer: usize,
    pub target: usize,
}

impl PeelChoice {
    /// `l`: next layer; `t`: next integrand target. Whether the key was used.
    pub fn key(&mut self, key: &str, peels: &[CapturedPeel]) -> bool {
        match key {
            "l" => self.layer = (self.layer + 1) % peels.len().max(1),
            "t" => {
                let targets = peels.first().map_or(1, |p| p.targets.len().max(1));
                self.target = (self.target + 1) % targets;
            }
            _ => return false,
        }
        true
    }

    pub const KEYS: [(&'static str, &'static str); 2] =
        [("l", "next peel layer"), ("t", "next integrand target")];

    /// The chosen peel's target filling `canvas`.
    pub fn draw_full(&self, canvas: &Canvas, peels: &[CapturedPeel]) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        if peels.is_empty() {
            return Ok(());
        }
        let layer = self.layer % peels.len();
        let peel = &peels[layer];
        let target = self.target % peel.targets.len().max(1);
        inset::draw_rgba(
            canvas,
            &peel.targets[target],
            (peel.width, peel.height),
            Rect::sized(canvas.width(), canvas.height()),
            &format!("peel {} of {}, target {target}", layer + 1, peels.len()),
        )?;
        Ok(())
    }

    /// Every peel's chosen target along the bottom of `canvas`.
    pub fn draw_strip(&self, canvas: &Canvas, peels: &[CapturedPeel]) -> anyhow::Result<()> {
        let shown = peels.len().min(6);
        for (k, rect) in inset::strip(canvas, shown).into_iter().enumerate() {
            let peel = &peels[shown - 1 - k];
            let target = self.target % peel.targets.len().max(1);
            inset::draw_rgba(
                canvas,
                &peel.targets[target],
                (peel.width, peel.height),
                rect,
                &format!("peel {}", shown - k),
            )?;
        }
        Ok(())
    }
}
