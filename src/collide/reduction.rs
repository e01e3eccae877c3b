//! Stream reduction [Sec. 5.3]: getting the CAPs out of `P0` without reading all of it.
//!
//! - Hierarchical [5.3.1]: `P0` is encoded 4x4 into `P1`, `P1` into `P2`, `P2` into `P3`
//!   (`i_max = 3`). A texel of `P_{i+1}` holds, as an exact integer in a float, the 16-bit
//!   mask of which texels of its 4x4 block of `P_i` are set. Decoding reads all of `P3`,
//!   then top down only the blocks that a set bit points to; the masks of `P1` are the
//!   CAPs themselves, so `P0` is never read.
//! - Reduced: one level `P1'`, each RGBA texel holding the 64-bit mask of an 8x8 block of
//!   `P0` (16 bits per channel); read whole, decoded on the CPU in constant time.
//! - Full: `P0` read whole, for comparison.
//!
//! The decoders here are pure functions of a [`LevelReader`]; the GPU passes that fill the
//! levels are in [`super::reduction_gpu`], and [`encode4`] / [`encode8`] are their CPU
//! references.

/// Which readback a frame used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Scheme {
    Hierarchical,
    Reduced,
    Full,
}

impl std::fmt::Display for Scheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Scheme::Hierarchical => "hierarchical",
            Scheme::Reduced => "reduced",
            Scheme::Full => "full",
        })
    }
}

/// `P0` pixels per `P1'` texel side in the reduced scheme, and per `P_{i+1}` texel side in
/// the hierarchical one.
pub const REDUCED_BLOCK: usize = 8;
pub const HIER_BLOCK: usize = 4;
/// `i_max`: levels above `P0` in the hierarchical scheme.
pub const HIER_LEVELS: usize = 3;

/// Size of the level above a `w x h` level when each texel encodes a `block x block` block.
pub fn encoded_size(w: usize, h: usize, block: usize) -> (usize, usize) {
    (w.div_ceil(block), h.div_ceil(block))
}

/// Sizes of `P0..P3` for a `w x h` `P0`.
pub fn hierarchy_sizes(w: usize, h: usize) -> [(usize, usize); HIER_LEVELS + 1] {
    let mut sizes = [(w, h); HIER_LEVELS + 1];
    for i in 1..=HIER_LEVELS {
        sizes[i] = encoded_size(sizes[i - 1].0, sizes[i - 1].1, HIER_BLOCK);
    }
    sizes
}

/// Reads rectangles of the levels back from wherever they live (GPU framebuffers, or CPU
/// arrays in tests). Rows are returned bottom-up from `y`, `w` texels each.
pub trait LevelReader {
    type Error;
    /// Red channel of level `level` (0 = `P0`, 1..=3 = `P1..P3`): 4 bytes per texel.
    fn read_red(
        &mut self,
        level: usize,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<f32>, Self::Error>;
    /// RGBA of the reduced level `P1'`: 16 bytes per texel.
    fn read_reduced(
        &mut self,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<[f32; 4]>, Self::Error>;
}

/// What a decode found and what it cost in readback.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Decoded {
    /// Set `P0` pixels `(row, column)` = (slot of X, slot of Y) within the tile, sorted.
    pub caps: Vec<(u32, u32)>,
    /// Bytes read back from the GPU.
    pub bytes: u64,
    /// `glReadPixels` calls made.
    pub reads: u32,
}

impl Decoded {
    #[allow(clippy::too_many_arguments)]
    fn read_red<R: LevelReader>(
        &mut self,
        r: &mut R,
        l: usize,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<f32>, R::Error> {
        self.bytes += (w * h * 4) as u64;
        self.reads += 1;
        r.read_red(l, x, y, w, h)
    }
}

/// Full readback: all of `P0`.
pub fn decode_full<R: LevelReader>(
    reader: &mut R,
    w: usize,
    h: usize,
) -> Result<Decoded, R::Error> {
    let mut out = Decoded::default();
    let p0 = out.read_red(reader, 0, 0, 0, w, h)?;
    // Row by row, skipping runs of 16 clear pixels at once (most of `P0` is clear).
    for (row, line) in p0.chunks_exact(w.max(1)).enumerate() {
        for (run, pixels) in line.chunks(16).enumerate() {
            if pixels.iter().fold(true, |clear, &v| clear & (v == 0.0)) {
                continue;
            }
            for (k, &v) in pixels.iter().enumerate() {
                if v != 0.0 {
                    out.caps.push((row as u32, (run * 16 + k) as u32));
                }
            }
        }
    }
    Ok(out)
}

/// Reduced readback: all of `P1'`, each texel's four 16-bit channels are rows `2c, 2c+1`
/// of its 8x8 block.
pub fn decode_reduced<R: LevelReader>(
    reader: &mut R,
    w: usize,
    h: usize,
) -> Result<Decoded, R::Error> {
    let (rw, rh) = encoded_size(w, h, REDUCED_BLOCK);
    let texels = reader.read_reduced(0, 0, rw, rh)?;
    let mut out = Decoded {
        bytes: (rw * rh * 16) as u64,
        reads: 1,
        ..Decoded::default()
    };
    // Row `b` of an 8x8 block is the byte `b % 2` of channel `b / 2`: walking block rows,
    // then the rows inside them, then the blocks along the row, gives the CAPs in order.
    for (by, blocks) in texels.chunks_exact(rw.max(1)).enumerate() {
        for b in 0..REDUCED_BLOCK {
            let (c, shift) = (b / 2, 8 * (b % 2));
            let row = (by * REDUCED_BLOCK + b) as u32;
            for (bx, t) in blocks.iter().enumerate() {
                let byte = ((t[c] as u32) >> shift) & 0xff;
                for a in (0..8).filter(|a| byte & (1 << a) != 0) {
                    out.caps.push((row, (bx * REDUCED_BLOCK + a) as u32));
                }
            }
        }
    }
    debug_assert!(out.caps.windows(2).all(|p| p[0] < p[1]));
    Ok(out)
}

/// Hierarchical readback: all of `P3`, then top down the blocks that set bits point to.
pub fn decode_hierarchical<R: LevelReader>(
    reader: &mut R,
    w: usize,
    h: usize,
) -> Result<Decoded, R::Error> {
    let sizes = hierarchy_sizes(w, h);
    let mut out = Decoded::default();
    let (tw, th) = sizes[HIER_LEVELS];
    let top = out.read_red(reader, HIER_LEVELS, 0, 0, tw, th)?;
    let mut frontier: Vec<(usize, usize, f32)> = top
        .iter()
        .enumerate()
        .filter(|(_, &v)| v != 0.0)
        .map(|(k, &v)| (k % tw, k / tw, v))
        .collect();
    // Each level down: read, for each set texel, the part of its 4x4 block that holds set
    // bits (one read per parent texel), and keep the set children.
    for level in (1..HIER_LEVELS).rev() {
        let (lw, lh) = sizes[level];
        let mut next = Vec::new();
        for &(px, py, mask) in &frontier {
            let bits: Vec<usize> = set_bits(mask).collect();
            let (ax, ay) = (
                bits.iter().map(|b| b % 4).min().unwrap(),
                bits.iter().map(|b| b / 4).min().unwrap(),
            );
            let (bx, by) = (
                bits.iter().map(|b| b % 4).max().unwrap(),
                bits.iter().map(|b| b / 4).max().unwrap(),
            );
            let (x0, y0) = (px * 4 + ax, py * 4 + ay);
            let (rw, rh) = (
                (px * 4 + bx + 1).min(lw) - x0,
                (py * 4 + by + 1).min(lh) - y0,
            );
            let block = out.read_red(reader, level, x0, y0, rw, rh)?;
            for &b in &bits {
                let (cx, cy) = (px * 4 + b % 4, py * 4 + b / 4);
                let v = block[(cy - y0) * rw + (cx - x0)];
                if v != 0.0 {
                    next.push((cx, cy, v));
                }
            }
        }
        frontier = next;
    }
    // The masks of P1 are the P0 pixels.
    for &(px, py, mask) in &frontier {
        for b in set_bits(mask) {
            out.caps
                .push(((py * 4 + b / 4) as u32, (px * 4 + b % 4) as u32));
        }
    }
    out.caps.sort_unstable();
    Ok(out)
}

/// The set bits of a mask stored as an exact integer in a float.
fn set_bits(v: f32) -> impl Iterator<Item = usize> {
    let m = v as u32;
    (0..16).filter(move |b| m & (1 << b) != 0)
}

/// CPU reference of one hierarchical encoding pass: texel `(x, y)` of the result is the
/// mask of the non-zero texels of the 4x4 block at `(4x, 4y)` (bit `4b + a` for `(a, b)`).
pub fn encode4(src: &[f32], w: usize, h: usize) -> (Vec<f32>, usize, usize) {
    let (ew, eh) = encoded_size(w, h, HIER_BLOCK);
    let mut out = vec![0.0; ew * eh];
    for y in 0..h {
        for x in 0..w {
            if src[y * w + x] != 0.0 {
                let bit = 4 * (y % 4) + x % 4;
                let t = &mut out[(y / 4) * ew + x / 4];
                *t = ((*t as u32) | (1 << bit)) as f32;
            }
        }
    }
    (out, ew, eh)
}

/// CPU reference of the reduced encoding: channel `c` of texel `(x, y)` holds rows
/// `2c, 2c+1` of the 8x8 block at `(8x, 8y)`, bit `8 (b - 2c) + a`.
pub fn encode8(src: &[f32], w: usize, h: usize) -> (Vec<[f32; 4]>, usize, usize) {
    let (ew, eh) = encoded_size(w, h, REDUCED_BLOCK);
    let mut out = vec![[0.0f32; 4]; ew * eh];
    for y in 0..h {
        for x in 0..w {
            if src[y * w + x] != 0.0 {
                let (a, b) = (x % 8, y % 8);
                let c = &mut out[(y / 8) * ew + x / 8][b / 2];
                *c = ((*c as u32) | (1 << (8 * (b % 2) + a))) as f32;
            }
        }
    }
    (out, ew, eh)
}

/// What a calibration fills `P0` with at a given `eta`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum P0Contents {
    /// Every pair a CAP with probability `eta`, independently.
    Uniform,
    /// CAPs in [`CLUSTER_BLOBS`] square blobs, as contacts make them (Sec. 5.3.1: "colliding
    /// triangles tend to be in close proximity"): see [`fill_p0`].
    Clustered,
}

impl std::fmt::Display for P0Contents {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            P0Contents::Uniform => "uniform",
            P0Contents::Clustered => "clustered",
        })
    }
}

/// Blobs of a clustered `P0`.
pub const CLUSTER_BLOBS: usize = 8;
/// Share of a blob's pixels that are CAPs (when the blob is large enough).
pub const CLUSTER_FILL: f64 = 0.25;

/// A `w x h` `P0` (row-major, 1.0 = CAP) with about `eta * w * h` CAPs.
///
/// Clustered: up to [`CLUSTER_BLOBS`] squares at random places, each pixel in them a CAP with
/// probability [`CLUSTER_FILL`] (higher when the squares would be smaller than a pixel), the
/// squares' side growing with `eta`. The model is fitted to the scenes' own `P0`s (tori,
/// bunnies, stand-ins at 2000 triangles, 512 x 512): their CAPs fill 2.1-3.7 per set 4x4
/// block (what the hierarchical readback reads at `P1`) and 8-85 per set 64x64 block (`P3`),
/// where uniform contents give 1-1.05 and 1-30; these blobs give 1.8-3.4 and 4-120 over the
/// same range of `eta` (0.01-0.7%). Deterministic in `rng`.
pub fn fill_p0(
    w: usize,
    h: usize,
    eta: f64,
    contents: P0Contents,
    rng: &mut super::deform::SplitMix64,
) -> Vec<f32> {
    let mut cells = vec![0.0f32; w * h];
    let target = eta * (w * h) as f64;
    match contents {
        P0Contents::Uniform => {
            for c in &mut cells {
                *c = f32::from((rng.unit() as f64) < eta);
            }
        }
        P0Contents::Clustered if target > 0.0 => {
            let blobs = (CLUSTER_BLOBS as f64).min(target.ceil());
            let side = ((target / (blobs * CLUSTER_FILL)).sqrt().ceil() as usize)
                .clamp(1, w.min(h).max(1));
            let fill = (target / (blobs * (side * side) as f64)).min(1.0);
            for _ in 0..blobs as usize {
                let x0 = (rng.next_u64() % (w - side + 1) as u64) as usize;
                let y0 = (rng.next_u64() % (h - side + 1) as u64) as usize;
                for y in y0..y0 + side {
                    for x in x0..x0 + side {
                        if (rng.unit() as f64) < fill {
                            cells[y * w + x] = 1.0;
                        }
                    }
                }
            }
        }
        P0Contents::Clustered => {}
    }
    cells
}

/// CAPs per set `block x block` block of a `w x h` `P0`: 1 when no two CAPs share a block.
pub fn caps_per_set_block(cells: &[f32], w: usize, h: usize, block: usize) -> f64 {
    let (bw, bh) = encoded_size(w, h, block);
    let mut set = vec![false; bw * bh];
    let mut caps = 0usize;
    for y in 0..h {
        for x in 0..w {
            if cells[y * w + x] != 0.0 {
                caps += 1;
                set[(y / block) * bw + x / block] = true;
            }
        }
    }
    let blocks = set.iter().filter(|&&b| b).count();
    if blocks == 0 {
        0.0
    } else {
        caps as f64 / blocks as f64
    }
}

/// CPU levels, for testing the decoders and for the calibration's bookkeeping.
pub struct CpuLevels {
    pub levels: Vec<(Vec<f32>, usize)>,
    pub reduced: (Vec<[f32; 4]>, usize),
}

impl CpuLevels {
    pub fn encode(p0: &[f32], w: usize, h: usize) -> CpuLevels {
        let mut levels = vec![(p0.to_vec(), w)];
        let (mut cw, mut ch) = (w, h);
        for _ in 0..HIER_LEVELS {
            let (next, nw, nh) = encode4(&levels.last().unwrap().0, cw, ch);
            levels.push((next, nw));
            (cw, ch) = (nw, nh);
        }
        let (r, rw, _) = encode8(p0, w, h);
        CpuLevels {
            levels,
            reduced: (r, rw),
        }
    }
}

fn cut<T: Copy>(data: &[T], stride: usize, x: usize, y: usize, w: usize, h: usize) -> Vec<T> {
    (y..y + h)
        .flat_map(|r| data[r * stride + x..r * stride + x + w].iter().copied())
        .collect()
}

impl LevelReader for CpuLevels {
    type Error = std::convert::Infallible;

    fn read_red(
        &mut self,
        level: usize,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<f32>, Self::Error> {
        let (data, stride) = &self.levels[level];
        Ok(cut(data, *stride, x, y, w, h))
    }

    fn read_reduced(
        &mut self,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<[f32; 4]>, Self::Error> {
        let (data, stride) = &self.reduced;
        Ok(cut(data, *stride, x, y, w, h))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::deform::SplitMix64;

    fn random_p0(w: usize, h: usize, eta: f32, seed: u64) -> Vec<f32> {
        let mut rng = SplitMix64(seed);
        (0..w * h).map(|_| f32::from(rng.unit() < eta)).collect()
    }

    #[test]
    fn every_scheme_decodes_exactly_the_set_pixels() {
        for (w, h) in [(64, 64), (256, 32), (37, 5), (1, 1), (512, 512)] {
            for eta in [0.0, 0.001, 0.05, 0.6] {
                let p0 = random_p0(w, h, eta, (w * h) as u64);
                let expected: Vec<(u32, u32)> = (0..w * h)
                    .filter(|&k| p0[k] != 0.0)
                    .map(|k| ((k / w) as u32, (k % w) as u32))
                    .collect();
                let mut levels = CpuLevels::encode(&p0, w, h);
                let full = decode_full(&mut levels, w, h).unwrap();
                let reduced = decode_reduced(&mut levels, w, h).unwrap();
                let hier = decode_hierarchical(&mut levels, w, h).unwrap();
                assert_eq!(full.caps, expected);
                assert_eq!(reduced.caps, expected);
                assert_eq!(hier.caps, expected, "{w}x{h} eta {eta}");
                assert_eq!(full.bytes, (w * h * 4) as u64);
            }
        }
    }

    #[test]
    fn sparse_hierarchical_readback_reads_under_one_percent_of_p0() {
        let (w, h) = (2048, 2048);
        let p0 = random_p0(w, h, 0.0005, 5);
        let mut levels = CpuLevels::encode(&p0, w, h);
        let hier = decode_hierarchical(&mut levels, w, h).unwrap();
        let full = decode_full(&mut levels, w, h).unwrap();
        assert_eq!(hier.caps, full.caps);
        assert!(
            hier.bytes * 100 < full.bytes,
            "{} vs {}",
            hier.bytes,
            full.bytes
        );
    }

    #[test]
    fn clustered_contents_hold_about_eta_caps_in_blobs() {
        let (w, h) = (512, 512);
        for eta in [1e-4, 7e-4, 7e-3, 5e-2] {
            let mut rng = SplitMix64(9);
            let uniform = fill_p0(w, h, eta, P0Contents::Uniform, &mut rng);
            let clustered = fill_p0(w, h, eta, P0Contents::Clustered, &mut rng);
            let target = eta * (w * h) as f64;
            for (cells, name) in [(&uniform, "uniform"), (&clustered, "clustered")] {
                let caps = cells.iter().filter(|&&c| c != 0.0).count() as f64;
                // Binomial spread (and blob overlap): within 25% plus a few CAPs.
                assert!(
                    (caps - target).abs() <= 0.25 * target + 8.0,
                    "{name} at eta {eta}: {caps} CAPs for {target}"
                );
            }
            // The scenes' P0s hold 2.1-3.7 CAPs per set 4x4 block; uniform CAPs this sparse
            // rarely share one. (Without the blobs, clustered would read about 1.)
            let c = caps_per_set_block(&clustered, w, h, 4);
            let u = caps_per_set_block(&uniform, w, h, 4);
            assert!((1.5..=4.5).contains(&c), "clustered at eta {eta}: {c}");
            if eta < 1e-3 {
                assert!(u < 1.1, "uniform at eta {eta}: {u}");
            }
        }
        let mut rng = SplitMix64(1);
        assert!(fill_p0(64, 64, 0.0, P0Contents::Clustered, &mut rng)
            .iter()
            .all(|&c| c == 0.0));
    }
}
