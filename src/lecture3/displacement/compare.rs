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

use super::camera::Camera;
use super::exact::{box_interval, trace, Hit};
use super::surface::Surface;
use super::tracer::Pixel;
use serde::Serialize;

/// Height perturbation the tests allow: fp32 rounding of grid coordinates up to ~150 patches
/// is about 1e-5 patch, times a slope of at most 1 height per patch; one order of magnitude
/// above that.
pub const DELTA: f64 = 1e-4;
/// Ray-parameter slack (world units) for the rounding of the reported hit itself.
pub const SLACK: f64 = 1e-4;

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
}

impl Reference {
    fn ambiguous(&self) -> bool {
        match (self.raised, self.lowered) {
            (Some(r), Some(l)) => (r.grid.truncate() - l.grid.truncate()).length() > 1.0,
            (None, None) => false,
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
}

/// The exact tracer's answers for every pixel of a view, traced once and used to judge any
/// number of frames of that view.
pub struct ReferenceImage {
    /// `None` for pixels not compared (silhouette or outside the box).
    pixels: Vec<Option<Reference>>,
}

impl ReferenceImage {
    /// Traces every pixel of `camera` (three times: exact, raised and lowered by DELTA).
    /// The rows are shared out among the machine's cores (every pixel traced on its own, as
    /// one thread would).
    pub fn trace(surface: &Surface, camera: &Camera) -> ReferenceImage {
        let (width, height) = (camera.width as usize, camera.height as usize);
        let threads = std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .clamp(1, height.max(1));
        let mut rows: Vec<Vec<Option<Reference>>> = (0..height).map(|_| Vec::new()).collect();
        std::thread::scope(|scope| {
            let workers: Vec<_> = (0..threads)
                .map(|t| {
                    scope.spawn(move || {
                        (t..height)
                            .step_by(threads)
                            .map(|y| {
                                let row = (0..width)
                                    .map(|x| reference(surface, camera, x as u32, y as u32))
                                    .collect::<Vec<_>>();
                                (y, row)
                            })
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            for worker in workers {
                let done = worker
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                for (y, row) in done {
                    rows[y] = row;
                }
            }
        });
        ReferenceImage {
            pixels: rows.into_iter().flatten().collect(),
        }
    }

    /// Judges a frame of the same view.
    pub fn judge(&self, pixels: &[Pixel]) -> (Comparison, Vec<Verdict>) {
        let mut c = Comparison::default();
        let verdicts = pixels
            .iter()
            .zip(&self.pixels)
            .map(|(pixel, reference)| {
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
                match (wrong, within) {
                    (true, _) => Verdict::WrongSurface,
                    (false, false) => Verdict::OutsideTolerance,
                    (false, true) => Verdict::Exact,
                }
            })
            .collect();
        (c, verdicts)
    }
}

/// The exact tracer's answers for pixel (x, y) of `camera`, `None` if not compared.
fn reference(surface: &Surface, camera: &Camera, x: u32, y: u32) -> Option<Reference> {
    let eye = camera.eye.as_dvec3();
    let scale = surface.world_to_grid().as_dvec3();
    let (wp, hp) = surface.patches();
    let dir = camera.pixel_direction(x, y);
    // Silhouette pixels: rasterisation and the analytic box may disagree there.
    match box_interval(eye * scale, dir * scale, wp as f64, hp as f64) {
        Some((t0, t1)) if t1 - t0 > SLACK => Some(Reference {
            exact: trace(surface, eye, dir, 0.0),
            raised: trace(surface, eye, dir, DELTA),
            lowered: trace(surface, eye, dir, -DELTA),
        }),
        _ => None,
    }
}

/// Compares `pixels` (a frame of `camera`, row by row from the bottom) with the exact tracer.
pub fn compare(surface: &Surface, camera: &Camera, pixels: &[Pixel]) -> Comparison {
    ReferenceImage::trace(surface, camera).judge(pixels).0
}
