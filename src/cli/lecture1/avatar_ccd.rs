//! `classic-gpgpu lecture1 avatar-ccd [ENV.obj]`: the first time of contact of a walking
//! figure of capsule links with a triangle environment (`src/lecture1/avatar_ccd/`).

use anyhow::Context as _;
use classic_gpgpu::gl::Context;
use classic_gpgpu::lecture1::avatar_ccd::body::{Body, Keyframes};
use classic_gpgpu::lecture1::avatar_ccd::environment::{published_room, room, Environment};
use classic_gpgpu::lecture1::avatar_ccd::reference::{gap_at, near_the_motion, sample, shapes};
use classic_gpgpu::lecture1::avatar_ccd::{
    advance, visibility, AvatarCcd, Options, DEFAULT_STEPS, DEFAULT_TOLERANCE,
};
use classic_gpgpu::mesh::load_obj;
use classic_gpgpu::values::{ranges, Count, Real, SMALLEST};
use glam::DVec3;
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct AvatarCcdArgs {
    /// The environment (OBJ triangles) [default: the built-in room: a floor, a wall across
    /// the path at z = 2.6, a bench and a pillar beside it].
    pub environment: Option<PathBuf>,
    /// The keyframes (JSON, see the command's description) [default: eight strides of 0.35
    /// along +z from the origin, the pelvis 1.06 above the floor].
    #[arg(long)]
    pub keyframes: Option<PathBuf>,
    /// A gap (distance less the link's radius) at most this is a contact (model units; at
    /// most the environment's size, checked when it is loaded).
    #[arg(long, default_value_t = DEFAULT_TOLERANCE, value_parser = TOLERANCE.of::<f64>())]
    pub tolerance: f64,
    /// Sub-intervals per keyframe interval (each with its own swept bounds).
    #[arg(long, default_value_t = DEFAULT_STEPS, value_parser = STEPS.of::<usize>())]
    pub steps: usize,
    /// Pixels per side of the visibility views.
    #[arg(long, default_value_t = visibility::DEFAULT_RESOLUTION,
          value_parser = RESOLUTION.of::<u32>())]
    pub resolution: u32,
    /// Skip the GPU visibility culling (the BVH's survivors go to the exact tests).
    #[arg(long)]
    pub no_gpu: bool,
    /// The scene: `room`, a 13-link walker and the built-in room (38 triangles); `published`,
    /// the avatar paper's scale: a 16-link avatar (the walker with a neck and hands) and,
    /// without ENV.obj, the room with eight generated tori beside the walk (102,438 triangles).
    /// With `published`, --check runs brute force on the triangles near the motion.
    #[arg(long, value_enum, default_value_t = Scale::Room)]
    pub scale: Scale,
    /// Also run the CPU reference (every link against every triangle at this many sampled
    /// times per keyframe interval, parry3d's distances) and compare.
    #[arg(long, value_parser = SAMPLES.of::<usize>())]
    pub check: Option<usize>,
}

/// `--tolerance`: a positive distance; the environment's size bounds it too ([`within_scene`]).
const TOLERANCE: Real = Real::new(
    "a tolerance",
    SMALLEST,
    f64::MAX,
    "a distance in model units, at most the environment's size (checked when it is loaded)",
);

/// `--steps`: the method's own range ([`AvatarCcd::run`] checks it too).
const STEPS: Count = Count::new(
    "a number of sub-intervals",
    1,
    100_000,
    "each sub-interval is a culling pass of every link",
);

/// `--resolution` of the visibility views (the renderer's texture size is checked when it runs).
const RESOLUTION: Count = Count {
    least: 8,
    ..ranges::TEXTURE_SIDE
};

/// `--check N`: samples of the CPU reference per keyframe interval.
const SAMPLES: Count = Count::new(
    "a number of samples",
    1,
    1_000_000,
    "each sample tests every link against every triangle on the CPU",
);

/// Refuses a tolerance beyond the environment's size: every gap would be within it, so the
/// answer would be a contact at once whatever the motion; that is outside the method's use,
/// and beyond fp32's range (1e100 and up) the GPU's bounds would not even hold it.
fn within_scene(env: &Environment, tolerance: f64) -> anyhow::Result<()> {
    let (low, high) = env.bounds();
    let size = (high - low).length();
    if tolerance > size {
        anyhow::bail!(
            "--tolerance {}: more than the environment's size ({size:.3} units corner to \
             corner), so every gap would be within it and the contact would be at time 0 \
             whatever the motion; give a tolerance above 0 and at most {size:.3}",
            classic_gpgpu::values::number(tolerance)
        );
    }
    Ok(())
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// 13 links, the built-in room of 38 triangles.
    Room,
    /// 16 links, 100k+ triangles (generated), as in Kim, Redon et al. 2007.
    Published,
}

pub fn run(args: &AvatarCcdArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    let body = match args.scale {
        Scale::Room => Body::walker(),
        Scale::Published => Body::avatar16(),
    };
    let mesh = match (&args.environment, args.scale) {
        (Some(path), _) => {
            load_obj(path).with_context(|| format!("reading environment {}", path.display()))?
        }
        (None, Scale::Room) => room(),
        (None, Scale::Published) => published_room(),
    };
    let env = Environment::new(&mesh).with_context(|| match &args.environment {
        Some(p) => format!("environment {}", p.display()),
        None => "the built-in room".into(),
    })?;
    let keyframes = match &args.keyframes {
        Some(path) => Keyframes::load(&body, path)?,
        None => Keyframes::walk(&body, DVec3::new(0.0, 1.06, 0.0), 8, 0.35),
    };
    within_scene(&env, args.tolerance)?;
    // The motion within the advancement's range (also checked by `run`), named by its file.
    if args.tolerance.is_finite() && args.tolerance > 0.0 {
        advance::check_range(&body, &keyframes, args.tolerance).with_context(|| {
            match &args.keyframes {
                Some(p) => format!("keyframes {} (--tolerance {})", p.display(), args.tolerance),
                None => format!("the built-in walk (--tolerance {})", args.tolerance),
            }
        })?;
    }
    let options = Options {
        tolerance: args.tolerance,
        steps: args.steps,
        resolution: args.resolution,
        gpu: !args.no_gpu,
    };
    let mut ccd = AvatarCcd::new(ctx, &options)?;
    let result = ccd.run(&body, &keyframes, &env, &options)?;
    let check = match args.check {
        Some(n) => {
            // At the published scale, brute force on the triangles near the motion (those
            // farther cannot come within the tolerance).
            let near = match args.scale {
                Scale::Published => Some(near_the_motion(&body, &keyframes, &env, 256, 0.25)?),
                Scale::Room => None,
            };
            let reference_env = near.as_ref().unwrap_or(&env);
            let sampled = sample(&body, &keyframes, reference_env, n, args.tolerance);
            let gap_there = result
                .time_of_contact
                .map(|t| gap_at(&body, &keyframes, &shapes(reference_env), t).0);
            Some(json!({
                "samples_per_interval": n,
                "reference_triangles": reference_env.triangles.len(),
                "first_within_tolerance": sampled.first_within_tolerance.map(|(t, _)| t),
                "first_within_tolerance_link": sampled
                    .first_within_tolerance
                    .map(|(_, l)| body.links[l].name.clone()),
                "first_overlap": sampled.first_overlap,
                "min_gap": sampled.min_gap,
                "reference_gap_at_time_of_contact": gap_there,
            }))
        }
        None => None,
    };
    let renderer = ctx.info().renderer_line();
    if json {
        let mut report = serde_json::to_value(&result)?;
        report["renderer"] = json!(renderer);
        report["links"] = json!(body.links.len());
        report["triangles"] = json!(env.triangles.len());
        if let Some(c) = check {
            report["reference"] = c;
        }
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("renderer: {renderer}");
    println!(
        "{} links, {} triangles, {} keyframes, {} sub-intervals examined",
        body.links.len(),
        env.triangles.len(),
        keyframes.poses.len(),
        result.counts.sub_intervals
    );
    match (result.time_of_contact, &result.link, result.contact_point) {
        (Some(t), Some(link), Some(p)) => println!(
            "first contact at time {t:.6} (keyframe intervals): {link} at ({:.4}, {:.4}, {:.4}), \
             gap {:.2e} (tolerance {})",
            p[0],
            p[1],
            p[2],
            result.gap.unwrap_or(0.0),
            result.tolerance
        ),
        _ => println!("no contact up to time {}", result.end_time),
    }
    if let Some(c) = check {
        println!("reference: {c}");
    }
    Ok(())
}
