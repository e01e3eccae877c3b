//! `compare --markdown`: the README's "What a run shows" table and its then-and-now lines,
//! printed from kept results. README.md holds the printed text between [`BEGIN`] and [`END`],
//! and a test fails when the two differ: no figure in that table is typed by hand.

use super::headline::{self, THEN_AND_NOW};
use super::Comparison;

/// The line before the generated text in README.md.
pub const BEGIN: &str = "<!-- compare:begin -->";
/// The line after it.
pub const END: &str = "<!-- compare:end -->";

/// A table cell: one line, with `|` escaped.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// The whole generated text: the table, what each column is, and the then-and-now lines.
pub fn text(c: &Comparison) -> String {
    let mut out = String::new();
    if c.quick {
        out.push_str(
            "These are `--quick` runs (small sizes, for CI): their figures show the mechanism, \
             not the papers' sizes.\n\n",
        );
    }
    out.push_str("| paper | claim | paper (its hardware) |");
    for m in &c.machines {
        out.push_str(&format!(
            " {}<br>{}, {} |",
            cell(&m.label),
            cell(&m.short_commit()),
            cell(m.day())
        ));
    }
    out.push_str("\n|---|---|---|");
    out.push_str(&"---|".repeat(c.machines.len()));
    out.push('\n');
    for row in &c.headlines {
        out.push_str(&format!(
            "| {} | {} | {} |",
            row.paper,
            cell(&row.label),
            cell(&row.published)
        ));
        for m in &row.cells {
            out.push_str(&format!(" {} |", cell(&m.text())));
        }
        out.push('\n');
    }
    out.push_str("\nThe columns, each a `results.json` kept in `assets/results/`:\n\n");
    for m in &c.machines {
        out.push_str(&format!(
            "- **{}**: {} (OpenGL {}, through {}); CPU {}; commit {}; {}; {}; `{}` \
             (`{}`)\n",
            m.label,
            m.renderer,
            m.gl_version,
            m.platform,
            m.cpu,
            m.short_commit(),
            m.date,
            m.load_in_words(),
            m.command(),
            kept_path(&m.file)
        ));
    }
    out.push_str(
        "\nThen and now, from the same runs (the frame time of the compute formulation over \
         the classic one):\n\n",
    );
    for row in &c.then_and_now {
        let parts: Vec<String> = THEN_AND_NOW
            .iter()
            .zip(&row.cells)
            .map(|((_, name), cell)| format!("{name} {}", headline::then_and_now_text(cell)))
            .collect();
        out.push_str(&format!("- {}: {}.\n", row.machine, parts.join(", ")));
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

/// The README's text for kept runs that cannot all share one table: one table per group of
/// runs that can (the papers' sizes first, then `--quick`; each version of the claims apart),
/// each under a heading that says which group it is. Runs are never mixed in one table.
pub fn grouped(paths: &[std::path::PathBuf]) -> anyhow::Result<String> {
    if paths.is_empty() {
        anyhow::bail!("compare: give at least one results.json (the file `reproduce` writes)");
    }
    let mut groups: Vec<Vec<super::Run>> = Vec::new();
    for path in paths {
        let run = super::Run::read(path)?;
        match groups
            .iter_mut()
            .find(|g| g[0].quick == run.quick && g[0].claims_version == run.claims_version)
        {
            Some(group) => group.push(run),
            None => groups.push(vec![run]),
        }
    }
    // Stable: the papers' sizes first, each size's groups in the order given.
    groups.sort_by_key(|g| g[0].quick);
    let several = groups.len() > 1;
    let mut out = String::new();
    for mut runs in groups {
        super::comparable(&runs)?;
        super::run::number_shared_labels(&mut runs);
        if several {
            let size = if runs[0].quick {
                "`--quick` runs (small sizes)"
            } else {
                "Runs at the papers' sizes"
            };
            let names: Vec<&str> = runs.iter().map(|r| r.label.as_str()).collect();
            out.push_str(&format!(
                "#### {size}: {} (claims version {})\n\n",
                names.join(", "),
                runs[0].claims_version
            ));
        }
        out.push_str(&text(&super::compare(runs)?));
        if several {
            out.push('\n');
        }
    }
    Ok(out)
}
