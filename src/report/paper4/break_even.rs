//! Where the GPU path costs as much as the analytic one: the crossing of Fig. 5's curves.

use super::bench::Paper4Results;
use crate::report::Table;

pub fn table(results: &Paper4Results) -> Table {
    Table {
        caption: "Resolution where the GPU path costs the same as the analytic one (wall clock)"
            .into(),
        header: ["object", "faces", "analytic (ms)", "break-even"]
            .map(String::from)
            .to_vec(),
        rows: results
            .objects
            .iter()
            .map(|o| {
                vec![
                    o.object.clone(),
                    o.faces.to_string(),
                    format!("{:.3}", o.analytic_ms),
                    o.break_even.clone(),
                ]
            })
            .collect(),
    }
}
