//! Step 6, "the first time of contact is estimated; within a user tolerance, no earlier
//! contact is missed": conservative advancement over the pairs that survived the culling of
//! one sub-interval. At time s each link's gap (the distance from its segment to its nearest
//! surviving triangle, less its radius) cannot shrink faster than the link's speed bound, so
//! no contact can happen before s + gap / speed; the time advances by the smallest such step
//! over the links until some gap is within the tolerance (the contact) or the sub-interval
//! ends. The reported time s therefore has a gap of at most the tolerance, and no time before
//! it has an overlap (a negative gap).

use super::body::{Body, Keyframes};
use super::environment::Environment;
use super::exact::{segment_triangle, Nearest};

/// Most advancement steps in one sub-interval (each is at least tolerance / speed long).
const MOST_STEPS: usize = 1_000_000;

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
        s += safe;
    }
    anyhow::bail!("conservative advancement took more than {MOST_STEPS} steps in [{t0}, {t1}]")
}
