//! Step 1, "a loop-free articulated body whose links are line skeletons with constant
//! offsets": each link is a capsule (a segment in the link's frame and a radius) hung from its
//! parent at a joint; a pose is the root's position and three joint angles per link; forward
//! kinematics gives every capsule in the world. Keyframe poses are interpolated link by link
//! (the root's position and each joint angle linearly), as the source says the in-between
//! motion "interpolates each link"; the interpolation rule itself is ours.

use anyhow::Context as _;
use glam::{DMat3, DVec3};
use serde::Deserialize;
use std::collections::HashMap;
use std::path::Path;

/// One link: a capsule hung from its parent.
#[derive(Clone, Debug)]
pub struct Link {
    pub name: String,
    /// The parent link (`None` for the root, which hangs from the pose's root position).
    pub parent: Option<usize>,
    /// Where the joint sits in the parent's frame (for the root: at the root position).
    pub joint: DVec3,
    /// The capsule's segment in the link's own frame (the joint at the origin).
    pub segment: [DVec3; 2],
    pub radius: f64,
}

/// An articulated body; parents come before their children.
#[derive(Clone, Debug)]
pub struct Body {
    pub links: Vec<Link>,
}

/// A capsule in the world: the segment and its radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    pub a: DVec3,
    pub b: DVec3,
    pub radius: f64,
}

/// A pose: the root's position and, per link, its joint angles (radians, about x then y then
/// z of the parent's frame: R = Rx · Ry · Rz).
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    pub root: DVec3,
    pub angles: Vec<DVec3>,
}

impl Body {
    /// A small walking figure facing +z with y up (13 links): pelvis, torso, head, upper and
    /// lower arms, thighs, shins and feet; 1.05 units from the soles to the pelvis.
    pub fn walker() -> Body {
        let v = DVec3::new;
        let mut links = Vec::new();
        let mut add = |name: &str, parent: Option<usize>, joint, a, b, radius| {
            links.push(Link {
                name: name.into(),
                parent,
                joint,
                segment: [a, b],
                radius,
            });
            links.len() - 1
        };
        let pelvis = add(
            "pelvis",
            None,
            v(0.0, 0.0, 0.0),
            v(-0.1, 0.0, 0.0),
            v(0.1, 0.0, 0.0),
            0.1,
        );
        let torso = add(
            "torso",
            Some(pelvis),
            v(0.0, 0.05, 0.0),
            v(0.0, 0.1, 0.0),
            v(0.0, 0.42, 0.0),
            0.13,
        );
        add(
            "head",
            Some(torso),
            v(0.0, 0.55, 0.0),
            v(0.0, 0.1, 0.0),
            v(0.0, 0.16, 0.0),
            0.1,
        );
        for (side, x) in [("left", 1.0), ("right", -1.0)] {
            let upper = add(
                &format!("{side} upper arm"),
                Some(torso),
                v(0.21 * x, 0.45, 0.0),
                v(0.0, 0.0, 0.0),
                v(0.0, -0.27, 0.0),
                0.05,
            );
            add(
                &format!("{side} forearm"),
                Some(upper),
                v(0.0, -0.3, 0.0),
                v(0.0, 0.0, 0.0),
                v(0.0, -0.26, 0.0),
                0.045,
            );
        }
        for (side, x) in [("left", 1.0), ("right", -1.0)] {
            let thigh = add(
                &format!("{side} thigh"),
                Some(pelvis),
                v(0.1 * x, -0.05, 0.0),
                v(0.0, -0.03, 0.0),
                v(0.0, -0.4, 0.0),
                0.07,
            );
            let shin = add(
                &format!("{side} shin"),
                Some(thigh),
                v(0.0, -0.45, 0.0),
                v(0.0, 0.0, 0.0),
                v(0.0, -0.38, 0.0),
                0.055,
            );
            add(
                &format!("{side} foot"),
                Some(shin),
                v(0.0, -0.45, 0.0),
                v(0.0, 0.0, -0.04),
                v(0.0, 0.0, 0.14),
                0.05,
            );
        }
        Body { links }
    }

    /// The published scale's avatar (Presence 2007: 16 links): the walker with a neck and
    /// two hands (capsules at the forearms' ends), 16 links in all.
    pub fn avatar16() -> Body {
        let mut body = Body::walker();
        let v = DVec3::new;
        let index = |body: &Body, name: &str| body.links.iter().position(|l| l.name == name);
        let torso = index(&body, "torso");
        body.links.push(Link {
            name: "neck".into(),
            parent: torso,
            joint: v(0.0, 0.45, 0.0),
            segment: [v(0.0, 0.0, 0.0), v(0.0, 0.08, 0.0)],
            radius: 0.05,
        });
        for side in ["left", "right"] {
            let forearm = index(&body, &format!("{side} forearm"));
            body.links.push(Link {
                name: format!("{side} hand"),
                parent: forearm,
                joint: v(0.0, -0.28, 0.0),
                segment: [v(0.0, 0.0, 0.0), v(0.0, -0.09, 0.0)],
                radius: 0.04,
            });
        }
        body
    }

    /// Check the body: parents first, finite offsets, positive radii.
    pub fn validate(&self) -> anyhow::Result<()> {
        anyhow::ensure!(!self.links.is_empty(), "the body has no links");
        for (k, link) in self.links.iter().enumerate() {
            if let Some(p) = link.parent {
                anyhow::ensure!(p < k, "link {} hangs from a later link {p}", link.name);
            }
            let finite = link.joint.is_finite() && link.segment.iter().all(|s| s.is_finite());
            anyhow::ensure!(
                finite && link.radius.is_finite() && link.radius > 0.0,
                "link {} has a non-finite offset or a radius that is not positive",
                link.name
            );
        }
        Ok(())
    }

    /// The links' frames (rotation, joint position in the world) at `pose`.
    pub fn frames(&self, pose: &Pose) -> Vec<(DMat3, DVec3)> {
        let mut frames: Vec<(DMat3, DVec3)> = Vec::with_capacity(self.links.len());
        for (k, link) in self.links.iter().enumerate() {
            let (parent_rotation, parent_origin) = match link.parent {
                Some(p) => frames[p],
                None => (DMat3::IDENTITY, pose.root),
            };
            let origin = parent_origin + parent_rotation * link.joint;
            frames.push((parent_rotation * joint_rotation(pose.angles[k]), origin));
        }
        frames
    }

    /// Forward kinematics: every link's capsule in the world at `pose`.
    pub fn capsules(&self, pose: &Pose) -> Vec<Capsule> {
        self.frames(pose)
            .iter()
            .zip(&self.links)
            .map(|(&(rotation, origin), link)| Capsule {
                a: origin + rotation * link.segment[0],
                b: origin + rotation * link.segment[1],
                radius: link.radius,
            })
            .collect()
    }

    /// The chain from the root down to `link` (root first).
    pub fn chain(&self, link: usize) -> Vec<usize> {
        let mut chain = vec![link];
        while let Some(p) = self.links[*chain.last().unwrap()].parent {
            chain.push(p);
        }
        chain.reverse();
        chain
    }
}

/// The joint rotation R = Rx(a.x) · Ry(a.y) · Rz(a.z).
pub fn joint_rotation(a: DVec3) -> DMat3 {
    DMat3::from_rotation_x(a.x) * DMat3::from_rotation_y(a.y) * DMat3::from_rotation_z(a.z)
}

/// Keyframe poses at times 0, 1, 2, ... (time is counted in keyframe intervals).
#[derive(Clone, Debug)]
pub struct Keyframes {
    pub poses: Vec<Pose>,
}

impl Keyframes {
    /// The time of the last keyframe.
    pub fn end(&self) -> f64 {
        (self.poses.len() - 1) as f64
    }

    /// The keyframe interval holding time `t` (the last one for t = end).
    pub fn interval_of(&self, t: f64) -> usize {
        (t.max(0.0).floor() as usize).min(self.poses.len().saturating_sub(2))
    }

    /// The pose at time `t` in [0, end]: root position and joint angles linear between the
    /// two keyframes around `t`.
    pub fn pose_at(&self, t: f64) -> Pose {
        if self.poses.len() == 1 {
            return self.poses[0].clone();
        }
        let k = self.interval_of(t);
        let s = (t - k as f64).clamp(0.0, 1.0);
        let (a, b) = (&self.poses[k], &self.poses[k + 1]);
        Pose {
            root: a.root.lerp(b.root, s),
            angles: a
                .angles
                .iter()
                .zip(&b.angles)
                .map(|(x, y)| x.lerp(*y, s))
                .collect(),
        }
    }

    /// A walk along +z: `steps` keyframes of `stride` each, legs and arms swinging in
    /// opposition, knees bending on the swing, from `start` (the pelvis's position).
    pub fn walk(body: &Body, start: DVec3, steps: usize, stride: f64) -> Keyframes {
        let index = |name: &str| body.links.iter().position(|l| l.name == name);
        let poses = (0..=steps)
            .map(|k| {
                let phase = if k % 2 == 0 { 1.0 } else { -1.0 };
                let mut angles = vec![DVec3::ZERO; body.links.len()];
                let mut set = |name: &str, a: DVec3| {
                    if let Some(i) = index(name) {
                        angles[i] = a;
                    }
                };
                // Hips swing about x: a negative angle brings the leg forward (+z).
                set("left thigh", DVec3::new(-0.35 * phase, 0.0, 0.0));
                set("right thigh", DVec3::new(0.35 * phase, 0.0, 0.0));
                set(
                    "left shin",
                    DVec3::new(0.25 * (1.0 + phase) / 2.0, 0.0, 0.0),
                );
                set(
                    "right shin",
                    DVec3::new(0.25 * (1.0 - phase) / 2.0, 0.0, 0.0),
                );
                set("left upper arm", DVec3::new(0.4 * phase, 0.0, -0.1));
                set("right upper arm", DVec3::new(-0.4 * phase, 0.0, 0.1));
                set("left forearm", DVec3::new(-0.3, 0.0, 0.0));
                set("right forearm", DVec3::new(-0.3, 0.0, 0.0));
                set("torso", DVec3::new(0.05, 0.08 * phase, 0.0));
                Pose {
                    root: start + DVec3::new(0.0, 0.0, stride * k as f64),
                    angles,
                }
            })
            .collect();
        Keyframes { poses }
    }

    /// Keyframes from JSON: `{"keyframes": [{"root": [x, y, z], "angles": {"link name": [rx,
    /// ry, rz], ...}}, ...]}`; a link left out has zero angles. Unknown link names, fewer than
    /// one keyframe and non-finite numbers are refused.
    pub fn from_json(body: &Body, text: &str, what: &str) -> anyhow::Result<Keyframes> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            keyframes: Vec<Frame>,
        }
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Frame {
            root: [f64; 3],
            #[serde(default)]
            angles: HashMap<String, [f64; 3]>,
        }
        let file: File =
            serde_json::from_str(text).with_context(|| format!("reading keyframes {what}"))?;
        anyhow::ensure!(
            !file.keyframes.is_empty(),
            "keyframes {what}: the list is empty (at least one pose is needed)"
        );
        let poses = file
            .keyframes
            .iter()
            .enumerate()
            .map(|(k, frame)| {
                let root = DVec3::from(frame.root);
                anyhow::ensure!(
                    root.is_finite(),
                    "keyframes {what}: keyframe {k} has a non-finite root"
                );
                let mut angles = vec![DVec3::ZERO; body.links.len()];
                for (name, a) in &frame.angles {
                    let i = body
                        .links
                        .iter()
                        .position(|l| &l.name == name)
                        .ok_or_else(|| {
                            anyhow::anyhow!(
                                "keyframes {what}: keyframe {k} names link {name:?}, which the \
                                 body does not have (links: {})",
                                body.links
                                    .iter()
                                    .map(|l| l.name.as_str())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            )
                        })?;
                    let a = DVec3::from(*a);
                    anyhow::ensure!(
                        a.is_finite(),
                        "keyframes {what}: keyframe {k}, link {name}: non-finite angles"
                    );
                    angles[i] = a;
                }
                Ok(Pose { root, angles })
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        Ok(Keyframes { poses })
    }

    /// Keyframes from a JSON file (see [`Keyframes::from_json`]).
    pub fn load(body: &Body, path: &Path) -> anyhow::Result<Keyframes> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("reading keyframes {}", path.display()))?;
        Self::from_json(body, &text, &path.display().to_string())
    }
}
