//! The papers walked pass by pass (issue 39, item 6): paper 1's AABB overlap pass against the
//! CPU on data the test makes, every region a walk names, and the six walk pages with a code
//! block and a picture for every pass.

mod common;

use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::learn::regions;
use classic_gpgpu::learn::walks::{self, paper1};
use std::path::Path;

/// The streaming AABB overlap pass (paper 1, Sec. 5.2, Table I) writes into `P0` exactly the
/// CPU's interval test of the slot boxes under the stencil arrays. Tolerance: none, since `P0`
/// holds 0 or 1 and the boxes are min/max of the same f32 vertices on both sides. Random
/// triangle soups of 150 and 90 triangles, 4 per leaf: streams with virtual slots (so the
/// stencil masks pairs), CAPs and pairs apart alike.
#[test]
fn the_aabb_overlap_pass_matches_the_cpu_interval_test() {
    let ctx = common::context();
    let mut masked = 0;
    for (seed, (nx, ny), size) in [(1, (150, 90), 0.15), (2, (40, 200), 0.3)] {
        let x = common::soup(nx, size, seed);
        let y = common::soup(ny, size, seed + 100);
        let options = Options {
            leaf_size: 4,
            readback: ReadbackMode::Hierarchical,
            ..Options::default()
        };
        let mut collider = StreamingCollider::new(&ctx, &x, &y, options).unwrap();
        collider.frame(&x.positions, &y.positions).unwrap();
        let gpu = collider.target.p0.download_f32().unwrap();

        // The CPU's side, from the test's own meshes.
        let (sx, sy) = (&collider.x.stream, &collider.y.stream);
        masked += sx.virtual_slots() + sy.virtual_slots();
        let cpu = paper1::cpu_overlaps(
            &sx.slot_boxes(&x.positions),
            &sx.stencil,
            &sy.slot_boxes(&y.positions),
            &sy.stencil,
        );
        assert_eq!(
            gpu.len(),
            sx.len() * sy.len(),
            "P0 is slots of X by slots of Y"
        );
        let caps = cpu.iter().filter(|&&v| v == 1.0).count();
        assert!(
            caps > 0 && caps < cpu.len() / 2,
            "seed {seed}: {caps} CAPs of {}: not a telling case",
            cpu.len()
        );
        let wrong = paper1::p0_differences(&gpu, &cpu);
        assert!(
            wrong.is_empty(),
            "seed {seed}: {} of {} texels of P0 differ from the CPU, first at index {:?}",
            wrong.len(),
            cpu.len(),
            wrong.first()
        );
        // The comparison sees a wrong texel.
        let mut broken = cpu.clone();
        broken[0] = 1.0 - broken[0];
        assert_eq!(paper1::p0_differences(&gpu, &broken), vec![0]);
    }
    assert!(masked > 0, "no virtual slot: the stencil masked nothing");
}

/// Every (file, region) a walk names is in the file and holds code, and every lesson it
/// builds on exists.
#[test]
fn every_region_and_lesson_a_walk_names_exists() {
    let named = walks::regions_named();
    assert!(named.len() >= 20, "only {} regions", named.len());
    for (file, name) in named {
        let region = regions::cut(file, name).unwrap_or_else(|e| panic!("{e}"));
        assert!(!region.text.trim().is_empty(), "{file}: {name} is empty");
    }
    for walk in walks::all() {
        assert!(!walk.steps.is_empty(), "{}", walk.id);
        for step in walk.steps {
            assert!(!step.code.is_empty(), "{}: {}", walk.id, step.pass);
            classic_gpgpu::learn::find(step.lesson).unwrap();
        }
    }
}

/// The walks' pages: six, each with its passes in order, a code block and at least one
/// picture per pass, every picture a file linked to itself (it opens at full size), and
/// every CPU check of the small runs agreeing.
#[test]
fn the_six_walk_pages_have_code_and_a_picture_per_pass() {
    let ctx = common::context();
    let dir = common::temp_dir("guide-walks", "pages");
    let pages = walks::write_pages(&ctx, &dir).unwrap();
    assert_eq!(pages.len(), 6);
    for walk in walks::all() {
        let name = walks::page_file(walk.id);
        assert!(pages.contains(&name), "{name}");
        let html = std::fs::read_to_string(dir.join(&name)).unwrap();
        assert!(
            !html.contains("did not run"),
            "{name}: the small run failed"
        );
        assert!(
            !html.contains("No picture"),
            "{name}: a pass without a picture"
        );
        assert!(!html.contains("DISAGREES"), "{name}: a CPU check failed");
        let steps: Vec<&str> = html.split("<div class=\"step\"").skip(1).collect();
        assert_eq!(steps.len(), walk.steps.len(), "{name}");
        for (step, listed) in steps.iter().zip(walk.steps) {
            assert!(
                step.contains(&escape(listed.pass)),
                "{name}: {}",
                listed.pass
            );
            assert!(
                step.contains("<pre><code>"),
                "{name}: {} has no code",
                listed.pass
            );
            assert!(
                step.contains("lesson-"),
                "{name}: {} names no lesson",
                listed.pass
            );
            let pictures = pictures_in(step);
            assert!(
                !pictures.is_empty(),
                "{name}: {} has no picture",
                listed.pass
            );
            for src in pictures {
                assert!(
                    step.contains(&format!("<a href=\"{src}\"><img src=\"{src}\"")),
                    "{name}: {src} does not open at full size"
                );
                assert_picture(&dir, &src);
            }
        }
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The `src` of every `<img>` in `html`.
fn pictures_in(html: &str) -> Vec<String> {
    html.split("<img src=\"")
        .skip(1)
        .map(|rest| rest.split('"').next().unwrap().to_string())
        .collect()
}

/// The picture exists, decodes, and is wide enough for its key's text to be 16 pixels high
/// (`gl::picture::glyph_for`), unless it is a rendered frame (no key in it).
fn assert_picture(dir: &Path, src: &str) {
    let path = dir.join(src);
    let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let frame = src.ends_with("frame.png");
    assert!(
        frame || image.width() >= 640,
        "{src}: {} pixels wide, its key would be drawn in 8-pixel text",
        image.width()
    );
}

/// Item 7 on the lesson pages: every buffer picture a lesson writes is drawn at least 640
/// pixels wide, so its key's numbers are 16 pixels high where the guide shows it at its own
/// size.
#[test]
fn lesson_pictures_are_wide_enough_for_legible_keys() {
    let ctx = common::context();
    let dir = common::temp_dir("guide-walks", "lesson-pictures");
    for id in ["texture-is-array", "reduction"] {
        let lesson = classic_gpgpu::learn::find(id).unwrap();
        let opts = classic_gpgpu::learn::LessonOptions {
            png_dir: Some(dir.join(id)),
            exercise: None,
        };
        std::fs::create_dir_all(dir.join(id)).unwrap();
        let run = lesson.run(&ctx, &opts).unwrap();
        let pictures: Vec<&String> = run
            .passes
            .iter()
            .filter_map(|p| p.picture.as_ref())
            .collect();
        assert!(!pictures.is_empty(), "{id}: no picture");
        for picture in pictures {
            let image = image::open(dir.join(id).join(picture)).unwrap();
            assert!(
                image.width() >= 640,
                "{id}: {picture} is {} wide",
                image.width()
            );
        }
    }
}
