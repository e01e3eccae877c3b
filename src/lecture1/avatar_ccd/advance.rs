//! Step 6, "the first time of contact is estimated; within a user tolerance, no earlier
//! contact is missed": conservative advancement over the pairs that survived the culling of
//! one sub-interval. At time s each link's gap (the distance from its segment to its nearest
//! surviving triangle, less its radius) cannot shrink faster than the link's speed bound, so
//! no contact can happen before s + gap / speed; the time advances by the smallest such step
//! over the links until some gap is within the tolerance (the contact) or the sub-interval
//! ends. The reported time s therefore has a gap of at most the tolerance, and no time before
//! it has an overlap (a negative gap).
//!
//! The method's range: while every gap is above the tolerance, a step is at least tolerance /
//! speed long, so a keyframe interval whose links move at most v takes at most v / tolerance
//! steps (plus one per sub-interval). [`check_range`] refuses, before anything runs, a motion
//! whose bound passes [`MOST_STEPS`]: a turn of thousands of radians between two keyframes
//! would otherwise run for minutes, and one beyond fp32 would make the bounds meaningless.

use super::body::{Body, Keyframes};
use super::environment::Environment;
use super::exact::{segment_triangle, Nearest};
use super::sweep_bound::{joint_rates, link_speeds};

/// Most advancement steps in one keyframe interval ([`check_range`]'s bound; the loop's limit
/// in each sub-interval too).
pub const MOST_STEPS: usize = 1_000_000;

/// A contact: when, which link and triangle, and the closest points there.
#[derive(Clone, Copy, Debug)]
pub struct ContactAt {
    pub time: f64,
    pub link: usize,
    pub triangle: u32,
    pub nearest: Nearest,
    /// Distance less radius (at most the tolerance).
    pub gap: f64,
}

/// The nearest surviving triangle of each link at time `s`: (link, triangle, nearest, gap).
fn gaps(
    body: &Body,
    keyframes: &Keyframes,
    env: &Environment,
    pairs: &[(usize, Vec<u32>)],
    s: f64,
) -> Vec<(usize, u32, Nearest, f64)> {
    let capsules = body.capsules(&keyframes.pose_at(s));
    pairs
        .iter()
        .filter_map(|(link, triangles)| {
            let c = capsules[*link];
            triangles
                .iter()
                .map(|&t| {
                    let n = segment_triangle(c.a, c.b, env.triangles[t as usize]);
                    (*link, t, n, n.distance - c.radius)
                })
                .min_by(|x, y| x.3.total_cmp(&y.3))
        })
        .collect()
}

/// Advance from `t0` to at most `t1` over `pairs` (link, its surviving triangles), `speeds`
/// per link; the contact if there is one, and the steps taken.
#[allow(clippy::too_many_arguments)]
pub fn advance(
    body: &Body,
    keyframes: &Keyframes,
    env: &Environment,
    pairs: &[(usize, Vec<u32>)],
    speeds: &[f64],
    (t0, t1): (f64, f64),
    tolerance: f64,
) -> anyhow::Result<(Option<ContactAt>, usize)> {
    let mut s = t0;
    for step in 1..=MOST_STEPS {
        let now = gaps(body, keyframes, env, pairs, s);
        let nearest = now.iter().min_by(|x, y| x.3.total_cmp(&y.3));
        let Some(&(link, triangle, nearest, gap)) = nearest else {
            return Ok((None, step));
        };
        anyhow::ensure!(
            gap.is_finite(),
            "a non-finite gap ({gap}) between link {link} and triangle {triangle} at time {s}"
        );
        if gap <= tolerance {
            return Ok((
                Some(ContactAt {
                    time: s,
                    link,
                    triangle,
                    nearest,
                    gap,
                }),
                step,
            ));
        }
        let safe = now
            .iter()
            .map(|&(l, _, _, g)| {
                if speeds[l] > 0.0 {
                    g / speeds[l]
                } else {
                    f64::INFINITY
                }
            })
            .fold(f64::INFINITY, f64::min);
        if s + safe >= t1 {
            return Ok((None, step));
        }
        anyhow::ensure!(
            s + safe > s,
            "conservative advancement stalled at time {s}: the step {safe:e} is below the time's \
             precision (link speeds too high for the tolerance {tolerance})"
        );
        s += safe;
    }
    anyhow::bail!("conservative advancement took more than {MOST_STEPS} steps in [{t0}, {t1}]")
}

/// Refuses a motion outside the advancement's range: in some keyframe interval the links'
/// speed bound over the tolerance passes [`MOST_STEPS`]. The error names the two keyframes and
/// the link whose angles change the most there (or the root, when it moves the most), with the
/// values, and what to do.
pub fn check_range(body: &Body, keyframes: &Keyframes, tolerance: f64) -> anyhow::Result<()> {
    for k in 0..keyframes.poses.len().saturating_sub(1) {
        let fastest = link_speeds(body, keyframes, k)
            .into_iter()
            .fold(
                0.0f64,
                |a, b| if b.is_nan() { f64::INFINITY } else { a.max(b) },
            );
        let worst = fastest / tolerance;
        if worst <= MOST_STEPS as f64 {
            continue;
        }
        let (a, b) = (&keyframes.poses[k], &keyframes.poses[k + 1]);
        let rates = joint_rates(keyframes, k);
        let turning = (0..rates.len()).max_by(|&x, &y| rates[x].total_cmp(&rates[y]));
        let root_move = (b.root - a.root).length();
        let what = match turning {
            Some(l) if rates[l] >= root_move => format!(
                "link \"{}\" turns from angles {:?} to {:?} rad ({} rad in all, {} turns)",
                body.links[l].name,
                a.angles[l].to_array(),
                b.angles[l].to_array(),
                number(rates[l]),
                number(rates[l] / std::f64::consts::TAU)
            ),
            _ => format!(
                "the root moves from {:?} to {:?}",
                a.root.to_array(),
                b.root.to_array()
            ),
        };
        anyhow::bail!(
            "keyframes {k} to {}: {what}; the figure's points then move up to {} units in the \
             interval, and conservative advancement at tolerance {tolerance} could need {} \
             steps there, more than the {MOST_STEPS} it is allowed (points may \
             move at most {:.3e} units per keyframe interval at this tolerance): split the \
             motion over more keyframes, or raise the tolerance",
            k + 1,
            number(fastest),
            number(worst),
            MOST_STEPS as f64 * tolerance
        );
    }
    Ok(())
}

/// A number for a message: `1.234e5`, or what it is when it is beyond a double.
fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3e}")
    } else {
        "more than a double holds".to_string()
    }
}
