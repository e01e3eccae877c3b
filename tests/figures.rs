//! Every figure of a quick report can be read where it is shown, without the code: each listed
//! figure is a PNG in the report's folder and carries what its drawing code recorded
//! (`results.json`'s `drawn`): a plot has a title, axis titles, at least two labelled ticks on
//! each axis and a legend entry per curve; a picture of float buffers has a title and a colour
//! key per panel, whole-texel enlargement, titles of at most three lines and no panel mostly
//! empty; rendered frames side by side are each titled. On the page (`index.html`) each figure
//! states the width it is shown at: at least half its own or linked to itself at full size,
//! and its smallest text at least 12 pixels as shown. `Drawn::problems_shown_at` names what is
//! wrong. The same report's timing claims all go through the report's one timing policy. Set
//! `CLASSIC_GPGPU_KEEP_FIGURES` to keep the report (its folder is printed) and look at it.

use classic_gpgpu::gl::drawn::Drawn;
use classic_gpgpu::report::{timing_policy, Basis, Section};
use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

/// The quick report the checks read, made once: its folder and `results.json`.
fn quick_report() -> &'static (PathBuf, serde_json::Value) {
    static REPORT: OnceLock<(PathBuf, serde_json::Value)> = OnceLock::new();
    REPORT.get_or_init(|| {
        let out: PathBuf =
            std::env::temp_dir().join(format!("classic-gpgpu-figures-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        let run = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
            .args(["reproduce", "--quick", "--runs", "1", "--json", "--out"])
            .arg(&out)
            .output()
            .expect("the binary runs");
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        eprintln!("report in {}", out.display());
        let text = std::fs::read_to_string(out.join("results.json")).unwrap();
        (out, serde_json::from_str(&text).unwrap())
    })
}

/// The width `index.html` shows `file` at, and whether the picture links to itself.
fn shown_on_the_page(html: &str, file: &str) -> Option<(u32, bool)> {
    let img = format!("<img src=\"{file}\"");
    let at = html.find(&img)?;
    let tag = &html[at..at + html[at..].find('>')?];
    let width = tag
        .split("width=\"")
        .nth(1)?
        .split('"')
        .next()?
        .parse()
        .ok()?;
    let before = &html[..at];
    let linked = before.ends_with(&format!("<a href=\"{file}\">"));
    Some((width, linked))
}

#[test]
fn a_quick_report_is_readable_where_shown_and_judges_timing_by_one_policy() {
    every_figure_is_readable_where_it_is_shown();
    no_timing_claim_of_a_software_renderers_report_escapes_the_policy();
    if std::env::var_os("CLASSIC_GPGPU_KEEP_FIGURES").is_none() {
        std::fs::remove_dir_all(&quick_report().0).ok();
    }
}

fn every_figure_is_readable_where_it_is_shown() {
    let (out, results) = quick_report();
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let mut problems = Vec::new();
    let (mut plots, mut pictures) = (0, 0);
    for section in results["sections"].as_array().unwrap() {
        let id = section["id"].as_str().unwrap();
        for figure in section["figures"].as_array().unwrap() {
            let file = figure["file"].as_str().unwrap().to_string();
            let caption = figure["caption"].as_str().unwrap_or("");
            if caption.trim().is_empty() {
                problems.push(format!("{id}/{file}: no caption"));
            }
            let Ok((width, _)) = image::image_dimensions(out.join(&file)) else {
                problems.push(format!("{id}/{file}: listed but not written"));
                continue;
            };
            let Some((shown, linked)) = shown_on_the_page(&html, &file) else {
                problems.push(format!("{id}/{file}: the page does not say its width"));
                continue;
            };
            let scale = shown as f64 / width as f64;
            if scale < 0.5 && !linked {
                problems.push(format!(
                    "{id}/{file}: shown at {:.0}% of its {width} pixels, with no link to it",
                    100.0 * scale
                ));
            }
            if shown > classic_gpgpu::page::html::CONTENT_WIDTH {
                problems.push(format!(
                    "{id}/{file}: shown {shown} px wide, wider than the page"
                ));
            }
            match serde_json::from_value::<Drawn>(section["drawn"][&file].clone()) {
                Ok(drawn) => {
                    match drawn {
                        Drawn::Plot(_) => plots += 1,
                        Drawn::Picture(_) | Drawn::Frames(_) => pictures += 1,
                        _ => {}
                    }
                    for p in drawn.problems_shown_at(scale) {
                        problems.push(format!("{id}/{file}: {p}"));
                    }
                }
                Err(_) => problems.push(format!(
                    "{id}/{file}: its drawing code recorded nothing of what it shows"
                )),
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{} figure problem(s):\n{}",
        problems.len(),
        problems.join("\n")
    );
    // The report has both kinds, so the checks above ran on each.
    assert!(
        plots >= 10 && pictures >= 5,
        "{plots} plots, {pictures} pictures"
    );
    // Printed, a table wider than the page comes as column groups, the header on each page.
    assert!(html.contains("printed in 2 parts") || html.contains("printed in 3 parts"));
    assert!(html.contains("<thead>"));
}

/// A report made here (llvmpipe or softpipe: a software renderer) judges every timing claim by
/// the one policy: none is left unjudged for the renderer or without a reason, and each says
/// that its verdict is the renderer's; the page says the policy once.
fn no_timing_claim_of_a_software_renderers_report_escapes_the_policy() {
    let (out, results) = quick_report();
    let software = ["llvmpipe", "softpipe", "swrast"].iter().any(|r| {
        results["renderer"]["renderer"]
            .as_str()
            .unwrap_or("")
            .contains(r)
    });
    let mut timing = 0;
    for value in results["sections"].as_array().unwrap() {
        let section: Section = serde_json::from_value(value.clone()).expect("a section");
        assert_eq!(timing_policy::problems(&section), Vec::<String>::new());
        for claim in section
            .claims
            .iter()
            .filter(|c| c.decided_by == Basis::Timing)
        {
            timing += 1;
            assert_eq!(
                claim.measured.ends_with(timing_policy::SOFTWARE_MARK),
                software,
                "{}: {}",
                section.id,
                claim.measured
            );
        }
    }
    assert!(timing >= 10, "{timing} timing claims");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let said = classic_gpgpu::page::html::escape(timing_policy::IN_WORDS);
    assert_eq!(html.matches(&said).count(), 1, "the policy, said once");
}
