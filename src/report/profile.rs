//! The per-pass table of a section: its measurement run under `gl::profile`, so the report
//! shows where the time of the run went (GPU time of each pass, wall time, waits).

use super::Table;
use crate::gl::{self, profile::ProfileTable};

/// Run `measure` with the profiler on; its result and the table.
pub fn profiled<T>(
    ctx: &gl::Context,
    measure: impl FnOnce() -> anyhow::Result<T>,
) -> anyhow::Result<(T, ProfileTable)> {
    gl::profile::start(ctx);
    let result = measure();
    let table = gl::profile::finish(ctx);
    let value = result?;
    let table = table.ok_or_else(|| anyhow::anyhow!("the profile stopped during the run"))?;
    Ok((value, table))
}

/// The profile as a report table: the rows whose wall or GPU time is at least `min_share` of
/// the run's wall time (the others are summed in one line), nesting shown by indentation.
pub fn table(profile: &ProfileTable, caption: &str, min_share: f64) -> Table {
    let cut = profile.wall_ms * min_share;
    let mut rows = Vec::new();
    let (mut rest, mut rest_rows) = (0.0, 0);
    for r in &profile.rows {
        let gpu = r.gpu_ms.unwrap_or(0.0);
        if r.wall_ms < cut && gpu < cut {
            rest += r.wall_ms;
            rest_rows += 1;
            continue;
        }
        rows.push(vec![
            format!("{}{}", "\u{a0}\u{a0}".repeat(r.depth), r.name),
            r.calls.to_string(),
            r.gpu_ms
                .map(|g| format!("{:.1}", g))
                .unwrap_or_else(|| "-".into()),
            format!("{:.1}", r.wall_ms),
            format!("{:.1}", r.wait_ms),
            format!("{:.1}", 100.0 * r.wall_ms / profile.wall_ms.max(1e-9)),
        ]);
    }
    if rest_rows > 0 {
        rows.push(vec![
            format!("({rest_rows} smaller rows)"),
            "-".into(),
            "-".into(),
            format!("{rest:.1}"),
            "-".into(),
            format!("{:.1}", 100.0 * rest / profile.wall_ms.max(1e-9)),
        ]);
    }
    rows.push(vec![
        "whole run".into(),
        "1".into(),
        "-".into(),
        format!("{:.1}", profile.wall_ms),
        format!("{:.1}", profile.wait_ms()),
        "100.0".into(),
    ]);
    Table {
        caption: format!(
            "{caption}: per-pass profile of this run on {} (GPU ms by timestamp queries read \
             after the run, approximate on a tile-based software renderer, where passes that \
             share a scene overlap; wall ms; wait ms: glFinish, readbacks and query results \
             inside the row, where a software renderer does the drawing issued before; nested \
             rows are part of the row above; rows under {:.1}% of the run summed)",
            profile.renderer,
            min_share * 100.0
        ),
        header: [
            "pass or step",
            "calls",
            "GPU ms",
            "wall ms",
            "wait ms",
            "% of run wall",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    }
}
