//! A GPU frame against the exact CPU tracer, pixel by pixel.
//!
//! Tolerance, stated once: a tracer in fp32 finds the exact hit of a height field perturbed
//! by its rounding. With `delta` (height units, the map spanning 0..1) above that rounding,
//! a correct tracer's hit lies between the exact hits of the field raised by `delta` and
//! lowered by `delta` (raising a field never makes its first hit later), within `slack` of
//! ray parameter; and where the lowered field is hit, it must hit. Where raising and lowering
//! by `delta` change which surface is hit, the pixel is ill-conditioned (a ray grazing a
//! crest): it is counted as ambiguous and not judged.
//!
//! A pixel's hit is on the "wrong surface" when it hits where the exact tracer misses (or the
//! reverse), or lands more than one patch away from the exact hit: relief mapping's artifact.
//!
//! What is drawn is judged too, on every pixel both hit (and not ill-conditioned): the kind
//! (the surface, or the box's wall where the ray enters through a side below the surface)
//! must be the exact tracer's; the normal the pixel is shaded with must be the field's normal
//! at the GPU's hit or at the exact hit (within `NORMAL_TOL`; beside a patch edge, that of
//! either patch, as the field's normal jumps there); and the colour must be the shading of
//! that normal and the checkerboard's albedo there, within `COLOUR_TOL`
//! ([`super::shading`]). Pixels where raising or lowering the field by `DELTA` changes the
//! kind are ill-conditioned as well.
//!
//! A prefiltered frame ([`super::prefilter`]) is judged the same way against the exact tracer
//! of the field its pixel's rule makes (each patch on the prefiltered patch of its cut node,
//! shaded with the stop level's shading of the facets facing the eye,
//! [`super::visible_shading`]); pixels whose stop level, or the cut of a patch on their way,
//! fp32 rounding could change are ill-conditioned.

use super::camera::Camera;
use super::exact::{box_interval, trace, Hit};
use super::prefilter::{LevelField, Prefilter, Traced};
use super::shading;
use super::surface::Surface;
use super::tracer::{Frame, Pixel};
use glam::DVec3;
use serde::Serialize;

/// Height perturbation the tests allow: fp32 rounding of grid coordinates up to ~150 patches
/// is about 1e-5 patch, times a slope of at most 1 height per patch; one order of magnitude
/// above that.
pub const DELTA: f64 = 1e-4;
/// Ray-parameter slack (world units) for the rounding of the reported hit itself.
pub const SLACK: f64 = 1e-4;
/// How far (patches) from a patch or square edge a hit may show either side's normal or
/// albedo: fp32 rounding of the grid position (~1e-5), with margin.
pub const EDGE: f64 = 1e-3;
/// The largest difference between the shown unit normal and the field's: fp32 evaluation of
/// slopes up to ~10 (~1e-5), with margin.
pub const NORMAL_TOL: f64 = 2e-3;
/// The largest difference (per channel, in [0, 1]) between the shown colour and the shading
/// of the shown normal: half a step of the 8-bit target, plus fp32 error.
pub const COLOUR_TOL: f64 = 1.0 / 255.0;

/// How a frame compares with the exact tracer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Comparison {
    /// Pixels whose ray crosses the box (more than `SLACK` inside it).
    pub compared: usize,
    /// Exact hits among them.
    pub exact_hits: usize,
    /// Ill-conditioned pixels (see the module doc), not judged.
    pub ambiguous: usize,
    /// Pixels outside the `DELTA` / `SLACK` tolerance.
    pub outside_tolerance: usize,
    /// Pixels whose hit is on another surface than the exact one (or hits/misses wrongly).
    pub wrong_surface: usize,
    /// Pixels that show the surface where the exact hit is on the box's wall, or the reverse.
    pub wrong_kind: usize,
    /// Pixels shaded with another normal than the field's (or the wall's) at the hit.
    pub wrong_normal: usize,
    /// Pixels whose colour is not the shading of their normal and albedo.
    pub wrong_colour: usize,
    /// The largest |tau - exact tau| over the pixels both hit and judged, world units.
    pub max_tau_error: f64,
    /// Traversals that did not end.
    pub unfinished: usize,
}

/// What the exact tracer says of one pixel.
struct Reference {
    exact: Option<Hit>,
    raised: Option<Hit>,
    lowered: Option<Hit>,
    /// The prefilter's stop level for this pixel (0 without the prefilter).
    level: u32,
    /// The stop level is at the edge of fp32 rounding.
    level_borderline: bool,
}

impl Reference {
    fn ambiguous(&self) -> bool {
        if self.level_borderline {
            return true;
        }
        match (self.raised, self.lowered, self.exact) {
            (Some(r), Some(l), Some(e)) => {
                (r.grid.truncate() - l.grid.truncate()).length() > 1.0
                    || r.wall != e.wall
                    || l.wall != e.wall
            }
            (None, None, None) => false,
            _ => true,
        }
    }

    fn within_tolerance(&self, pixel: &Pixel) -> bool {
        match *pixel {
            Pixel::Hit { tau, .. } => {
                let earliest = self.raised.map(|h| h.tau);
                let latest = self.lowered.map_or(f64::INFINITY, |h| h.tau);
                earliest.is_some_and(|e| e - SLACK <= tau) && tau <= latest + SLACK
            }
            Pixel::Miss => self.lowered.is_none(),
            Pixel::Unfinished => false,
        }
    }

    fn wrong_surface(&self, pixel: &Pixel) -> bool {
        match (*pixel, self.exact) {
            (Pixel::Hit { grid, .. }, Some(e)) => {
                (grid.truncate() - e.grid.truncate()).length() > 1.0
            }
            (Pixel::Miss, None) => false,
            _ => true,
        }
    }
}

/// How the pixel's drawing departs from the exact hit's, if it does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Drawn {
    Right,
    WrongKind,
    WrongNormal,
    WrongColour,
}

/// The kind, normal and colour of a pixel that hit where the exact tracer hit `exact`
/// (`rgb`: its shown colour).
fn judge_drawing(
    surface: &Surface,
    field: Option<&LevelField>,
    exact: &Hit,
    pixel: &Pixel,
    rgb: [f64; 3],
) -> Drawn {
    let Pixel::Hit {
        grid, wall, normal, ..
    } = *pixel
    else {
        return Drawn::Right;
    };
    if wall != exact.wall {
        return Drawn::WrongKind;
    }
    // The exact point's candidates reach as far as the GPU's hit is from it.
    let reach = (grid - exact.grid).truncate().length() + EDGE;
    let normals_at = |g: DVec3, margin: f64| match (wall, field) {
        (true, _) => shading::wall_normals(surface, g, margin),
        (false, Some(field)) => field.surface_normals(g),
        (false, None) => shading::surface_normals(surface, g, margin),
    };
    let mut normals = normals_at(grid, EDGE);
    normals.extend(normals_at(exact.grid, reach));
    if !normals.iter().any(|n| (*n - normal).length() <= NORMAL_TOL) {
        return Drawn::WrongNormal;
    }
    let mut albedos = shading::albedos(grid, EDGE);
    albedos.extend(shading::albedos(exact.grid, reach));
    let shaded = |albedo| shading::shade(albedo, normal);
    let close = |c: [f64; 3]| (0..3).all(|k| (c[k] - rgb[k]).abs() <= COLOUR_TOL);
    if !albedos.into_iter().any(|a| close(shaded(a))) {
        return Drawn::WrongColour;
    }
    Drawn::Right
}

/// What the comparison says of one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// The ray grazes the box's silhouette (or misses the box): not compared.
    NotCompared,
    /// Ill-conditioned: not judged.
    Ambiguous,
    /// Within tolerance, on the exact surface.
    Exact,
    /// On the exact surface but outside the DELTA / SLACK tolerance.
    OutsideTolerance,
    /// On another surface than the exact one, or a wrong hit / miss.
    WrongSurface,
    /// At the exact hit, but drawn as a wall where the surface is hit (or the reverse).
    WrongKind,
    /// At the exact hit, but shaded with a wrong normal or colour.
    WrongShading,
}

/// The exact tracer's answers for every pixel of a view, traced once and used to judge any
/// number of frames of that view.
pub struct ReferenceImage {
    surface: Surface,
    /// The prefilter's rule and fields, for prefiltered frames.
    prefilter: Option<Prefilter>,
    /// `None` for pixels not compared (silhouette or outside the box).
    pixels: Vec<Option<Reference>>,
}

impl ReferenceImage {
    /// Traces every pixel of `camera` (three times: exact, raised and lowered by DELTA).
    /// The rows are shared out among the machine's cores (every pixel traced on its own, as
    /// one thread would).
    pub fn trace(surface: &Surface, camera: &Camera) -> ReferenceImage {
        ReferenceImage::trace_with(surface, camera, None)
    }

    /// The reference for prefiltered frames of `camera`: each pixel traced through the field
    /// of its stop level.
    pub fn trace_prefiltered(surface: &Surface, camera: &Camera) -> ReferenceImage {
        ReferenceImage::trace_with(surface, camera, Some(Prefilter::new(surface, camera)))
    }

    fn trace_with(
        surface: &Surface,
        camera: &Camera,
        prefilter: Option<Prefilter>,
    ) -> ReferenceImage {
        let rule = prefilter.as_ref();
        let (width, height) = (camera.width as usize, camera.height as usize);
        let rows: Vec<usize> = (0..height).collect();
        let (pixels, _) = crate::lecture3::map_on_all_cores(&rows, |&y| {
            (0..width)
                .map(|x| reference(surface, camera, rule, x as u32, y as u32))
                .collect::<Vec<_>>()
        });
        ReferenceImage {
            surface: surface.clone(),
            prefilter,
            pixels: pixels.into_iter().flatten().collect(),
        }
    }

    /// The deepest stop level of the view's compared pixels (0 without the prefilter).
    pub fn max_level(&self) -> u32 {
        self.pixels
            .iter()
            .flatten()
            .map(|r| r.level)
            .max()
            .unwrap_or(0)
    }

    /// Judges a frame of the same view: where each pixel's ray stops, and what it shows.
    pub fn judge(&self, frame: &Frame) -> (Comparison, Vec<Verdict>) {
        let mut c = Comparison::default();
        let pixels = frame.pixels();
        let verdicts = pixels
            .iter()
            .zip(&self.pixels)
            .enumerate()
            .map(|(i, (pixel, reference))| {
                if *pixel == Pixel::Unfinished {
                    c.unfinished += 1;
                }
                let Some(reference) = reference else {
                    return Verdict::NotCompared;
                };
                c.compared += 1;
                c.exact_hits += reference.exact.is_some() as usize;
                if reference.ambiguous() {
                    c.ambiguous += 1;
                    return Verdict::Ambiguous;
                }
                let within = reference.within_tolerance(pixel);
                let wrong = reference.wrong_surface(pixel);
                c.outside_tolerance += !within as usize;
                c.wrong_surface += wrong as usize;
                if let (Pixel::Hit { tau, .. }, Some(e)) = (*pixel, reference.exact) {
                    c.max_tau_error = c.max_tau_error.max((tau - e.tau).abs());
                }
                let drawn = match (wrong, reference.exact) {
                    (false, Some(exact)) => {
                        let (x, y) = (i as u32 % frame.width, i as u32 / frame.width);
                        let field = self
                            .prefilter
                            .as_ref()
                            .filter(|_| reference.level > 0)
                            .map(|p| &p.levels[reference.level as usize]);
                        judge_drawing(&self.surface, field, &exact, pixel, frame.rgb(x, y))
                    }
                    _ => Drawn::Right,
                };
                c.wrong_kind += (drawn == Drawn::WrongKind) as usize;
                c.wrong_normal += (drawn == Drawn::WrongNormal) as usize;
                c.wrong_colour += (drawn == Drawn::WrongColour) as usize;
                match (wrong, drawn, within) {
                    (true, _, _) => Verdict::WrongSurface,
                    (false, Drawn::WrongKind, _) => Verdict::WrongKind,
                    (false, Drawn::WrongNormal | Drawn::WrongColour, _) => Verdict::WrongShading,
                    (false, Drawn::Right, false) => Verdict::OutsideTolerance,
                    (false, Drawn::Right, true) => Verdict::Exact,
                }
            })
            .collect();
        (c, verdicts)
    }
}

/// The exact tracer's answers for pixel (x, y) of `camera` (through the field of its stop
/// level, with `prefilter`), `None` if not compared.
fn reference(
    surface: &Surface,
    camera: &Camera,
    prefilter: Option<&Prefilter>,
    x: u32,
    y: u32,
) -> Option<Reference> {
    let eye = camera.eye.as_dvec3();
    let scale = surface.world_to_grid().as_dvec3();
    let (wp, hp) = surface.patches();
    let dir = camera.pixel_direction(x, y);
    // Silhouette pixels: rasterisation and the analytic box may disagree there.
    match box_interval(eye * scale, dir * scale, wp as f64, hp as f64) {
        Some((t0, t1)) if t1 - t0 > SLACK => {
            let traced = |offset| match prefilter {
                Some(p) => p.trace_ray(surface, eye, dir, t0, offset),
                None => Traced {
                    level: 0,
                    hit: trace(surface, eye, dir, offset),
                    borderline: false,
                },
            };
            let (exact, raised, lowered) = (traced(0.0), traced(DELTA), traced(-DELTA));
            Some(Reference {
                exact: exact.hit,
                raised: raised.hit,
                lowered: lowered.hit,
                level: exact.level,
                level_borderline: exact.borderline || raised.borderline || lowered.borderline,
            })
        }
        _ => None,
    }
}

/// Compares `frame` (of `camera`) with the exact tracer.
pub fn compare(surface: &Surface, camera: &Camera, frame: &Frame) -> Comparison {
    ReferenceImage::trace(surface, camera).judge(frame).0
}

/// Compares a prefiltered `frame` (of `camera`) with the CPU reference of the same rule.
pub fn compare_prefiltered(surface: &Surface, camera: &Camera, frame: &Frame) -> Comparison {
    ReferenceImage::trace_prefiltered(surface, camera)
        .judge(frame)
        .0
}
