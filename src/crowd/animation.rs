//! Looping locomotion clips (the soldier's walk, the horse's gallop) as sums of periodic
//! joint rotations, sampled at any phase so that every character moves independently.
//!
//! A clip is data: a list of channels, each turning one bone about one axis by
//! `bias + amplitude * wave(2 pi (harmonic * phase + offset))`, plus a vertical bob of the
//! root. `stride` is the ground distance covered by one cycle, so the behaviour layer can
//! advance the phase by distance walked and feet do not slide.

use glam::{DQuat, DVec3};
use std::f64::consts::TAU;

use super::skeleton::{Pose, Skeleton};

/// The shape of one channel over a cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wave {
    /// A plain sine (swinging hips, shoulders, tail).
    Sine,
    /// `max(0, sin)`: joints that only bend one way (knees, hocks).
    HalfSine,
}

/// One periodic rotation of one bone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Channel {
    pub bone: usize,
    pub axis: DVec3,
    pub bias: f64,
    pub amplitude: f64,
    /// Phase offset in cycles.
    pub offset: f64,
    /// Cycles of this channel per cycle of the clip.
    pub harmonic: f64,
    pub wave: Wave,
}

/// A looping clip.
#[derive(Clone, Debug, PartialEq)]
pub struct Clip {
    pub name: &'static str,
    pub channels: Vec<Channel>,
    /// Vertical bob of the root: amplitude (model units), harmonic, offset (cycles).
    pub bob: (f64, f64, f64),
    /// Ground distance per cycle (model units).
    pub stride: f64,
}

impl Channel {
    /// The angle (radians) of this channel at clip phase `phase` (cycles).
    pub fn angle(&self, phase: f64) -> f64 {
        let x = (TAU * (self.harmonic * phase + self.offset)).sin();
        let w = match self.wave {
            Wave::Sine => x,
            Wave::HalfSine => x.max(0.0),
        };
        self.bias + self.amplitude * w
    }
}

impl Clip {
    /// The pose at `phase` (cycles; any real number, the clip loops with period 1).
    pub fn sample(&self, skeleton: &Skeleton, phase: f64) -> Pose {
        let mut pose = skeleton.bind_pose();
        for channel in &self.channels {
            let turn = DQuat::from_axis_angle(channel.axis, channel.angle(phase));
            let local = &mut pose.local_rotations[channel.bone];
            *local = (*local * turn).normalize();
        }
        let (amplitude, harmonic, offset) = self.bob;
        pose.root_offset = DVec3::Y * amplitude * (TAU * (harmonic * phase + offset)).sin();
        pose
    }
}
