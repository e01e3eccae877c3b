//! Technique 4: interpolation error per table size, and the speed of a lookup against
//! computing the function.

use super::results::Lecture3Results;
use crate::report::Table;

pub fn error_table(results: &Lecture3Results) -> Table {
    Table {
        caption: format!(
            "4. A function in a 1D texture (linear filtering): error against the exact function \
             over {} samples, the bound h^2 max|f''| / 8, and the filter's own error (against \
             exact linear interpolation of the table), on {}",
            results.function.errors.first().map_or(0, |r| r.samples),
            results.renderer
        ),
        header: [
            "function",
            "texels",
            "max error",
            "RMS error",
            "bound",
            "filter error",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .function
            .errors
            .iter()
            .map(|r| {
                vec![
                    r.function.clone(),
                    r.texels.to_string(),
                    format!("{:.2e}", r.max_error),
                    format!("{:.2e}", r.rms_error),
                    format!("{:.2e}", r.bound),
                    format!("{:.2e}", r.filter_error),
                ]
            })
            .collect(),
    }
}

pub fn speed_table(results: &Lecture3Results) -> Table {
    Table {
        caption: format!(
            "4. Computing the function against looking it up (256 texels), on {}",
            results.renderer
        ),
        header: [
            "function",
            "evaluations",
            "computed in the shader (ms)",
            "looked up (ms)",
            "computed / looked up",
            "CPU f64 (ms)",
            "CPU / lookup",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .function
            .speed
            .iter()
            .map(|r| {
                vec![
                    r.function.clone(),
                    r.evaluations.to_string(),
                    format!("{:.2}", r.exact_ms),
                    format!("{:.2}", r.lookup_ms),
                    format!("{:.2}", r.exact_ms / r.lookup_ms),
                    format!("{:.1}", r.cpu_ms),
                    format!("{:.1}", r.cpu_ms / r.lookup_ms),
                ]
            })
            .collect(),
    }
}
