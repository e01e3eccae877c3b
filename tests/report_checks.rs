//! What the report sections say against what they run, without a GL context: the checks a
//! summary names come from the section's list and must all be made ([`checks::verify`], run
//! by `run_section` for every section); every path a run of lecture 1, lecture 3 or paper 4
//! can take has a fidelity row; the "not built" tables name what the sources name and the
//! project does not do.

use classic_gpgpu::report::checks::{self, Check};
use classic_gpgpu::report::lecture1::{self, Block, Lecture1Results};
use classic_gpgpu::report::{lecture3, not_built, paper4, Fidelity};

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[test]
fn verify_fails_a_claimed_check_not_made_a_made_check_not_claimed_and_a_path_without_a_row() {
    let rows = vec![Fidelity::new("f", "paper", "code", "why").covers(&["path a"])];
    let listed = strings(&["one", "two"]);
    // As it should be.
    checks::verify(
        "s",
        &listed,
        &strings(&["two", "one"]),
        &strings(&["path a"]),
        &rows,
    )
    .unwrap();
    // The summary names "two", the run did not make it.
    let e = checks::verify("s", &listed, &strings(&["one"]), &[], &rows).unwrap_err();
    assert!(e.to_string().contains("'two'"), "{e}");
    // The run made "three", the list does not name it.
    let made = strings(&["one", "two", "three"]);
    let e = checks::verify("s", &listed, &made, &[], &rows).unwrap_err();
    assert!(e.to_string().contains("'three'"), "{e}");
    // The run took "path b", no row covers it.
    let e = checks::verify("s", &listed, &listed, &strings(&["path b"]), &rows).unwrap_err();
    assert!(e.to_string().contains("'path b'"), "{e}");
}

fn assert_every_path_covered(section: &str, paths: &[&str], rows: &[Fidelity]) {
    let covered = checks::covered(rows);
    for path in paths {
        assert!(
            covered.iter().any(|c| c == path),
            "{section}: no fidelity row covers the path '{path}'"
        );
    }
    for row in rows {
        for text in [&row.feature, &row.paper, &row.code, &row.deviation] {
            assert!(!text.trim().is_empty(), "{section}: {row:?}");
        }
        for path in &row.paths {
            assert!(
                paths.contains(&path.as_str()),
                "{section}: row '{}' covers '{path}', which is not a path of the section",
                row.feature
            );
        }
    }
}

fn row<'a>(rows: &'a [Fidelity], feature: &str) -> &'a Fidelity {
    rows.iter()
        .find(|r| r.feature.contains(feature))
        .unwrap_or_else(|| panic!("no fidelity row '{feature}'"))
}

#[test]
fn every_path_of_lecture1_lecture3_and_paper4_has_a_fidelity_row() {
    assert_every_path_covered("lecture1", lecture1::ALL_PATHS, &lecture1::fidelity_rows());
    assert_every_path_covered("lecture3", lecture3::ALL_PATHS, &lecture3::fidelity_rows());
    assert_every_path_covered("paper4", paper4::ALL_PATHS, &paper4::fidelity_rows());
}

#[test]
fn the_rows_the_issue_asked_for_are_there_and_say_what_the_code_does() {
    let l1 = lecture1::fidelity_rows();
    let field = row(&l1, "distance field of a mesh");
    assert!(field.deviation.contains("GL_MIN"), "{field:?}");
    assert!(field.deviation.contains("not used"), "{field:?}");
    assert!(row(&l1, "Voronoi diagram, exact")
        .deviation
        .contains("the default"));
    row(&l1, "Hoff's distance meshes");
    let swept = row(&l1, "swept volume");
    assert!(swept.deviation.contains("not fast marching"), "{swept:?}");
    assert!(swept.deviation.contains("topological"), "{swept:?}");
    assert!(row(&l1, "independent reference")
        .deviation
        .contains("parry3d"));
    assert!(row(&l1, "the avatar's scene").deviation.contains("13-link"));
    // Built since: Hoff's meshes in 3D and the avatar at the published scale.
    assert!(row(&l1, "distance field by Hoff's distance meshes")
        .deviation
        .contains("depth buffer"));
    assert!(row(&l1, "published scale").deviation.contains("16 links"));
    let l3 = lecture3::fidelity_rows();
    assert!(row(&l3, "octree").deviation.contains("reconstruction"));
    let p4 = paper4::fidelity_rows();
    assert!(row(&p4, "viscous drag").deviation.contains("c = 1"));
    assert!(row(&p4, "viscous drag")
        .deviation
        .contains("velocity of the centre of mass"));
    assert!(row(&p4, "extra damping")
        .feature
        .contains("--extra-damping"));
    let step = row(&p4, "rigid-body integration");
    assert!(step.deviation.contains("semi-implicit Euler"), "{step:?}");
    assert!(step.deviation.contains("dt = 1/60 s"), "{step:?}");
    let scene = row(&p4, "the 50-body scene");
    assert!(scene.deviation.contains("densities"), "{scene:?}");
    assert!(scene.deviation.contains("0.3, 0.4 or 0.5 m"), "{scene:?}");
    assert!(row(&p4, "teapot").deviation.contains("closed teapot"));
    // Buoyancy's passes write one target (glsl/mass/integrands_eq4.frag), the listing three.
    let eq4 = row(&p4, "four integrands of eq. 4");
    assert!(eq4.feature.contains("one render target"), "{eq4:?}");
    let shader = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl/mass/integrands_eq4.frag"),
    )
    .unwrap();
    assert!(shader.contains("out vec4 FragData[1]"), "{shader}");
    assert!(row(&p4, "mass properties: the integrands")
        .feature
        .contains("three render targets"));
}

#[test]
fn lecture1s_summary_names_exactly_its_listed_checks() {
    // A run without compute claims no compute check; with it, every check of the list.
    let without: Vec<&str> = lecture1::listed_checks(false)
        .iter()
        .map(|c| c.id)
        .collect();
    assert!(!without
        .iter()
        .any(|id| lecture1::NEEDS_COMPUTE.contains(id)));
    assert_eq!(lecture1::listed_checks(true).len(), lecture1::CHECKS.len());
    for compute in [false, true] {
        let results = Lecture1Results {
            renderer: "a renderer".into(),
            software: true,
            quick: true,
            runs: "1 run".into(),
            compute,
            blocks: vec![Block {
                summary: "A block's result.".into(),
                ..Block::default()
            }],
        };
        let summary = lecture1::summary(&results);
        let listed: Vec<Check> = lecture1::listed_checks(compute);
        assert!(summary.contains(&checks::sentence(&listed)), "{summary}");
        // The checks it does not list are not named.
        for check in lecture1::CHECKS {
            if !listed.iter().any(|c| c.id == check.id) {
                assert!(!summary.contains(check.says), "{summary}");
            }
        }
        // The old blanket claim (one predicate for every part) is gone.
        assert!(!summary.contains("same exact predicate, in the same run"));
    }
    // Every check id is unique.
    for (i, a) in lecture1::CHECKS.iter().enumerate() {
        for b in &lecture1::CHECKS[i + 1..] {
            assert_ne!(a.id, b.id);
        }
    }
}

#[test]
fn the_not_built_tables_name_what_the_issue_lists() {
    let text = |rows: &[not_built::NotBuilt]| {
        rows.iter()
            .map(|r| format!("{} | {} | {} | {}", r.what, r.source, r.instead, r.needed))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let l1 = text(not_built::LECTURE1);
    for named in [
        "bounding volume hierarchies",
        "model simplification",
        "tolerance verification",
        "convex decomposition",
        "fast-marching",
        "topological refinement",
        "swept surfaces",
        "interval arithmetic",
        "general arrangements",
        "16-link",
        "DiFi",
    ] {
        assert!(
            l1.contains(named),
            "lecture 1's 'not built' lacks '{named}'"
        );
    }
    assert!(!not_built::LECTURE3.is_empty());
    let table = not_built::table("lecture 1", not_built::LECTURE1);
    assert_eq!(table.rows.len(), not_built::LECTURE1.len());
    assert!(table.caption.starts_with("Not built"));
    for r in not_built::LECTURE1.iter().chain(not_built::LECTURE3) {
        assert!(!r.needed.trim().is_empty(), "{r:?}");
    }
}

/// Papers 1 to 3 list their checks too: a run whose made checks differ from the list fails.
#[test]
fn papers_1_to_3_fail_when_their_list_and_their_checks_differ() {
    for (section, list) in [
        ("paper1", checks::PAPER1),
        ("paper2", checks::PAPER2),
        ("paper3", checks::PAPER3),
    ] {
        let listed = checks::ids(list);
        checks::verify(section, &listed, &listed, &[], &[]).unwrap();
        for (i, a) in list.iter().enumerate() {
            assert!(list[i + 1..].iter().all(|b| b.id != a.id), "{section}");
            // One listed check not made.
            let fewer: Vec<String> = listed.iter().filter(|id| *id != a.id).cloned().collect();
            let e = checks::verify(section, &listed, &fewer, &[], &[]).unwrap_err();
            assert!(e.to_string().contains(a.id), "{e}");
            assert!(checks::sentence(list).contains(a.says));
        }
        // One made check not listed.
        let mut more = listed.clone();
        more.push("an unlisted check".into());
        let e = checks::verify(section, &listed, &more, &[], &[]).unwrap_err();
        assert!(e.to_string().contains("an unlisted check"), "{e}");
    }
    assert!(checks::made(&[(true, "a"), (false, "b")]) == vec!["a".to_string()]);
}

/// Where the compute formulation cannot run (softpipe, OpenGL 3.3), papers 1 and 3 neither
/// name nor ask for the then-and-now check; the others are still required.
#[test]
fn a_check_the_context_cannot_make_is_left_out_of_the_list_and_the_summary() {
    for (section, list, compute_check) in [
        ("paper1", checks::PAPER1, "then and now same pairs"),
        ("paper3", checks::PAPER3, "then and now same outputs"),
    ] {
        let kept = checks::without(list, &[compute_check]);
        assert_eq!(kept.len(), list.len() - 1, "{section}");
        let listed = checks::ids(&kept);
        checks::verify(section, &listed, &listed, &[], &[]).unwrap();
        let says = list.iter().find(|c| c.id == compute_check).unwrap().says;
        assert!(!checks::sentence(&kept).contains(says), "{section}");
        // The full list still asks for it.
        let e = checks::verify(section, &checks::ids(list), &listed, &[], &[]).unwrap_err();
        assert!(e.to_string().contains(compute_check), "{e}");
    }
}

/// Each departure from the papers a referee read found undeclared has its row, and each thing
/// the sources name that is not built has its "not built" row (issue 53).
#[test]
fn every_departure_found_by_a_referee_is_declared() {
    let says = |rows: &[Fidelity], words: &[&str]| {
        rows.iter().any(|r| {
            let text = format!("{} {} {} {}", r.feature, r.paper, r.code, r.deviation);
            words.iter().all(|w| text.contains(w))
        })
    };
    let p4 = paper4::fidelity_rows();
    assert!(says(
        &p4,
        &["eq. 2", "eq. 5", "centre of mass", "assemble.rs"]
    ));
    assert!(says(&p4, &["sgn(n_z)", "gl_FrontFacing", "peel_main.frag"]));
    let p3 = classic_gpgpu::report::paper3::fidelity_rows();
    assert!(says(&p3, &["one hidden layer", "30", "not given"]));
    let p1 = classic_gpgpu::report::paper1::fidelity_rows();
    assert!(says(&p1, &["main()", "(float3)", "global"]));
    let l3 = lecture3::fidelity_rows();
    assert!(says(
        &l3,
        &["atomic counter", "preferred", "pipeline statistics"]
    ));
    let named = |rows: &[not_built::NotBuilt], words: &[&str]| {
        rows.iter().any(|r| {
            let text = format!("{} {} {}", r.what, r.source, r.instead);
            words.iter().all(|w| text.contains(w))
        })
    };
    assert!(named(
        not_built::LECTURE3,
        &["adaptive screen interpolation", "Ki & Oh"]
    ));
    assert!(named(not_built::PAPER3, &["learning on the GPU", "CPU"]));
    assert!(named(not_built::PAPER4, &["not a plane", "section 5.2"]));
    assert!(named(
        not_built::LECTURE5,
        &["CUDA", "G80", "compute shaders"]
    ));
}

/// Table 1's objects at the paper's vertex and face counts, or a fidelity row naming the
/// object with both its counts and the paper's; the bunny and the pipe are refined to the
/// paper's counts and stay closed.
#[test]
fn table1_objects_have_the_papers_counts_or_a_row_says_how_far() {
    use classic_gpgpu::mass::models;
    use classic_gpgpu::report::published::Published;
    let paper = &Published::get().unwrap().paper4;
    let rows = paper4::fidelity_rows();
    for name in models::PAPER_OBJECTS {
        let mesh = models::paper_object(name).unwrap();
        let published = paper
            .object(name)
            .unwrap_or_else(|| panic!("{name} in Table 1"));
        let (v, f) = (mesh.vertex_count(), mesh.triangle_count());
        if (v as u32, f as u32) == (published.vertices, published.faces) {
            continue;
        }
        let ours = format!("{v} vertices");
        let declared = rows.iter().any(|r| {
            r.deviation.contains(name)
                && r.deviation.contains(&ours)
                && r.deviation.contains(&f.to_string())
                && r.paper
                    .contains(&format!("{}/{}", published.vertices, published.faces))
        });
        assert!(
            declared,
            "{name}: {v}/{f} against Table 1's {}/{}, and no fidelity row says so",
            published.vertices, published.faces
        );
    }
    for name in ["bunny", "pipe"] {
        let mesh = models::paper_object(name).unwrap();
        assert!(mesh.closedness().is_closed(), "{name} is not closed");
        let p = paper.object(name).unwrap();
        assert_eq!(
            (mesh.vertex_count() as u32, mesh.triangle_count() as u32),
            (p.vertices, p.faces),
            "{name}"
        );
    }
}
