//! Where a result comes from, so that a number in `results.json` can be traced back to the
//! run that made it: the commit the binary was built from, the command line, and how busy the
//! machine was. Each claim carries its own version ([`super::versions`]).

/// The commit this binary was built from (`git rev-parse HEAD` at build time), ending in
/// `-dirty` when the tree held changes not committed; "unknown" when built without git.
pub const COMMIT: &str = env!("CLASSIC_GPGPU_COMMIT");

/// The command line of this process, program name first (arguments that are not UTF-8 are
/// written with replacement characters).
pub fn command_line() -> Vec<String> {
    std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect()
}

/// Whether `commit` was built from a tree with changes not committed.
pub fn is_dirty(commit: &str) -> bool {
    commit.ends_with("-dirty")
}

/// A commit as a reader sees it: the first 7 hex digits, `-dirty` kept.
pub fn short_commit(commit: &str) -> String {
    let (hash, dirty) = match commit.strip_suffix("-dirty") {
        Some(hash) => (hash, "-dirty"),
        None => (commit, ""),
    };
    if hash.len() > 7 && hash.chars().all(|c| c.is_ascii_hexdigit()) {
        format!("{}{dirty}", &hash[..7])
    } else {
        commit.to_string()
    }
}
