//! Deformations of the benchmark scenes [Sec. 7.2]: wavy (travelling, damped sine/cosine
//! bumps) and pulsating (motion along the vertex normal). Both are closed-form functions
//! of the rest pose and the time, so every frame of a scene is reproducible bit for bit.

use crate::mesh::Mesh;
use glam::Vec3;

/// A deformation applied to a rest mesh; `positions(t)` gives the vertices at time `t`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub enum Deformation {
    Rigid,
    Wavy(Wavy),
    Pulsating(Pulsating),
}

/// "Random bumps with wave functions are generated on the surfaces ... and propagated to
/// the entire surfaces ... damped out while being propagated" [Sec. 7.2].
///
/// Bump `k` starts at time `k * interval` at a vertex drawn from `seed`; its ring front
/// travels at `speed`; the surface moves along its rest normal by
/// `amplitude * exp(-damping * tau) * sin(wavenumber * (speed * tau - r)) * cos(omega * tau)`
/// inside the front (`r` distance to the bump's centre, `tau` the bump's age). The bumps
/// repeat with period `bumps * interval`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Wavy {
    pub amplitude: f32,
    pub wavenumber: f32,
    pub speed: f32,
    pub damping: f32,
    pub omega: f32,
    pub interval: f32,
    pub bumps: usize,
    pub seed: u64,
}

/// "Vertex positions periodically move up and down in the direction of a surface normal
/// (bulging effect)" [Sec. 7.2]: offset `amplitude * sin(omega * t + wavenumber * (d . p))`
/// along the rest normal, `p` the rest position, `d` a fixed direction, so bulges travel.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Pulsating {
    pub amplitude: f32,
    pub omega: f32,
    pub wavenumber: f32,
    pub direction: Vec3,
}

impl Wavy {
    /// Bumps scaled to a model of the given size.
    pub fn for_size(size: f32, seed: u64) -> Wavy {
        Wavy {
            amplitude: 0.02 * size,
            wavenumber: 12.0 / size,
            speed: 0.5 * size,
            damping: 1.0,
            omega: 3.0,
            interval: 0.4,
            bumps: 6,
            seed,
        }
    }
}

impl Pulsating {
    pub fn for_size(size: f32) -> Pulsating {
        Pulsating {
            amplitude: 0.015 * size,
            omega: 4.0,
            wavenumber: 8.0 / size,
            direction: Vec3::new(0.6, 0.8, 0.0),
        }
    }
}

/// A mesh in its rest pose with what its deformation needs.
#[derive(Clone, Debug)]
pub struct Deforming {
    pub rest: Mesh,
    pub normals: Vec<Vec3>,
    pub deformation: Deformation,
    bump_centres: Vec<Vec3>,
}

impl Deforming {
    pub fn new(rest: Mesh, deformation: Deformation) -> Deforming {
        let normals = vertex_normals(&rest);
        let bump_centres = match &deformation {
            Deformation::Wavy(w) if !rest.positions.is_empty() => {
                let mut rng = SplitMix64(w.seed);
                (0..w.bumps)
                    .map(|_| {
                        rest.positions[(rng.next_u64() % rest.positions.len() as u64) as usize]
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        Deforming {
            rest,
            normals,
            deformation,
            bump_centres,
        }
    }

    /// Vertex positions at time `t` (seconds of animation).
    pub fn positions(&self, t: f32) -> Vec<Vec3> {
        let rest = &self.rest.positions;
        match &self.deformation {
            Deformation::Rigid => rest.clone(),
            Deformation::Wavy(w) => rest
                .iter()
                .zip(&self.normals)
                .map(|(&p, &n)| p + n * self.wavy_offset(w, p, t))
                .collect(),
            Deformation::Pulsating(s) => rest
                .iter()
                .zip(&self.normals)
                .map(|(&p, &n)| {
                    p + n * s.amplitude * (s.omega * t + s.wavenumber * s.direction.dot(p)).sin()
                })
                .collect(),
        }
    }

    fn wavy_offset(&self, w: &Wavy, p: Vec3, t: f32) -> f32 {
        let period = w.interval * w.bumps as f32;
        self.bump_centres
            .iter()
            .enumerate()
            .map(|(k, &c)| {
                let tau = (t - k as f32 * w.interval).rem_euclid(period);
                let r = p.distance(c);
                let front = w.speed * tau;
                if r > front {
                    return 0.0;
                }
                w.amplitude
                    * (-w.damping * tau).exp()
                    * (w.wavenumber * (front - r)).sin()
                    * (w.omega * tau).cos()
            })
            .sum()
    }
}

/// Area-weighted vertex normals of the rest pose (zero for unused vertices).
pub fn vertex_normals(mesh: &Mesh) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; mesh.positions.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = mesh.triangle(t);
        let n = (b - a).cross(c - a);
        for &v in tri {
            normals[v as usize] += n;
        }
    }
    normals.iter().map(|n| n.normalize_or_zero()).collect()
}

/// A tiny deterministic generator (SplitMix64), so scenes need no RNG crate.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> Mesh {
        Mesh::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0)],
            vec![[0, 1, 2], [2, 1, 3]],
        )
    }

    #[test]
    fn deformations_move_along_the_normal_and_repeat_exactly() {
        for def in [
            Deformation::Wavy(Wavy::for_size(1.0, 3)),
            Deformation::Pulsating(Pulsating::for_size(1.0)),
        ] {
            let d = Deforming::new(quad(), def);
            let a = d.positions(0.7);
            assert_eq!(
                a,
                Deforming::new(quad(), d.deformation.clone()).positions(0.7)
            );
            let moved = a.iter().zip(&d.rest.positions).any(|(p, r)| p != r);
            assert!(moved);
            for (p, r) in a.iter().zip(&d.rest.positions) {
                assert_eq!((p.x, p.y), (r.x, r.y), "the quad's normal is +z");
            }
        }
    }
}
