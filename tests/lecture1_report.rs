//! Lecture 1's report section (`reproduce --quick --only lecture1`): every self-collision
//! frame and every triangle count agrees with brute force, the figures are PNG files, the
//! tables are there (by triangle count, two models, then and now), the page says which parts
//! are reconstructions; on a context without OpenGL 4.3 the compute columns say why they are
//! empty.

use common::classic_gpgpu;

mod common;

#[test]
fn the_quick_section_agrees_with_brute_force_and_writes_its_figures() {
    let (ctx, has_compute) = common::compute_context();
    drop(ctx);
    let out_dir = std::env::temp_dir().join(format!("l1-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out_dir);
    let out = classic_gpgpu(&[
        "reproduce",
        "--quick",
        "--only",
        "lecture1",
        "--runs",
        "1",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(out_dir.join("results.json")).unwrap();
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let section = &report["sections"][0];
    assert_eq!(section["id"], "lecture1");
    let blocks = section["results"]["blocks"].as_array().unwrap();
    let block = |id: &str| {
        blocks
            .iter()
            .find(|b| b["id"] == id)
            .unwrap_or_else(|| panic!("no block {id}"))
    };
    // Self-collision: every frame of the three scenes equal to brute force, with pairs found.
    let scenes = block("self-collision")["results"].as_array().unwrap();
    assert_eq!(scenes.len(), 3);
    let mut pairs = 0;
    for scene in scenes {
        for frame in scene["frames"].as_array().unwrap() {
            assert_eq!(frame["equal"], true, "{scene}");
            assert_eq!(frame["gpu_pairs"], frame["cpu_pairs"]);
            pairs += frame["cpu_pairs"].as_u64().unwrap();
        }
    }
    assert!(pairs > 0);
    // Pairwise: every count agrees; the compute column ran exactly where 4.3 is available.
    let pairwise = &block("pairwise")["results"];
    for row in pairwise["by_count"].as_array().unwrap() {
        assert_eq!(row["all_equal"], true, "{row}");
        assert_eq!(row["compute_ms"].is_null(), !has_compute, "{row}");
    }
    let two = &pairwise["two_models"];
    assert!(two["pairs"].as_u64().unwrap() > 0, "{two}");
    assert_eq!(two["pairwise_equal"], true);
    assert_eq!(two["streaming_equal"], true);
    assert_eq!(pairwise["compute_unavailable"].is_null(), has_compute);
    let then_and_now = &block("then-and-now")["results"];
    if has_compute {
        assert_eq!(then_and_now["same_answer"], true, "{then_and_now}");
    } else {
        let why = then_and_now["unavailable"].as_str().unwrap();
        assert!(why.contains("needs OpenGL 4.3"), "{why}");
    }
    // Figures on disk, tables and the reconstruction wording on the page.
    // Self-collision's three scenes, pairwise's buffers and plot, and one figure each for
    // the distance field, the swept volume and penetration depth.
    let figures = section["figures"].as_array().unwrap();
    assert_eq!(figures.len(), 8);
    for figure in figures {
        let file = out_dir.join(figure["file"].as_str().unwrap());
        let image = image::open(&file).unwrap();
        assert!(image.width() > 100, "{}", file.display());
    }
    let tables: Vec<&str> = section["tables"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["caption"].as_str().unwrap())
        .collect();
    assert_eq!(tables.len(), 10, "{tables:?}");
    for start in [
        "Where each wins",
        "Then and now",
        "Distance field",
        "Swept volume",
        "Penetration depth",
        "Continuous collision for an avatar (a reconstruction)",
        "Continuous collision for an avatar: the reported time",
        "Not built: what the sources of lecture 1 name",
    ] {
        assert!(
            tables.iter().any(|c| c.starts_with(start)),
            "{start}: {tables:?}"
        );
    }
    // The summary names the checks the run made, and only those (run_section fails the
    // section otherwise); every path the run took has a fidelity row.
    let strings = |v: &serde_json::Value| {
        let mut v: Vec<String> = v
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s.as_str().unwrap().to_string())
            .collect();
        v.sort();
        v
    };
    let listed = strings(&section["checks_listed"]);
    assert_eq!(listed, strings(&section["checks_made"]));
    assert_eq!(
        listed.len(),
        ::classic_gpgpu::report::lecture1::listed_checks(has_compute).len()
    );
    let summary = section["summary"].as_str().unwrap();
    for check in ::classic_gpgpu::report::lecture1::listed_checks(has_compute) {
        assert!(summary.contains(check.says), "{summary}");
    }
    let covered: Vec<&str> = section["fidelity"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r["paths"].as_array().cloned().unwrap_or_default())
        .map(|p| p.as_str().unwrap().to_string().leak() as &str)
        .collect();
    for path in strings(&section["paths"]) {
        assert!(covered.contains(&path.as_str()), "{path}");
    }
    assert!(summary.contains("parry3d"), "{summary}");
    let page = std::fs::read_to_string(out_dir.join("index.html")).unwrap();
    assert!(page.contains("reconstruction"));
    std::fs::remove_dir_all(&out_dir).ok();
}
