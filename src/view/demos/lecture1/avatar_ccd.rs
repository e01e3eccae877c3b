//! Lecture 1, continuous collision for an avatar live (`view lecture1 avatar-ccd`): the
//! walking figure of capsule links walks through the built-in room towards the wall; the
//! query runs once over the whole walk, and each step moves the figure an eighth of a
//! keyframe interval along it until the first time of contact, where it stops with the link
//! in contact drawn red.

use crate::collide::snapshot::SnapshotModel;
use crate::gl::Context;
use crate::lecture1::avatar_ccd::body::{Body, Capsule, Keyframes};
use crate::lecture1::avatar_ccd::environment::{room, Environment};
use crate::lecture1::avatar_ccd::{AvatarCcd, Contact, Options};
use crate::mesh::Mesh;
use crate::view::{Canvas, Demo, ViewState};
use glam::{DVec3, Vec3};

/// Time (keyframe intervals) the figure moves per step.
const STEP: f64 = 0.125;

pub struct AvatarCcdDemo {
    body: Body,
    keyframes: Keyframes,
    room: Mesh,
    contact: Contact,
    time: f64,
}

impl AvatarCcdDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<AvatarCcdDemo> {
        let body = Body::walker();
        let keyframes = Keyframes::walk(&body, DVec3::new(0.0, 1.06, 0.0), 8, 0.35);
        let room = room();
        let env = Environment::new(&room)?;
        let options = Options {
            resolution: 32,
            ..Options::default()
        };
        let contact = AvatarCcd::new(ctx, &options)?.run(&body, &keyframes, &env, &options)?;
        Ok(AvatarCcdDemo {
            body,
            keyframes,
            room,
            contact,
            time: 0.0,
        })
    }

    /// Where the walk stops: the first time of contact, or its end.
    fn stop(&self) -> f64 {
        self.contact.time_of_contact.unwrap_or(self.keyframes.end())
    }

    /// The figure's capsules as triangles, and which of them are the contact link's (once the
    /// figure stands at the time of contact).
    fn figure(&self) -> (Vec<[Vec3; 3]>, Vec<u32>) {
        let capsules = self.body.capsules(&self.keyframes.pose_at(self.time));
        let mut triangles = Vec::new();
        let mut red = Vec::new();
        let touching = (self.time >= self.stop())
            .then_some(self.contact.link_index)
            .flatten();
        for (k, c) in capsules.iter().enumerate() {
            let start = triangles.len();
            capsule_triangles(c, &mut triangles);
            if touching == Some(k) {
                red.extend(start as u32..triangles.len() as u32);
            }
        }
        (triangles, red)
    }
}

/// A capsule as a closed triangle mesh: 12 sides, 3 rings per end cap.
fn capsule_triangles(c: &Capsule, out: &mut Vec<[Vec3; 3]>) {
    const SIDES: usize = 12;
    const RINGS: usize = 3;
    let axis = c.b - c.a;
    let d = if axis.length() > 0.0 {
        axis.normalize()
    } else {
        DVec3::Y
    };
    let u = d.any_orthonormal_vector();
    let w = d.cross(u);
    // Rings from the far pole of a to the far pole of b.
    let mut rings: Vec<Vec<Vec3>> = Vec::new();
    for (end, sign) in [(c.a, -1.0), (c.b, 1.0)] {
        for r in 0..=RINGS {
            let level = if sign < 0.0 { RINGS - r } else { r };
            let polar = std::f64::consts::FRAC_PI_2 * level as f64 / RINGS as f64;
            let (along, across) = (polar.sin() * c.radius * sign, polar.cos() * c.radius);
            rings.push(
                (0..SIDES)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as f64 / SIDES as f64;
                        (end + d * along + (u * a.cos() + w * a.sin()) * across).as_vec3()
                    })
                    .collect(),
            );
        }
    }
    for pair in rings.windows(2) {
        for k in 0..SIDES {
            let k2 = (k + 1) % SIDES;
            out.push([pair[0][k], pair[0][k2], pair[1][k2]]);
            out.push([pair[0][k], pair[1][k2], pair[1][k]]);
        }
    }
}

impl Demo for AvatarCcdDemo {
    /// The figure moves one step along the walk, never past the first time of contact.
    fn step(&mut self) -> anyhow::Result<()> {
        self.time = (self.time + STEP).min(self.stop());
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        let (figure, red) = self.figure();
        let avatar = SnapshotModel {
            triangles: figure,
            colliding: &red,
            cap_boxes: Vec::new(),
        };
        let environment = SnapshotModel {
            triangles: self
                .room
                .triangles
                .iter()
                .map(|t| t.map(|v| self.room.positions[v as usize]))
                .collect(),
            colliding: &[],
            cap_boxes: Vec::new(),
        };
        super::draw_models(canvas, (&avatar, &environment), canvas.below_text(), view)?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec!["the walking figure in the room".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let c = &self.contact;
        let mut lines = vec![format!(
            "lecture 1, avatar CCD: time {:.3} of {} keyframe intervals, {} links, {} triangles",
            self.time,
            self.keyframes.end(),
            self.body.links.len(),
            self.room.triangles.len()
        )];
        lines.push(match (c.time_of_contact, &c.link) {
            (Some(t), Some(link)) => format!(
                "first contact at {t:.4}: {link}{}",
                if self.time >= t { " (stopped)" } else { "" }
            ),
            _ => "no contact on the walk".into(),
        });
        lines.push(format!(
            "{} sub-intervals: {} link bounds, {} after the BVH, {} after the occlusion \
             queries, {} pairs exact",
            c.counts.sub_intervals,
            c.counts.links_bounded,
            c.counts.links_after_bvh,
            c.counts.links_after_gpu,
            c.counts.pairs_after_exact
        ));
        lines
    }

    fn timings(&self) -> String {
        format!(
            "avatar CCD: visibility passes {:.2} ms GPU",
            self.contact.times.visibility_gpu_ms
        )
    }
}
