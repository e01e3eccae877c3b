//! The folder `reproduce` writes its report into, and what in it is the report's own.
//!
//! A marker file in the folder lists every file the run wrote and the section it belongs to.
//! Only those files are ever replaced or removed: a folder without the marker that holds
//! anything is someone else's, refused without `--force`, and even with it nothing the
//! marker does not list is deleted. A lock beside the folder keeps two runs from writing one
//! report at once; the final swap moves the old report aside first, so a run killed between
//! the two renames leaves it where the next run finds and restores it.

use anyhow::{bail, Context as _};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The marker's file name, inside the report folder.
pub const MARKER: &str = ".classic-gpgpu-report";

/// The marker's first line (anything else on it is not ours).
const MARKER_HEADER: &str = "classic-gpgpu report: the files `classic-gpgpu reproduce` wrote \
    here (section, path); it replaces or removes only these";

/// What a report wrote: relative path (`/`-separated) to the section that wrote it (`-` for
/// the page and the results).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Owned {
    files: BTreeMap<String, String>,
}

impl Owned {
    /// The marker of `dir`, `None` when it has none (a folder this program did not make).
    pub fn read(dir: &Path) -> anyhow::Result<Option<Owned>> {
        let path = dir.join(MARKER);
        if !path.exists() {
            return Ok(None);
        }
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("reading {}", path.display()))?;
        let mut lines = text.lines();
        if lines.next() != Some(MARKER_HEADER) {
            bail!("{} is not a classic-gpgpu report marker", path.display());
        }
        let mut files = BTreeMap::new();
        for line in lines.filter(|l| !l.is_empty()) {
            let (section, file) = line
                .split_once('\t')
                .with_context(|| format!("{}: malformed line '{line}'", path.display()))?;
            files.insert(file.to_string(), section.to_string());
        }
        Ok(Some(Owned { files }))
    }

    /// What a report made by an older version wrote, read from its own `results.json`: the
    /// page, the results and every figure the sections list.
    pub fn from_results(dir: &Path) -> Owned {
        let mut owned = Owned::default();
        let Ok(text) = std::fs::read_to_string(dir.join("results.json")) else {
            return owned;
        };
        let results: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
        if !(results["renderer"].is_object() && results["sections"].is_array()) {
            // Not a report of this program's: none of it is ours.
            return Owned::default();
        }
        for section in results["sections"].as_array().into_iter().flatten() {
            let id = section["id"].as_str().unwrap_or("-");
            for figure in section["figures"].as_array().into_iter().flatten() {
                if let Some(file) = figure["file"].as_str() {
                    owned.add(id, file);
                }
            }
        }
        owned.add("-", "results.json");
        owned.add("-", "index.html");
        owned
    }

    pub fn add(&mut self, section: &str, file: &str) {
        self.files.insert(file.to_string(), section.to_string());
    }

    pub fn contains(&self, file: &str) -> bool {
        self.files.contains_key(file)
    }

    /// Every file, with its section.
    pub fn files(&self) -> impl Iterator<Item = (&str, &str)> {
        self.files.iter().map(|(f, s)| (s.as_str(), f.as_str()))
    }

    /// The files `section` wrote.
    pub fn files_of<'a>(&'a self, section: &'a str) -> impl Iterator<Item = &'a str> + 'a {
        self.files
            .iter()
            .filter(move |(_, s)| s.as_str() == section)
            .map(|(f, _)| f.as_str())
    }

    /// Writes the marker into `dir` (whole or not at all).
    pub fn write(&self, dir: &Path) -> anyhow::Result<()> {
        let mut text = format!("{MARKER_HEADER}\n");
        for (file, section) in &self.files {
            text.push_str(&format!("{section}\t{file}\n"));
        }
        crate::files::write_bytes(&dir.join(MARKER), text.as_bytes())
    }
}

/// Every file under `dir`, relative and `/`-separated, sorted (the marker left out).
pub fn list_files(dir: &Path) -> anyhow::Result<Vec<String>> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) -> anyhow::Result<()> {
        for entry in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
            let entry = entry?;
            let path = entry.path();
            if entry.file_type()?.is_dir() {
                walk(root, &path, out)?;
            } else {
                let relative = path.strip_prefix(root).expect("under the root");
                let name = relative
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy())
                    .collect::<Vec<_>>()
                    .join("/");
                if name != MARKER {
                    out.push(name);
                }
            }
        }
        Ok(())
    }
    let mut files = Vec::new();
    if dir.is_dir() {
        walk(dir, dir, &mut files)?;
    }
    files.sort();
    Ok(files)
}

/// Refuses, before any work, an `--out` that is a file, or a folder with anything in it that
/// this program did not make (no marker) unless `force` says to add the report to it.
pub fn check_out(out: &Path, force: bool) -> anyhow::Result<()> {
    if !out.exists() {
        return Ok(());
    }
    if !out.is_dir() {
        bail!(
            "--out {}: exists and is not a folder; choose another --out",
            out.display()
        );
    }
    if force || Owned::read(out)?.is_some() {
        return Ok(());
    }
    let first = std::fs::read_dir(out)
        .with_context(|| format!("--out {}: cannot read the folder", out.display()))?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .min();
    if let Some(first) = first {
        bail!(
            "--out {}: the folder holds files this program did not write (e.g. {first}; it has \
             no {MARKER} marker), so it is not a report of classic-gpgpu's. Choose another \
             --out, or pass --force to write the report into it (files that are not the \
             report's are never removed)",
            out.display()
        );
    }
    Ok(())
}

/// The lock of one report folder: held while a run reads the old report and writes the new
/// one, released when dropped (or when the process dies, however it dies). A run that ends
/// normally removes the lock file; one that was killed leaves it, and the next run reuses it.
pub struct Lock {
    file: std::fs::File,
    path: PathBuf,
}

impl Lock {
    /// Takes the lock of `out`, a file `.NAME.lock` beside it; refuses clearly when another
    /// run holds it.
    pub fn take(out: &Path) -> anyhow::Result<Lock> {
        let (parent, name) = parent_and_name(out)?;
        std::fs::create_dir_all(&parent)
            .with_context(|| format!("creating {}", parent.display()))?;
        let path = parent.join(format!(".{name}.lock"));
        // A holder removes the file before it unlocks, so a lock taken on a file that is no
        // longer at `path` is stale: open the file at `path` again.
        for _ in 0..16 {
            let file = open_lock_file(&path)?;
            match rustix::fs::flock(&file, rustix::fs::FlockOperation::NonBlockingLockExclusive) {
                Ok(()) if still_at(&file, &path) => return Ok(Lock { file, path }),
                Ok(()) => continue,
                Err(rustix::io::Errno::WOULDBLOCK) => bail!(
                    "--out {}: another `classic-gpgpu reproduce` is writing this report now (it \
                     holds {}); run again when it has finished, or choose another --out",
                    out.display(),
                    path.display()
                ),
                Err(e) => return Err(e).with_context(|| format!("locking {}", path.display())),
            }
        }
        bail!(
            "locking {}: the lock file kept being replaced",
            path.display()
        )
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        // Removed while still held; the flock goes with the file handle just after.
        if still_at(&self.file, &self.path) {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// The lock is a file's flock, not its contents: it is opened, never written.
fn open_lock_file(path: &Path) -> anyhow::Result<std::fs::File> {
    std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
        .with_context(|| format!("opening the lock {}", path.display()))
}

/// Whether `path` is still the file `file` has open.
fn still_at(file: &std::fs::File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(open), Ok(named)) => open.dev() == named.dev() && open.ino() == named.ino(),
        _ => false,
    }
}

/// `out`'s parent folder (`.` for a bare name) and file name.
pub fn parent_and_name(out: &Path) -> anyhow::Result<(PathBuf, String)> {
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let name = out
        .file_name()
        .with_context(|| format!("--out {}: needs a folder name", out.display()))?
        .to_string_lossy()
        .into_owned();
    Ok((parent, name))
}

/// The staging folder of the run `pid` (same file system as `out`, so the swap is a rename).
pub fn staging_of(out: &Path, pid: u32) -> anyhow::Result<PathBuf> {
    let (parent, name) = parent_and_name(out)?;
    Ok(parent.join(format!(".{name}.staging-{pid}")))
}

/// Where the swap moves the old report aside.
fn aside_of(staging: &Path) -> PathBuf {
    let mut name = staging.file_name().unwrap_or_default().to_os_string();
    name.push(".old");
    staging.with_file_name(name)
}

/// Cleans up after runs that were killed (under the lock, so none of them is running):
/// an old report a run moved aside and did not put back is restored (or, when the new report
/// had already replaced it, removed); unfinished staging folders are removed; a finished one
/// (a run killed just before its swap) is kept and named.
pub fn recover(out: &Path) -> anyhow::Result<()> {
    let (parent, name) = parent_and_name(out)?;
    let prefix = format!(".{name}.staging-");
    let Ok(entries) = std::fs::read_dir(&parent) else {
        return Ok(());
    };
    let mut names: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(&prefix))
        .collect();
    // Moved-aside reports first: restoring one may make `out` exist again.
    names.sort_by_key(|n| !n.ends_with(".old"));
    for entry in names {
        let path = parent.join(&entry);
        let rest = &entry[prefix.len()..];
        if rest.ends_with(".old") {
            if out.exists() {
                // The swap had finished: this is the report the new one replaced.
                std::fs::remove_dir_all(&path).ok();
            } else {
                std::fs::rename(&path, out).with_context(|| {
                    format!(
                        "restoring the report an interrupted run moved aside: {} is intact; \
                         move it to {} yourself",
                        path.display(),
                        out.display()
                    )
                })?;
                eprintln!(
                    "restored {} (an interrupted run had moved it aside to {})",
                    out.display(),
                    path.display()
                );
            }
        } else if rest.parse::<u32>().is_ok() {
            if path.join(MARKER).exists() {
                eprintln!(
                    "note: {} holds the finished report of an interrupted run; it is left there",
                    path.display()
                );
            } else {
                std::fs::remove_dir_all(&path).ok();
            }
        }
    }
    Ok(())
}

/// Test hook: a fault in the final swap (`kill`: the process exits between its two renames;
/// `fail`: the second rename fails).
pub const SWAP_FAULT_ENV: &str = "CLASSIC_GPGPU_SWAP_FAULT";

/// Puts the finished report in `staging` (its marker written last) in place of `out`.
///
/// When `out` holds only the old report's files, the two folders are swapped: the old one
/// moved aside, the new one renamed in, the old one removed. When it holds files of someone
/// else's too, they stay where they are: the new files are renamed in one by one, the old
/// report's files that the new one does not have are removed, and the marker comes last.
pub fn install(staging: &Path, out: &Path, owned: &Owned) -> anyhow::Result<()> {
    let old = match Owned::read(out)? {
        Some(old) => old,
        None => Owned::from_results(out),
    };
    let present = list_files(out)?;
    let foreign: Vec<&String> = present.iter().filter(|f| !old.contains(f)).collect();
    let kept = |e: anyhow::Error| {
        e.context(format!(
            "the finished report is in {}; {} is as it was",
            staging.display(),
            out.display()
        ))
    };
    if foreign.is_empty() {
        return swap(staging, out);
    }
    if let Some(clash) = foreign.iter().find(|f| owned.contains(f)) {
        return Err(kept(anyhow::anyhow!(
            "{} in --out {} is not the report's, and the new report has a file of that name",
            clash,
            out.display()
        )));
    }
    for (_, file) in owned.files() {
        let (from, to) = (staging.join(file), out.join(file));
        if let Some(dir) = to.parent() {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("creating {}", dir.display()))
                .map_err(kept)?;
        }
        std::fs::rename(&from, &to)
            .with_context(|| format!("moving {} into place", to.display()))
            .map_err(|e| {
                e.context(format!(
                    "the rest of the finished report is in {}",
                    staging.display()
                ))
            })?;
    }
    for (_, file) in old.files() {
        if !owned.contains(file) {
            std::fs::remove_file(out.join(file)).ok();
        }
    }
    std::fs::rename(staging.join(MARKER), out.join(MARKER))
        .with_context(|| format!("writing {}", out.join(MARKER).display()))?;
    std::fs::remove_dir_all(staging).ok();
    Ok(())
}

/// Replaces `out` (absent, empty or only the old report) by `staging`: the old report is
/// moved aside first and removed last.
fn swap(staging: &Path, out: &Path) -> anyhow::Result<()> {
    let aside = aside_of(staging);
    let fault = std::env::var(SWAP_FAULT_ENV).unwrap_or_default();
    if out.exists() {
        std::fs::rename(out, &aside).with_context(|| {
            format!(
                "moving the old {} aside; the finished report is in {}",
                out.display(),
                staging.display()
            )
        })?;
    }
    if fault == "kill" {
        std::process::exit(137);
    }
    let second = if fault == "fail" {
        Err(std::io::Error::other("failed on purpose"))
    } else {
        std::fs::rename(staging, out)
    };
    if let Err(e) = second {
        let restored = !aside.exists() || std::fs::rename(&aside, out).is_ok();
        let old = if restored {
            format!("{} is as it was", out.display())
        } else {
            format!("the old report is in {}", aside.display())
        };
        return Err(anyhow::Error::from(e).context(format!(
            "moving the new report to {}: the finished report is in {}; {old}",
            out.display(),
            staging.display()
        )));
    }
    if aside.exists() {
        std::fs::remove_dir_all(&aside).ok();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_run_holds_the_lock_and_leaves_no_file() {
        let dir = std::env::temp_dir().join(format!("cg-lock-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let out = dir.join("report");
        let lock_file = dir.join(".report.lock");
        let held = Lock::take(&out).unwrap();
        assert!(lock_file.exists());
        let second = Lock::take(&out)
            .err()
            .expect("a second lock while the first is held");
        assert!(format!("{second:#}").contains("another"), "{second:#}");
        drop(held);
        assert!(!lock_file.exists(), "the lock file outlived its run");
        // A lock file a killed run left is simply taken over.
        std::fs::write(&lock_file, "").unwrap();
        drop(Lock::take(&out).unwrap());
        assert!(!lock_file.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
