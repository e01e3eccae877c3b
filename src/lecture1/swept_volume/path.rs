//! The motion: PATH.json keyframes, interpolated linearly (translation) and by slerp
//! (rotation), sampled at K poses.
//!
//! PATH.json is a list of keyframes, equally spaced in time from 0 to 1:
//!
//! ```json
//! [{"translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
//!  {"translation": [2, 0, 0], "rotation": [0.7071068, 0, 0.7071068, 0]}]
//! ```
//!
//! `rotation` is a unit quaternion `[w, x, y, z]`; one whose length differs from 1 by more
//! than [`UNIT_TOLERANCE`] is refused (never silently normalised). A pose moves a model point
//! `p` to `rotation * p + translation`.

use anyhow::Context as _;
use glam::{DQuat, DVec3};
use serde::Deserialize;
use std::path::Path;

/// How far from 1 a keyframe's quaternion length may be (rounding in a written file).
pub const UNIT_TOLERANCE: f64 = 1e-6;

/// One keyframe as written.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Keyframe {
    pub translation: [f64; 3],
    /// `[w, x, y, z]`.
    pub rotation: [f64; 4],
}

/// A rigid pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub rotation: DQuat,
    pub translation: DVec3,
}

impl Pose {
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.rotation * p + self.translation
    }
}

/// The keyframes of a path, checked.
#[derive(Clone, Debug)]
pub struct Path3 {
    pub keyframes: Vec<Pose>,
}

impl Path3 {
    pub fn load(path: &Path) -> anyhow::Result<Path3> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("reading the path {}", path.display()))?;
        Path3::parse(&text).with_context(|| format!("the path {}", path.display()))
    }

    pub fn parse(text: &str) -> anyhow::Result<Path3> {
        let frames: Vec<Keyframe> = serde_json::from_str(text).context(
            "expected a list of keyframes [{\"translation\": [x, y, z], \"rotation\": [w, x, y, \
             z]}, ...]",
        )?;
        Path3::new(&frames)
    }

    pub fn new(frames: &[Keyframe]) -> anyhow::Result<Path3> {
        anyhow::ensure!(!frames.is_empty(), "the path has no keyframe");
        let mut keyframes = Vec::with_capacity(frames.len());
        for (i, k) in frames.iter().enumerate() {
            let t = DVec3::from(k.translation);
            let [w, x, y, z] = k.rotation;
            let q = DQuat::from_xyzw(x, y, z, w);
            anyhow::ensure!(
                t.is_finite() && q.is_finite(),
                "keyframe {i}: a coordinate is not finite"
            );
            let length = q.length();
            anyhow::ensure!(
                (length - 1.0).abs() <= UNIT_TOLERANCE,
                "keyframe {i}: the rotation [{w}, {x}, {y}, {z}] has length {length}, not 1; \
                 give a unit quaternion [w, x, y, z]"
            );
            keyframes.push(Pose {
                rotation: q.normalize(),
                translation: t,
            });
        }
        Ok(Path3 { keyframes })
    }

    /// The pose at time `t` in [0, 1]: keyframe `i` at `i / (m - 1)`, translation linear and
    /// rotation by slerp between neighbours.
    pub fn at(&self, t: f64) -> Pose {
        let m = self.keyframes.len();
        if m == 1 {
            return self.keyframes[0];
        }
        let x = t.clamp(0.0, 1.0) * (m - 1) as f64;
        let i = (x.floor() as usize).min(m - 2);
        let f = x - i as f64;
        let (a, b) = (self.keyframes[i], self.keyframes[i + 1]);
        Pose {
            rotation: a.rotation.slerp(b.rotation, f),
            translation: a.translation.lerp(b.translation, f),
        }
    }

    /// `k` poses at equal steps of time, the first and last keyframes included.
    pub fn sample(&self, k: usize) -> Vec<Pose> {
        (0..k)
            .map(|i| {
                self.at(if k == 1 {
                    0.0
                } else {
                    i as f64 / (k - 1) as f64
                })
            })
            .collect()
    }
}
