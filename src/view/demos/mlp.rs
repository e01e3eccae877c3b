//! Paper 3 live: text detection by a multilayer perceptron run as render passes, the detected
//! text pixels overlaid on the image in red, the threshold adjustable with `+` and `-`
//! [Oh & Jung 2004, Sec. 4, Fig. 2]. The network runs once, when the demo starts (the image
//! does not change); each step leaves it as it is.

use crate::gl::picture::{fixed, Panel, Scale};
use crate::gl::Context;
use crate::mlp::chain::{Formulation, GpuMlp, StepTimes};
use crate::mlp::cpu::CpuProduct;
use crate::mlp::detect::{classify_cpu, classify_gpu, shipped_detector, THRESHOLD};
use crate::view::inset::{self, Probed, Shown};
use crate::view::{Canvas, Demo, ViewState};
use anyhow::Context as _;
use image::GrayImage;
use std::path::Path;

pub struct MlpDemo {
    name: String,
    image: GrayImage,
    outputs: Vec<f32>,
    /// The CPU forward pass's outputs (the probe's reference).
    cpu_outputs: Vec<f32>,
    times: StepTimes,
    /// The threshold in hundredths (keys step it by 5).
    threshold: i32,
}

/// The largest image the viewer classifies (pixels): each is 121 inputs through the network.
const MAX_PIXELS: u64 = 1 << 20;

impl MlpDemo {
    pub fn new(ctx: &Context, path: &Path) -> anyhow::Result<Self> {
        let image = crate::files::read_image(path, "image")?.to_luma8();
        let pixels = image.width() as u64 * image.height() as u64;
        if pixels == 0 || pixels > MAX_PIXELS {
            anyhow::bail!(
                "{}: {} x {} pixels; the viewer takes images of 1 to {MAX_PIXELS} pixels",
                path.display(),
                image.width(),
                image.height()
            );
        }
        let net = shipped_detector().context("the shipped detector")?;
        let gpu = GpuMlp::new(ctx)?;
        let loaded = gpu.load(&net, Formulation::Faithful)?;
        let classified = classify_gpu(&loaded, &image, 1 << 18, None)?;
        crate::gl::ensure_finite(
            classified.outputs.iter().copied(),
            "the detector's outputs",
            "mlp detect (viewer)",
        )?;
        let cpu_outputs = classify_cpu(&net, &image, CpuProduct::Optimised, 1 << 18).outputs;
        Ok(MlpDemo {
            name: path.display().to_string(),
            image,
            outputs: classified.outputs,
            cpu_outputs,
            times: classified.times,
            threshold: (THRESHOLD * 100.0).round() as i32,
        })
    }

    fn threshold(&self) -> f32 {
        self.threshold as f32 / 100.0
    }

    /// RGBA rows from the bottom: the image grey, text pixels tinted red (buffer 0), the raw
    /// network output as grey (1), or the black-on-white mask `mlp detect --out` writes (2).
    fn picture(&self, shown: usize) -> Vec<u8> {
        let (w, h) = self.image.dimensions();
        let t = self.threshold();
        let mut out = Vec::with_capacity((w * h * 4) as usize);
        for y in (0..h).rev() {
            for x in 0..w {
                let grey = self.image.get_pixel(x, y).0[0];
                let output = self.outputs[(y * w + x) as usize];
                let text = output > t;
                let px = match shown {
                    1 => {
                        let v = (output.clamp(0.0, 1.0) * 255.0).round() as u8;
                        [v, v, v]
                    }
                    2 => {
                        let v = if text { 0 } else { 255 };
                        [v, v, v]
                    }
                    _ if text => [255, grey / 3, grey / 3],
                    _ => [grey, grey, grey],
                };
                out.extend_from_slice(&[px[0], px[1], px[2], 255]);
            }
        }
        out
    }
}

impl Demo for MlpDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.1, 0.1, 0.12, 1.0])?;
        let shown = view.shown % 3;
        let rect = canvas.below_text();
        // Rows from the bottom, as the probe and the pictures count them.
        let (w, h) = self.image.dimensions();
        let from_bottom = |v: &[f32]| -> Vec<f32> {
            v.chunks_exact(w as usize)
                .rev()
                .flatten()
                .copied()
                .collect()
        };
        let (gpu, cpu) = (from_bottom(&self.outputs), from_bottom(&self.cpu_outputs));
        if shown == 1 {
            let panel = Panel {
                title: "network output (0: background, 1: text)".into(),
                values: gpu,
                width: w,
                height: h,
                scale: Scale::fixed(0.0, 1.0),
            };
            let shown = Shown {
                panel,
                probe_values: None,
                reference: Some(cpu),
            };
            return Ok(inset::draw_picture(canvas, vec![shown], rect)?);
        }
        let placed = inset::draw_rgba(canvas, &self.picture(shown), (w, h), rect, "")?;
        if let Some(placement) = placed {
            canvas.add_probed(Probed {
                name: "network output".into(),
                placement,
                values: gpu,
                reference: Some(cpu),
            });
        }
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec![
            "image + text pixels".into(),
            "network output".into(),
            "mask".into(),
        ]
    }

    fn overlay(&self) -> Vec<String> {
        let t = self.threshold();
        let text = self.outputs.iter().filter(|&&v| v > t).count();
        vec![
            format!(
                "mlp detect {}: {} x {}, 121-30-1 detector",
                self.name,
                self.image.width(),
                self.image.height()
            ),
            format!(
                "threshold {t:.2} [+/-]: {text} text pixels ({}%)",
                fixed(100.0 * text as f64 / self.outputs.len() as f64, 1)
            ),
        ]
    }

    fn timings(&self) -> String {
        let t = &self.times;
        format!(
            "textures {:.1} matmul {:.1} sigmoid {:.1} readback {:.1} ms (once)",
            t.texture_creation, t.matmul, t.activation, t.readback
        )
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        vec![("+", "threshold up 0.05"), ("-", "threshold down 0.05")]
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        match key {
            "+" | "=" => self.threshold = (self.threshold + 5).min(100),
            "-" => self.threshold = (self.threshold - 5).max(0),
            _ => return Ok(false),
        }
        Ok(true)
    }
}
