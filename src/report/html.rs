//! `index.html`: one section per paper, with the claims, the tables beside the paper's
//! numbers, the figures and the fidelity table. Self-contained: no scripts, no external CSS.

use super::{Report, Section, Table};

pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn table(t: &Table) -> String {
    let mut out = format!("<table>\n<caption>{}</caption>\n<tr>", escape(&t.caption));
    for h in &t.header {
        out.push_str(&format!("<th>{}</th>", escape(h)));
    }
    out.push_str("</tr>\n");
    for row in &t.rows {
        out.push_str("<tr>");
        for cell in row {
            out.push_str(&format!("<td>{}</td>", escape(cell)));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</table>\n");
    out
}

fn section(s: &Section) -> String {
    let mut out = format!(
        "<section id=\"{}\">\n<h2>{}</h2>\n<p>{}</p>\n",
        escape(&s.id),
        escape(&s.title),
        escape(&s.summary)
    );
    if !s.claims.is_empty() {
        let claims = Table {
            caption: "What the paper claims, and what this machine measured".into(),
            header: ["claim", "paper", "measured here", "holds"]
                .map(String::from)
                .to_vec(),
            rows: s
                .claims
                .iter()
                .map(|c| {
                    let holds = match c.holds {
                        Some(true) => "yes",
                        Some(false) => "no",
                        None => "not judged here",
                    };
                    vec![
                        c.claim.clone(),
                        c.paper.clone(),
                        c.measured.clone(),
                        holds.into(),
                    ]
                })
                .collect(),
        };
        out.push_str(&table(&claims));
    }
    for t in &s.tables {
        out.push_str(&table(t));
    }
    for f in &s.figures {
        out.push_str(&format!(
            "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
            escape(&f.file),
            escape(&f.caption),
            escape(&f.caption)
        ));
    }
    if !s.fidelity.is_empty() {
        let fidelity = Table {
            caption: "Fidelity: the GL feature the paper used, where this code uses it, and \
                      what differs from the paper"
                .into(),
            header: ["feature", "paper", "code", "deviation"]
                .map(String::from)
                .to_vec(),
            rows: s
                .fidelity
                .iter()
                .map(|f| {
                    vec![
                        f.feature.clone(),
                        f.paper.clone(),
                        f.code.clone(),
                        f.deviation.clone(),
                    ]
                })
                .collect(),
        };
        out.push_str(&table(&fidelity));
    }
    out.push_str("</section>\n");
    out
}

pub(crate) const STYLE: &str =
    "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;\
color:#222}table{border-collapse:collapse;margin:1em 0;font-size:90%}caption{text-align:left;\
font-weight:bold;padding:.3em 0}td,th{border:1px solid #bbb;padding:.25em .5em;text-align:right}\
th{background:#eee}td:first-child{text-align:left}img{max-width:100%;border:1px solid #ddd}\
figure{margin:1em 0}.note{background:#ffd;padding:.5em 1em;border:1px solid #dd8}";

/// The whole page.
pub fn page(report: &Report) -> String {
    let mut out = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>classic-gpgpu reproduction</title>\
         <style>{STYLE}</style></head><body>\n<h1>classic-gpgpu: the papers reproduced</h1>\n"
    );
    out.push_str(&format!(
        "<p>Renderer: <b>{}</b> ({}). GL {} / GLSL {}. CPU: {}. Generated {} in {:.0} s.</p>\n",
        escape(&report.renderer.renderer),
        escape(&report.renderer.platform.to_string()),
        escape(&report.renderer.version),
        escape(&report.renderer.glsl_version),
        escape(&report.cpu),
        escape(&report.date),
        report.elapsed_s
    ));
    out.push_str(&format!("<p>Timings: {}.</p>\n", escape(&report.runs)));
    if report.quick {
        out.push_str(
            "<p class=\"note\">Quick mode: small sizes for CI and smoke tests. These numbers \
             are not comparable with the papers' tables; run <code>classic-gpgpu reproduce</code> \
             without <code>--quick</code> for that.</p>\n",
        );
    }
    out.push_str("<ul>\n");
    for s in &report.sections {
        out.push_str(&format!(
            "<li><a href=\"#{}\">{}</a></li>\n",
            escape(&s.id),
            escape(&s.title)
        ));
    }
    out.push_str("</ul>\n");
    for s in &report.sections {
        out.push_str(&section(s));
    }
    out.push_str("</body></html>\n");
    out
}
