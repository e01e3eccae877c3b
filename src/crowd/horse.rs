//! The "horse": a procedural quadruped standing in for the paper's rigged horse model, whose
//! mesh and skeleton are not published. The skeleton (20 bones), the proportions and the
//! gallop are this project's choices; the paper gives only the polygon counts of the LOD
//! meshes and at most 4 bones per vertex.

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
const NECK1: usize = 3;
const NECK2: usize = 4;
const HEAD: usize = 5;
const TAIL1: usize = 6;
const TAIL2: usize = 7;
/// First bone (upper leg) of each leg: front left, front right, hind left, hind right.
const LEG: [usize; 4] = [8, 11, 14, 17];

/// Skeleton, body parts and gallop of the horse (1.8 m at the head, facing +z).
pub fn blueprint() -> Blueprint {
    Blueprint {
        skeleton: skeleton(),
        parts: parts(),
        clip: gallop(),
    }
}

/// Side (x sign) and whether the leg is a front leg, per entry of [`LEG`].
const LEG_SIDES: [(f64, bool); 4] = [(1.0, true), (-1.0, true), (1.0, false), (-1.0, false)];

fn skeleton() -> Skeleton {
    let mut bones = vec![
        bone("pelvis", None, v(0.0, 1.12, -0.55), v(0.0, 1.15, -0.15)),
        bone("spine", Some(PELVIS), v(0.0, 1.15, -0.15), v(0.0, 1.2, 0.3)),
        bone("chest", Some(SPINE), v(0.0, 1.2, 0.3), v(0.0, 1.22, 0.62)),
        bone("neck1", Some(CHEST), v(0.0, 1.3, 0.62), v(0.0, 1.55, 0.85)),
        bone("neck2", Some(NECK1), v(0.0, 1.55, 0.85), v(0.0, 1.72, 1.0)),
        bone("head", Some(NECK2), v(0.0, 1.72, 1.0), v(0.0, 1.42, 1.35)),
        bone(
            "tail1",
            Some(PELVIS),
            v(0.0, 1.2, -0.82),
            v(0.0, 1.05, -0.98),
        ),
        bone(
            "tail2",
            Some(TAIL1),
            v(0.0, 1.05, -0.98),
            v(0.0, 0.62, -1.05),
        ),
    ];
    let names = [
        ["upper_fl", "lower_fl", "hoof_fl"],
        ["upper_fr", "lower_fr", "hoof_fr"],
        ["upper_hl", "lower_hl", "hoof_hl"],
        ["upper_hr", "lower_hr", "hoof_hr"],
    ];
    for (leg, &(sx, front)) in LEG_SIDES.iter().enumerate() {
        let [upper, lower, hoof] = names[leg];
        let first = LEG[leg];
        let x = 0.16 * sx;
        let (parent, z, top) = if front {
            (CHEST, 0.55, 1.0)
        } else {
            (PELVIS, -0.6, 1.05)
        };
        let knee_z = if front { z + 0.02 } else { z - 0.08 };
        bones.push(bone(upper, Some(parent), v(x, top, z), v(x, 0.6, knee_z)));
        bones.push(bone(lower, Some(first), v(x, 0.6, knee_z), v(x, 0.12, z)));
        bones.push(bone(
            hoof,
            Some(first + 1),
            v(x, 0.12, z),
            v(x, 0.0, z + 0.05),
        ));
    }
    Skeleton::new(bones).expect("the horse skeleton lists parents first")
}

fn parts() -> Vec<BodyPart> {
    let mut parts = vec![
        BodyPart {
            name: "body",
            stations: vec![
                st(0.0, 1.15, -0.95, 0.08, 0.08),
                st(0.0, 1.15, -0.82, 0.2, 0.22),
                st(0.0, 1.13, -0.5, 0.24, 0.27),
                st(0.0, 1.12, 0.0, 0.25, 0.29),
                st(0.0, 1.14, 0.45, 0.24, 0.3),
                st(0.0, 1.18, 0.75, 0.18, 0.24),
                st(0.0, 1.22, 0.85, 0.06, 0.08),
            ],
            side: DVec3::X,
            bones: vec![PELVIS, SPINE, CHEST],
            base_segments: 14,
            base_rings: 9,
        },
        BodyPart {
            name: "neck",
            stations: vec![
                st(0.0, 1.2, 0.55, 0.1, 0.16),
                st(0.0, 1.4, 0.75, 0.09, 0.14),
                st(0.0, 1.6, 0.92, 0.08, 0.11),
                st(0.0, 1.74, 1.02, 0.06, 0.07),
            ],
            side: DVec3::X,
            bones: vec![CHEST, NECK1, NECK2, HEAD],
            base_segments: 10,
            base_rings: 6,
        },
        BodyPart {
            name: "head",
            stations: vec![
                st(0.0, 1.78, 0.96, 0.05, 0.05),
                st(0.0, 1.72, 1.02, 0.085, 0.1),
                st(0.0, 1.55, 1.2, 0.07, 0.08),
                st(0.0, 1.42, 1.36, 0.05, 0.06),
                st(0.0, 1.39, 1.4, 0.02, 0.02),
            ],
            side: DVec3::X,
            bones: vec![NECK2, HEAD],
            base_segments: 10,
            base_rings: 5,
        },
        BodyPart {
            name: "tail",
            stations: vec![
                st(0.0, 1.2, -0.85, 0.04, 0.04),
                st(0.0, 1.05, -0.98, 0.05, 0.05),
                st(0.0, 0.62, -1.05, 0.03, 0.03),
                st(0.0, 0.55, -1.05, 0.005, 0.005),
            ],
            side: DVec3::X,
            bones: vec![PELVIS, TAIL1, TAIL2],
            base_segments: 6,
            base_rings: 5,
        },
    ];
    let names = ["leg_fl", "leg_fr", "leg_hl", "leg_hr"];
    for (leg, &(sx, front)) in LEG_SIDES.iter().enumerate() {
        let first = LEG[leg];
        let x = 0.16 * sx;
        let (parent, z, top) = if front {
            (CHEST, 0.55, 1.0)
        } else {
            (PELVIS, -0.6, 1.05)
        };
        let knee_z = if front { z + 0.02 } else { z - 0.08 };
        parts.push(BodyPart {
            name: names[leg],
            stations: vec![
                st(x, top + 0.08, z, 0.07, 0.09),
                st(x, top, z, 0.09, 0.11),
                st(x, 0.6, knee_z, 0.05, 0.055),
                st(x, 0.14, z, 0.035, 0.04),
                st(x, 0.06, z + 0.01, 0.05, 0.05),
                st(x, 0.0, z + 0.02, 0.05, 0.05),
            ],
            side: DVec3::X,
            bones: vec![parent, first, first + 1, first + 2],
            base_segments: 8,
            base_rings: 7,
        });
    }
    parts
}

fn channel(bone: usize, bias: f64, amplitude: f64, offset: f64, wave: Wave) -> Channel {
    Channel {
        bone,
        axis: DVec3::X,
        bias,
        amplitude,
        offset,
        harmonic: 1.0,
        wave,
    }
}

/// A rotary gallop: hind left, hind right, front left, front right strike in sequence;
/// the back flexes, the neck pumps against it, the tail streams. 3 m per cycle.
fn gallop() -> Clip {
    let mut channels = vec![
        channel(SPINE, 0.0, 0.06, 0.0, Wave::Sine),
        channel(CHEST, 0.0, 0.05, 0.25, Wave::Sine),
        channel(NECK1, 0.0, 0.12, 0.3, Wave::Sine),
        channel(HEAD, 0.0, 0.08, 0.55, Wave::Sine),
        channel(TAIL1, 0.3, 0.2, 0.0, Wave::Sine),
        channel(TAIL2, 0.2, 0.25, 0.15, Wave::Sine),
    ];
    let footfall = [0.5, 0.6, 0.0, 0.1];
    for (leg, &offset) in footfall.iter().enumerate() {
        let first = LEG[leg];
        channels.push(channel(first, 0.0, 0.5, offset, Wave::Sine));
        channels.push(channel(first + 1, 0.0, 0.8, offset - 0.25, Wave::HalfSine));
        channels.push(channel(first + 2, 0.0, 0.3, offset, Wave::Sine));
    }
    Clip {
        name: "gallop",
        channels,
        bob: (0.07, 1.0, 0.0),
        stride: 3.0,
    }
}
