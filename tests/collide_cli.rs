//! The `collide`, `collide-scene` and `collide-bench` commands as a user meets them.

use classic_gpgpu::collide::brute_force::all_pairs;
use classic_gpgpu::collide::Predicate;
use classic_gpgpu::mesh;
use common::{classic_gpgpu, json_of};
use glam::{Affine3A, Quat, Vec3};

mod common;

#[test]
fn collide_json_lists_exactly_the_brute_force_pairs_and_dumps_fig6() {
    let dir = common::temp_dir("collide-cli", "pairs");
    let a = mesh::torus_with_triangles(1.0, 0.33, 500);
    let b = a.transformed(&Affine3A::from_rotation_translation(
        Quat::from_rotation_x(1.4),
        Vec3::new(1.5, 0.1, 0.0),
    ));
    let (pa, pb) = (dir.join("a.obj"), dir.join("b.obj"));
    mesh::write_obj(&a, &pa).unwrap();
    mesh::write_obj(&b, &pb).unwrap();
    // The reference reads the same files, so face order and coordinates are the CLI's.
    let (la, lb) = (mesh::load_obj(&pa).unwrap(), mesh::load_obj(&pb).unwrap());
    let expected = all_pairs(&la, &la.positions, &lb, &lb.positions, Predicate::Exact);
    assert!(!expected.is_empty());
    let dump = dir.join("dump");
    for readback in ["hierarchical", "reduced", "full", "auto"] {
        let v = json_of(&[
            "collide",
            pa.to_str().unwrap(),
            pb.to_str().unwrap(),
            "--readback",
            readback,
            "--predicate",
            "exact",
            "--leaf-size",
            "6",
            "--dump",
            dump.to_str().unwrap(),
            "--json",
        ]);
        let pairs: Vec<(u32, u32)> = v["pairs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| (p[0].as_u64().unwrap() as u32, p[1].as_u64().unwrap() as u32))
            .collect();
        assert_eq!(pairs, expected, "{readback}");
        assert_eq!(v["ctps"].as_u64().unwrap() as usize, expected.len());
        assert_eq!(
            v["triangles"][0].as_u64().unwrap() as usize,
            la.triangles.len()
        );
        assert!(v["renderer"].as_str().is_some_and(|r| !r.is_empty()));
        assert!(v["readback"]["bytes"].as_u64().unwrap() > 0);
        for key in [
            "overlap", "readback", "tri_test", "download", "update", "total",
        ] {
            assert!(v["timings_ms"][key].as_f64().is_some(), "{key}");
        }
    }
    for png in [
        "P0.png",
        "P1.png",
        "P2.png",
        "P3.png",
        "P1_reduced.png",
        "T_min_X_0.png",
    ] {
        assert!(dump.join(png).is_file(), "{png} not written");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_inputs_fail_with_a_message_naming_them() {
    let dir = common::temp_dir("collide-cli", "bad");
    let empty = dir.join("empty.obj");
    std::fs::write(&empty, "# nothing\n").unwrap();
    let good = dir.join("good.obj");
    mesh::write_obj(&mesh::cube(1.0), &good).unwrap();
    let missing = dir.join("missing.obj");
    let cases: [(&std::path::Path, &str); 2] = [(&missing, "missing.obj"), (&empty, "empty.obj")];
    for (path, name) in cases {
        let out = classic_gpgpu(&["collide", path.to_str().unwrap(), good.to_str().unwrap()]);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(name), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let out = classic_gpgpu(&["collide-scene", "teapots"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("interlocking-tori"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn collide_scene_and_bench_print_json() {
    let v = json_of(&[
        "collide-scene",
        "touching-tori",
        "--frames",
        "2",
        "--triangles",
        "800",
        "--json",
    ]);
    assert_eq!(v["frames"].as_array().unwrap().len(), 2);
    let dir = common::temp_dir("collide-cli", "bench");
    let v = json_of(&[
        "collide-bench",
        "--quick",
        "--scenes",
        "merging-tori",
        "--frames",
        "1",
        "--triangles",
        "600",
        "--no-leaf-sweep",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["id"], "paper1");
    assert!(v["tables"].as_array().unwrap().len() >= 4);
    for png in [
        "paper1_fig7_readback.png",
        "paper1_fig7_readback_uniform.png",
        "paper1_fig10_merging-tori.png",
        "paper1_fig12_merging-tori.png",
    ] {
        assert!(dir.join(png).is_file(), "{png} not written");
    }
    // Sec. 5.5: a scene forced through tiles, beside the same frames as one rectangle.
    let tiles = v["results"]["tiles"]["rows"].as_array().unwrap();
    assert!(tiles.iter().any(|r| r["tiles"].as_u64().unwrap() > 1));
    let captions: Vec<&str> = v["tables"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["caption"].as_str().unwrap())
        .collect();
    assert!(captions.iter().any(|c| c.starts_with("Sec. 5.5: tiles")));
    assert!(captions
        .iter()
        .any(|c| c.starts_with("Fig. 7, clustered CAPs")));
    std::fs::remove_dir_all(&dir).ok();
}

/// Two interlocking tori scaled by 1e25 (a file `mesh check` accepts): by default `collide`
/// reports exactly the pairs brute force finds with exact arithmetic; `--predicate moller`
/// is the paper's float test, which at this scale reports pairs that do not touch.
#[test]
fn the_default_predicate_is_exact_far_from_unit_scale() {
    let dir = common::temp_dir("collide-cli", "scale");
    let scale = Affine3A::from_scale(Vec3::splat(1e25));
    let a = mesh::torus_with_triangles(1.0, 0.33, 600).transformed(&scale);
    let b = mesh::torus_with_triangles(1.0, 0.33, 600).transformed(
        &(scale
            * Affine3A::from_rotation_translation(
                Quat::from_rotation_x(1.4),
                Vec3::new(1.5, 0.1, 0.0),
            )),
    );
    let (pa, pb) = (dir.join("a.obj"), dir.join("b.obj"));
    mesh::write_obj(&a, &pa).unwrap();
    mesh::write_obj(&b, &pb).unwrap();
    let (la, lb) = (mesh::load_obj(&pa).unwrap(), mesh::load_obj(&pb).unwrap());
    let exact = all_pairs(&la, &la.positions, &lb, &lb.positions, Predicate::Exact);
    assert!(!exact.is_empty());
    let pairs = |extra: &[&str]| {
        let mut args = vec![
            "collide",
            pa.to_str().unwrap(),
            pb.to_str().unwrap(),
            "--json",
        ];
        args.extend_from_slice(extra);
        let v = json_of(&args);
        let pairs: Vec<(u32, u32)> = v["pairs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| (p[0].as_u64().unwrap() as u32, p[1].as_u64().unwrap() as u32))
            .collect();
        (v["predicate"].as_str().unwrap().to_string(), pairs)
    };
    assert_eq!(pairs(&[]), ("exact".to_string(), exact.clone()));
    let (name, moller) = pairs(&["--predicate", "moller"]);
    assert_eq!(name, "moller");
    let moller_cpu = all_pairs(&la, &la.positions, &lb, &lb.positions, Predicate::Moller);
    assert_eq!(moller, moller_cpu);
    assert_ne!(
        moller, exact,
        "Möller's float test is exact here: the test shows nothing"
    );
    let out = classic_gpgpu(&[
        "collide",
        "--predicate",
        "float",
        pa.to_str().unwrap(),
        pb.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("exact"));
    std::fs::remove_dir_all(&dir).ok();
}
