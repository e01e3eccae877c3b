//! `index.html`: one section per paper, with the claims, the tables beside the paper's
//! numbers, the figures and the fidelity table. Self-contained: no scripts, no external CSS.

use super::{Claim, Report, Section, Table};
use crate::page::html::{escape, escape_cell, print_min_width, print_parts, CONTENT_WIDTH, STYLE};

/// Whether a cell reads as a number (possibly with a unit or a range: "7.86", "-0.5%",
/// "12.8 steps/s", "1.4-2x", "2048 x 2048"): such columns are right-aligned, text left.
fn is_numeric(cell: &str) -> bool {
    let cell = cell.trim();
    let Some(first) = cell.chars().next() else {
        return false;
    };
    let starts_like_a_number = first.is_ascii_digit()
        || (matches!(first, '-' | '+' | '.' | '~' | '<' | '>' | '\u{2248}')
            && cell
                .chars()
                .nth(1)
                .is_some_and(|c| c.is_ascii_digit() || c == '.'));
    // A number with at most a unit or two after it, not a sentence that starts with one.
    starts_like_a_number && cell.split_whitespace().count() <= 4
}

/// A column is numeric when every filled cell of it is (a dash or an empty cell counts as
/// filler).
fn numeric_columns(t: &Table) -> Vec<bool> {
    let columns = t
        .rows
        .iter()
        .map(Vec::len)
        .chain([t.header.len()])
        .max()
        .unwrap_or(0);
    (0..columns)
        .map(|c| {
            let mut filled = t
                .rows
                .iter()
                .filter_map(|r| r.get(c))
                .map(|v| v.trim())
                .filter(|v| !v.is_empty() && !matches!(*v, "-" | "\u{2014}" | "n/a"))
                .peekable();
            filled.peek().is_some() && filled.all(is_numeric)
        })
        .collect()
}

/// A table, and where it is wider than a printed page, the same rows again as column groups
/// for print (each group repeating the first column; the style shows the one or the other).
fn table_with_ids(t: &Table, row_ids: &[String], numeric: &[bool]) -> String {
    let columns = t
        .rows
        .iter()
        .map(Vec::len)
        .chain([t.header.len()])
        .max()
        .unwrap_or(0);
    let widths: Vec<u32> = (0..columns)
        .map(|c| {
            let number = numeric.get(c).copied().unwrap_or(false);
            let cells: Vec<(&str, bool)> = t
                .header
                .get(c)
                .map(|h| (h.as_str(), false))
                .into_iter()
                .chain(
                    t.rows
                        .iter()
                        .filter_map(|r| r.get(c))
                        .map(|v| (v.as_str(), number)),
                )
                .collect();
            print_min_width(&cells)
        })
        .collect();
    let parts = print_parts(&widths);
    let screen = one_table(t, row_ids, numeric);
    if parts.len() <= 1 {
        return screen;
    }
    let mut out = format!("<div class=\"screen\">{screen}</div><div class=\"print\">");
    for (k, part) in parts.iter().enumerate() {
        let pick = |cells: &[String]| -> Vec<String> {
            part.iter()
                .map(|&c| cells.get(c).cloned().unwrap_or_default())
                .collect()
        };
        let piece = Table {
            caption: format!(
                "{} (printed in {} parts: part {}, columns {})",
                t.caption,
                parts.len(),
                k + 1,
                part.iter()
                    .map(|&c| t.header.get(c).map_or(String::new(), |h| h.clone()))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            header: pick(&t.header),
            rows: t.rows.iter().map(|r| pick(r)).collect(),
        };
        let numeric: Vec<bool> = part
            .iter()
            .map(|&c| numeric.get(c).copied().unwrap_or(false))
            .collect();
        out.push_str(&one_table(&piece, &[], &numeric));
    }
    out.push_str("</div>\n");
    out
}

/// A table in its own scrolling box (a table still wider than the page after its text has
/// wrapped scrolls there, not the page), its caption above the box so that it wraps at the
/// page's width and is never cut at the box's edge; the columns marked in `numeric`
/// right-aligned, the others (text) left. `row_ids` gives rows an anchor.
fn one_table(t: &Table, row_ids: &[String], numeric: &[bool]) -> String {
    let class = |c: usize| {
        if numeric.get(c).copied().unwrap_or(false) {
            " class=\"num\""
        } else {
            ""
        }
    };
    let mut out = format!(
        "<div class=\"table\"><p class=\"caption\">{}</p><div class=\"scroll\"><table>\n<thead><tr>",
        escape(&t.caption)
    );
    for (c, h) in t.header.iter().enumerate() {
        out.push_str(&format!("<th{}>{}</th>", class(c), escape_cell(h)));
    }
    // The header row repeats on every printed page the table runs over.
    out.push_str("</tr></thead>\n<tbody>");
    for (r, row) in t.rows.iter().enumerate() {
        match row_ids.get(r) {
            Some(id) => out.push_str(&format!("<tr id=\"{}\">", escape(id))),
            None => out.push_str("<tr>"),
        }
        for (c, cell) in row.iter().enumerate() {
            out.push_str(&format!("<td{}>{}</td>", class(c), escape_cell(cell)));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table></div></div>\n");
    out
}

/// A table of measurements: numeric columns right-aligned.
fn table(t: &Table) -> String {
    table_with_ids(t, &[], &numeric_columns(t))
}

/// A table of sentences (claims, fidelity): every column left-aligned.
fn text_table(t: &Table, row_ids: &[String]) -> String {
    table_with_ids(t, row_ids, &[])
}

/// The anchor of claim `i` of section `id`.
fn claim_anchor(id: &str, i: usize) -> String {
    format!("{id}-claim-{}", i + 1)
}

/// The holds column: "yes", "no", or "not judged" (the measured text says why), and what
/// decided it: "yes, by counts", "not judged (timing)".
fn holds_text(claim: &Claim) -> String {
    let basis = claim.decided_by.in_words();
    match (claim.holds, basis.is_empty()) {
        (Some(true), true) => "yes".into(),
        (Some(false), true) => "no".into(),
        (None, true) => "not judged".into(),
        (Some(true), false) => format!("yes, by {basis}"),
        (Some(false), false) => format!("no, by {basis}"),
        (None, false) => format!("not judged ({basis})"),
    }
}

/// Every claim of every section, each linking to its row in its section.
fn claims_summary(sections: &[Section]) -> String {
    let mut out = String::from(
        "<div class=\"table\"><p class=\"caption\">Every claim at a glance (a link leads to \
         the claim and what was measured)</p><div class=\"scroll\"><table class=\"summary\">\n\
         <tr><th>section</th><th>claim</th><th>holds here</th></tr>\n",
    );
    for s in sections {
        for (i, c) in s.claims.iter().enumerate() {
            out.push_str(&format!(
                "<tr><td><a href=\"#{}\">{}</a></td><td><a href=\"#{}\">{}</a></td>\
                 <td class=\"{}\">{}</td></tr>\n",
                escape(&s.id),
                escape(&s.id),
                escape(&claim_anchor(&s.id, i)),
                escape(&c.claim),
                match c.holds {
                    Some(true) => "yes",
                    Some(false) => "no",
                    None => "unjudged",
                },
                holds_text(c)
            ));
        }
    }
    out.push_str("</table></div></div>\n");
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
                    vec![
                        c.claim.clone(),
                        c.paper.clone(),
                        c.measured.clone(),
                        holds_text(c),
                    ]
                })
                .collect(),
        };
        let ids: Vec<String> = (0..s.claims.len())
            .map(|i| claim_anchor(&s.id, i))
            .collect();
        out.push_str(&text_table(&claims, &ids));
    }
    for t in &s.tables {
        out.push_str(&table(t));
    }
    for f in &s.figures {
        out.push_str(&figure(f, s.figure_sizes.get(&f.file).copied()));
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
        out.push_str(&text_table(&fidelity, &[]));
    }
    out.push_str("</section>\n");
    out
}

/// A figure at the width it is shown (its own, or the page's where it is wider: then it links
/// to itself at full size and its caption says how much it was shrunk). `size` is the PNG's,
/// in pixels, where known.
fn figure(f: &super::Figure, size: Option<(u32, u32)>) -> String {
    let (src, alt) = (escape(&f.file), escape(&f.caption));
    let Some((width, height)) = size.filter(|s| s.0 > 0) else {
        return format!(
            "<figure><img src=\"{src}\" alt=\"{alt}\"><figcaption>{alt}</figcaption></figure>\n"
        );
    };
    let shown = width.min(CONTENT_WIDTH);
    let shown_height = (height as u64 * shown as u64 / width as u64) as u32;
    let img =
        format!("<img src=\"{src}\" alt=\"{alt}\" width=\"{shown}\" height=\"{shown_height}\">");
    if shown == width {
        return format!("<figure>{img}<figcaption>{alt}</figcaption></figure>\n");
    }
    format!(
        "<figure><a href=\"{src}\">{img}</a><figcaption>{alt} (shown at {}% of its {width} x \
         {height} pixels: the picture links to it at full size)</figcaption></figure>\n",
        100 * shown / width
    )
}

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
    out.push_str(&format!(
        "<p>Built from commit <code>{}</code>; made by <code>{}</code>.</p>\n",
        escape(&report.commit),
        escape(&report.command_line.join(" "))
    ));
    out.push_str(&format!("<p>Timings: {}.</p>\n", escape(&report.runs)));
    if let Some(dir) = &report.glsl_dir {
        out.push_str(&format!(
            "<p class=\"note\">Modified shaders: every result here was made with \
             <code>--glsl-dir {}</code>, whose shader files replaced the shipped ones; they \
             are not the shipped code's results.</p>\n",
            escape(dir)
        ));
    }
    if report.quick {
        out.push_str(
            "<p class=\"note\">Quick mode: small sizes for CI and smoke tests. These numbers \
             are not comparable with the papers' tables; run <code>classic-gpgpu reproduce</code> \
             without <code>--quick</code> for that.</p>\n",
        );
    }
    out.push_str(&contents(&report.sections));
    out.push_str("</body></html>\n");
    out
}

/// Everything below the page's header: the list of sections, how timings are judged, the
/// summary of every claim, and the sections.
fn contents(sections: &[Section]) -> String {
    let mut out = String::from("<ul>\n");
    for s in sections {
        out.push_str(&format!(
            "<li><a href=\"#{}\">{}</a></li>\n",
            escape(&s.id),
            escape(&s.title)
        ));
    }
    out.push_str("</ul>\n");
    out.push_str(&format!(
        "<p id=\"timing-policy\">{}</p>\n",
        escape(super::timing_policy::IN_WORDS)
    ));
    out.push_str(&format!(
        "<p>A claim judged on a timing is not judged (\"not judged: machine loaded\") when the \
         1-minute load average was above {:.1} per core while it was measured, or when its runs \
         fall on both sides of the paper's number; its measured text gives the runs and the \
         load.</p>\n",
        crate::timing::LOADED_PER_CORE
    ));
    out.push_str(&format!(
        "<p>{}</p>\n",
        escape(crate::gl::picture::MAPPING_IN_WORDS)
    ));
    out.push_str(&claims_summary(sections));
    for s in sections {
        out.push_str(&section(s));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{Claim, Table};

    fn section(id: &str, claims: &[(&str, Option<bool>)]) -> Section {
        Section {
            id: id.into(),
            title: format!("Paper {id}"),
            claims: claims
                .iter()
                .map(|&(claim, holds)| Claim {
                    claim: claim.into(),
                    paper: "the paper's words".into(),
                    measured: "12.5 ms on llvmpipe".into(),
                    holds,
                    decided_by: crate::report::Basis::Timing,
                    ..Claim::default()
                })
                .collect(),
            tables: vec![Table {
                caption: "Table III".into(),
                header: ["scene", "triangles", "ms", "note"]
                    .map(String::from)
                    .to_vec(),
                rows: vec![
                    ["tori", "15000", "7.86", "a long note in words"]
                        .map(String::from)
                        .to_vec(),
                    ["bunnies", "69451 x 2", "-", "another note"]
                        .map(String::from)
                        .to_vec(),
                ],
            }],
            ..Section::default()
        }
    }

    /// The `<td>` cells of the first row of the table with `caption`.
    fn first_row_cells<'a>(html: &'a str, caption: &str) -> Vec<&'a str> {
        let table = &html[html
            .find(&format!("<p class=\"caption\">{caption}</p>"))
            .unwrap()..];
        let start = ["<tr><td", "<tr id"]
            .iter()
            .filter_map(|t| table.find(t))
            .min()
            .unwrap();
        let row = &table[start..];
        let row = &row[..row.find("</tr>").unwrap()];
        row.split("<td").skip(1).collect()
    }

    #[test]
    fn text_columns_are_left_aligned_and_numbers_right() {
        let html = contents(&[section("paper1", &[("fast", Some(true))])]);
        let cells = first_row_cells(&html, "Table III");
        assert!(cells[0].starts_with('>'), "scene is text: {}", cells[0]);
        assert!(cells[1].starts_with(" class=\"num\""), "{}", cells[1]);
        assert!(cells[2].starts_with(" class=\"num\""), "{}", cells[2]);
        assert!(cells[3].starts_with('>'), "note is text: {}", cells[3]);
        // The claim table: claim, paper and measured are text.
        let claim = first_row_cells(
            &html,
            "What the paper claims, and what this machine measured",
        );
        assert!(claim.iter().all(|c| c.starts_with('>')), "{claim:?}");
        assert!(
            STYLE.contains("text-align:left") && STYLE.contains("td.num,th.num{text-align:right")
        );
        // Every table scrolls in its own box, its caption above the box.
        assert_eq!(
            html.matches("<table").count(),
            html.matches("</p><div class=\"scroll\"><table").count()
        );
        assert_eq!(
            html.matches("<table").count(),
            html.matches("<div class=\"table\"><p class=\"caption\">")
                .count()
        );
        assert!(STYLE.contains("div.scroll{overflow-x:auto"));
        assert!(STYLE.contains("::-webkit-scrollbar{height:12px"));
    }

    #[test]
    fn text_and_headers_wrap_and_only_numbers_keep_to_one_line() {
        // Text cells and headers may break anywhere, so a wide table fits the page.
        assert!(STYLE.contains("vertical-align:top;overflow-wrap:break-word}"));
        let nowrap: Vec<&str> = STYLE
            .split('}')
            .filter(|rule| rule.contains("white-space:nowrap"))
            .map(|rule| rule.split('{').next().unwrap())
            .collect();
        assert_eq!(nowrap, ["td.num"]);
        // A long caption is said whole, outside the scrolling box.
        let mut s = section("paper1", &[]);
        s.tables[0].caption = "Fig. 7, clustered CAPs: ... (paper: 0.095%, GeForce 7800)".into();
        let html = contents(&[s]);
        let at = html.find("(paper: 0.095%, GeForce 7800)</p>").unwrap();
        assert!(at < html.find("<div class=\"scroll\"><table>").unwrap());
    }

    #[test]
    fn the_summary_lists_every_claim_and_its_links_resolve() {
        let html = contents(&[
            section("paper1", &[("fast", Some(true)), ("exact", Some(false))]),
            section("paper4", &[("interactive", None)]),
        ]);
        let summary = &html[html.find("Every claim at a glance").unwrap()..];
        let summary = &summary[..summary.find("</table>").unwrap()];
        for claim in ["fast", "exact", "interactive"] {
            assert!(summary.contains(&format!(">{claim}</a>")), "{claim}");
        }
        assert!(summary.contains(">not judged (timing)</td>"));
        assert!(summary.contains(">yes, by timing</td>"));
        let links: Vec<&str> = summary
            .split("href=\"#")
            .skip(1)
            .map(|rest| &rest[..rest.find('"').unwrap()])
            .collect();
        assert_eq!(links.len(), 6, "a section link and a claim link per claim");
        // How pictures map values is said once, before the sections.
        let mapping = html.find("zero is always the same dark grey").unwrap();
        assert!(mapping < html.find("Every claim at a glance").unwrap());
        for link in links {
            assert_eq!(
                html.matches(&format!(" id=\"{link}\"")).count(),
                1,
                "#{link} names no single element"
            );
        }
    }
}
