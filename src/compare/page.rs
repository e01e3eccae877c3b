//! The compare page (`index.html`): for each group of runs of the same sizes, the machines, the
//! headline figures and their plots, the then-and-now ratios, the claims whose definition
//! changed between the runs, and every claim (a row per version of it) with each run's
//! verdict, measured figure, commit, date and load. Every text of a results.json is escaped.
//! The style every page shares ([`crate::page::html::STYLE`]), self-contained.

use super::headline::{then_and_now_text, THEN_AND_NOW};
use super::plot::Figure;
use super::{Comparison, Group};
use crate::page::html::{escape, escape_cell, STYLE};

/// The verdict's class in the report's style (green, red, grey).
fn class(holds: Option<bool>, ran: bool) -> &'static str {
    match (ran, holds) {
        (true, Some(true)) => "yes",
        (true, Some(false)) => "no",
        _ => "unjudged",
    }
}

/// A table in the report's scrolling box: header cells, then rows of (class, html) cells.
fn table(caption: &str, header: &[String], rows: &[Vec<(String, String)>]) -> String {
    let mut out = format!(
        "<div class=\"table\"><table>\n<caption>{}</caption>\n<tr>",
        escape(caption)
    );
    for h in header {
        out.push_str(&format!("<th>{}</th>", escape_cell(h)));
    }
    out.push_str("</tr>\n");
    for row in rows {
        out.push_str("<tr>");
        for (class, html) in row {
            if class.is_empty() {
                out.push_str(&format!("<td>{html}</td>"));
            } else {
                out.push_str(&format!("<td class=\"{class}\">{html}</td>"));
            }
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</table></div>\n");
    out
}

fn text(t: &str) -> (String, String) {
    (String::new(), escape_cell(t))
}

fn machines_table(c: &Group) -> String {
    let header: Vec<String> = [
        "machine", "renderer", "OpenGL", "CPU", "date", "commit", "load", "command", "results",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<(String, String)>> = c
        .machines
        .iter()
        .map(|m| {
            vec![
                (String::new(), format!("<b>{}</b>", escape(&m.label))),
                text(&format!("{} (through {})", m.renderer, m.platform)),
                text(&format!("{} / GLSL {}", m.gl_version, m.glsl_version)),
                text(&m.cpu),
                text(&m.date),
                (String::new(), format!("<code>{}</code>", escape(&m.commit))),
                text(&m.load_in_words()),
                (
                    String::new(),
                    format!("<code>{}</code>", escape_cell(&m.command())),
                ),
                (
                    String::new(),
                    format!(
                        "<code>{}</code>{}",
                        escape_cell(&m.file),
                        if m.stamped.is_empty() {
                            String::new()
                        } else {
                            format!("<br><small>{}</small>", escape_cell(&m.stamped))
                        }
                    ),
                ),
            ]
        })
        .collect();
    table(
        "The machines: each column below is one results.json",
        &header,
        &rows,
    )
}

fn headlines(c: &Group) -> String {
    let mut header: Vec<String> = ["paper", "claim", "paper (its hardware)"]
        .map(String::from)
        .to_vec();
    header.extend(c.machines.iter().map(|m| m.label.clone()));
    let rows: Vec<Vec<(String, String)>> = c
        .headlines
        .iter()
        .map(|r| {
            let mut row = vec![text(&r.paper), text(&r.label), text(&r.published)];
            let current = super::current_version(&r.id, c.quick);
            row.extend(r.cells.iter().map(|cell| {
                let class = match cell.verdict.as_str() {
                    "yes" => "yes",
                    "no" => "no",
                    _ => "unjudged",
                };
                let stale = cell.verdict != "not run" && current.as_ref() != Some(&cell.version);
                let note = if stale {
                    format!(
                        "<br><small><i>{}</i></small>",
                        escape(&format!(
                            "not this build's definition ({})",
                            super::version_words(&cell.version)
                        ))
                    )
                } else {
                    String::new()
                };
                (
                    class.to_string(),
                    format!("{}{note}", escape_cell(&cell.text())),
                )
            }));
            row
        })
        .collect();
    table(
        "The headline claims: each machine's verdict and the figure it rests on",
        &header,
        &rows,
    )
}

fn then_and_now(c: &Group) -> String {
    let mut header = vec!["section".to_string()];
    header.extend(c.machines.iter().map(|m| m.label.clone()));
    let rows: Vec<Vec<(String, String)>> = THEN_AND_NOW
        .iter()
        .enumerate()
        .map(|(i, (_, name))| {
            let mut row = vec![text(name)];
            row.extend(
                c.then_and_now
                    .iter()
                    .map(|m| text(&then_and_now_text(&m.cells[i]))),
            );
            row
        })
        .collect();
    table(
        "Then and now: the frame time of the compute formulation over the classic one",
        &header,
        &rows,
    )
}

fn claims(c: &Group) -> String {
    let mut header: Vec<String> = ["section", "claim", "the paper (its hardware)"]
        .map(String::from)
        .to_vec();
    header.extend(c.machines.iter().map(|m| m.label.clone()));
    let rows: Vec<Vec<(String, String)>> = c
        .claims
        .iter()
        .map(|r| {
            let mut row = vec![
                text(&r.section),
                (
                    String::new(),
                    format!(
                        "{}<br><small><code>{}</code>: {}</small>",
                        escape_cell(&r.claim),
                        escape(&r.id),
                        escape(&format!(
                            "{}; {}",
                            super::version_words(&r.version),
                            r.status
                        ))
                    ),
                ),
                text(&format!("{} ({})", r.paper, r.hardware)),
            ];
            row.extend(r.cells.iter().map(|cell| {
                (
                    class(cell.holds, cell.ran).to_string(),
                    format!(
                        "<b>{}</b><br><small>{}</small>{}",
                        escape(cell.verdict()),
                        escape_cell(&cell.measured),
                        if cell.ran {
                            format!(
                                "<br><small><i>{}</i></small>",
                                escape(&format!("{}, {}, {}", cell.commit, cell.date, cell.load))
                            )
                        } else {
                            String::new()
                        }
                    ),
                )
            }));
            row
        })
        .collect();
    table(
        "Every claim, a row per version of it: on each machine the verdict, what was measured, \
         and the commit, date and load (1-minute load average at the section's start and end) \
         of the run",
        &header,
        &rows,
    )
}

/// The claims whose definition differs between the runs, as a list.
fn changed(c: &Group) -> String {
    if c.changed.is_empty() {
        return String::new();
    }
    let mut out = String::from(
        "<p>Claims whose definition differs between these runs (each version has a row of its \
         own below; no cell mixes two):</p>\n<ul>\n",
    );
    for changed in &c.changed {
        out.push_str(&format!(
            "<li><code>{}</code>: {}; {}</li>\n",
            escape(&changed.id),
            escape(&changed.since),
            escape(&changed.versions.join("; "))
        ));
    }
    out.push_str("</ul>\n");
    out
}

/// The whole page.
pub fn page(c: &Comparison, figures: &[Figure]) -> String {
    let machines: usize = c.groups.iter().map(|g| g.machines.len()).sum();
    let mut out = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>classic-gpgpu: the \
         papers' claims across machines</title><style>{STYLE}</style></head><body>\n\
         <h1>classic-gpgpu: the papers' claims across machines</h1>\n"
    );
    out.push_str(&format!(
        "<p>{machines} run{}. Each claim has an id and a version (a hash of what decides it: \
         its rule, the published values and the workload); runs compare side by side on every \
         claim whose version they share, and runs at other sizes form a group of their \
         own.</p>\n",
        if machines == 1 { "" } else { "s" },
    ));
    for (i, group) in c.groups.iter().enumerate() {
        if !group.reason.is_empty() {
            out.push_str(&format!(
                "<h2>{}</h2>\n<p class=\"note\">{}</p>\n",
                if group.quick {
                    "--quick runs"
                } else {
                    "Runs at the papers' sizes"
                },
                escape(&group.reason)
            ));
        } else if group.quick {
            out.push_str(
                "<p class=\"note\">Quick runs: small sizes for CI and smoke tests, not \
                 comparable with the papers' tables.</p>\n",
            );
        }
        out.push_str(&machines_table(group));
        out.push_str(&headlines(group));
        for f in figures.iter().filter(|f| f.group == i) {
            out.push_str(&format!(
                "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                escape(&f.file),
                escape(&f.caption),
                escape(&f.caption)
            ));
        }
        out.push_str(&then_and_now(group));
        out.push_str(&changed(group));
        out.push_str(&claims(group));
    }
    out.push_str("</body></html>\n");
    out
}
