//! The GPU path's CPU reference: the same integrand sums at the same pixel centres, by
//! casting the vertical line through each pixel centre against every triangle. What the
//! depth peels deliver per pixel (every surface crossing, signed by `n_z`) is computed here
//! by hand, so tests can compare the GPU with a tolerance set by fp32 alone; and the
//! restriction below a water plane follows section 5.2 pass for pass.

use super::framing::Framing;
use super::integrals::VolumeIntegrals;
use super::peel_depth::{self, PeelDepth};
use crate::mesh::Mesh;
use glam::DVec3;

/// One surface crossing of a pixel's vertical line: depth `z` (framing-relative) and
/// `sgn(n_z)`.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    z: f64,
    sign: f64,
}

/// Eq. 4 and 6 summed over pixel centres, like the GPU, about the framing centre. With
/// `water = Some(level)` only the part below the plane `z = level` counts (section 5.2:
/// crossings above the water are discarded and the water patch is added where the first
/// crossing below it faces down).
pub fn integrate(mesh: &Mesh, framing: &Framing, water: Option<f64>) -> VolumeIntegrals {
    integrate_at(mesh, framing, water, PeelDepth::Float32)
}

/// [`integrate`] as peels compared at `depth` find the crossings: at 24 bits, crossings in
/// one depth step are one layer ([`peel_depth::keep_distinct_steps`]).
pub fn integrate_at(
    mesh: &Mesh,
    framing: &Framing,
    water: Option<f64>,
    depth: PeelDepth,
) -> VolumeIntegrals {
    let crossings = crossings_per_pixel(mesh, framing);
    let n = framing.resolution;
    let water_local = water.map(|level| level - framing.center.z);
    // Framing-relative sums (the integrands' x, y, z are measured from its centre).
    let mut sum = VolumeIntegrals::default();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = framing.pixel_center(i, j);
            let mut hits = crossings[(j * n + i) as usize].clone();
            if let Some(level) = water_local {
                hits.retain(|h| h.z <= level);
            }
            if depth == PeelDepth::Fixed24 {
                let heights: Vec<f64> = hits.iter().map(|h| h.z).collect();
                let kept = peel_depth::keep_distinct_steps(framing, &heights);
                hits = kept.into_iter().map(|k| hits[k]).collect();
            }
            if let Some(level) = water_local {
                let first_below = hits.iter().max_by(|a, b| a.z.total_cmp(&b.z));
                if first_below.is_some_and(|h| h.sign < 0.0) {
                    hits.push(Crossing {
                        z: level,
                        sign: 1.0,
                    });
                }
            }
            for h in hits {
                sum += integrand(x, y, h.z, h.sign);
            }
        }
    }
    let area = framing.pixel_size().powi(2);
    VolumeIntegrals {
        origin: framing.center,
        ..sum * area
    }
}

/// The most surface crossings of any pixel centre's line (below `water` when given): the
/// number of peels the GPU needs.
pub fn layers(mesh: &Mesh, framing: &Framing, water: Option<f64>) -> usize {
    let level = water.map(|l| l - framing.center.z).unwrap_or(f64::INFINITY);
    crossings_per_pixel(mesh, framing)
        .iter()
        .map(|hits| hits.iter().filter(|h| h.z <= level).count())
        .max()
        .unwrap_or(0)
}

/// The pixels where two surface crossings (below `water` when given) lie within `steps`
/// steps of a 24-bit depth buffer: the only pixels where peels at 24 bits and in float
/// can differ ([`peel_depth`]).
pub fn close_crossings(mesh: &Mesh, framing: &Framing, water: Option<f64>, steps: f64) -> usize {
    let level = water.map(|l| l - framing.center.z).unwrap_or(f64::INFINITY);
    crossings_per_pixel(mesh, framing)
        .iter()
        .filter(|hits| {
            let mut depths: Vec<f64> = hits
                .iter()
                .filter(|h| h.z <= level)
                .map(|h| peel_depth::window_depth(framing, h.z))
                .collect();
            depths.sort_by(f64::total_cmp);
            depths
                .windows(2)
                .any(|w| (w[1] - w[0]) * peel_depth::STEPS_24 < steps)
        })
        .count()
}

/// Eq. 4 and 6 summed per peel, like the paper's order (`PeelOrder::KeepLayers`): entry k
/// is the k-th crossing from the top (below `water` when given) at every pixel, and with
/// water a last entry holds the fluid-surface patch `T_w`. About the framing centre.
pub fn integrate_layers(
    mesh: &Mesh,
    framing: &Framing,
    water: Option<f64>,
) -> Vec<VolumeIntegrals> {
    let crossings = crossings_per_pixel(mesh, framing);
    let n = framing.resolution;
    let level = water.map(|l| l - framing.center.z);
    let mut layers: Vec<VolumeIntegrals> = Vec::new();
    let mut patch = VolumeIntegrals::default();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = framing.pixel_center(i, j);
            let mut hits = crossings[(j * n + i) as usize].clone();
            hits.retain(|h| level.is_none_or(|l| h.z <= l));
            hits.sort_by(|a, b| b.z.total_cmp(&a.z));
            for (k, h) in hits.iter().enumerate() {
                if layers.len() <= k {
                    layers.push(VolumeIntegrals::default());
                }
                layers[k] += integrand(x, y, h.z, h.sign);
            }
            if let (Some(l), Some(first)) = (level, hits.first()) {
                if first.sign < 0.0 {
                    patch += integrand(x, y, l, 1.0);
                }
            }
        }
    }
    if water.is_some() {
        layers.push(patch);
    }
    let area = framing.pixel_size().powi(2);
    layers
        .into_iter()
        .map(|l| VolumeIntegrals {
            origin: framing.center,
            ..l * area
        })
        .collect()
}

/// Whether the first surface below `level` faces down (`n_z < 0`) at each pixel centre,
/// row by row from the bottom: the stencil bit pass 1 of section 5.2 writes.
pub fn first_below_faces_down(mesh: &Mesh, framing: &Framing, level: f64) -> Vec<bool> {
    let level = level - framing.center.z;
    crossings_per_pixel(mesh, framing)
        .iter()
        .map(|hits| {
            hits.iter()
                .filter(|h| h.z <= level)
                .max_by(|a, b| a.z.total_cmp(&b.z))
                .is_some_and(|h| h.sign < 0.0)
        })
        .collect()
}

/// The integrands of eq. 4 and 6 at one crossing, with their 1/2 and 1/3 factors.
fn integrand(x: f64, y: f64, z: f64, sign: f64) -> VolumeIntegrals {
    let c = sign * z;
    VolumeIntegrals {
        origin: DVec3::ZERO,
        v: c,
        x: c * x,
        y: c * y,
        z: c * z / 2.0,
        xx: c * x * x,
        yy: c * y * y,
        zz: c * z * z / 3.0,
        xy: c * x * y,
        yz: c * y * z / 2.0,
        zx: c * z * x / 2.0,
    }
}

/// Every crossing at every pixel centre. Pixel centres exactly on an edge follow a
/// top-left rule, so a line through a shared edge crosses the surface once, as in GL.
fn crossings_per_pixel(mesh: &Mesh, framing: &Framing) -> Vec<Vec<Crossing>> {
    let n = framing.resolution as i64;
    let s = framing.pixel_size();
    let mut out = vec![Vec::new(); (n * n) as usize];
    for t in 0..mesh.triangles.len() {
        let mut v = mesh.triangle(t).map(|p| p.as_dvec3() - framing.center);
        let area2 = (v[1] - v[0]).truncate().perp_dot((v[2] - v[0]).truncate());
        if area2 == 0.0 {
            continue; // edge-on (n_z = 0): not rasterized
        }
        let sign = area2.signum();
        if sign < 0.0 {
            v.swap(1, 2);
        }
        let lo = v[0].min(v[1]).min(v[2]);
        let hi = v[0].max(v[1]).max(v[2]);
        let to_pixel = |c: f64| (c + framing.half_width) / s - 0.5;
        let (i0, i1) = (
            to_pixel(lo.x).ceil().max(0.0) as i64,
            (to_pixel(hi.x).floor() as i64).min(n - 1),
        );
        let (j0, j1) = (
            to_pixel(lo.y).ceil().max(0.0) as i64,
            (to_pixel(hi.y).floor() as i64).min(n - 1),
        );
        for j in j0..=j1 {
            for i in i0..=i1 {
                let (x, y) = framing.pixel_center(i as u32, j as u32);
                if let Some(z) = depth_inside(&v, x, y, area2.abs()) {
                    out[(j * n + i) as usize].push(Crossing { z, sign });
                }
            }
        }
    }
    out
}

/// The depth of counter-clockwise triangle `v` above (x, y), if (x, y) is inside.
fn depth_inside(v: &[DVec3; 3], x: f64, y: f64, area2: f64) -> Option<f64> {
    let mut w = [0.0; 3];
    for k in 0..3 {
        let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        let e = (b - a).truncate();
        let f = e.perp_dot(glam::DVec2::new(x - a.x, y - a.y));
        let top_left = e.y < 0.0 || (e.y == 0.0 && e.x < 0.0);
        if f < 0.0 || (f == 0.0 && !top_left) {
            return None;
        }
        w[k] = f / area2;
    }
    Some(w[0] * v[0].z + w[1] * v[1].z + w[2] * v[2].z)
}
