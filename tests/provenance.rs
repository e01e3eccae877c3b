//! `results.json` says where its numbers come from: the commit the binary was built from, each
//! claim's id and version, the command line, and the machine's load around each section.

use std::process::Command;

/// `git rev-parse HEAD` of this checkout, if git and a checkout are there.
fn git_head() -> Option<String> {
    let out = Command::new("git")
        .args(["-C", env!("CARGO_MANIFEST_DIR"), "rev-parse", "HEAD"])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

#[test]
fn results_name_the_commit_the_command_and_the_load() {
    let out = std::env::temp_dir().join(format!("classic-gpgpu-provenance-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args([
            "reproduce",
            "--quick",
            "--only",
            "blocks",
            "--runs",
            "1",
            "--out",
        ])
        .arg(&out)
        .output()
        .expect("the binary runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();

    // The commit: the checkout's HEAD (with -dirty when the tree had changes), or "unknown".
    let commit = results["commit"].as_str().expect("a commit");
    match git_head() {
        Some(head) => assert_eq!(commit.strip_suffix("-dirty").unwrap_or(commit), head),
        None => assert_eq!(commit, "unknown"),
    }
    assert_eq!(commit, classic_gpgpu::report::provenance::COMMIT);
    // Each claim: its id, and this build's version of it at --quick sizes.
    use classic_gpgpu::report::{claim_defs, versions};
    let claims = results["sections"][0]["claims"].as_array().unwrap();
    assert!(!claims.is_empty());
    for claim in claims {
        let id = claim["id"].as_str().expect("an id");
        let def =
            claim_defs::find(id).unwrap_or_else(|| panic!("{id} is not a claim of the build"));
        assert_eq!(
            claim["version"].as_str(),
            Some(versions::current(def, true).unwrap().as_str()),
            "{id}"
        );
    }

    // The command line, as typed.
    let command: Vec<&str> = results["command_line"]
        .as_array()
        .expect("a command line")
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert!(command[0].ends_with("classic-gpgpu"), "{command:?}");
    assert_eq!(
        &command[1..7],
        ["reproduce", "--quick", "--only", "blocks", "--runs", "1"]
    );

    // The load at the start and end of each section: a 1-minute load average and the cores.
    let sections = results["sections"].as_array().unwrap();
    assert_eq!(sections.len(), 1);
    for key in ["load_start", "load_end"] {
        let load = &sections[0][key];
        let one_minute = load["one_minute"].as_f64().expect(key);
        assert!(one_minute >= 0.0, "{key}: {load}");
        assert!(load["cores"].as_u64().is_some_and(|c| c >= 1), "{load}");
    }
    assert_eq!(sections[0]["commit"].as_str(), Some(commit));

    // The page says it too.
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains(&format!("<code>{commit}</code>")));
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn the_build_says_where_it_comes_from() {
    use classic_gpgpu::report::provenance::COMMIT;
    // build.rs ran git here (a checkout), or said it could not.
    let hash = COMMIT.strip_suffix("-dirty").unwrap_or(COMMIT);
    assert!(
        hash == "unknown" || (hash.len() == 40 && hash.chars().all(|c| c.is_ascii_hexdigit())),
        "{COMMIT}"
    );
}

#[test]
fn commits_are_shortened_as_git_does() {
    use classic_gpgpu::report::provenance::{is_dirty, short_commit};
    let full = "0592cce1a2b3c4d5e6f708192a3b4c5d6e7f8091";
    assert_eq!(short_commit(full), "0592cce");
    assert_eq!(short_commit(&format!("{full}-dirty")), "0592cce-dirty");
    assert_eq!(short_commit("unknown"), "unknown");
    assert!(is_dirty("abc-dirty") && !is_dirty("abc"));
}
