//! `compare --markdown`: the README's "What a run shows" table and its then-and-now lines,
//! printed from kept results. README.md holds the printed text between [`BEGIN`] and [`END`],
//! and a test fails when the two differ: no figure in that table is typed by hand.
//!
//! A table per size (the papers' sizes, then `--quick`), a column per machine. Each cell is
//! the newest kept run of its machine whose version of the claim is this build's; where the
//! claim changed since that machine's newest run, the cell says "re-run needed" instead of a
//! stale figure. Every text that comes from a results.json is escaped ([`md`]): a results.json
//! is data, never markup.

use super::headline::{self, Headline, THEN_AND_NOW};
use super::run::Run;
use crate::report::published::Published;

/// The line before the generated text in README.md.
pub const BEGIN: &str = "<!-- compare:begin -->";
/// The line after it.
pub const END: &str = "<!-- compare:end -->";

/// `text` as inert markdown in a table cell: HTML's characters as entities, markdown's
/// punctuation backslash-escaped (no link, image, emphasis or code span can start), `|`
/// escaped for the table, on one line.
pub fn md(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '\\' | '`' | '*' | '_' | '[' | ']' | '|' | '~' | '!' | '#' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' | '\t' => out.push(' '),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}

/// One machine of a table: its runs, newest first.
struct Column<'a> {
    label: String,
    runs: Vec<&'a Run>,
}

impl Column<'_> {
    fn newest(&self) -> &Run {
        self.runs[0]
    }
}

/// The runs of `group` by machine (renderer), in the order first given, newest run first.
fn columns(group: &[Run]) -> Vec<Column<'_>> {
    let mut columns: Vec<Column> = Vec::new();
    for run in group {
        let label = super::run::short_name(&run.renderer);
        match columns.iter_mut().find(|c| c.label == label) {
            Some(column) => column.runs.push(run),
            None => columns.push(Column {
                label,
                runs: vec![run],
            }),
        }
    }
    for column in &mut columns {
        column.runs.sort_by(|a, b| b.date.cmp(&a.date));
    }
    columns
}

/// Headline `h` in `column`: the newest run whose version of the claim is `current`, or why
/// there is none.
fn cell(h: &Headline, column: &Column, current: Option<&str>, published: &Published) -> String {
    let found: Vec<(&Run, _)> = column
        .runs
        .iter()
        .filter_map(|r| headline::find(r, h).map(|f| (*r, f)))
        .collect();
    let Some((newest_with, (claim, _))) = found.first() else {
        return "not run".into();
    };
    let fresh = found
        .iter()
        .find(|(_, (claim, _))| current == Some(claim.version.as_str()));
    match fresh {
        Some((run, found)) => {
            let text = headline::cell(h, Some(*found), published).text();
            if std::ptr::eq(*run, column.newest()) {
                md(&text)
            } else {
                format!("{} ({})", md(&text), md(&run.short_commit()))
            }
        }
        None if claim.version.is_empty() => format!(
            "re-run needed: {} is a run before per-claim versions",
            md(&newest_with.short_commit())
        ),
        None => format!(
            "re-run needed: the claim changed since {}",
            md(&newest_with.short_commit())
        ),
    }
}

/// The generated text for one group of runs of the same sizes: the table, what each column
/// is, and the then-and-now lines.
fn table(group: &[Run]) -> String {
    let Ok(published) = Published::get() else {
        return String::new();
    };
    let quick = group[0].quick;
    let columns = columns(group);
    let mut out = String::new();
    if quick {
        out.push_str(
            "These are `--quick` runs (small sizes, for CI): their figures show the mechanism, \
             not the papers' sizes.\n\n",
        );
    }
    out.push_str("| paper | claim | paper (its hardware) |");
    for column in &columns {
        let run = column.newest();
        out.push_str(&format!(
            " {}<br>{}, {} |",
            md(&column.label),
            md(&run.short_commit()),
            md(run.day())
        ));
    }
    out.push_str("\n|---|---|---|");
    out.push_str(&"---|".repeat(columns.len()));
    out.push('\n');
    for h in headline::headlines() {
        let runs: Vec<&Run> = columns
            .iter()
            .flat_map(|c| c.runs.iter().copied())
            .collect();
        let Some((first, _)) = runs.iter().find_map(|r| headline::find(r, &h)) else {
            continue;
        };
        let current = super::current_version(h.id, quick);
        out.push_str(&format!(
            "| {} | {} | {} |",
            h.paper,
            md(h.label),
            md(&first.paper)
        ));
        for column in &columns {
            out.push_str(&format!(
                " {} |",
                cell(&h, column, current.as_deref(), published)
            ));
        }
        out.push('\n');
    }
    out.push_str(
        "\nEach cell is the newest kept run of its machine whose version of the claim is this \
         build's (its commit in brackets when it is not the column's newest run); \"re-run \
         needed\" where the claim changed since the machine's newest run.\n",
    );
    out.push_str("\nThe columns, each a `results.json` kept in `assets/results/`:\n\n");
    for column in &columns {
        for m in &column.runs {
            out.push_str(&format!(
                "- **{}**: {} (OpenGL {}, through {}); CPU {}; commit {}; {}; {}; command: {} \
                 ({})\n",
                md(&column.label),
                md(&m.renderer),
                md(&m.gl_version),
                md(&m.platform),
                md(&m.cpu),
                md(&m.short_commit()),
                md(&m.date),
                md(&m.load_in_words()),
                md(&m.command()),
                md(&kept_path(&m.file))
            ));
            if !m.stamped.is_empty() {
                out.push_str(&format!("  Its claims' versions: {}.\n", md(&m.stamped)));
            }
        }
    }
    out.push_str(
        "\nThen and now, from each machine's newest run (the frame time of the compute \
         formulation over the classic one):\n\n",
    );
    let newest: Vec<Run> = columns.iter().map(|c| c.newest().clone()).collect();
    for (row, column) in headline::then_and_now(&newest).iter().zip(&columns) {
        let parts: Vec<String> = THEN_AND_NOW
            .iter()
            .zip(&row.cells)
            .map(|((_, name), cell)| format!("{name} {}", headline::then_and_now_text(cell)))
            .collect();
        out.push_str(&format!(
            "- {} ({}): {}.\n",
            md(&column.label),
            md(&column.newest().short_commit()),
            md(&parts.join(", "))
        ));
    }
    out
}

/// A kept file as the README names it: from `assets/` on, or the path as given.
fn kept_path(file: &str) -> String {
    match file.find("assets/results/") {
        Some(at) => file[at..].to_string(),
        None => file.to_string(),
    }
}

/// The text between the markers of `readme`, or why there is none.
pub fn between_markers(readme: &str) -> Result<&str, String> {
    let begin = readme
        .find(BEGIN)
        .ok_or_else(|| format!("README.md has no {BEGIN} line"))?;
    let start = begin + BEGIN.len();
    let start = start + readme[start..].find('\n').map_or(0, |i| i + 1);
    let end = readme[start..]
        .find(END)
        .ok_or_else(|| format!("README.md has no {END} line after {BEGIN}"))?;
    Ok(&readme[start..start + end])
}

/// The README's text for kept runs: one table per size (the papers' sizes first), each under
/// a heading that says which it is where there are several. Runs of other sizes are never
/// mixed in one table.
pub fn grouped(paths: &[std::path::PathBuf]) -> anyhow::Result<String> {
    let groups = super::groups(super::read(paths)?);
    let several = groups.len() > 1;
    let mut out = String::new();
    for runs in groups {
        if several {
            let size = if runs[0].quick {
                "`--quick` runs (small sizes)"
            } else {
                "Runs at the papers' sizes"
            };
            let names: Vec<String> = columns(&runs).iter().map(|c| md(&c.label)).collect();
            out.push_str(&format!("#### {size}: {}\n\n", names.join(", ")));
        }
        out.push_str(&table(&runs));
        if several {
            out.push('\n');
        }
    }
    Ok(out)
}
