//! The compare page (`index.html`): the machines, the headline figures and their plots, the
//! then-and-now ratios, and every claim with each machine's verdict, measured figure and load.
//! The style every page shares ([`crate::page::html::STYLE`]), self-contained.

use super::headline::{then_and_now_text, THEN_AND_NOW};
use super::plot::Figure;
use super::Comparison;
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

fn machines(c: &Comparison) -> String {
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
                    format!("<code>{}</code>", escape_cell(&m.file)),
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

fn headlines(c: &Comparison) -> String {
    let mut header: Vec<String> = ["paper", "claim", "paper (its hardware)"]
        .map(String::from)
        .to_vec();
    header.extend(c.machines.iter().map(|m| m.label.clone()));
    let rows: Vec<Vec<(String, String)>> = c
        .headlines
        .iter()
        .map(|r| {
            let mut row = vec![text(&r.paper), text(&r.label), text(&r.published)];
            row.extend(r.cells.iter().map(|cell| {
                let class = match cell.verdict.as_str() {
                    "yes" => "yes",
                    "no" => "no",
                    _ => "unjudged",
                };
                (class.to_string(), escape_cell(&cell.text()))
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

fn then_and_now(c: &Comparison) -> String {
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

fn claims(c: &Comparison) -> String {
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
                text(&r.claim),
                text(&format!("{} ({})", r.paper, r.hardware)),
            ];
            row.extend(r.cells.iter().map(|cell| {
                (
                    class(cell.holds, cell.ran).to_string(),
                    format!(
                        "<b>{}</b><br><small>{}</small>{}",
                        escape(cell.verdict()),
                        escape_cell(&cell.measured),
                        if cell.load.is_empty() {
                            String::new()
                        } else {
                            format!("<br><small><i>{}</i></small>", escape(&cell.load))
                        }
                    ),
                )
            }));
            row
        })
        .collect();
    table(
        "Every claim: on each machine the verdict, what was measured, and the section's load \
         (1-minute load average at its start and end)",
        &header,
        &rows,
    )
}

/// The whole page.
pub fn page(c: &Comparison, figures: &[Figure]) -> String {
    let mut out = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>classic-gpgpu: the \
         papers' claims across machines</title><style>{STYLE}</style></head><body>\n\
         <h1>classic-gpgpu: the papers' claims across machines</h1>\n"
    );
    out.push_str(&format!(
        "<p>{} machine{}, every one at {} and judging claims version <code>{}</code> (a \
         hash of the report's code and the published tables: results of other versions or \
         sizes are refused, never mixed).</p>\n",
        c.machines.len(),
        if c.machines.len() == 1 { "" } else { "s" },
        if c.quick {
            "--quick sizes"
        } else {
            "the papers' sizes"
        },
        escape(&c.claims_version)
    ));
    if c.quick {
        out.push_str(
            "<p class=\"note\">Quick runs: small sizes for CI and smoke tests, not comparable \
             with the papers' tables.</p>\n",
        );
    }
    out.push_str(&machines(c));
    out.push_str(&headlines(c));
    for f in figures {
        out.push_str(&format!(
            "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
            escape(&f.file),
            escape(&f.caption),
            escape(&f.caption)
        ));
    }
    out.push_str(&then_and_now(c));
    out.push_str(&claims(c));
    out.push_str("</body></html>\n");
    out
}
