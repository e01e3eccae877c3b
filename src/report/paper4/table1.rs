//! Table 1: the test objects, their sizes and depth peels, beside the paper's.

use super::bench::Paper4Results;
use crate::report::published;
use crate::report::Table;

pub fn table(results: &Paper4Results, paper: &published::Paper4) -> Table {
    let mut table = Table {
        caption: "Table 1: test objects (paper beside ours; peels = depth layers under the view \
                  down -z, which depend on orientation and resolution; turned = rotated 90 \
                  degrees about x, at 32x32)"
            .into(),
        header: [
            "object",
            "vertices",
            "paper",
            "faces",
            "paper",
            "peels (32x32)",
            "peels (finest)",
            "peels (turned)",
            "paper",
            "closed",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for o in &results.objects {
        let published = paper.object(&o.object);
        let cell = |f: fn(&published::Paper4Object) -> u32| {
            published.map_or("-".to_string(), |p| f(p).to_string())
        };
        let peels_at_32 = o
            .resolutions
            .iter()
            .find(|r| r.resolution == 32)
            .map_or(0, |r| r.peels);
        table.rows.push(vec![
            o.object.clone(),
            o.vertices.to_string(),
            cell(|p| p.vertices),
            o.faces.to_string(),
            cell(|p| p.faces),
            peels_at_32.to_string(),
            o.resolutions
                .last()
                .map(|r| format!("{} ({}x{})", r.peels, r.resolution, r.resolution))
                .unwrap_or_default(),
            o.peels_turned_90_about_x.to_string(),
            cell(|p| p.peels),
            if o.closed {
                "yes".into()
            } else {
                "no (analytic unreliable)".into()
            },
        ]);
    }
    table
}
