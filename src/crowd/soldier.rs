//! The "soldier": a procedural humanoid standing in for the paper's rigged soldier model,
//! whose mesh and skeleton are not published. The skeleton (18 bones, one of them a spear
//! held in the right hand), the proportions and the walk cycle are this project's choices;
//! the paper gives only the polygon counts of the LOD meshes and at most 4 bones per vertex.

use glam::DVec3;

use super::animation::{Channel, Clip, Wave};
use super::blueprint::Blueprint;
use super::body_part::{BodyPart, Station};
use super::skeleton::{Bone, Skeleton};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn st(x: f64, y: f64, z: f64, r0: f64, r1: f64) -> Station {
    Station {
        at: v(x, y, z),
        radius: [r0, r1],
    }
}

fn bone(name: &'static str, parent: Option<usize>, head: DVec3, tail: DVec3) -> Bone {
    Bone {
        name,
        parent,
        head,
        tail,
    }
}

// Bone indices.
const PELVIS: usize = 0;
const SPINE: usize = 1;
const CHEST: usize = 2;
const NECK: usize = 3;
const HEAD: usize = 4;
const ARM: [usize; 2] = [5, 8]; // upper arm, then forearm and hand follow
const LEG: [usize; 2] = [11, 14]; // thigh, then shin and foot follow
const SPEAR: usize = 17;

/// Skeleton, body parts and walk cycle of the soldier (1.9 m tall, facing +z).
pub fn blueprint() -> Blueprint {
    Blueprint {
        skeleton: skeleton(),
        parts: parts(),
        clip: walk(),
    }
}

fn skeleton() -> Skeleton {
    let mut bones = vec![
        bone("pelvis", None, v(0.0, 0.98, 0.0), v(0.0, 1.1, 0.0)),
        bone("spine", Some(PELVIS), v(0.0, 1.1, 0.0), v(0.0, 1.3, 0.0)),
        bone("chest", Some(SPINE), v(0.0, 1.3, 0.0), v(0.0, 1.5, 0.0)),
        bone("neck", Some(CHEST), v(0.0, 1.5, 0.0), v(0.0, 1.6, 0.0)),
        bone("head", Some(NECK), v(0.0, 1.6, 0.0), v(0.0, 1.85, 0.0)),
    ];
    let names = [
        ["upperarm_l", "forearm_l", "hand_l"],
        ["upperarm_r", "forearm_r", "hand_r"],
    ];
    for (side, sx) in [(0, 1.0), (1, -1.0)] {
        let [upper, fore, hand] = names[side];
        let a = ARM[side];
        bones.push(bone(
            upper,
            Some(CHEST),
            v(0.21 * sx, 1.45, 0.0),
            v(0.23 * sx, 1.17, 0.0),
        ));
        bones.push(bone(
            fore,
            Some(a),
            v(0.23 * sx, 1.17, 0.0),
            v(0.24 * sx, 0.92, 0.02),
        ));
        bones.push(bone(
            hand,
            Some(a + 1),
            v(0.24 * sx, 0.92, 0.02),
            v(0.24 * sx, 0.8, 0.03),
        ));
    }
    let names = [
        ["thigh_l", "shin_l", "foot_l"],
        ["thigh_r", "shin_r", "foot_r"],
    ];
    for (side, sx) in [(0, 1.0), (1, -1.0)] {
        let [thigh, shin, foot] = names[side];
        let l = LEG[side];
        bones.push(bone(
            thigh,
            Some(PELVIS),
            v(0.1 * sx, 0.95, 0.0),
            v(0.1 * sx, 0.52, 0.0),
        ));
        bones.push(bone(
            shin,
            Some(l),
            v(0.1 * sx, 0.52, 0.0),
            v(0.1 * sx, 0.09, -0.01),
        ));
        bones.push(bone(
            foot,
            Some(l + 1),
            v(0.1 * sx, 0.09, -0.01),
            v(0.1 * sx, 0.03, 0.17),
        ));
    }
    let hand_r = ARM[1] + 2;
    bones.push(bone(
        "spear",
        Some(hand_r),
        v(-0.24, 0.86, 0.05),
        v(-0.24, 2.1, 0.05),
    ));
    Skeleton::new(bones).expect("the soldier skeleton lists parents first")
}

fn parts() -> Vec<BodyPart> {
    let mut parts = vec![
        BodyPart {
            name: "torso",
            stations: vec![
                st(0.0, 0.86, 0.0, 0.10, 0.08),
                st(0.0, 0.96, 0.0, 0.17, 0.11),
                st(0.0, 1.12, 0.0, 0.15, 0.10),
                st(0.0, 1.32, 0.0, 0.18, 0.11),
                st(0.0, 1.46, 0.0, 0.21, 0.12),
                st(0.0, 1.53, 0.0, 0.08, 0.07),
            ],
            side: DVec3::X,
            bones: vec![PELVIS, SPINE, CHEST, NECK],
            base_segments: 12,
            base_rings: 8,
        },
        BodyPart {
            name: "head",
            stations: vec![
                st(0.0, 1.55, 0.0, 0.05, 0.05),
                st(0.0, 1.62, 0.01, 0.07, 0.07),
                st(0.0, 1.72, 0.02, 0.095, 0.105),
                st(0.0, 1.82, 0.01, 0.085, 0.09),
                st(0.0, 1.87, 0.0, 0.03, 0.03),
            ],
            side: DVec3::X,
            bones: vec![NECK, HEAD],
            base_segments: 10,
            base_rings: 6,
        },
        BodyPart {
            name: "helmet",
            stations: vec![
                st(0.0, 1.76, -0.01, 0.125, 0.13),
                st(0.0, 1.85, 0.0, 0.11, 0.115),
                st(0.0, 1.91, 0.0, 0.04, 0.04),
            ],
            side: DVec3::X,
            bones: vec![HEAD],
            base_segments: 10,
            base_rings: 3,
        },
        BodyPart {
            name: "spear",
            stations: vec![
                st(-0.24, 0.2, 0.05, 0.015, 0.015),
                st(-0.24, 1.9, 0.05, 0.015, 0.015),
                st(-0.24, 1.95, 0.05, 0.035, 0.012),
                st(-0.24, 2.12, 0.05, 0.003, 0.003),
            ],
            side: DVec3::Z,
            bones: vec![SPEAR],
            base_segments: 4,
            base_rings: 3,
        },
    ];
    for (side, sx) in [(0, 1.0), (1, -1.0)] {
        let (a, l) = (ARM[side], LEG[side]);
        parts.push(BodyPart {
            name: ["arm_l", "arm_r"][side],
            stations: vec![
                st(0.21 * sx, 1.5, 0.0, 0.05, 0.05),
                st(0.215 * sx, 1.44, 0.0, 0.065, 0.065),
                st(0.23 * sx, 1.17, 0.0, 0.05, 0.05),
                st(0.24 * sx, 0.93, 0.02, 0.04, 0.04),
                st(0.24 * sx, 0.86, 0.03, 0.045, 0.03),
                st(0.24 * sx, 0.78, 0.03, 0.02, 0.015),
            ],
            side: DVec3::Z,
            bones: vec![CHEST, a, a + 1, a + 2],
            base_segments: 8,
            base_rings: 7,
        });
        parts.push(BodyPart {
            name: ["leg_l", "leg_r"][side],
            stations: vec![
                st(0.1 * sx, 1.0, 0.0, 0.06, 0.06),
                st(0.1 * sx, 0.94, 0.0, 0.085, 0.085),
                st(0.1 * sx, 0.52, 0.0, 0.06, 0.06),
                st(0.1 * sx, 0.12, -0.01, 0.045, 0.045),
                st(0.1 * sx, 0.06, -0.01, 0.035, 0.035),
            ],
            side: DVec3::X,
            bones: vec![PELVIS, l, l + 1, l + 2],
            base_segments: 8,
            base_rings: 7,
        });
        parts.push(BodyPart {
            name: ["foot_l", "foot_r"][side],
            stations: vec![
                st(0.1 * sx, 0.07, -0.05, 0.04, 0.035),
                st(0.1 * sx, 0.05, 0.08, 0.045, 0.035),
                st(0.1 * sx, 0.04, 0.18, 0.03, 0.02),
            ],
            side: DVec3::X,
            bones: vec![l + 1, l + 2],
            base_segments: 6,
            base_rings: 3,
        });
    }
    parts
}

fn channel(bone: usize, axis: DVec3, bias: f64, amplitude: f64, offset: f64) -> Channel {
    Channel {
        bone,
        axis,
        bias,
        amplitude,
        offset,
        harmonic: 1.0,
        wave: Wave::Sine,
    }
}

/// The walk: legs swing in opposition (a positive turn about x swings a limb backwards),
/// knees bend during the swing phase, arms swing against the legs, hips and shoulders
/// counter-rotate, the body bobs twice per cycle. 1.4 m per cycle.
fn walk() -> Clip {
    let mut channels = vec![
        channel(PELVIS, DVec3::Y, 0.0, 0.06, 0.0),
        channel(PELVIS, DVec3::Z, 0.0, 0.03, 0.0),
        channel(SPINE, DVec3::Y, 0.0, 0.07, 0.5),
        Channel {
            harmonic: 2.0,
            ..channel(HEAD, DVec3::X, 0.0, 0.03, 0.0)
        },
    ];
    for (side, leg_offset) in [(0, 0.0), (1, 0.5)] {
        let (a, l) = (ARM[side], LEG[side]);
        channels.push(channel(l, DVec3::X, 0.0, 0.45, leg_offset));
        channels.push(Channel {
            wave: Wave::HalfSine,
            ..channel(l + 1, DVec3::X, 0.0, 0.7, leg_offset - 0.25)
        });
        channels.push(channel(l + 2, DVec3::X, 0.0, 0.2, leg_offset));
        let arm_offset = leg_offset + 0.5;
        channels.push(channel(a, DVec3::X, 0.0, 0.35, arm_offset));
        channels.push(channel(a + 1, DVec3::X, -0.3, 0.15, arm_offset));
    }
    Clip {
        name: "walk",
        channels,
        bob: (0.025, 2.0, 0.25),
        stride: 1.4,
    }
}
