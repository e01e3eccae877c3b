//! Lecture 1, the compute counterpart of the pairwise triangle tests (OpenGL 4.3): its pairs
//! equal the classic pair quad's and brute force with paper 1's exact predicate, between two
//! models and within one, at extreme scales, and when the pair list overflows its first size;
//! `lecture1 pairwise --formulation compute` prints them. On a context without 4.3
//! (softpipe) asking for it is the clear error naming both versions, in the library and in
//! the command.

use classic_gpgpu::lecture1::knotted_tube::{KnottedTube, RADIUS_RANGE};
use classic_gpgpu::lecture1::pairwise::PairwiseTester;
use classic_gpgpu::lecture1::pairwise_compute::ComputePairwiseTester;
use classic_gpgpu::lecture1::reference::{pairs_between, self_pairs};
use classic_gpgpu::lecture1::weld::weld;
use classic_gpgpu::mesh::{self, Mesh};
use common::{classic_gpgpu, compute_context, soup};

mod common;

fn scaled(mesh: &Mesh, s: f32) -> Mesh {
    Mesh::new(
        mesh.positions.iter().map(|p| *p * s).collect(),
        mesh.triangles.clone(),
    )
}

#[test]
fn compute_pairs_equal_classic_and_brute_force() {
    let (ctx, has_compute) = compute_context();
    if !has_compute {
        let err = ComputePairwiseTester::new(&ctx).err().unwrap().to_string();
        assert!(err.contains("needs OpenGL 4.3"), "{err}");
        return;
    }
    let mut compute = ComputePairwiseTester::new(&ctx).unwrap();
    let classic = PairwiseTester::new(&ctx, 64).unwrap();
    // Two soups, at unit scale and at extreme ones.
    let (x, y) = (soup(200, 0.15, 11), soup(180, 0.15, 12));
    for s in [1.0f32, 1e24, 1e-30] {
        let (x, y) = (scaled(&x, s), scaled(&y, s));
        let expected = pairs_between(&x, &y);
        assert!(expected.len() > 10, "scale {s}: {}", expected.len());
        let now = compute.run(&x, Some(&y)).unwrap();
        let then = classic.run(&x, Some(&y)).unwrap();
        assert_eq!(now.pairs, expected, "scale {s}");
        assert_eq!(then.pairs, expected, "scale {s}");
        // The same filter: the same candidates, whichever formulation ran it.
        assert_eq!(now.candidates, then.candidates, "scale {s}");
    }
    // One model: the swelling knot at its thickest, neighbours excluded.
    let tube = KnottedTube::new(40, 8);
    let mut thick = tube.mesh.clone();
    thick.positions = tube.positions_at_radius(RADIUS_RANGE.1);
    let expected = self_pairs(&weld(&thick), &thick.positions);
    assert!(!expected.is_empty());
    assert_eq!(compute.run(&thick, None).unwrap().pairs, expected);
    assert_eq!(classic.run(&thick, None).unwrap().pairs, expected);
    // The thinnest: no pairs.
    assert!(compute.run(&tube.mesh, None).unwrap().pairs.is_empty());
}

#[test]
fn an_overflowing_pair_list_is_grown_and_the_test_rerun() {
    let (ctx, has_compute) = compute_context();
    if !has_compute {
        return;
    }
    // Large triangles crowded in the unit cube: most of the 200 x 200 pairs intersect, far
    // more than the list's first 4096 slots.
    let (x, y) = (soup(200, 1.5, 21), soup(200, 1.5, 22));
    let expected = pairs_between(&x, &y);
    assert!(expected.len() > 4096, "{}", expected.len());
    let mut compute = ComputePairwiseTester::new(&ctx).unwrap();
    let first = compute.run(&x, Some(&y)).unwrap();
    assert_eq!(first.tiles, 2, "the list should have overflowed once");
    assert_eq!(first.pairs, expected);
    // The grown list stays: the next run needs one dispatch.
    let second = compute.run(&x, Some(&y)).unwrap();
    assert_eq!((second.tiles, second.pairs), (1, expected));
}

#[test]
fn the_command_takes_the_formulation() {
    let (_ctx, has_compute) = compute_context();
    let dir = std::env::temp_dir().join(format!("l1-compute-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (pa, pb) = (dir.join("a.obj"), dir.join("b.obj"));
    mesh::write_obj(&soup(60, 0.3, 31), &pa).unwrap();
    mesh::write_obj(&soup(50, 0.3, 32), &pb).unwrap();
    // The reference reads the same files, so the coordinates are the command's.
    let (a, b) = (mesh::load_obj(&pa).unwrap(), mesh::load_obj(&pb).unwrap());
    let expected: Vec<[u32; 2]> = pairs_between(&a, &b)
        .into_iter()
        .map(|(i, j)| [i, j])
        .collect();
    assert!(!expected.is_empty());
    let (pa, pb) = (pa.to_str().unwrap(), pb.to_str().unwrap());
    for formulation in ["classic", "compute"] {
        let out = classic_gpgpu(&[
            "lecture1",
            "pairwise",
            pa,
            pb,
            "--formulation",
            formulation,
            "--check",
            "--json",
        ]);
        if formulation == "compute" && !has_compute {
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{err}");
            assert!(err.contains("needs OpenGL 4.3"), "{err}");
            continue;
        }
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["formulation"], formulation);
        let pairs: Vec<[u32; 2]> = serde_json::from_value(json["pairs"].clone()).unwrap();
        assert_eq!(pairs, expected, "{formulation}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
