//! Sec. 5.5, handling large models: streams larger than a tile rendered as tiles into one
//! render target, each read back on its own. The paper expects time linear in the number of
//! tiles and finds it super-linear on the 7800; here the same model at doubling stream
//! lengths, in tiles of a fixed side and as one rectangle.

use super::bench::{Paper1Results, TileRow};
use super::{f2, header};
use crate::report::Table;

/// Culling time per tile relative to the one-tile row: 1 when time grows linearly with the
/// number of tiles, above 1 when super-linearly.
pub fn per_tile_growth(rows: &[TileRow]) -> Vec<f64> {
    let Some(first) = rows.first() else {
        return Vec::new();
    };
    let base = first.tiled.total() / first.tiles.max(1) as f64;
    rows.iter()
        .map(|r| r.tiled.total() / r.tiles.max(1) as f64 / base)
        .collect()
}

pub fn table(results: &Paper1Results) -> Table {
    let t = &results.tiles;
    let growth = per_tile_growth(&t.rows);
    Table {
        caption: format!(
            "Sec. 5.5: tiles of {0}x{0} on the {1} ({2} triangles each), readback {3}, median of \
             {4} frames ({5}): GPU culling ms per frame (overlap + stencil + encode + read and \
             decode), tiled and as one rectangle taking turns",
            t.tile, t.scene, t.triangles, t.readback, t.frames, results.renderer
        ),
        header: header(&[
            "n",
            "stream slots",
            "tiles",
            "CAPs",
            "overlap",
            "stencil",
            "encode",
            "read+decode",
            "tiled total",
            "per tile",
            "per tile / 1 tile",
            "one rectangle",
            "tiled / one rectangle",
        ]),
        rows: t
            .rows
            .iter()
            .zip(growth)
            .map(|(r, g)| {
                let c = &r.tiled;
                vec![
                    r.leaf_size.to_string(),
                    format!("{} x {}", r.slots[0], r.slots[1]),
                    r.tiles.to_string(),
                    r.caps.to_string(),
                    f2(c.overlap),
                    f2(c.stencil),
                    f2(c.encode),
                    f2(c.readback),
                    f2(c.total()),
                    f2(c.total() / r.tiles.max(1) as f64),
                    f2(g),
                    f2(r.one_rectangle.total()),
                    f2(c.total() / r.one_rectangle.total()),
                ]
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::paper1::bench::CullTimes;

    fn row(tiles: usize, overlap: f64) -> TileRow {
        TileRow {
            tiles,
            tiled: CullTimes {
                overlap,
                ..CullTimes::default()
            },
            ..TileRow::default()
        }
    }

    #[test]
    fn per_tile_growth_is_one_when_time_is_linear_in_tiles() {
        let linear = [row(1, 2.0), row(4, 8.0), row(16, 32.0)];
        assert_eq!(per_tile_growth(&linear), vec![1.0, 1.0, 1.0]);
        let super_linear = [row(1, 2.0), row(4, 16.0)];
        assert_eq!(per_tile_growth(&super_linear), vec![1.0, 2.0]);
        assert!(per_tile_growth(&[]).is_empty());
    }
}
