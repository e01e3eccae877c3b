//! Levels of detail [paper section 3, Fig. 4-5]: three meshes of 1,084, 544 and 312
//! polygons, chosen per character by distance. Beyond them, sprites (impostors) are this
//! project's extension, off unless asked for: the paper does not describe them (the
//! tutorial's lecture 2 mentions sprites for still larger crowds).
//!
//! The polygon counts are the paper's and are met exactly: [`tessellate_to_budget`] picks
//! each body part's segments and rings so that the character's triangle total equals the
//! target. The distances at which the level changes are this project's choice; the paper
//! gives none.

use serde::Serialize;
use thiserror::Error;

use super::body_part::{BodyPart, Tessellation};

/// The paper's three LOD meshes, in triangles ("polygons").
pub const LOD_TRIANGLES: [usize; 3] = [1084, 544, 312];

/// What a character is drawn with this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Level {
    /// One of the skinned LOD meshes, 0 = finest.
    Mesh(usize),
    /// A camera-facing sprite (impostor): this project's extension.
    Sprite,
}

/// Distance thresholds from the eye (metres): LOD 0 up to `mesh_until[0]`, LOD 1 up to
/// `mesh_until[1]`, LOD 2 beyond, or a sprite beyond `sprites_beyond` when it is set.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LodPolicy {
    pub mesh_until: [f32; 2],
    /// `None` in the paper's setup (three meshes only).
    pub sprites_beyond: Option<f32>,
}

/// Where the sprite level starts when it is on ([`LodPolicy::with_sprites`]).
pub const SPRITES_BEYOND: f32 = 90.0;

impl Default for LodPolicy {
    /// The paper's setup, three meshes and no sprites, at this project's distances: for a
    /// 1.8 m character seen with a 60 degree field of view at 720 lines, LOD 0 while it is
    /// over ~90 pixels tall, LOD 1 over ~35, LOD 2 below.
    fn default() -> Self {
        Self {
            mesh_until: [15.0, 40.0],
            sprites_beyond: None,
        }
    }
}

impl LodPolicy {
    /// The paper's setup plus this project's sprite level beyond [`SPRITES_BEYOND`] (where
    /// a character is under ~15 pixels tall under the same assumptions).
    pub fn with_sprites() -> Self {
        Self {
            sprites_beyond: Some(SPRITES_BEYOND),
            ..Self::default()
        }
    }

    /// The level for a character at `distance` from the eye.
    pub fn select(&self, distance: f32) -> Level {
        if self.sprites_beyond.is_some_and(|d| distance > d) {
            return Level::Sprite;
        }
        Level::Mesh(
            self.mesh_until
                .iter()
                .position(|&limit| distance <= limit)
                .unwrap_or(self.mesh_until.len()),
        )
    }
}

/// A polygon budget the body parts cannot meet.
#[derive(Debug, Error, PartialEq)]
pub enum LodError {
    #[error("cannot tessellate {parts} body parts to exactly {target} triangles (the smallest possible is {smallest}; odd totals are impossible)")]
    Unreachable {
        target: usize,
        parts: usize,
        smallest: usize,
    },
}

const MIN_SEGMENTS: u32 = 4;
const MIN_RINGS: u32 = 2;

fn scaled(part: &BodyPart, density: f64) -> Tessellation {
    let even = |x: f64| 2 * ((x / 2.0).round() as u32);
    Tessellation {
        segments: even(part.base_segments as f64 * density).max(MIN_SEGMENTS),
        rings: ((part.base_rings as f64 * density).round() as u32).max(MIN_RINGS),
        pole_caps: [false, false],
    }
}

fn total(tessellations: &[Tessellation]) -> usize {
    tessellations.iter().map(Tessellation::triangle_count).sum()
}

/// Tessellations of `parts` whose triangle counts add up to exactly `target`.
///
/// Every part scales by one density (the largest whose total stays within the budget);
/// the remainder is filled by adding rings (2 x segments triangles each) to the parts
/// least refined relative to their base, and then by turning flat caps into pole caps
/// (2 triangles each).
pub fn tessellate_to_budget(
    parts: &[BodyPart],
    target: usize,
) -> Result<Vec<Tessellation>, LodError> {
    let smallest = total(&parts.iter().map(|p| scaled(p, 0.0)).collect::<Vec<_>>());
    let unreachable = || LodError::Unreachable {
        target,
        parts: parts.len(),
        smallest,
    };
    let mut best: Option<Vec<Tessellation>> = None;
    for step in 1..=800 {
        let candidate: Vec<Tessellation> = parts
            .iter()
            .map(|p| scaled(p, step as f64 / 100.0))
            .collect();
        let t = total(&candidate);
        if t <= target && best.as_ref().is_none_or(|b| total(b) < t) {
            best = Some(candidate);
        }
    }
    let mut tess = best.ok_or_else(unreachable)?;
    let mut deficit = target - total(&tess);
    // Add rings where they are relatively scarcest.
    loop {
        let choice = (0..parts.len())
            .filter(|&i| 2 * tess[i].segments as usize <= deficit)
            .min_by(|&a, &b| {
                let ratio = |i: usize| tess[i].rings as f64 / parts[i].base_rings as f64;
                ratio(a).total_cmp(&ratio(b))
            });
        let Some(i) = choice else { break };
        tess[i].rings += 1;
        deficit -= 2 * tess[i].segments as usize;
    }
    // Then pole caps, two triangles each.
    for end in 0..2 {
        for t in tess.iter_mut() {
            if deficit >= 2 && !t.pole_caps[end] {
                t.pole_caps[end] = true;
                deficit -= 2;
            }
        }
    }
    if deficit != 0 {
        return Err(unreachable());
    }
    Ok(tess)
}
