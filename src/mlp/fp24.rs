//! The period precision of paper 3's board: the ATI RADEON 9700 PRO (R300) computed every
//! fragment-shader value as a 24-bit float (sign, 7-bit exponent, 16-bit stored mantissa).
//! With [`Precision::Fp24`] the faithful passes wrap each intermediate result of the matrix
//! product, the bias add and the sigmoid in `fp24()` (`glsl/mlp/fp24.glsl`), and this module
//! holds the CPU model of that rounding and a CPU forward pass that rounds at the same steps.
//!
//! The format as emulated (choices where the board's behaviour is not documented publicly):
//! round to nearest, ties to even, on the 16 kept mantissa bits; an IEEE-like exponent of
//! bias 63, so normal values run from 2^-62 ([`MIN_POSITIVE`]) to (2 - 2^-16) 2^63 ([`MAX`]);
//! no denormals: a result below 2^-62 after rounding flushes to a zero of its sign; a result
//! above [`MAX`] after rounding becomes an infinity of its sign (which the project's finite
//! checks then report); infinities and NaNs pass through.
//!
//! How faithful this is. Each step is computed in fp32 and then rounded to fp24, so a result
//! is fp24(fp32(a op b)), not the correctly rounded fp24(a op b): the two differ only where the
//! fp32 rounding lands exactly on a halfway point of the 24-bit grid (double rounding, a few
//! cases in 2^7). What the R300 did and this cannot reproduce: its own rounding mode (whether
//! it rounded to nearest or truncated is not documented), whether its multiply-add (MAD)
//! rounded the product before adding (here it does, as two steps), its `exp` and reciprocal
//! approximations (here fp32 `exp` and division, then rounded), and its texture sampler's
//! path (fp32 texels are rounded to fp24 as the shader reads them; texture coordinates are not
//! rounded, which changes nothing at the sizes of 2048 and below where every texel centre is
//! exact to 17 bits). The render targets are R32F, so a stored result keeps its 24-bit value.

use super::network::{Activation, Network};
use crate::gl::{Context, Framebuffer, GlError, Program, ShaderSource, Texture, TextureFormat};
use crate::shader;
use ndarray::{Array2, ArrayView2};

/// Stored mantissa bits of the R300's fragment floats.
pub const MANTISSA_BITS: u32 = 16;
/// Exponent bits.
pub const EXPONENT_BITS: u32 = 7;
/// fp32 mantissa bits that the rounding drops.
const DROPPED_BITS: u32 = 23 - MANTISSA_BITS;
/// The largest finite value, (2 - 2^-16) 2^63.
pub const MAX: f32 = f32::from_bits((190 << 23) | (0xFFFF << DROPPED_BITS));
/// The smallest positive (normal) value, 2^-62.
pub const MIN_POSITIVE: f32 = f32::from_bits(65 << 23);
/// The unit roundoff of the 24-bit format, 2^-17 (half the spacing above 1).
pub const UNIT_ROUNDOFF: f64 = 1.0 / 131_072.0;

/// The arithmetic of the faithful passes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// Today's: fp32 throughout.
    #[default]
    Fp32,
    /// The R300's 24-bit floats, emulated by rounding each intermediate result.
    Fp24,
}

impl Precision {
    /// The generated line that selects the precision in `glsl/mlp/fp24.glsl`; it goes before
    /// the snippet in every paper-3 program that includes it.
    pub fn shader_define(self) -> ShaderSource<'static> {
        ShaderSource {
            name: "mlp precision (generated)",
            source: match self {
                Precision::Fp32 => "#define PERIOD_FP24 0\n",
                Precision::Fp24 => "#define PERIOD_FP24 1\n",
            },
        }
    }

    /// As the report and JSON name it.
    pub fn name(self) -> &'static str {
        match self {
            Precision::Fp32 => "fp32",
            Precision::Fp24 => "fp24 (R300)",
        }
    }
}

/// `x` rounded to the R300's 24-bit float (see the module doc for the rounding, range,
/// underflow and overflow), returned as the fp32 value it equals.
pub fn fp24(x: f32) -> f32 {
    let bits = x.to_bits();
    let sign = bits & 0x8000_0000;
    let magnitude = bits & 0x7FFF_FFFF;
    if magnitude >= f32::INFINITY.to_bits() {
        return x; // infinities and NaNs
    }
    let odd = (magnitude >> DROPPED_BITS) & 1;
    let half_unit = (1 << (DROPPED_BITS - 1)) - 1 + odd;
    let rounded = (magnitude + half_unit) & !((1 << DROPPED_BITS) - 1);
    if rounded > MAX.to_bits() {
        f32::from_bits(sign | f32::INFINITY.to_bits())
    } else if rounded < MIN_POSITIVE.to_bits() {
        f32::from_bits(sign)
    } else {
        f32::from_bits(sign | rounded)
    }
}

/// Whether `x` is a value of the 24-bit format (zero, infinity and NaN included).
pub fn is_fp24(x: f32) -> bool {
    x.to_bits() == fp24(x).to_bits()
}

/// The forward pass as the faithful passes compute it at [`Precision::Fp24`], step for step:
/// each fetched weight and input, each product and each partial sum (in order k = 0..N), the
/// fetched bias, the bias add, and each step of the sigmoid `1 / (1 + e^-m)` rounded to fp24.
/// Batches are L x N (row j = input vector j), outputs L x M.
pub fn forward_fp24(net: &Network, batch: ArrayView2<f32>) -> Array2<f32> {
    assert_eq!(batch.ncols(), net.inputs(), "input length");
    let mut x = batch.to_owned();
    for layer in net.layers() {
        let w = layer.weights.mapv(fp24);
        let mut out = Array2::zeros((x.nrows(), layer.outputs()));
        for (x_j, mut out_j) in x.outer_iter().zip(out.outer_iter_mut()) {
            let x_j: Vec<f32> = x_j.iter().map(|&v| fp24(v)).collect();
            for ((w_i, &b_i), r) in w.outer_iter().zip(&layer.bias).zip(out_j.iter_mut()) {
                let sum = w_i
                    .iter()
                    .zip(&x_j)
                    .fold(0.0f32, |sum, (&w, &x)| fp24(sum + fp24(w * x)));
                *r = activation_fp24(layer.activation, fp24(sum + fp24(b_i)));
            }
        }
        x = out;
    }
    x
}

/// The activation of `m` with each step rounded, as `glsl/mlp/bias_sigmoid.frag` does it.
pub fn activation_fp24(activation: Activation, m: f32) -> f32 {
    match activation {
        Activation::Sigmoid => fp24(1.0 / fp24(1.0 + fp24((-m).exp()))),
        Activation::Identity => m,
    }
}

/// A bound on |computed - exact| of every output of any evaluation that rounds as
/// [`forward_fp24`] does (in any summation order): [`super::cpu::rounding_bound`] with the
/// unit roundoff of fp24 after fp32 (2^-17 + 2^-23: a value is rounded to fp32, then to fp24),
/// four more rounded steps per term (the weight, the input, the product and the bias), and a
/// sigmoid whose three rounded steps and fp32 `exp` stay within 4 units of 2^-17.
pub fn error_bound_fp24(net: &Network, batch: ArrayView2<f32>) -> Array2<f32> {
    let u = UNIT_ROUNDOFF + f64::from(f32::EPSILON) / 2.0;
    super::cpu::rounding_bound(net, batch, u, 4, 4.0 * UNIT_ROUNDOFF)
}

/// Texels per row of [`round_on_gpu`]'s texture.
const ROUND_WIDTH: usize = 256;

/// `values` rounded by the shaders' `fp24()` (`glsl/mlp/fp24_round.frag`, one fragment per
/// value through an R32F texture and render target): what the emulation does on this
/// renderer, to hold against [`fp24`].
pub fn round_on_gpu(ctx: &Context, values: &[f32]) -> Result<Vec<f32>, GlError> {
    if values.is_empty() {
        return Ok(Vec::new());
    }
    let width = ROUND_WIDTH.min(values.len());
    let height = values.len().div_ceil(width);
    let mut texels = values.to_vec();
    texels.resize(width * height, 0.0);
    let (w, h) = (width as u32, height as u32);
    let input = Texture::from_f32(ctx, w, h, TextureFormat::R32F, &texels)?;
    let target = Framebuffer::new(
        ctx,
        "mlp fp24 rounding",
        &[&Texture::new_2d(ctx, w, h, TextureFormat::R32F)?],
        None,
    )?;
    let program = Program::rect(
        ctx,
        &[
            Precision::Fp24.shader_define(),
            shader!("glsl/mlp/fp24.glsl"),
            shader!("glsl/mlp/fp24_round.frag"),
        ],
    )?;
    target
        .pass(&program, "mlp fp24 rounding")?
        .texture("u_values", &input)
        .draw_full()?;
    let mut rounded = target.read_f32(0, target.rect())?;
    rounded.truncate(values.len());
    Ok(rounded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mlp::cpu::{error_bound, forward, CpuProduct};
    use crate::mlp::Layer;
    use ndarray::{array, Array1};

    const ULP_AT_ONE: f32 = 1.0 / 65536.0; // 2^-16

    #[test]
    fn the_format_edges() {
        assert_eq!(MAX, (2.0 - 2f32.powi(-16)) * 2f32.powi(63));
        assert_eq!(MIN_POSITIVE, 2f32.powi(-62));
        assert_eq!(MANTISSA_BITS + EXPONENT_BITS + 1, 24);
        assert!(is_fp24(MAX) && is_fp24(MIN_POSITIVE) && is_fp24(-MAX));
        assert!(!is_fp24(1.0 + 2f32.powi(-17)) && is_fp24(1.0 + ULP_AT_ONE));
    }

    #[test]
    fn representable_values_are_unchanged() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            3.0,
            1.0 + ULP_AT_ONE,
            65535.0,
            65536.0,
            3.0 * 2f32.powi(40),
        ] {
            assert_eq!(fp24(x).to_bits(), f32::to_bits(x), "{x}");
        }
        assert_eq!(fp24(f32::INFINITY), f32::INFINITY);
        assert_eq!(fp24(f32::NEG_INFINITY), f32::NEG_INFINITY);
        assert!(fp24(f32::NAN).is_nan());
    }

    #[test]
    fn rounds_to_nearest_with_ties_to_even() {
        let half = 2f32.powi(-17); // half the spacing at 1
                                   // ties: 1 + 1/2 ulp goes down to the even 1; 1 + 3/2 ulp up to the even 1 + 2 ulp
        assert_eq!(fp24(1.0 + half), 1.0);
        assert_eq!(fp24(1.0 + 3.0 * half), 1.0 + 2.0 * ULP_AT_ONE);
        assert_eq!(fp24(-(1.0 + 3.0 * half)), -(1.0 + 2.0 * ULP_AT_ONE));
        // off the tie by one fp32 ulp: to the nearer
        let fp32_ulp = f32::EPSILON;
        assert_eq!(fp24(1.0 + half + fp32_ulp), 1.0 + ULP_AT_ONE);
        assert_eq!(fp24(1.0 + half - fp32_ulp), 1.0);
        // the spacing from 2^17 to 2^18 is 2: 131073 is a tie between 131072 (even) and 131074
        // (odd), 131075 one between 131074 (odd) and 131076 (even)
        assert_eq!(fp24(131_073.0), 131_072.0);
        assert_eq!(fp24(131_075.0), 131_076.0);
        assert_eq!(fp24(65_537.0), 65_537.0); // below 2^17 the spacing is 1
                                              // a carry into the exponent: just under 2 rounds up to 2
        assert_eq!(fp24(2.0 - f32::EPSILON), 2.0);
        // 0.1 = 1.6 x 2^-4: mantissa 0x4CCCCD in fp32, 0x9999.9A in 16 bits, rounds up to 0x999A
        assert_eq!(fp24(0.1), (1.0 + f32::from(0x999Au16) / 65536.0) / 16.0);
    }

    #[test]
    fn overflow_goes_to_infinity_past_the_largest_value() {
        let step = 2f32.powi(63 - 16); // the spacing at the top binade
        assert_eq!(fp24(MAX), MAX);
        // below the halfway point to the next (missing) value: rounds back to MAX
        assert_eq!(fp24(MAX + step / 4.0), MAX);
        // the halfway point is a tie with an odd MAX: rounds up, out of range
        assert_eq!(fp24(MAX + step / 2.0), f32::INFINITY);
        assert_eq!(fp24(2f32.powi(64)), f32::INFINITY);
        assert_eq!(fp24(-2f32.powi(64)), f32::NEG_INFINITY);
        assert_eq!(fp24(f32::MAX), f32::INFINITY);
    }

    #[test]
    fn underflow_flushes_to_a_signed_zero() {
        assert_eq!(fp24(MIN_POSITIVE), MIN_POSITIVE);
        // the largest fp32 below 2^-62 rounds up to 2^-62 first, so it stays
        let below = f32::from_bits(MIN_POSITIVE.to_bits() - 1);
        assert_eq!(fp24(below), MIN_POSITIVE);
        // but one that rounds to a 24-bit value below 2^-62 flushes (no denormals)
        let far_below = f32::from_bits(MIN_POSITIVE.to_bits() - 0x80);
        assert_eq!(fp24(far_below).to_bits(), 0);
        assert_eq!(fp24(-far_below).to_bits(), 0x8000_0000);
        assert_eq!(fp24(2f32.powi(-63)).to_bits(), 0);
        assert_eq!(fp24(f32::MIN_POSITIVE).to_bits(), 0);
        assert_eq!(fp24(-1e-40).to_bits(), 0x8000_0000); // an fp32 denormal
    }

    #[test]
    fn relative_error_is_at_most_half_an_ulp() {
        let mut x = 1.0e-15f32;
        while x < 1.0e15 {
            for v in [x, -x * 1.37] {
                let r = fp24(v);
                assert!((f64::from(r) - f64::from(v)).abs() <= UNIT_ROUNDOFF * f64::from(v.abs()));
                assert!(is_fp24(r));
            }
            x *= 1.013;
        }
    }

    fn small_net(activation: Activation) -> Network {
        Network::new(vec![
            Layer {
                weights: array![[0.1, 0.2, -0.3], [0.7, -0.05, 0.25]],
                bias: Array1::from(vec![0.3, -0.1]),
                activation: Activation::Sigmoid,
            },
            Layer {
                weights: array![[1.1, -0.9]],
                bias: Array1::from(vec![0.01]),
                activation,
            },
        ])
        .unwrap()
    }

    #[test]
    fn forward_rounds_every_step_and_stays_near_fp32() {
        let x = array![[0.3f32, 0.7, 0.11], [1.0 / 3.0, 0.0, -2.0]];
        for activation in [Activation::Sigmoid, Activation::Identity] {
            let net = small_net(activation);
            let fp24_out = forward_fp24(&net, x.view());
            let fp32_out = forward(CpuProduct::Plain, &net, x.view()).outputs;
            let bound24 = error_bound_fp24(&net, x.view());
            let bound32 = error_bound(&net, x.view());
            for ((a, b), (e24, e32)) in fp24_out
                .iter()
                .zip(&fp32_out)
                .zip(bound24.iter().zip(&bound32))
            {
                assert!(is_fp24(*a), "{a} is not a 24-bit value");
                assert!((a - b).abs() <= e24 + e32, "{a} {b} {e24}");
            }
            assert_ne!(fp24_out, fp32_out, "rounding changed nothing");
        }
    }

    #[test]
    fn forward_matches_a_hand_rounded_evaluation() {
        // one input vector through a one-layer identity network, each step rounded by hand
        let net = Network::new(vec![Layer {
            weights: array![[0.1, 0.2]],
            bias: Array1::from(vec![0.3]),
            activation: Activation::Identity,
        }])
        .unwrap();
        let x = array![[0.7f32, 0.9]];
        let p0 = fp24(fp24(0.1) * fp24(0.7));
        let p1 = fp24(fp24(0.2) * fp24(0.9));
        let expect = fp24(fp24(p0 + p1) + fp24(0.3));
        assert_eq!(forward_fp24(&net, x.view())[[0, 0]], expect);
        assert!((expect - 0.55).abs() < 4.0 * ULP_AT_ONE);
    }
}
