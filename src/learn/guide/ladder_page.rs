//! The reduction ladder on its lesson's guide page: each rung's one change, then a small
//! ladder timed for the guide (2^16 to 2^18 values, exactly 3 runs each, so that `learn
//! --guide` stays quick on llvmpipe) as a table and a plot of effective bandwidth against
//! size, with the command that times the full sweep to 2^22 named on the page.

use crate::gl::Context;
use crate::learn::ladder::{self, LadderBench};
use crate::page::html::escape;
use crate::page::plot::{Plot, Series};
use crate::timing::Runs;
use std::path::Path;

/// The lesson whose page shows the ladder.
pub const LESSON: &str = "compute-reduction";
/// The sizes the guide times.
pub const GUIDE_SIZES: [u32; 3] = [1 << 16, 1 << 17, 1 << 18];
/// The picture, relative to the guide's folder.
const PICTURE: &str = "pictures/compute-reduction/ladder.png";

/// The ladder's section of lesson `id`'s page (empty for every other lesson): run on `ctx`,
/// its plot written under `dir`. A ladder that could not run says why on the page.
pub fn section(ctx: &Context, id: &str, dir: &Path) -> String {
    if id != LESSON {
        return String::new();
    }
    let mut out = String::from("<h2>The ladder after Harris</h2>\n<ol>\n");
    for rung in &ladder::RUNGS {
        out.push_str(&format!(
            "<li><b>{}</b> (<code>{}</code>): {}</li>\n",
            escape(rung.name),
            escape(rung.shader.name),
            escape(rung.change)
        ));
    }
    out.push_str("</ol>\n");
    match ladder::bench(ctx, &GUIDE_SIZES, Runs::exactly(3)) {
        Ok(bench) => match plot(&bench).write_png(&dir.join(PICTURE)) {
            Ok(()) => out.push_str(&timed(&bench)),
            Err(e) => out.push_str(&format!(
                "<p class=\"fail\">The ladder's plot could not be written: {}</p>\n",
                escape(&format!("{e:#}"))
            )),
        },
        Err(e) => out.push_str(&format!(
            "<p class=\"fail\">The ladder did not run here: {}</p>\n",
            escape(&format!("{e:#}"))
        )),
    }
    out
}

/// The table and the plot of a bench.
fn timed(bench: &LadderBench) -> String {
    let load = bench.load.map_or("load unknown".into(), |l| l.in_words());
    let mut out = format!(
        "<p>Timed for this guide on {} ({}): {} values, {}. Timed: {}. The full sweep, 2^16 \
         to 2^22 values (Harris's size), is <code>classic-gpgpu learn {LESSON} --bench</code>; \
         <code>--size N</code> times one size and <code>--out FILE.json</code> keeps the \
         numbers.</p>\n",
        escape(&bench.renderer),
        escape(&load),
        GUIDE_SIZES
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        escape(&bench.runs),
        escape(bench.what_is_timed)
    );
    out.push_str(&format!(
        "<p>One clock for every rung: the {}, because {}.</p>\n",
        escape(bench.clock.clock.in_words()),
        escape(&bench.clock.why)
    ));
    if let Some(why) = &bench.compute_skipped {
        out.push_str(&format!("<p>Compute rungs: {}.</p>\n", escape(why)));
    }
    out.push_str("<table><tr><th>rung</th>");
    for n in &bench.sizes {
        out.push_str(&format!(
            "<th>{n} values: median ms (range), passes</th><th>GB/s</th><th>step</th>"
        ));
    }
    out.push_str("</tr>\n");
    for rung in &ladder::RUNGS {
        let rows: Vec<_> = bench
            .rungs
            .iter()
            .filter(|t| t.rung == rung.number)
            .collect();
        if rows.is_empty() {
            continue;
        }
        out.push_str(&format!(
            "<tr><td>{}. {}</td>",
            rung.number,
            escape(rung.name)
        ));
        for t in &rows {
            out.push_str(&format!(
                "<td>{:.3} ({:.3}-{:.3}), {}</td><td>{:.3}</td><td>{}</td>",
                t.ms.median,
                t.ms.min,
                t.ms.max,
                t.passes,
                t.gb_per_s,
                t.step.map_or("-".into(), |s| format!("{s:.2}x"))
            ));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("<tr><td>CPU: f64 sum, one core (wall clock)</td>");
    for c in &bench.cpu {
        out.push_str(&format!(
            "<td>{:.3} ({:.3}-{:.3}), -</td><td>{:.3}</td><td>-</td>",
            c.ms.median, c.ms.min, c.ms.max, c.gb_per_s
        ));
    }
    out.push_str("</tr>\n</table>\n");
    out.push_str(&format!(
        "<p>Effective bandwidth is the bytes of input read (4 per value) over the median time; \
         step is the median of the rung before (of the same kind) over this one's. Every \
         rung's sum was checked equal to the CPU's before it was timed.</p>\n\
         <p><img src=\"{PICTURE}\" alt=\"the ladder: effective bandwidth against size, one \
         line per rung and the CPU\" style=\"max-width:100%\"></p>\n"
    ));
    for s in &bench.slower {
        out.push_str(&format!(
            "<p>At {} values rung {} was slower than rung {}; both rerun in turn: {} against \
             {}: {}</p>\n",
            s.n,
            s.rung,
            s.before,
            escape(&s.rerun.0.in_words(" ms")),
            escape(&s.rerun.1.in_words(" ms")),
            escape(&s.why)
        ));
    }
    out.push_str(&harris_table());
    out
}

/// Harris's G80 table, to set beside the full sweep's 2^22 row.
fn harris_table() -> String {
    let mut out = format!(
        "<p>{}, as published (the total from his times). <code>classic-gpgpu learn {LESSON} \
         --bench</code> prints them beside this renderer's compute rungs at his size, 2^22 \
         values.</p>\n<table><tr><th>kernel</th><th>compute rung</th><th>ms</th><th>GB/s</th>\
         <th>step</th><th>total</th></tr>\n",
        escape(ladder::HARRIS_SOURCE)
    );
    for p in &ladder::HARRIS {
        let rung = ladder::RUNGS
            .iter()
            .find(|r| r.kernel() == Some(p.kernel))
            .map_or("-", |r| r.name);
        out.push_str(&format!(
            "<tr><td>{}</td><td>{}</td><td>{:.3}</td><td>{:.3}</td><td>{}</td><td>{:.2}x</td></tr>\n",
            p.kernel,
            escape(rung),
            p.ms,
            p.gb_per_s,
            p.step.map_or("-".into(), |s| format!("{s:.2}x")),
            p.cumulative()
        ));
    }
    out.push_str("</table>\n");
    out
}

/// Bandwidth against size, a line per rung and one for the CPU.
fn plot(bench: &LadderBench) -> Plot {
    let mut series: Vec<Series> = Vec::new();
    for rung in &ladder::RUNGS {
        let points: Vec<(f64, f64)> = bench
            .rungs
            .iter()
            .filter(|t| t.rung == rung.number)
            .map(|t| (t.n as f64, t.gb_per_s))
            .collect();
        if !points.is_empty() {
            series.push(Series::new(
                format!("{}. {}", rung.number, rung.name),
                points,
            ));
        }
    }
    let cpu = bench.cpu.iter().map(|c| (c.n as f64, c.gb_per_s)).collect();
    series.push(Series::new("CPU: f64 sum, one core", cpu).dashed());
    Plot {
        // The renderer is named in the page's text above the plot (its name is long).
        title: "The reduction ladder: effective bandwidth by rung".into(),
        x_label: "values summed (n)".into(),
        y_label: "effective bandwidth, GB/s (4 n bytes / median time)".into(),
        log_x: true,
        log_y: true,
        series,
    }
}
