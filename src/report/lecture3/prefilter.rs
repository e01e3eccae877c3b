//! Technique 2's minification prefilter (`crate::lecture3::displacement::prefilter`): as the
//! camera moves away, each frame's error against a supersampled unfiltered image and its GPU
//! time and traversal steps, with and without the prefilter, and the prefiltered frame judged
//! pixel by pixel against the CPU reference of the same rule.

use super::scene::DEPTH;
use super::timed::gpu_ms_warm;
use crate::lecture3::displacement::compare::{Comparison, ReferenceImage};
use crate::lecture3::displacement::prefilter::{image_error, may_act, shown_of_rgba8};
use crate::lecture3::displacement::tracer::supersampled;
use crate::lecture3::displacement::{Camera, DisplacementRenderer, Frame, Method, Pixel, Surface};
use crate::lecture3::HeightMap;
use crate::report::BenchOptions;
use crate::timing::{Runs, Spread};
use serde::Serialize;

/// A prefiltered frame's quality beside the unfiltered frame of the same view.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PrefilterQuality {
    /// Rays per pixel along each side of the supersampled reference.
    pub samples: u32,
    /// RMS difference (RGB in 0..1) from the supersampled image, over the pixels either shows.
    pub prefiltered_error: f64,
    pub unfiltered_error: f64,
    /// Mean traversal steps per hit pixel.
    pub prefiltered_steps: f64,
    pub unfiltered_steps: f64,
}

/// Rays per pixel side of the command's and the report's reference.
pub const SUPERSAMPLES: u32 = 4;

/// Mean traversal steps per hit pixel of a frame.
pub fn mean_steps(frame: &Frame) -> f64 {
    let steps: Vec<f64> = frame
        .pixels()
        .iter()
        .filter_map(|p| match p {
            Pixel::Hit { iterations, .. } => Some(*iterations as f64),
            _ => None,
        })
        .collect();
    steps.iter().sum::<f64>() / steps.len().max(1) as f64
}

/// `prefiltered` (a prefiltered frame of `camera`) and the unfiltered frame of the same view
/// against a `SUPERSAMPLES`-squared unfiltered reference.
pub fn prefilter_quality(
    renderer: &DisplacementRenderer,
    camera: &Camera,
    prefiltered: &Frame,
) -> anyhow::Result<PrefilterQuality> {
    let reference = supersampled(renderer, camera, SUPERSAMPLES)?;
    let target = renderer.target(camera.width, camera.height)?;
    renderer.render(&target, camera, Method::Pyramid)?;
    let unfiltered = renderer.read(&target)?;
    unfiltered.check_finished()?;
    Ok(PrefilterQuality {
        samples: SUPERSAMPLES,
        prefiltered_error: finite(image_error(
            &shown_of_rgba8(&prefiltered.colour),
            &reference,
        ))?,
        unfiltered_error: finite(image_error(&shown_of_rgba8(&unfiltered.colour), &reference))?,
        prefiltered_steps: mean_steps(prefiltered),
        unfiltered_steps: mean_steps(&unfiltered),
    })
}

fn finite(x: f64) -> anyhow::Result<f64> {
    anyhow::ensure!(x.is_finite(), "an image error that is not a number: {x}");
    Ok(x)
}

/// One camera distance at one elevation.
#[derive(Clone, Debug, Serialize)]
pub struct PrefilterRow {
    pub distance: f32,
    /// Degrees above the map's plane.
    pub elevation: f32,
    /// The largest stop level of the view's pixels (0: the prefilter changes nothing).
    pub max_level: u32,
    pub quality: PrefilterQuality,
    pub unfiltered_ms: f64,
    pub unfiltered_spread: Spread,
    pub prefiltered_ms: f64,
    pub prefiltered_spread: Spread,
    /// Of the prefiltered frame's time, drawing its shading pyramid toward the camera (0 where
    /// no pixel stops above level 0: it is not drawn).
    pub shading_ms: f64,
    pub shading_spread: Spread,
    /// The prefiltered frame against the CPU reference of the same rule.
    pub comparison: Comparison,
}

// region: workload prefilter-distances
/// The camera distances of the sweep.
pub fn distances(quick: bool) -> &'static [f32] {
    if quick {
        &[3.2, 12.8]
    } else {
        &[3.2, 6.4, 12.8, 25.6]
    }
}
// endregion

/// The elevations of the sweep (degrees): the report's view, seen steeply, and grazing.
pub const ELEVATIONS: [f32; 3] = [35.0, 70.0, 15.0];

/// The elevations below which a view counts as grazing.
pub const GRAZING: f32 = 20.0;

/// The sweep on `map` at each of [`ELEVATIONS`]. A prefiltered frame's time includes drawing
/// its shading pyramid toward the camera.
pub fn measure(
    opts: &BenchOptions,
    map: &HeightMap,
    runs: Runs,
) -> anyhow::Result<Vec<PrefilterRow>> {
    let ctx = opts.gl;
    // region: workload prefilter-image
    let image = if opts.quick { 64 } else { 128 };
    // endregion
    let renderer = DisplacementRenderer::new(ctx, Surface::new(map.clone(), DEPTH)?)?;
    let target = renderer.target(image, image)?;
    ELEVATIONS
        .iter()
        .flat_map(|&elevation| distances(opts.quick).iter().map(move |&d| (d, elevation)))
        .map(|(distance, elevation)| {
            let camera = Camera::orbit(
                renderer.surface().centre(),
                distance,
                225.0,
                elevation,
                image,
                image,
            );
            renderer.render(&target, &camera, Method::Prefiltered)?;
            let frame = renderer.read(&target)?;
            frame.check_finished()?;
            let reference = ReferenceImage::trace_prefiltered(renderer.surface(), &camera);
            let (comparison, _) = reference.judge(&frame);
            let quality = prefilter_quality(&renderer, &camera, &frame)?;
            let time = |method| {
                renderer.render(&target, &camera, method)?;
                gpu_ms_warm(ctx, runs, || Ok(renderer.render(&target, &camera, method)?))
            };
            let unfiltered = time(Method::Pyramid)?;
            let prefiltered = time(Method::Prefiltered)?;
            let shading = if may_act(&camera, renderer.surface()) {
                gpu_ms_warm(ctx, runs, || Ok(renderer.draw_shading(&camera)?))?
            } else {
                Spread::default()
            };
            Ok(PrefilterRow {
                distance,
                elevation,
                max_level: reference.max_level(),
                quality,
                unfiltered_ms: unfiltered.median,
                unfiltered_spread: unfiltered,
                prefiltered_ms: prefiltered.median,
                prefiltered_spread: prefiltered,
                shading_ms: shading.median,
                shading_spread: shading,
                comparison,
            })
        })
        .collect()
}
