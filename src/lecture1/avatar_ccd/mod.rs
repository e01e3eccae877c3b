//! Continuous collision detection for an avatar: Kim, Redon, Lin, Manocha & Templeman,
//! "Interactive continuous collision detection using swept volume for avatars", Presence
//! 16(2), 2007 (earlier: Redon et al., IEEE VR 2004).
//!
//! Confirmed of the paper (`lecture1-sources.md`, section 4): a loop-free articulated body of
//! line-skeleton links with constant offsets moves between discrete poses through a polygon
//! environment; the in-between motion interpolates each link; a bound of each link's swept
//! space (interval arithmetic) and a BVH cull distant links; the swept volumes of the rest
//! are tested for interference on graphics hardware, the surfaces generated at run time; the
//! first time of contact is estimated so that, within a tolerance, no earlier contact is
//! missed. Which GPU query, the bounds and the search are not public, so each step below is a
//! reconstruction:
//!
//! 1. [`body`]: capsule links, forward kinematics, keyframes interpolated link by link.
//! 2. [`sweep_bound`]: a speed bound per link from its chain; the swept capsule bound of a
//!    sub-interval.
//! 3. [`environment`]: the triangles and their BVH (parry3d); a link whose bound meets no
//!    triangle box is culled.
//! 4. [`visibility`] (OpenGL 3.3): CULLIDE's visibility culling with occlusion queries
//!    between the surviving links' swept bounds and their nearby triangles, both grown by a
//!    pixel as in R-CULLIDE so that no contact is culled. Chosen because CULLIDE is the
//!    GPU culling a co-author published in the same years, it needs only what the paper's
//!    GeForce 6800 had (occlusion queries), and it works on the swept bounds drawn as they
//!    are made, with no precomputation.
//! 5. [`exact`]: the segment–triangle distance in f64 against each survivor's swept radius.
//! 6. [`advance`]: conservative advancement to the first time a gap is within the tolerance.
//!
//! [`reference`](mod@reference) is brute force over densely sampled times with parry3d's distances.
//! Shaders: `glsl/lecture1/avatar_visibility.*`.

pub mod advance;
pub mod body;
pub mod environment;
pub mod exact;
pub mod reference;
pub mod sweep_bound;
pub mod visibility;

use crate::gl::{Context, GlError};
use body::{Body, Keyframes};
use environment::Environment;
use serde::Serialize;
use std::time::Instant;
use sweep_bound::{link_speeds, swept_capsule};
use visibility::VisibilityCuller;

/// Default sub-intervals per keyframe interval.
pub const DEFAULT_STEPS: usize = 8;
/// Default distance tolerance (model units).
pub const DEFAULT_TOLERANCE: f64 = 1e-3;

/// How to run the query.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// A gap (distance less radius) at most this counts as contact.
    pub tolerance: f64,
    /// Sub-intervals per keyframe interval (each gets its own swept bounds).
    pub steps: usize,
    /// Pixels per side of the visibility views.
    pub resolution: u32,
    /// Run the GPU visibility culling (else the BVH's survivors go straight to the exact
    /// tests: the comparison of where the time goes).
    pub gpu: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            tolerance: DEFAULT_TOLERANCE,
            steps: DEFAULT_STEPS,
            resolution: visibility::DEFAULT_RESOLUTION,
            gpu: true,
        }
    }
}

/// What each stage kept, summed over the sub-intervals examined.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Counts {
    pub sub_intervals: usize,
    /// Link bounds made.
    pub links_bounded: usize,
    /// Links whose bound meets a triangle box of the BVH.
    pub links_after_bvh: usize,
    /// (link, triangle) pairs the BVH kept.
    pub pairs_after_bvh: usize,
    /// Links and pairs the visibility culling kept (the BVH's when it does not run).
    pub links_after_gpu: usize,
    pub pairs_after_gpu: usize,
    /// Pairs whose exact distance is within the swept radius.
    pub pairs_after_exact: usize,
    pub occlusion_queries: usize,
    pub advancement_steps: usize,
    /// The largest growth ε of the visibility passes.
    pub epsilon: f64,
}

/// Where the time went (wall clock, ms; the GPU passes also by timer queries).
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Times {
    pub bounds_ms: f64,
    pub bvh_ms: f64,
    /// Visibility culling, wall clock (upload, passes, query results).
    pub visibility_ms: f64,
    /// Visibility passes, timer queries.
    pub visibility_gpu_ms: f64,
    pub exact_ms: f64,
    pub advance_ms: f64,
}

/// The answer.
#[derive(Clone, Debug, Serialize)]
pub struct Contact {
    /// The first time of contact in keyframe intervals (keyframe k at time k); `None` when
    /// the motion has none.
    pub time_of_contact: Option<f64>,
    /// The link in contact, by name and index.
    pub link: Option<String>,
    pub link_index: Option<usize>,
    /// The environment triangle touched.
    pub triangle: Option<u32>,
    /// The closest point of the environment to the link at that time.
    pub contact_point: Option<[f64; 3]>,
    /// The gap there (at most the tolerance).
    pub gap: Option<f64>,
    pub tolerance: f64,
    /// The motion's end time (the last keyframe).
    pub end_time: f64,
    pub steps: usize,
    pub resolution: u32,
    pub gpu: bool,
    pub counts: Counts,
    pub times: Times,
}

/// The GPU culler (absent when the query runs without it).
pub struct AvatarCcd {
    culler: Option<VisibilityCuller>,
}

impl AvatarCcd {
    pub fn new(ctx: &Context, options: &Options) -> Result<AvatarCcd, GlError> {
        Ok(AvatarCcd {
            culler: if options.gpu {
                Some(VisibilityCuller::new(ctx, options.resolution)?)
            } else {
                None
            },
        })
    }

    /// The first contact of `body` moving through `keyframes` in `env`.
    pub fn run(
        &mut self,
        body: &Body,
        keyframes: &Keyframes,
        env: &Environment,
        options: &Options,
    ) -> anyhow::Result<Contact> {
        body.validate()?;
        anyhow::ensure!(
            keyframes
                .poses
                .iter()
                .all(|p| p.angles.len() == body.links.len()),
            "every keyframe needs angles for each of the body's {} links",
            body.links.len()
        );
        anyhow::ensure!(
            options.tolerance.is_finite() && options.tolerance > 0.0,
            "the tolerance must be a positive distance, not {}",
            options.tolerance
        );
        anyhow::ensure!(
            (1..=100_000).contains(&options.steps),
            "the sub-intervals per keyframe interval must be 1 to 100000, not {}",
            options.steps
        );
        advance::check_range(body, keyframes, options.tolerance)?;
        let mut counts = Counts::default();
        let mut times = Times::default();
        let mut found = None;
        let intervals = keyframes.poses.len().saturating_sub(1).max(1);
        'all: for k in 0..intervals {
            let speeds = link_speeds(body, keyframes, k);
            // One pose: a body at rest, one zero-length sub-interval.
            let steps = if keyframes.poses.len() < 2 {
                1
            } else {
                options.steps
            };
            for step in 0..steps {
                let h = if keyframes.poses.len() < 2 {
                    0.0
                } else {
                    1.0 / steps as f64
                };
                let (t0, t1) = (k as f64 + step as f64 * h, k as f64 + (step + 1) as f64 * h);
                let t1 = t1.min(keyframes.end().max(t0));
                counts.sub_intervals += 1;
                let pairs = self.survivors(
                    body,
                    keyframes,
                    env,
                    &speeds,
                    (t0, t1),
                    options,
                    &mut counts,
                    &mut times,
                )?;
                if pairs.is_empty() {
                    continue;
                }
                let clock = Instant::now();
                let (contact, steps) = advance::advance(
                    body,
                    keyframes,
                    env,
                    &pairs,
                    &speeds,
                    (t0, t1),
                    options.tolerance,
                )?;
                times.advance_ms += ms(clock);
                counts.advancement_steps += steps;
                if let Some(c) = contact {
                    found = Some(c);
                    break 'all;
                }
            }
        }
        Ok(Contact {
            time_of_contact: found.map(|c| c.time),
            link: found.map(|c| body.links[c.link].name.clone()),
            link_index: found.map(|c| c.link),
            triangle: found.map(|c| c.triangle),
            contact_point: found.map(|c| c.nearest.on_triangle.to_array()),
            gap: found.map(|c| c.gap),
            tolerance: options.tolerance,
            end_time: keyframes.end(),
            steps: options.steps,
            resolution: options.resolution,
            gpu: self.culler.is_some(),
            counts,
            times,
        })
    }

    /// One sub-interval's culling: the swept bounds, the BVH, the visibility passes and the
    /// exact tests; the (link, triangles) pairs left.
    #[allow(clippy::too_many_arguments)]
    fn survivors(
        &mut self,
        body: &Body,
        keyframes: &Keyframes,
        env: &Environment,
        speeds: &[f64],
        (t0, t1): (f64, f64),
        options: &Options,
        counts: &mut Counts,
        times: &mut Times,
    ) -> anyhow::Result<Vec<(usize, Vec<u32>)>> {
        // Swept capsule bounds, grown by the tolerance (a gap within it is a contact).
        let clock = Instant::now();
        let middle = body.capsules(&keyframes.pose_at(0.5 * (t0 + t1)));
        let bounds: Vec<_> = middle
            .iter()
            .zip(speeds)
            .map(|(c, &v)| {
                let mut b = swept_capsule(*c, v, t0, t1);
                b.radius += options.tolerance;
                b
            })
            .collect();
        anyhow::ensure!(
            bounds
                .iter()
                .all(|b| b.a.is_finite() && b.b.is_finite() && b.radius.is_finite()),
            "a link's swept bound in [{t0}, {t1}] is not finite"
        );
        counts.links_bounded += bounds.len();
        times.bounds_ms += ms(clock);
        // The BVH culls far links.
        let clock = Instant::now();
        let mut pairs: Vec<(usize, Vec<u32>)> = bounds
            .iter()
            .enumerate()
            .map(|(l, b)| (l, env.near(b)))
            .filter(|(_, near)| !near.is_empty())
            .collect();
        counts.links_after_bvh += pairs.len();
        counts.pairs_after_bvh += pairs.iter().map(|p| p.1.len()).sum::<usize>();
        times.bvh_ms += ms(clock);
        if pairs.is_empty() {
            return Ok(pairs);
        }
        // The visibility culling on the GPU.
        if let Some(culler) = &mut self.culler {
            let clock = Instant::now();
            let mut triangles: Vec<u32> = pairs.iter().flat_map(|p| p.1.iter().copied()).collect();
            triangles.sort_unstable();
            triangles.dedup();
            let links: Vec<_> = pairs.iter().map(|p| bounds[p.0]).collect();
            let corners: Vec<_> = triangles
                .iter()
                .map(|&t| env.triangles[t as usize])
                .collect();
            let kept = culler.cull(&links, &corners)?;
            counts.occlusion_queries += kept.queries;
            counts.epsilon = counts.epsilon.max(kept.epsilon);
            times.visibility_gpu_ms += kept.gpu_ms;
            let mut visible = vec![false; env.triangles.len()];
            for &k in &kept.triangles {
                visible[triangles[k] as usize] = true;
            }
            pairs = kept
                .links
                .iter()
                .map(|&k| {
                    let (link, near) = &pairs[k];
                    (
                        *link,
                        near.iter()
                            .copied()
                            .filter(|&t| visible[t as usize])
                            .collect(),
                    )
                })
                .filter(|(_, near): &(usize, Vec<u32>)| !near.is_empty())
                .collect();
            times.visibility_ms += ms(clock);
        }
        counts.links_after_gpu += pairs.len();
        counts.pairs_after_gpu += pairs.iter().map(|p| p.1.len()).sum::<usize>();
        // The exact tests: the middle segment within the swept radius of the triangle.
        let clock = Instant::now();
        for (link, near) in &mut pairs {
            let b = bounds[*link];
            near.retain(|&t| {
                exact::segment_triangle(b.a, b.b, env.triangles[t as usize]).distance <= b.radius
            });
        }
        pairs.retain(|p| !p.1.is_empty());
        counts.pairs_after_exact += pairs.iter().map(|p| p.1.len()).sum::<usize>();
        times.exact_ms += ms(clock);
        Ok(pairs)
    }
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}
