//! Technique 2, artifacts: pixels whose hit is on another surface than the exact one, for
//! the pyramid traversal and relief mapping, against the view's elevation.

use super::images::GRAZING_PNG;
use super::results::Lecture3Results;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

pub fn table(results: &Lecture3Results) -> Table {
    let d = &results.displacement;
    let methods: Vec<String> = d
        .artifacts
        .first()
        .map(|r| r.methods.iter().map(|m| m.method.clone()).collect())
        .unwrap_or_default();
    let mut header = vec![
        "elevation".to_string(),
        "pixels compared".into(),
        "ill-conditioned".into(),
    ];
    header.extend(methods.iter().map(|m| format!("{m}: wrong surface")));
    header.push("pyramid: outside tolerance".into());
    header.push("pyramid: wall / surface, normal, colour wrong".into());
    Table {
        caption: format!(
            "2. Hits on the wrong surface against the exact CPU tracer, {0}x{0} pixels, map {1} \
             ({2}x{3}), azimuth 225 degrees; tolerance: the exact hits of the map raised and \
             lowered by 1e-4; what each pixel shows (surface or wall, normal, colour) judged \
             against the exact hit's too",
            d.image, d.map, d.map_size.0, d.map_size.1
        ),
        header,
        rows: d
            .artifacts
            .iter()
            .map(|r| {
                let first = &r.methods[0].comparison;
                let mut row = vec![
                    format!("{} deg", r.elevation),
                    first.compared.to_string(),
                    first.ambiguous.to_string(),
                ];
                row.extend(
                    r.methods
                        .iter()
                        .map(|m| m.comparison.wrong_surface.to_string()),
                );
                row.push(first.outside_tolerance.to_string());
                row.push(format!(
                    "{} / {} / {}",
                    first.wrong_kind, first.wrong_normal, first.wrong_colour
                ));
                row
            })
            .collect(),
    }
}

pub fn figures(opts: &BenchOptions, results: &Lecture3Results) -> anyhow::Result<Vec<Figure>> {
    let d = &results.displacement;
    let count = d.artifacts.first().map_or(0, |r| r.methods.len());
    let series = (0..count)
        .map(|m| {
            Series::new(
                d.artifacts[0].methods[m].method.clone(),
                d.artifacts
                    .iter()
                    .map(|r| {
                        let c = &r.methods[m].comparison;
                        (
                            r.elevation as f64,
                            100.0 * c.wrong_surface as f64 / c.compared.max(1) as f64,
                        )
                    })
                    .collect(),
            )
        })
        .collect();
    let file = "lecture3_displacement_artifacts.png";
    Plot {
        title: format!(
            "2. Wrong-surface pixels against elevation ({})",
            results.renderer_name
        ),
        x_label: "view elevation (degrees)".into(),
        y_label: "pixels on the wrong surface (% of compared)".into(),
        log_x: false,
        log_y: false,
        series,
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(vec![
        Figure {
            file: file.into(),
            caption: "2. Share of pixels whose hit lies on another surface than the exact one \
                      (or hits where it should miss), against the view's elevation"
                .into(),
        },
        Figure {
            file: GRAZING_PNG.into(),
            caption: "2. At 8 degrees: each method's frame (top) and its verdicts (bottom): \
                      grey exact, red wrong surface, orange outside tolerance, magenta wall \
                      drawn for surface (or the reverse), green wrong normal or colour, blue \
                      ill-conditioned"
                .into(),
        },
    ])
}
