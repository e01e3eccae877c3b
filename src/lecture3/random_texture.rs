//! Technique 5, random numbers into a texture: one generator per texel, its state in an
//! RGBA32UI texture, advanced by one render pass per step into the other of two state
//! textures (ping-pong), the numbers drawn written beside it. The generator (`HybridTaus`,
//! Howes & Thomas, GPU Gems 3 ch. 37, 2007) uses only 32-bit integer operations, so the CPU
//! generator here is bit-exact with the GPU's; [`statistics`] holds the tests of uniformity
//! and independence the test suite applies.
//!
//! The lecture names the technique only; the generator, its seeding (splitmix64 of the seed
//! and the texel index, so neighbouring texels start far apart) and the tests are ours.

use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::lecture3::error::Error;
use crate::shader;
use std::cell::Cell;

/// The hybrid Tausworthe generator: three Tausworthe components and an LCG.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HybridTaus {
    pub z: [u32; 4],
}

fn taus_step(z: u32, s1: u32, s2: u32, s3: u32, m: u32) -> u32 {
    let b = ((z << s1) ^ z) >> s2;
    ((z & m) << s3) ^ b
}

fn splitmix64(x: &mut u64) -> u64 {
    *x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *x;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl HybridTaus {
    /// The generator of texel `index` for `seed`. The Tausworthe components need states of at
    /// least 2, 8 and 16: bit 7 is set in each.
    pub fn seeded(seed: u64, index: u64) -> HybridTaus {
        let mut x = seed ^ index.wrapping_mul(0xd134_2543_de82_ef95);
        let a = splitmix64(&mut x);
        let b = splitmix64(&mut x);
        HybridTaus {
            z: [
                a as u32 | 128,
                (a >> 32) as u32 | 128,
                b as u32 | 128,
                (b >> 32) as u32,
            ],
        }
    }

    /// One step; the 32-bit output.
    pub fn next_u32(&mut self) -> u32 {
        let z = &mut self.z;
        z[0] = taus_step(z[0], 13, 19, 12, 4_294_967_294);
        z[1] = taus_step(z[1], 2, 25, 4, 4_294_967_288);
        z[2] = taus_step(z[2], 3, 11, 17, 4_294_967_280);
        z[3] = z[3].wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        z[0] ^ z[1] ^ z[2] ^ z[3]
    }

    /// One step; its top 24 bits as a float in [0, 1), as the shader writes it.
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

/// A `width x height` texture of generators on the GPU.
pub struct RandomTexture {
    program: Program,
    /// Each writes its state texture and the shared value texture.
    targets: [Framebuffer; 2],
    /// Which target holds the current state.
    current: Cell<usize>,
}

impl RandomTexture {
    /// Generators seeded by [`HybridTaus::seeded`] for texels 0.. (row by row from the bottom).
    pub fn new(ctx: &Context, width: u32, height: u32, seed: u64) -> Result<RandomTexture, Error> {
        let max = ctx.info().limits.max_texture_size;
        if !(1..=max).contains(&width) || !(1..=max).contains(&height) {
            return Err(Error::input(
                "--size",
                format!("{width}x{height} generators: each side must be 1 to {max}"),
            ));
        }
        let states = [
            Texture::new_2d(ctx, width, height, TextureFormat::Rgba32Ui)?,
            Texture::new_2d(ctx, width, height, TextureFormat::Rgba32Ui)?,
        ];
        let values = Texture::new_2d(ctx, width, height, TextureFormat::R32F)?;
        let seeds: Vec<u32> = (0..width as u64 * height as u64)
            .flat_map(|i| HybridTaus::seeded(seed, i).z)
            .collect();
        states[0].upload_u32(&seeds)?;
        let target =
            |i: usize| Framebuffer::new(ctx, "random numbers", &[&states[i], &values], None);
        Ok(RandomTexture {
            program: Program::rect(ctx, &[shader!("glsl/lecture3/random_step.frag")])?,
            targets: [target(0)?, target(1)?],
            current: Cell::new(0),
        })
    }

    pub fn width(&self) -> u32 {
        self.targets[0].width()
    }
    pub fn height(&self) -> u32 {
        self.targets[0].height()
    }

    /// Advances every generator one step: one pass from the current state texture into the
    /// other, which becomes current.
    pub fn step(&self) -> Result<(), GlError> {
        let (from, to) = (self.current.get(), 1 - self.current.get());
        self.targets[to]
            .pass(&self.program, "random step")?
            .texture("u_state", self.targets[from].color(0))
            .draw_full()?;
        self.current.set(to);
        Ok(())
    }

    /// The current states, four words per texel.
    pub fn states(&self) -> Result<Vec<u32>, GlError> {
        self.targets[self.current.get()].color(0).download_u32()
    }

    /// The numbers drawn by the last step.
    pub fn values(&self) -> Result<Vec<f32>, GlError> {
        let fb = &self.targets[self.current.get()];
        fb.read_f32(1, Rect::sized(fb.width(), fb.height()))
    }

    /// The texture holding the numbers of the last step.
    pub fn value_texture(&self) -> &Texture {
        self.targets[0].color(1)
    }
}

/// The tests of uniformity and independence, on numbers in [0, 1).
pub mod statistics {
    /// Pearson's chi-square statistic of `values` in `bins` equal bins.
    pub fn chi_square(values: &[f32], bins: usize) -> f64 {
        let mut counts = vec![0u64; bins];
        for &v in values {
            counts[((v as f64 * bins as f64) as usize).min(bins - 1)] += 1;
        }
        let expected = values.len() as f64 / bins as f64;
        counts
            .iter()
            .map(|&c| (c as f64 - expected).powi(2) / expected)
            .sum()
    }

    /// The chi-square distribution's upper quantile for `df` degrees of freedom and normal
    /// quantile `z` (z = 3.09 for a 0.1% level), by Wilson & Hilferty's approximation
    /// (relative error below 1% for df >= 30).
    pub fn chi_square_critical(df: f64, z: f64) -> f64 {
        let a = 2.0 / (9.0 * df);
        df * (1.0 - a + z * a.sqrt()).powi(3)
    }

    /// The correlation coefficient of the pairs (a_i, b_i).
    pub fn correlation(pairs: &[(f32, f32)]) -> f64 {
        let n = pairs.len() as f64;
        let (ma, mb) = pairs.iter().fold((0.0, 0.0), |(x, y), &(a, b)| {
            (x + a as f64 / n, y + b as f64 / n)
        });
        let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
        for &(a, b) in pairs {
            let (da, db) = (a as f64 - ma, b as f64 - mb);
            sab += da * db;
            saa += da * da;
            sbb += db * db;
        }
        sab / (saa * sbb).sqrt()
    }

    /// The bound |r| must stay under for `n` independent pairs at normal quantile `z`
    /// (r is about normal with standard deviation 1 / sqrt(n)).
    pub fn correlation_bound(n: usize, z: f64) -> f64 {
        z / (n as f64).sqrt()
    }
}
