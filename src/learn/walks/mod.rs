//! The papers walked pass by pass (issue 39, item 6): one guide page per paper and per lecture,
//! made from a small run at guide time. Each pass, in the order the paper runs them, shows the
//! paper's section and step, the code that runs it (cut out of the files by named regions,
//! [`super::regions`]), the buffer it wrote (the whole picture, its key beside it) and the
//! lesson it builds on.
//!
//! A walk is a list ([`Walk::steps`]) and a small run ([`Walk::run`]) that gives one
//! [`Shot`] per step. The lists name regions only; a test asks for every one of them.

pub mod lecture1;
pub mod lecture3;
pub mod paper1;
pub mod paper2;
pub mod paper3;
pub mod paper4;

use super::regions;
use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::page::html::{escape, STYLE};
use std::path::{Path, PathBuf};

/// One pass of a walk, as the paper names it and as the code runs it.
#[derive(Clone, Copy, Debug)]
pub struct Step {
    /// The pass, short ("streaming AABB overlap test").
    pub pass: &'static str,
    /// Where the paper describes it ("Sec. 5.2, step 2").
    pub section: &'static str,
    /// The step in the paper's words.
    pub step: &'static str,
    /// What the pass reads and what it writes, a sentence each.
    pub reads: &'static str,
    pub writes: &'static str,
    /// The code: (file, region) pairs, host code first, then its shader.
    pub code: &'static [(&'static str, &'static str)],
    /// The id of the lesson this pass builds on ([`crate::learn::all`]).
    pub lesson: &'static str,
}

/// What one step of the small run left: its pictures (relative to the walk's picture folder),
/// the key of their colours in words, and the CPU check made on it, if any.
#[derive(Clone, Debug, Default)]
pub struct Shot {
    pub pictures: Vec<String>,
    pub key: String,
    pub check: Option<Check>,
}

/// A comparison of a pass's output with the CPU, made in the walk's run.
#[derive(Clone, Debug)]
pub struct Check {
    pub what: String,
    pub passed: bool,
}

/// A paper or lecture walked pass by pass.
pub struct Walk {
    /// The page is `walk-<id>.html`; pictures go to `pictures/walks/<id>/`.
    pub id: &'static str,
    pub title: &'static str,
    /// The source, cited.
    pub source: &'static str,
    /// What the small run is, a sentence.
    pub run_is: &'static str,
    pub steps: &'static [Step],
    /// Run the small case, writing each step's pictures into the folder given; one shot per
    /// step, in order.
    pub run: fn(&Context, &Path) -> anyhow::Result<Vec<Shot>>,
}

/// Every walk, in the guide's order: the papers, then the lectures.
pub fn all() -> [&'static Walk; 6] {
    [
        &paper1::WALK,
        &paper2::WALK,
        &paper3::WALK,
        &paper4::WALK,
        &lecture1::WALK,
        &lecture3::WALK,
    ]
}

/// The file of a walk's page.
pub fn page_file(id: &str) -> String {
    format!("walk-{id}.html")
}

/// The width pictures are drawn at, at least: from 640 pixels the picture's text is 16
/// pixels high ([`crate::gl::picture::glyph_for`]), and the page shows pictures at their own
/// size (scrolling sideways when wider than the page), so a key's numbers stay legible.
pub const PICTURE_WIDTH: u32 = 720;

/// Run every walk on `ctx` and write its page into `staging`, its pictures under
/// `staging/pictures/walks/<id>/`; returns the pages' names. A walk that cannot run here
/// still gets its page, saying why.
pub fn write_pages(ctx: &Context, staging: &Path) -> anyhow::Result<Vec<String>> {
    let mut names = Vec::new();
    for walk in all() {
        let dir = staging.join("pictures").join("walks").join(walk.id);
        let shots = (walk.run)(ctx, &dir).map_err(|e| format!("{e:#}"));
        let html = page(walk, &ctx.info().renderer_line(), &shots)?;
        let name = page_file(walk.id);
        crate::files::write_bytes(&staging.join(&name), html.as_bytes())?;
        names.push(name);
    }
    Ok(names)
}

/// The regions every walk names, as (file, region) pairs.
pub fn regions_named() -> Vec<(&'static str, &'static str)> {
    all()
        .iter()
        .flat_map(|w| w.steps.iter().flat_map(|s| s.code.iter().copied()))
        .collect()
}

const WALK_STYLE: &str = "nav a{margin-right:1.5em}.step{border-top:1px solid #ccd;\
margin-top:1.5em}.meta td{padding:.1em .8em .1em 0;vertical-align:top}pre{background:#f6f6f6;\
padding:.6em;overflow-x:auto;font-size:90%}.where{color:#555;font-size:90%;margin:.8em 0 .2em}\
.shots{overflow-x:auto}.shots img{max-width:none;image-rendering:pixelated;display:block;\
margin:.4em 0}.key{font-size:100%;margin:.2em 0 .8em}.pass{color:#070}.fail{color:#b00}\
code{background:#f2f2f2;padding:0 .2em}";

/// The page of `walk`, from its run's `shots` (or the reason it did not run).
fn page(walk: &Walk, renderer: &str, shots: &Result<Vec<Shot>, String>) -> anyhow::Result<String> {
    let mut body = format!(
        "<h1>{}</h1>\n<p>{}</p>\n<p>Every pass below, in the order it runs, with the code that \
         runs it (cut from the files when this guide was made), the buffer it wrote in a small \
         run ({}) on <b>{}</b>, and the lesson it builds on. Each picture opens at full size.</p>\n",
        escape(walk.title),
        escape(walk.source),
        escape(walk.run_is),
        escape(renderer)
    );
    if let Err(e) = shots {
        body.push_str(&format!(
            "<p class=\"fail\">The small run did not run here: {}</p>\n",
            escape(e)
        ));
    }
    body.push_str("<ol>\n");
    for (k, step) in walk.steps.iter().enumerate() {
        body.push_str(&format!(
            "<li><a href=\"#pass-{}\">{}</a></li>\n",
            k + 1,
            escape(step.pass)
        ));
    }
    body.push_str("</ol>\n");
    for (k, step) in walk.steps.iter().enumerate() {
        let shot = shots.as_ref().ok().and_then(|s| s.get(k));
        body.push_str(&step_html(walk, k, step, shot)?);
    }
    body.push_str("<p><a href=\"reading.html\">&larr; the reading order</a></p>\n");
    Ok(format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}\
         {WALK_STYLE}</style></head><body>\n<nav><a href=\"index.html\">Lessons</a> \
         <a href=\"reading.html\">Reading order</a> <a href=\"glossary.html\">Glossary</a></nav>\n\
         {body}</body></html>\n",
        escape(walk.title)
    ))
}

fn step_html(walk: &Walk, k: usize, step: &Step, shot: Option<&Shot>) -> anyhow::Result<String> {
    let lesson = crate::learn::find(step.lesson)?.info();
    let mut out = format!(
        "<div class=\"step\" id=\"pass-{}\"><h2>{}. {}</h2>\n<table class=\"meta\">\
         <tr><td>paper</td><td>{}: \u{201c}{}\u{201d}</td></tr>\
         <tr><td>reads</td><td>{}</td></tr><tr><td>writes</td><td>{}</td></tr>\
         <tr><td>builds on</td><td><a href=\"lesson-{}.html\">lesson {}: {}</a></td></tr>\
         </table>\n",
        k + 1,
        k + 1,
        escape(step.pass),
        escape(step.section),
        escape(step.step),
        escape(step.reads),
        escape(step.writes),
        lesson.id,
        lesson.number,
        escape(lesson.title)
    );
    for (file, name) in step.code {
        let region = regions::cut(file, name).map_err(anyhow::Error::msg)?;
        out.push_str(&format!(
            "<p class=\"where\"><code>{}</code>, from line {} (region <code>{}</code>)</p>\n\
             <pre><code>{}</code></pre>\n",
            escape(region.file),
            region.first_line,
            escape(name),
            escape(&region.text)
        ));
    }
    match shot {
        Some(shot) if !shot.pictures.is_empty() => {
            out.push_str("<div class=\"shots\">");
            for picture in &shot.pictures {
                let src = format!("pictures/walks/{}/{}", walk.id, picture);
                out.push_str(&format!(
                    "<a href=\"{0}\"><img src=\"{0}\" alt=\"{1}: {2}\"></a>",
                    escape(&src),
                    escape(step.pass),
                    escape(picture)
                ));
            }
            out.push_str("</div>\n");
            out.push_str(&format!(
                "<p class=\"key\">Key: {}</p>\n",
                escape(&shot.key)
            ));
            if let Some(check) = &shot.check {
                out.push_str(&format!(
                    "<p>Checked against the CPU: {} (<span class=\"{}\">{}</span>)</p>\n",
                    escape(&check.what),
                    if check.passed { "pass" } else { "fail" },
                    if check.passed { "agrees" } else { "DISAGREES" }
                ));
            }
        }
        _ => out
            .push_str("<p class=\"fail\">No picture: the small run did not reach this pass.</p>\n"),
    }
    out.push_str("</div>\n");
    Ok(out)
}

/// One float buffer as a picture `file` in `dir`: one panel per named channel of
/// `channels`-component texels, each on its own scale with its colour key, at least
/// [`PICTURE_WIDTH`] wide and whole texels (the dump's rules, [`crate::gl::dump`]).
pub fn buffer_png(
    dir: &Path,
    file: &str,
    title: &str,
    texels: &[f32],
    channels: usize,
    names: &[&str],
    dims: (u32, u32),
) -> anyhow::Result<String> {
    let panels: Vec<Panel> = names
        .iter()
        .enumerate()
        .map(|(c, name)| {
            let panel = Panel::channel(
                format!("{title} {name}"),
                texels,
                channels,
                c,
                dims,
                Scale::fixed(0.0, 0.0),
            );
            Panel {
                scale: Scale::of([panel.values.as_slice()]),
                ..panel
            }
        })
        .collect();
    panels_png(dir, file, &panels)
}

/// `panels` as one picture `file` in `dir`, at least [`PICTURE_WIDTH`] wide.
pub fn panels_png(dir: &Path, file: &str, panels: &[Panel]) -> anyhow::Result<String> {
    let columns = panels.len().clamp(1, 3) as u32;
    let rows = panels.len().div_ceil(columns as usize).max(1) as u32;
    let cell = PICTURE_WIDTH / columns;
    let path: PathBuf = dir.join(file);
    crate::gl::dump::picture_png(panels, (PICTURE_WIDTH, rows * (cell + 90)), &path)?;
    Ok(file.to_string())
}
