//! The finest step of the traversal: where a ray segment first meets one bilinear patch.
//!
//! Patch (i, j) of the height field spans samples i..=i+1, j..=j+1; at local coordinates
//! (s, t) in [0, 1]^2 its height is `H(s, t) = h00 + A s + B t + C s t` with `A = h10 - h00`,
//! `B = h01 - h00`, `C = h00 - h10 - h01 + h11`. Along the ray `(s0 + u ds, t0 + u dt,
//! z0 + u dz)` the height above the patch, `f(u) = z(u) - H(s(u), t(u))`, is a quadratic in
//! u, `a u^2 + b u + c`; the hit is its first root in the segment (the VRST 2006 abstract
//! names the intersection with the bilinearly interpolated map; this closed form is our
//! reconstruction). `glsl/lecture3/displace_common.glsl` solves the same quadratic in fp32.

/// The four corner heights: `[h00, h10, h01, h11]` (h10 is sample i + 1, j).
pub type Corners = [f64; 4];

/// A ray segment in the patch's local frame: start (s0, t0, z0) and step per unit of u.
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    pub start: [f64; 3],
    pub step: [f64; 3],
    /// The segment is u in [0, length].
    pub length: f64,
}

/// The coefficients (a, b, c) of f(u) = z(u) - H(s(u), t(u)).
pub fn quadratic(h: Corners, seg: &Segment) -> (f64, f64, f64) {
    let (a_, b_, c_) = (h[1] - h[0], h[2] - h[0], h[0] - h[1] - h[2] + h[3]);
    let [s0, t0, z0] = seg.start;
    let [ds, dt, dz] = seg.step;
    let a = -c_ * ds * dt;
    let b = dz - a_ * ds - b_ * dt - c_ * (s0 * dt + t0 * ds);
    let c = z0 - (h[0] + a_ * s0 + b_ * t0 + c_ * s0 * t0);
    (a, b, c)
}

/// The height of the patch at (s, t).
pub fn height(h: Corners, s: f64, t: f64) -> f64 {
    h[0] + (h[1] - h[0]) * s + (h[2] - h[0]) * t + (h[0] - h[1] - h[2] + h[3]) * s * t
}

/// The first u in [0, length] where the ray is at or below the patch (f(u) <= 0), if any.
/// A segment that starts below the patch hits at u = 0.
pub fn first_hit(h: Corners, seg: &Segment) -> Option<f64> {
    let (a, b, c) = quadratic(h, seg);
    if c <= 0.0 {
        return Some(0.0);
    }
    let in_segment = |u: f64| (0.0..=seg.length).contains(&u);
    // f(0) > 0: the first root in the segment is where the ray first meets the patch.
    let roots = roots(a, b, c);
    roots
        .into_iter()
        .flatten()
        .filter(|&u| in_segment(u))
        .reduce(f64::min)
}

/// The real roots of a u^2 + b u + c (numerically stable: no cancellation between -b and
/// the square root); a linear or constant f has one or none.
pub fn roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if a.abs() <= 1e-12 * scale {
        return [(b != 0.0).then(|| -c / b), None];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let r1 = q / a;
    let r2 = if q != 0.0 { c / q } else { r1 };
    [Some(r1), Some(r2)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first crossing by dense sampling and bisection, for comparison.
    fn sampled_first_hit(h: Corners, seg: &Segment) -> Option<f64> {
        let f = |u: f64| {
            let p: Vec<f64> = (0..3).map(|k| seg.start[k] + u * seg.step[k]).collect();
            p[2] - height(h, p[0], p[1])
        };
        if f(0.0) <= 0.0 {
            return Some(0.0);
        }
        let n = 20_000;
        for k in 1..=n {
            let (lo, hi) = ((k - 1) as f64 / n as f64, k as f64 / n as f64);
            let (lo, hi) = (lo * seg.length, hi * seg.length);
            if f(hi) <= 0.0 {
                let (mut lo, mut hi) = (lo, hi);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if f(mid) <= 0.0 {
                        hi = mid
                    } else {
                        lo = mid
                    }
                }
                return Some(hi);
            }
        }
        None
    }

    #[test]
    fn first_hit_matches_dense_sampling() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut hits = 0;
        for _ in 0..2000 {
            let h = [next(), next(), next(), next()];
            let start = [next(), next(), 0.3 + next()];
            let step = [next() - 0.5, next() - 0.5, -next() * 1.5];
            let length = 1.0;
            let seg = Segment {
                start,
                step,
                length,
            };
            let exact = first_hit(h, &seg);
            let sampled = sampled_first_hit(h, &seg);
            match (exact, sampled) {
                (Some(a), Some(b)) => {
                    hits += 1;
                    assert!((a - b).abs() < 1e-6, "{h:?} {seg:?}: {a} vs {b}")
                }
                (None, None) => {}
                // A tangent touch between samples: the closed form finds it, sampling not.
                (Some(a), None) => {
                    let (qa, qb, _) = quadratic(h, &seg);
                    let slope = 2.0 * qa * a + qb;
                    assert!(
                        slope.abs() < 1e-3,
                        "{h:?} {seg:?}: missed by sampling at {a}"
                    );
                }
                (None, Some(b)) => panic!("{h:?} {seg:?}: closed form missed {b}"),
            }
        }
        assert!(hits > 500, "the random segments must hit often: {hits}");
    }
}
