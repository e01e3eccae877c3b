//! The viewer's texel probe, headless: the value it shows under a pixel is the buffer's value
//! read back independently through the library (exact equality: both are the same f32 printed
//! with enough digits to tell any two fp32 apart in the demo's range), and the CPU reference
//! it shows beside it is the module's; every overlay fits the canvas at the default size and
//! a small one.

use classic_gpgpu::lecture3::pyramid::{cpu_pyramid, Extreme, PyramidBuilder};
use classic_gpgpu::lecture3::random_texture::RandomTexture;
use classic_gpgpu::lecture3::HeightMap;
use classic_gpgpu::view::demos::lecture3::Technique;
use classic_gpgpu::view::{headless_frame, overlay, DemoSpec, ViewState};
use common::context;

mod common;

/// Run `technique` headless for `frames` with the probe at `at`; the probe's lines.
fn probe(technique: Technique, frames: usize, size: (u32, u32), at: (u32, u32)) -> Vec<String> {
    let ctx = context();
    let view = ViewState {
        probe: Some(at),
        ..ViewState::default()
    };
    let spec = DemoSpec::Lecture3 { technique };
    headless_frame(&spec, &ctx, size, frames, &view, "")
        .unwrap()
        .1
}

/// (texel x, texel y) and the GPU and CPU values of a readout.
fn parse(lines: &[String]) -> ((u32, u32), f32, Option<f32>) {
    let texel = lines[0]
        .split("texel (")
        .nth(1)
        .unwrap_or_else(|| panic!("no texel in {lines:?}"));
    let (x, y) = texel.trim_end_matches(')').split_once(", ").unwrap();
    let value = |prefix: &str| {
        lines
            .iter()
            .find_map(|l| l.strip_prefix(prefix))
            .map(|v| v.trim().parse::<f32>().unwrap())
    };
    (
        (x.parse().unwrap(), y.parse().unwrap()),
        value("GPU ").expect("a GPU value"),
        value("CPU "),
    )
}

#[test]
fn random_probe_shows_the_number_read_back_from_the_texture() {
    // The demo's generators: 64x64, seed 2007; after 3 frames, the numbers of step 3.
    let lines = probe(Technique::Random, 3, (320, 240), (40, 120));
    let ((x, y), gpu, cpu) = parse(&lines);
    let ctx = context();
    let texture = RandomTexture::new(&ctx, 64, 64, 2007).unwrap();
    for _ in 0..3 {
        texture.step().unwrap();
    }
    let read = texture.values().unwrap()[(y * 64 + x) as usize];
    assert_eq!(gpu, read, "probe {lines:?}");
    assert_eq!(cpu, Some(read), "the CPU generator is bit-exact: {lines:?}");
}

#[test]
fn pyramid_probe_shows_the_level_read_back_and_the_cpu_level() {
    // Over the first panel (level 0 of the max pyramid), near its top-left corner.
    let lines = probe(Technique::Pyramid, 1, (960, 600), (30, 120));
    assert!(lines[0].contains("max level 0"), "{lines:?}");
    let ((x, y), gpu, cpu) = parse(&lines);
    let map = HeightMap::generated(64);
    let ctx = context();
    let read = PyramidBuilder::new(&ctx)
        .unwrap()
        .from_image(64, 64, map.heights(), Extreme::Max)
        .unwrap()
        .read_levels()
        .unwrap();
    assert_eq!(gpu, read[0].at(x, y), "{lines:?}");
    let levels = cpu_pyramid(64, 64, map.heights(), Extreme::Max);
    assert_eq!(cpu, Some(levels[0].at(x, y)), "{lines:?}");
}

#[test]
fn probe_outside_every_buffer_says_so() {
    let lines = probe(Technique::Histogram, 1, (320, 240), (2, 2));
    assert_eq!(lines.len(), 1);
    assert!(lines[0].contains("no buffer"), "{lines:?}");
}

#[test]
fn overlay_lines_fit_the_default_and_a_small_canvas() {
    let lines: Vec<String> = vec![
        "mlp detect assets/mlp/text.png: 512 x 384, 121-30-1 detector".into(),
        "centre of mass GPU (0.000, -0.125, 0.333)  analytic (0.000, -0.125, 0.333)".into(),
    ];
    for (w, h) in [(960, 600), (256, 192), (128, 96)] {
        let (scale, fitted) = overlay::fit(&lines, w, h);
        for l in &fitted {
            assert!(
                l.chars().count() as u32 * 8 * scale + 8 <= w,
                "{l:?} does not fit {w} pixels"
            );
        }
        // Nothing lost by wrapping: the words are all there.
        let words = |v: &[String]| v.join(" ").split_whitespace().count();
        if (w, h) != (128, 96) {
            assert_eq!(words(&fitted), words(&lines), "{fitted:?}");
        }
    }
}

/// A demo whose overlay gains lines while it draws (a figure the frame measures, a line that
/// then wraps): it records where the canvas told it the text ends each time it drew.
struct GrowingText {
    drawn: usize,
    tops: Vec<u32>,
}

impl classic_gpgpu::view::Demo for GrowingText {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }
    fn render(
        &mut self,
        canvas: &classic_gpgpu::view::Canvas,
        _view: &ViewState,
    ) -> anyhow::Result<()> {
        self.drawn += 1;
        let below = canvas.below_text();
        self.tops.push(canvas.height() - below.h);
        Ok(())
    }
    fn buffers(&self) -> Vec<String> {
        vec!["scene".into()]
    }
    fn overlay(&self) -> Vec<String> {
        // Three lines before the first drawing, eight once it has drawn.
        let lines = if self.drawn == 0 { 3 } else { 8 };
        (0..lines).map(|i| format!("line {i}")).collect()
    }
    fn timings(&self) -> String {
        String::new()
    }
}

#[test]
fn text_that_grows_while_a_frame_draws_is_never_drawn_over_the_frame() {
    let ctx = context();
    let canvas = classic_gpgpu::view::Canvas::new(&ctx, 960, 600).unwrap();
    let mut demo = GrowingText {
        drawn: 0,
        tops: Vec::new(),
    };
    let view = ViewState::default();
    classic_gpgpu::view::draw_frame(&mut demo, &canvas, &view, 1).unwrap();
    // Drawn again below the taller text: the last drawing's top is the final text's height.
    assert_eq!(demo.drawn, 2, "drawn {} times", demo.drawn);
    let mut lines = vec!["frame 1  [tab] scene  [h] help".to_string()];
    lines.extend(classic_gpgpu::view::Demo::overlay(&demo));
    let text = overlay::text_height(&lines, 960, 600);
    let last_top = *demo.tops.last().unwrap();
    assert!(
        last_top >= text,
        "text {text} px tall, the frame drawn from {last_top} px: {:?}",
        demo.tops
    );
}
