//! The `--out` folder of `compare`: the folder rule of every writer ([`crate::page::folder`]) with a marker
//! of its own. A folder with files this program did not write is refused without `--force`;
//! even with it, a file of someone else's is never replaced; another command's folder (a
//! `reproduce` report, whose page would be lost) is never written into.

use crate::page::folder::{self, Owned};
use anyhow::bail;
use std::path::{Path, PathBuf};

/// The command whose marker the page's folder holds, and the section of its files.
const OWNER: &str = "compare";

/// Refuses `out` before any work: a file, a `reproduce` report, a folder of someone else's
/// without `force`, or a folder where a file the page needs is an input.
pub fn check(out: &Path, inputs: &[PathBuf], names: &[&str], force: bool) -> anyhow::Result<()> {
    folder::check_folder("--out", OWNER, out, force)?;
    let owned = Owned::read_of(out, OWNER)?;
    for name in names {
        let path = out.join(name);
        if let Some(input) = inputs.iter().find(|i| crate::files::same_file(&path, i)) {
            bail!(
                "--out {}: {name} there is the input {}; an input is never overwritten, so \
                 choose another --out",
                out.display(),
                input.display()
            );
        }
        let ours = owned.as_ref().is_some_and(|o| o.contains(name));
        if path.exists() && !ours {
            bail!(
                "--out {}: {name} there is not a file compare wrote; it is never replaced, so \
                 choose another --out",
                out.display()
            );
        }
    }
    Ok(())
}

/// Writes `files` (name, bytes) into `out`, each whole or not at all, then the marker; files
/// an earlier compare wrote that this one does not are removed.
pub fn write(out: &Path, files: &[(String, Vec<u8>)]) -> anyhow::Result<()> {
    let old = Owned::read_of(out, OWNER)?.unwrap_or_default();
    let mut owned = Owned::default();
    for (name, bytes) in files {
        crate::files::write_bytes(&out.join(name), bytes)?;
        owned.add(OWNER, name);
    }
    for (_, file) in old.files() {
        if !owned.contains(file) {
            std::fs::remove_file(out.join(file)).ok();
        }
    }
    owned.write_of(out, OWNER)
}
