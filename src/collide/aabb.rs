//! Axis-aligned bounding boxes, the bounding volume of the whole paper.

use glam::Vec3;

/// An axis-aligned box `[min, max]`. Boxes are closed: two boxes that only touch overlap,
/// which is what keeps the streaming test conservative (a touching triangle pair is never
/// culled by its boxes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The smallest box holding every point. Componentwise min/max is exact in floating
    /// point, so this equals what the GPU computes from the same f32 coordinates.
    pub fn from_points<I: IntoIterator<Item = Vec3>>(points: I) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| b.grow(p))
    }

    pub fn grow(self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The interval test on the three principal axes (the test of paper Table I).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        !(self.min.x > other.max.x
            || self.max.x < other.min.x
            || self.min.y > other.max.y
            || self.max.y < other.min.y
            || self.min.z > other.max.z
            || self.max.z < other.min.z)
    }

    pub fn extent(&self) -> Vec3 {
        self.max - self.min
    }

    pub fn volume(&self) -> f32 {
        let e = self.extent().max(Vec3::ZERO);
        e.x * e.y * e.z
    }

    /// Index of the longest axis (0 = x, 1 = y, 2 = z).
    pub fn longest_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn touching_boxes_overlap_and_separated_boxes_do_not() {
        let a = Aabb::from_points([Vec3::ZERO, Vec3::ONE]);
        let touching = Aabb::from_points([Vec3::new(1.0, 0.5, 0.5), Vec3::splat(2.0)]);
        let apart = Aabb::from_points([Vec3::new(1.0001, 0.0, 0.0), Vec3::splat(2.0)]);
        assert!(a.overlaps(&touching));
        assert!(!a.overlaps(&apart));
        assert!(!Aabb::EMPTY.overlaps(&a));
    }
}
