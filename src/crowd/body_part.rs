//! Body parts: closed generalized cylinders ("tubes") swept along a chain of bones, the
//! way low-polygon game characters of the paper's time were modelled: limbs, torso and
//! head as separate closed shells that overlap at the joints.
//!
//! A part is a polyline of stations (centre and two half-widths). Its tessellation, a
//! number of segments around and rings along, is chosen by the LOD budget solver
//! ([`super::lod`]) so that a whole character hits the paper's polygon counts exactly.
//! Skin weights are smooth: inverse fourth power of the distance to each candidate bone,
//! the four strongest kept and normalised.

use glam::DVec3;

use super::skeleton::Skeleton;

/// A cross-section of a body part in the bind pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Station {
    pub at: DVec3,
    /// Half-widths along the part's side direction and across it.
    pub radius: [f64; 2],
}

/// A tube swept through stations, skinned to the bones it may follow.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyPart {
    pub name: &'static str,
    pub stations: Vec<Station>,
    /// Direction of `radius[0]` (projected perpendicular to the tube axis).
    pub side: DVec3,
    /// Bones allowed to influence this part (the chain it follows and its parent).
    pub bones: Vec<usize>,
    /// Segments around and rings along at density 1 (the solver scales both).
    pub base_segments: u32,
    pub base_rings: u32,
}

/// How one part is tessellated: `segments` around (even, >= 4), `rings` along (>= 2), and
/// how each end is closed: a pole fan (`segments` triangles) or a flat polygon fan
/// (`segments - 2` triangles).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tessellation {
    pub segments: u32,
    pub rings: u32,
    pub pole_caps: [bool; 2],
}

impl Tessellation {
    pub fn triangle_count(&self) -> usize {
        let s = self.segments as usize;
        let cap = |pole: bool| if pole { s } else { s - 2 };
        2 * s * (self.rings as usize - 1) + cap(self.pole_caps[0]) + cap(self.pole_caps[1])
    }
}

/// A part's triangles, vertex positions and bone influences (not yet validated).
#[derive(Clone, Debug, Default)]
pub struct PartGeometry {
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    pub influences: Vec<[(u32, f64); 4]>,
}

impl BodyPart {
    /// Total arc length of the station polyline.
    fn length(&self) -> f64 {
        self.stations
            .windows(2)
            .map(|w| w[0].at.distance(w[1].at))
            .sum()
    }

    /// Centre, half-widths and unit tangent at arc-length fraction `u` in [0, 1]; the
    /// tangent blends the directions of neighbouring segments so rings turn smoothly.
    fn frame_at(&self, u: f64) -> (DVec3, [f64; 2], DVec3) {
        let target = u * self.length();
        let mut walked = 0.0;
        let last = self.stations.len() - 2;
        for i in 0..=last {
            let (a, b) = (self.stations[i], self.stations[i + 1]);
            let len = a.at.distance(b.at);
            if target <= walked + len || i == last {
                let t = if len > 0.0 {
                    ((target - walked) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let centre = a.at.lerp(b.at, t);
                let radius = [
                    a.radius[0] + (b.radius[0] - a.radius[0]) * t,
                    a.radius[1] + (b.radius[1] - a.radius[1]) * t,
                ];
                let tangent = self
                    .station_tangent(i)
                    .lerp(self.station_tangent(i + 1), t)
                    .normalize();
                return (centre, radius, tangent);
            }
            walked += len;
        }
        unreachable!("a body part has at least two stations")
    }

    /// Mean direction of the segments meeting at station `i`.
    fn station_tangent(&self, i: usize) -> DVec3 {
        let s = &self.stations;
        let before = if i > 0 {
            (s[i].at - s[i - 1].at).normalize()
        } else {
            DVec3::ZERO
        };
        let after = if i + 1 < s.len() {
            (s[i + 1].at - s[i].at).normalize()
        } else {
            DVec3::ZERO
        };
        (before + after).normalize()
    }

    /// Sweeps the tube with tessellation `tess` and skins it to `skeleton`.
    pub fn build(&self, tess: Tessellation, skeleton: &Skeleton) -> PartGeometry {
        let s = tess.segments;
        let mut geometry = PartGeometry::default();
        for k in 0..tess.rings {
            let u = k as f64 / (tess.rings - 1) as f64;
            let (centre, radius, tangent) = self.frame_at(u);
            let side = (self.side - tangent * self.side.dot(tangent)).normalize();
            let across = tangent.cross(side);
            for j in 0..s {
                let theta = std::f64::consts::TAU * j as f64 / s as f64;
                let p = centre + side * radius[0] * theta.cos() + across * radius[1] * theta.sin();
                geometry.positions.push(p);
            }
        }
        let ring = |k: u32, j: u32| k * s + j % s;
        // Sides: the quad (k, j)..(k+1, j+1) as two triangles, counter-clockwise seen
        // from outside (around the tangent, then along it).
        for k in 0..tess.rings - 1 {
            for j in 0..s {
                let (a, b) = (ring(k, j), ring(k, j + 1));
                let (c, d) = (ring(k + 1, j + 1), ring(k + 1, j));
                geometry.triangles.push([a, b, c]);
                geometry.triangles.push([a, c, d]);
            }
        }
        self.close_end(&mut geometry, tess, 0);
        self.close_end(&mut geometry, tess, tess.rings - 1);
        geometry.influences = geometry
            .positions
            .iter()
            .map(|&p| smooth_influences(p, &self.bones, skeleton))
            .collect();
        geometry
    }

    /// Closes ring `k` (the first or last) with a pole fan or a flat polygon fan.
    fn close_end(&self, geometry: &mut PartGeometry, tess: Tessellation, k: u32) {
        let s = tess.segments;
        let start = k == 0;
        let first = k * s;
        // The start cap faces back along the tangent, so its winding is reversed.
        let oriented = |a: u32, b: u32, c: u32| if start { [a, c, b] } else { [a, b, c] };
        if tess.pole_caps[usize::from(!start)] {
            let (centre, radius, tangent) = self.frame_at(if start { 0.0 } else { 1.0 });
            let bulge = 0.6 * radius[0].min(radius[1]);
            let pole = centre + tangent * if start { -bulge } else { bulge };
            let pole_index = geometry.positions.len() as u32;
            geometry.positions.push(pole);
            for j in 0..s {
                let (a, b) = (first + j, first + (j + 1) % s);
                geometry.triangles.push(oriented(pole_index, a, b));
            }
        } else {
            for j in 1..s - 1 {
                geometry
                    .triangles
                    .push(oriented(first, first + j, first + j + 1));
            }
        }
    }
}

/// Distance from `p` to the segment from `a` to `b`.
fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Weights below this share are dropped before normalising (they only blur rigid parts).
const MIN_SHARE: f64 = 0.01;

/// Up to four (bone, weight) pairs for a bind-pose point: weight ~ 1 / distance^4 to the
/// bone segment, strongest first, small shares dropped, normalised to sum one. Empty
/// slots repeat the strongest bone with weight 0.
pub fn smooth_influences(p: DVec3, bones: &[usize], skeleton: &Skeleton) -> [(u32, f64); 4] {
    let mut candidates: Vec<(u32, f64)> = bones
        .iter()
        .map(|&b| {
            let bone = &skeleton.bones()[b];
            let d = distance_to_segment(p, bone.head, bone.tail).max(1e-3);
            (b as u32, d.powi(-4))
        })
        .collect();
    candidates.sort_by(|x, y| y.1.total_cmp(&x.1));
    candidates.truncate(4);
    let total: f64 = candidates.iter().map(|c| c.1).sum();
    candidates.retain(|c| c.1 / total >= MIN_SHARE);
    let kept: f64 = candidates.iter().map(|c| c.1).sum();
    let mut out = [(candidates[0].0, 0.0); 4];
    for (slot, (bone, w)) in candidates.into_iter().enumerate() {
        out[slot] = (bone, w / kept);
    }
    out
}
