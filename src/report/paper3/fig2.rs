//! Fig. 2: the test image and its classification (black = text), with how many pixels each
//! evaluation calls text and how often the GPU agrees with the CPU.

use super::bench::{DetectionRun, Paper3Results};
use super::fig2_files::{FIG2A_FILE, FIG2B_FILE};
use super::table1::ms;
use crate::report::{Figure, Table};

pub fn table(results: &Paper3Results) -> Table {
    let d = &results.detection;
    let share = |count: usize| format!("{:.2}%", 100.0 * count as f64 / d.pixels() as f64);
    let gpu_row = |name: &str, run: &DetectionRun| {
        vec![
            name.to_string(),
            share(run.text_pixels),
            format!("{:.4}%", 100.0 * run.agreement_with_cpu),
            ms(run.times_ms.total()),
        ]
    };
    Table {
        caption: format!(
            "Fig. 2: text detection on text.png ({} x {} = {} pixels, one batch; GPU ms: \
             median of {} runs; {})",
            d.width,
            d.height,
            d.pixels(),
            d.faithful.runs.max(d.packed.runs),
            results.renderer
        ),
        header: ["evaluated by", "text pixels", "same class as CPU", "GPU ms"]
            .map(String::from)
            .to_vec(),
        rows: vec![
            gpu_row("Faithful", &d.faithful),
            gpu_row("Packed", &d.packed),
            vec![
                "CPU (sgemm)".into(),
                share(d.cpu_text_pixels),
                "100%".into(),
                "-".into(),
            ],
        ],
    }
}

pub fn figures() -> Vec<Figure> {
    vec![
        Figure {
            file: FIG2A_FILE.into(),
            caption: "Fig. 2(a): the test image (scikit-image text.png, public domain)".into(),
        },
        Figure {
            file: FIG2B_FILE.into(),
            caption: "Fig. 2(b): every pixel classified by the MLP on the GPU in one batch \
                      (black = text)"
                .into(),
        },
    ]
}
