//! Handling large models [Sec. 5.5]: when `2^d_max` exceeds the largest texture the GPU
//! takes, each stream is cut into segments of `tile` slots (its own AABB, stencil and
//! vertex textures), and the `2^dX x 2^dY` rectangle is rendered as tiles, segment of X
//! against segment of Y, one after the other into one render target reused by all tiles.

use super::CollideError;

/// How the rectangle of all slot pairs is cut into tiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TileLayout {
    /// Slots per segment: a power of two, at most the GPU's maximum texture size.
    pub tile: usize,
    /// Segments of S^X (tile rows) and of S^Y (tile columns).
    pub segments: [usize; 2],
}

/// The most tiles a query may take before it is refused as too large (a 2^26-leaf stream
/// pair on a 4096 texture limit); far beyond any model that fits in memory.
pub const MAX_TILES: usize = 1 << 16;

impl TileLayout {
    /// Tiles for streams of `len_x` and `len_y` slots (powers of two), with tiles no larger
    /// than `max_tile` (the texture limit, or smaller when forced).
    pub fn new(len_x: usize, len_y: usize, max_tile: usize) -> Result<TileLayout, CollideError> {
        if max_tile == 0 {
            return Err(CollideError::BadInput(
                "the tile size must be at least 1".into(),
            ));
        }
        let max_tile = prev_power_of_two(max_tile);
        let tile = max_tile.min(len_x.max(len_y));
        let segments = [len_x.div_ceil(tile), len_y.div_ceil(tile)];
        let layout = TileLayout { tile, segments };
        if layout.count() > MAX_TILES {
            return Err(CollideError::BadInput(format!(
                "streams of {len_x} x {len_y} AABBs need {} tiles of {tile} x {tile}, more \
                 than the budget of {MAX_TILES}; use a larger leaf size",
                layout.count()
            )));
        }
        Ok(layout)
    }

    pub fn count(&self) -> usize {
        self.segments[0] * self.segments[1]
    }

    /// Slot range `[start, end)` of segment `s` of a stream of `len` slots.
    pub fn segment(&self, s: usize, len: usize) -> std::ops::Range<usize> {
        let start = s * self.tile;
        start..(start + self.tile).min(len)
    }
}

fn prev_power_of_two(n: usize) -> usize {
    1 << (usize::BITS - 1 - n.leading_zeros())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_cut_into_power_of_two_segments() {
        let t = TileLayout::new(4096, 1024, 1000).unwrap();
        assert_eq!((t.tile, t.segments), (512, [8, 2]));
        assert_eq!(t.segment(7, 4096), 3584..4096);
        let small = TileLayout::new(16, 2, 4096).unwrap();
        assert_eq!((small.tile, small.segments), (16, [1, 1]));
        assert_eq!(small.segment(0, 2), 0..2);
        assert!(TileLayout::new(1 << 26, 1 << 26, 4096)
            .unwrap_err()
            .to_string()
            .contains("tiles"));
    }
}
