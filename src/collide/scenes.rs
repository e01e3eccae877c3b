//! The benchmark scenes of paper Table III [Sec. 7.2]: two deforming models per scene.
//!
//! 1-3: interlocking, touching and merging tori, 15K triangles each, wavy deformation.
//! 4: bump bunnies, 15K each (the Stanford bunny re-tessellated), pulsating deformation.
//! 5-6: the paper's happy buddhas (20K) and intimate animals (50K) are scanned models we do
//! not have. Stand-ins of the same triangle counts: two intertwined trefoil-knot tubes
//! (20K, non-convex, genus 1) and two facing bunnies re-tessellated to 50K. Every table
//! names them as stand-ins.

use super::deform::{Deformation, Deforming, Pulsating, Wavy};
use super::CollideError;
use crate::mesh::{self, Mesh, TorusKnot};
use glam::{Affine3A, Quat, Vec3};

/// Scene names, in Table III's order.
pub const SCENES: [&str; 6] = [
    "interlocking-tori",
    "touching-tori",
    "merging-tori",
    "bump-bunnies",
    "happy-buddhas",
    "intimate-animals",
];

/// Two deforming models and the animation clock.
pub struct Scene {
    pub name: &'static str,
    /// Table III's name, with "(stand-in: ...)" where the model is not the paper's.
    pub label: String,
    /// Triangles of each model.
    pub triangles: usize,
    pub x: Deforming,
    pub y: Deforming,
    /// Seconds of animation per frame.
    pub dt: f32,
}

impl Scene {
    /// Scene `name` at the paper's size, or with `triangles` per model instead (tests).
    pub fn build(name: &str, triangles: Option<usize>) -> Result<Scene, CollideError> {
        let index = SCENES.iter().position(|&s| s == name).ok_or_else(|| {
            CollideError::BadInput(format!(
                "unknown scene '{name}'; the scenes are {}",
                SCENES.join(", ")
            ))
        })?;
        let paper_size = [15_000, 15_000, 15_000, 15_000, 20_000, 50_000][index];
        let n = triangles.unwrap_or(paper_size);
        let (label, x, y, deformation) = match index {
            0..=2 => {
                let a = mesh::torus_with_triangles(TORUS_R, TORUS_R / 3.0, n);
                let b = match index {
                    // B stands in the xz plane through A's hole, grazing A's inner side.
                    0 => place(
                        &a,
                        Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
                        Vec3::X * 1.38,
                    ),
                    // Side by side in one plane, the tubes just touching.
                    1 => place(
                        &a,
                        Quat::IDENTITY,
                        Vec3::X * (2.0 * (TORUS_R + TORUS_R / 3.0) - 0.02),
                    ),
                    // In one plane, overlapping by a radius: long intersection curves.
                    _ => place(&a, Quat::from_rotation_x(0.15), Vec3::X * TORUS_R),
                };
                let label = ["interlocking tori", "touching tori", "merging tori"][index];
                (label.to_string(), a, b, Kind::Wavy)
            }
            3 => {
                let a = bunny(n)?;
                let b = place(
                    &a,
                    Quat::from_rotation_y(0.4),
                    Vec3::new(0.55, 0.05, 0.1) * size(&a),
                );
                ("bump bunnies".into(), a, b, Kind::Pulsating)
            }
            4 => {
                let a = knot(n);
                let b = place(
                    &a,
                    Quat::from_rotation_z(0.5) * Quat::from_rotation_x(0.3),
                    Vec3::new(0.3, 0.1, 0.0),
                );
                (
                    "happy buddhas (stand-in: two trefoil-knot tubes)".into(),
                    a,
                    b,
                    Kind::Pulsating,
                )
            }
            _ => {
                let a = bunny(n)?;
                let b = place(
                    &a,
                    Quat::from_rotation_y(std::f32::consts::PI),
                    Vec3::new(0.75, 0.0, -0.1) * size(&a),
                );
                (
                    "intimate animals (stand-in: two facing bunnies)".into(),
                    a,
                    b,
                    Kind::Pulsating,
                )
            }
        };
        let deform = |m: Mesh, seed| {
            let s = size(&m);
            let d = match deformation {
                Kind::Wavy => Deformation::Wavy(Wavy::for_size(s, seed)),
                Kind::Pulsating => Deformation::Pulsating(Pulsating::for_size(s)),
            };
            Deforming::new(m, d)
        };
        Ok(Scene {
            name: SCENES[index],
            label,
            triangles: x.triangles.len(),
            x: deform(x, 11),
            y: deform(y, 23),
            dt: 1.0 / 30.0,
        })
    }

    /// The vertices of X and Y at frame `f`.
    pub fn frame(&self, f: usize) -> (Vec<Vec3>, Vec<Vec3>) {
        let t = f as f32 * self.dt;
        (self.x.positions(t), self.y.positions(t))
    }
}

#[derive(Clone, Copy)]
enum Kind {
    Wavy,
    Pulsating,
}

const TORUS_R: f32 = 1.0;

fn place(m: &Mesh, rotation: Quat, offset: Vec3) -> Mesh {
    m.transformed(&Affine3A::from_rotation_translation(rotation, offset))
}

fn size(m: &Mesh) -> f32 {
    let b = m.bounds();
    (b.max - b.min).max_element()
}

/// The bunny re-tessellated to `n` triangles (never coarser than the shipped one).
fn bunny(n: usize) -> Result<Mesh, CollideError> {
    let b = mesh::load_bunny();
    if n <= b.triangles.len() {
        return Ok(b);
    }
    mesh::retessellate(&b, n).map_err(|e| CollideError::BadInput(format!("bunny: {e}")))
}

/// A trefoil-knot tube of about `n` triangles.
fn knot(n: usize) -> Mesh {
    let radial = 16;
    let tubular = (n / (2 * radial)).max(8);
    mesh::torus_knot(&TorusKnot {
        p: 2,
        q: 3,
        radius: 1.0,
        tube_radius: 0.18,
        tubular_segments: tubular,
        radial_segments: radial,
    })
}
