//! Every number a pass hands back is checked before anything reports it: a NaN or an
//! infinity (an fp32 overflow, a texel the renderer left undefined, a driver bug) becomes an
//! error naming what was computed and the pass that produced it, never a printed NaN.

use super::GlError;

/// `values` (read back from the pass `pass`) must all be finite; `what` names the result
/// and whose it is ("mass: the volume integrals of body 3 (torus)").
pub fn ensure_finite<T: Copy + Into<f64>>(
    values: impl IntoIterator<Item = T>,
    what: &str,
    pass: &str,
) -> Result<(), GlError> {
    match values
        .into_iter()
        .map(Into::into)
        .enumerate()
        .find(|(_, v)| !v.is_finite())
    {
        None => Ok(()),
        Some((index, value)) => Err(GlError::NonFinite {
            what: what.to_string(),
            pass: pass.to_string(),
            index,
            value,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_non_finite_value_names_the_result_the_pass_and_the_value() {
        assert!(ensure_finite([1.0f32, -2.5, 0.0], "x", "p").is_ok());
        assert!(ensure_finite(Vec::<f64>::new(), "x", "p").is_ok());
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let err = ensure_finite([0.0, 1.0, bad, 2.0], "mass: body 3 (torus)", "reduction")
                .unwrap_err()
                .to_string();
            assert!(err.starts_with("mass: body 3 (torus): "), "{err}");
            assert!(err.contains("pass 'reduction'"), "{err}");
            assert!(err.contains(&format!("{bad}")), "{err}");
            assert!(err.contains("value 2"), "{err}");
        }
        let err = ensure_finite([f32::NAN], "y", "q").unwrap_err();
        assert!(matches!(err, GlError::NonFinite { index: 0, .. }), "{err}");
    }
}
