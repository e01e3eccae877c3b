//! Model pairs with known depths, for the report, the viewer and the tests: a convex pair
//! (its depth exact from its one Minkowski sum) and a pair whose A is a union of two convex
//! pieces, whose nearest way out is over a re-entrant corner (a closed form).

use super::pieces::{pieces_of_meshes, Piece};
use crate::mesh::{cuboid, Mesh};
use glam::Vec3;

/// A pair of models, with the exact depth when a closed form gives it.
pub struct Scene {
    pub name: &'static str,
    pub a: Vec<Piece>,
    pub b: Vec<Piece>,
    /// The exact depth by a closed form (`None`: from the convex reference).
    pub closed_form: Option<f64>,
}

impl Scene {
    /// The exact depth: the closed form, or the convex reference of a single sum.
    pub fn exact_depth(&self) -> anyhow::Result<f64> {
        if let Some(d) = self.closed_form {
            return Ok(d);
        }
        let sums = super::minkowski::minkowski_sums(&self.a, &self.b)?;
        anyhow::ensure!(sums.len() == 1, "{}: no closed form for a union", self.name);
        super::reference::convex_depth(&sums[0], 0.0)
            .map(|(d, _)| d)
            .ok_or_else(|| anyhow::anyhow!("{}: the models do not overlap", self.name))
    }
}

/// The box [lo, hi].
pub fn box_between(lo: Vec3, hi: Vec3) -> Mesh {
    cuboid((hi - lo) / 2.0).translated((lo + hi) / 2.0)
}

/// A tetrahedron with outward faces.
pub fn tetrahedron(corners: [Vec3; 4]) -> Mesh {
    let m = Mesh::new(
        corners.to_vec(),
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    );
    if m.signed_volume() < 0.0 {
        m.flipped()
    } else {
        m
    }
}

/// Two tetrahedra overlapping in general position: one Minkowski sum, exact depth from it.
pub fn convex_pair() -> Scene {
    let a = tetrahedron([
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.1, 0.0),
        Vec3::new(0.3, 1.8, 0.2),
        Vec3::new(0.4, 0.5, 1.9),
    ]);
    let b = tetrahedron([
        Vec3::new(0.5, 0.4, 0.3),
        Vec3::new(1.6, 1.2, 0.8),
        Vec3::new(0.2, 1.5, 1.4),
        Vec3::new(1.3, -0.4, 1.1),
    ]);
    Scene {
        name: "two tetrahedra (convex)",
        a: pieces_of_meshes("A", &[a]).expect("a convex tetrahedron"),
        b: pieces_of_meshes("B", &[b]).expect("a convex tetrahedron"),
        closed_form: None,
    }
}

/// An L of two boxes (tall in z) and a small cube near its inner corner: the nearest way
/// out is over the re-entrant corner, 0.15 √2 along (1, 1, 0) / √2, where the two sums meet.
pub fn corner_pair() -> Scene {
    let a = [
        box_between(Vec3::new(0.0, 0.0, -5.0), Vec3::new(3.0, 1.0, 5.0)),
        box_between(Vec3::new(0.0, 0.0, -5.0), Vec3::new(1.0, 3.0, 5.0)),
    ];
    let b = cuboid(Vec3::splat(0.05)).translated(Vec3::new(0.9, 0.9, 0.0));
    Scene {
        name: "L of two boxes and a cube (union)",
        a: pieces_of_meshes("A", &a).expect("boxes are convex"),
        b: pieces_of_meshes("B", &[b]).expect("a box is convex"),
        closed_form: Some(0.15 * std::f64::consts::SQRT_2),
    }
}
