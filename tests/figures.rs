//! Every figure of a quick report can be read without the code: each listed figure is a PNG in
//! the report's folder and carries what its drawing code recorded
//! (`results.json`'s `drawn`): a plot has a title, axis titles, at least two labelled ticks on
//! each axis and a legend entry per curve; a picture of float buffers has a title and a colour
//! key per panel, whole-texel enlargement and titles of at most three lines; rendered frames
//! side by side are each titled. `Drawn::problems` names what is missing. Set
//! `CLASSIC_GPGPU_KEEP_FIGURES` to keep the report (its folder is printed) and look at it.

use classic_gpgpu::gl::drawn::Drawn;
use std::path::PathBuf;
use std::process::Command;

#[test]
fn every_figure_of_a_quick_report_is_readable() {
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
    let results: serde_json::Value = serde_json::from_str(&text).unwrap();
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
            match serde_json::from_value::<Drawn>(section["drawn"][&file].clone()) {
                Ok(drawn) => {
                    match drawn {
                        Drawn::Plot(_) => plots += 1,
                        Drawn::Picture(_) | Drawn::Frames(_) => pictures += 1,
                        _ => {}
                    }
                    for p in drawn.problems() {
                        problems.push(format!("{id}/{file}: {p}"));
                    }
                }
                Err(_) => problems.push(format!(
                    "{id}/{file}: its drawing code recorded nothing of what it shows"
                )),
            }
            if !out.join(&file).is_file() {
                problems.push(format!("{id}/{file}: listed but not written"));
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
    if std::env::var_os("CLASSIC_GPGPU_KEEP_FIGURES").is_none() {
        std::fs::remove_dir_all(&out).ok();
    }
}
