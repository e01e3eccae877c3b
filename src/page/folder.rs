//! The folders the program writes (`reproduce`'s report, `mass --dump`, every `*-bench --out`
//! ...), and what in each is the command's own. One rule for all of them, [`Staged`]:
//!
//! A marker file in the folder lists every file the command wrote (and, for the report, the
//! section it belongs to). Only those files are ever replaced or removed: a folder that holds
//! anything the marker does not list is someone else's, refused without `--force`, and even
//! with it nothing the marker does not list is deleted, nor replaced. A folder with another
//! command's marker (a report, a `compare` page, a guide, another lesson's pictures) is that
//! command's, refused even with `--force`: its marker is never replaced. A rerun removes the
//! files of the earlier run that it did not write again. A destination that is a link to a
//! folder is followed (the folder is written, the link stays); a link to nothing or a loop of
//! links is refused, and so is a mount point, which the swap cannot replace
//! ([`crate::files::check_destination`]). The files are written into a staging folder beside
//! the destination; a lock beside it (`.NAME.classic-gpgpu-lock`, a name no file of the user's
//! has; a file of that name that is not a lock is never touched) keeps two runs from writing
//! one folder at once; the final swap moves the old folder aside first, so a run killed
//! between the two renames leaves it where the next run finds and restores it.
//!
//! The rule was first the report's, and its texts still say "report" for the folder being
//! written; every command that writes a folder uses it (the guide, `compare`, `mass --dump`,
//! the `*-bench` folders), each naming itself in the marker.

use anyhow::{bail, Context as _};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The marker's file name, inside the report folder.
pub const MARKER: &str = ".classic-gpgpu-report";

/// The marker's first line for `reproduce` (anything else on it is not the report's).
const MARKER_HEADER: &str = "classic-gpgpu report: the files `classic-gpgpu reproduce` wrote \
    here (section, path); it replaces or removes only these";

/// The marker's first line for `command` (`mass --dump`): the command owns the files listed
/// under its own line only.
fn marker_header(command: &str) -> String {
    if command == REPRODUCE {
        return MARKER_HEADER.to_string();
    }
    format!(
        "classic-gpgpu files: the files `classic-gpgpu {command}` wrote here (section, path); \
         it replaces or removes only these"
    )
}

/// The command whose marker [`Owned::read`] and [`Owned::write`] read and write.
const REPRODUCE: &str = "reproduce";

/// The section name `compare` gave its files when it wrote the report's marker (before it had
/// one of its own); a report marker listing only such files is a `compare` page's.
const COMPARE: &str = "compare";

/// The command whose marker `dir` holds (`reproduce`, `compare`, `mass --dump`, ...); `None`
/// without a marker. A file of the marker's name that this program did not write is refused:
/// it is never replaced.
pub fn owner(dir: &Path) -> anyhow::Result<Option<String>> {
    let path = dir.join(MARKER);
    if std::fs::symlink_metadata(&path).is_err() {
        return Ok(None);
    }
    let not_ours = || {
        format!(
            "{}: not a marker this program wrote; it is never replaced, so move it away or \
             choose another folder",
            path.display()
        )
    };
    let text = std::fs::read_to_string(&path).with_context(not_ours)?;
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    if header == MARKER_HEADER {
        let sections: Vec<&str> = lines
            .filter_map(|l| l.split_once('\t').map(|(section, _)| section))
            .collect();
        let compare = !sections.is_empty() && sections.iter().all(|s| *s == COMPARE);
        return Ok(Some(if compare { COMPARE } else { REPRODUCE }.to_string()));
    }
    let command = header
        .strip_prefix("classic-gpgpu files: the files `classic-gpgpu ")
        .and_then(|rest| rest.split_once("` wrote here"))
        .map(|(command, _)| command.to_string());
    match command {
        Some(command) => Ok(Some(command)),
        None => bail!(not_ours()),
    }
}

/// What a report wrote: relative path (`/`-separated) to the section that wrote it (`-` for
/// the page and the results).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Owned {
    files: BTreeMap<String, String>,
}

impl Owned {
    /// The report's marker in `dir`, `None` when it has none (a folder this program did not
    /// make).
    pub fn read(dir: &Path) -> anyhow::Result<Option<Owned>> {
        Self::read_of(dir, REPRODUCE)
    }

    /// The marker `command` wrote in `dir`; `None` when there is none, or when it is another
    /// command's (whose files are not this command's to replace).
    pub fn read_of(dir: &Path, command: &str) -> anyhow::Result<Option<Owned>> {
        if owner(dir)?.as_deref() != Some(command) {
            return Ok(None);
        }
        let path = dir.join(MARKER);
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("reading {}", path.display()))?;
        let mut files = BTreeMap::new();
        for line in text.lines().skip(1).filter(|l| !l.is_empty()) {
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

    /// Writes the report's marker into `dir` (whole or not at all).
    pub fn write(&self, dir: &Path) -> anyhow::Result<()> {
        self.write_of(dir, REPRODUCE)
    }

    /// Writes `command`'s marker into `dir` (whole or not at all).
    pub fn write_of(&self, dir: &Path, command: &str) -> anyhow::Result<()> {
        let mut text = format!("{}\n", marker_header(command));
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
    check_folder("--out", REPRODUCE, out, force)
}

/// Refuses, before any work, a destination `out` (given as the option `what`) that is a
/// file, a mount point, another command's folder (even with `force`), or a folder holding
/// anything without `command`'s marker, unless `force` says to write beside those files (a
/// folder with the marker may hold files it does not list: they were there when `--force` was
/// given, and stay).
pub fn check_folder(what: &str, command: &str, out: &Path, force: bool) -> anyhow::Result<()> {
    if !out.exists() {
        return crate::files::check_destination(what, out);
    }
    if !out.is_dir() {
        bail!(
            "{what} {}: exists and is not a folder; choose another {what}",
            out.display()
        );
    }
    crate::files::check_destination(what, out)?;
    match owner(out)? {
        // Given to the command once (with --force if it held other files): those stay, and
        // are never replaced.
        Some(owner) if owner == command => return Ok(()),
        Some(owner) => bail!(
            "{what} {}: the folder is `classic-gpgpu {owner}`'s (its {MARKER} marker lists \
             the files it wrote); one command's folder is never written by another, not even \
             with --force, since each replaces only the files its own marker lists: choose \
             another {what}",
            out.display()
        ),
        None if force => return Ok(()),
        None => {}
    }
    let first = std::fs::read_dir(out)
        .with_context(|| format!("{what} {}: cannot read the folder", out.display()))?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .min();
    let Some(first) = first else {
        return Ok(());
    };
    let (whose, what_goes) = if command == REPRODUCE {
        ("a report of classic-gpgpu's".to_string(), "the report")
    } else {
        (
            format!("a folder `classic-gpgpu {command}` wrote"),
            "the files",
        )
    };
    bail!(
        "{what} {}: the folder holds files this program did not write (e.g. {first}) and no \
         {MARKER} marker, so it is not {whose}. Choose another {what}, or pass --force to \
         write {what_goes} into it (files that are not its own are never removed or replaced)",
        out.display()
    );
}

/// The folder `out` really names: a link to a folder is followed (the folder is written,
/// the link stays as it is), a link to nothing or to a file is refused, and `.` or `..` is
/// given its full name (the swap renames the folder, so it needs one).
pub fn resolve(what: &str, out: &Path) -> anyhow::Result<PathBuf> {
    let Ok(meta) = std::fs::symlink_metadata(out) else {
        return Ok(out.to_path_buf());
    };
    let target = || {
        std::fs::read_link(out)
            .map(|t| t.display().to_string())
            .unwrap_or_else(|_| "?".into())
    };
    if meta.file_type().is_symlink() {
        let real = crate::files::follow(what, out)?;
        if !real.is_dir() {
            bail!(
                "{what} {}: a link to {}, which is not a folder; give a folder",
                out.display(),
                target()
            );
        }
        return Ok(real);
    }
    if meta.is_dir() && out.file_name().is_none() {
        return std::fs::canonicalize(out)
            .with_context(|| format!("{what} {}: cannot find its full name", out.display()));
    }
    Ok(out.to_path_buf())
}

/// A folder a command writes by the one rule (see the module's doc): made with
/// [`Staged::begin`] before any work, written into at [`Staged::path`], put in place by
/// [`Staged::finish`]. Dropped unfinished (an error), it leaves the destination as it was.
pub struct Staged {
    command: String,
    /// The destination as given (a link not followed), for messages.
    given: PathBuf,
    out: PathBuf,
    staging: PathBuf,
    installing: bool,
    _lock: Lock,
}

impl Staged {
    /// Checks the destination `out` (given as option `what` of `command`, e.g. `--dump` of
    /// `mass --dump`) by the rule, locks it and makes an empty staging folder beside it.
    pub fn begin(what: &str, command: &str, given: &Path, force: bool) -> anyhow::Result<Staged> {
        let out = resolve(what, given)?;
        check_folder(what, command, &out, force)?;
        let lock = Lock::take_for(what, command, &out)?;
        recover(&out)?;
        // Checked again under the lock: a recovered folder is a folder too.
        check_folder(what, command, &out, force)?;
        let staging = staging_of(&out, std::process::id())?;
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("removing {}", staging.display()))?;
        }
        std::fs::create_dir_all(&staging).with_context(|| {
            format!(
                "{what} {}: creating the folder {} that the files are written into first",
                out.display(),
                staging.display()
            )
        })?;
        Ok(Staged {
            command: command.to_string(),
            given: given.to_path_buf(),
            out,
            staging,
            installing: false,
            _lock: lock,
        })
    }

    /// Where the files are written (a staging folder beside the destination).
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The destination (a link followed).
    pub fn out(&self) -> &Path {
        &self.out
    }

    /// Where `path`, written under [`Staged::path`], will be once finished, under the
    /// destination as it was given (for messages); other paths as they are.
    pub fn shown(&self, path: &Path) -> PathBuf {
        match path.strip_prefix(&self.staging) {
            Ok(relative) => self.given.join(relative),
            Err(_) => path.to_path_buf(),
        }
    }

    /// Puts every file written at [`Staged::path`] in place, with the marker listing them;
    /// the earlier run's files that this one did not write again are removed. Returns the
    /// files, relative to the destination.
    pub fn finish(mut self) -> anyhow::Result<Vec<String>> {
        let files = list_files(&self.staging)?;
        let mut owned = Owned::default();
        for file in &files {
            owned.add("-", file);
        }
        owned.write_of(&self.staging, &self.command)?;
        // From here on a failure names the staging folder as holding the files: keep it.
        self.installing = true;
        install_of(&self.staging, &self.out, &owned, &self.command)?;
        Ok(files)
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.installing {
            std::fs::remove_dir_all(&self.staging).ok();
        }
    }
}

/// The lock of one report folder: held while a run reads the old report and writes the new
/// one, released when dropped (or when the process dies, however it dies). A run that ends
/// normally removes the lock file; one that was killed leaves it, and the next run reuses it.
pub struct Lock {
    file: std::fs::File,
    path: PathBuf,
}

impl Lock {
    /// Takes the lock of the report `out`, a file `.NAME.classic-gpgpu-lock` beside it;
    /// refuses clearly when another run holds it.
    pub fn take(out: &Path) -> anyhow::Result<Lock> {
        Self::take_for("--out", REPRODUCE, out)
    }

    /// Takes the lock of the folder `out` that `command` writes (its option `what`).
    pub fn take_for(what: &str, command: &str, out: &Path) -> anyhow::Result<Lock> {
        let (parent, name) = parent_and_name(out)?;
        std::fs::create_dir_all(&parent)
            .with_context(|| format!("creating {}", parent.display()))?;
        let path = parent.join(format!(".{name}.{LOCK_SUFFIX}"));
        // A holder removes the file before it unlocks, so a lock taken on a file that is no
        // longer at `path` is stale: open the file at `path` again.
        for _ in 0..16 {
            let (file, made) = open_lock_file(&path)?;
            if !made && !is_a_lock(&path) {
                bail!(
                    "{what} {}: {} is in the way of this program's lock: a file of that name \
                     that it did not write, which it never removes; move it away, or choose \
                     another {what}",
                    out.display(),
                    path.display()
                );
            }
            match rustix::fs::flock(&file, rustix::fs::FlockOperation::NonBlockingLockExclusive) {
                Ok(()) if still_at(&file, &path) => {
                    use std::io::Write as _;
                    // Held from here: a failed write (a full disk) drops it, removing the file.
                    let lock = Lock { file, path };
                    (&lock.file)
                        .write_all(LOCK_TEXT.as_bytes())
                        .with_context(|| {
                            format!(
                                "{what} {}: writing the lock {} (is its file system full?); \
                                 nothing was written",
                                out.display(),
                                lock.path.display()
                            )
                        })?;
                    return Ok(lock);
                }
                Ok(()) => continue,
                Err(rustix::io::Errno::WOULDBLOCK) => bail!(
                    "{what} {}: another `classic-gpgpu {command}` is writing this {} now (it \
                     holds {}); run again when it has finished, or choose another {what}",
                    out.display(),
                    if command == REPRODUCE {
                        "report"
                    } else {
                        "folder"
                    },
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

/// The end of a lock file's name: `.NAME.classic-gpgpu-lock` beside the folder NAME.
pub const LOCK_SUFFIX: &str = "classic-gpgpu-lock";

/// What a lock file says, for whoever finds one (the lock itself is the file's flock).
const LOCK_TEXT: &str = "classic-gpgpu: the lock of a run writing the folder beside this \
    file; the run removes it when it ends\n";

/// Opens the lock file at `path`, made if missing; and whether this call made it.
fn open_lock_file(path: &Path) -> anyhow::Result<(std::fs::File, bool)> {
    let open = |new: bool| {
        std::fs::OpenOptions::new()
            .create_new(new)
            .create(!new)
            .truncate(false)
            .write(true)
            .open(path)
    };
    match open(true) {
        Ok(file) => Ok((file, true)),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => open(false)
            .map(|file| (file, false))
            .with_context(|| format!("opening the lock {}", path.display())),
        Err(e) => Err(e).with_context(|| format!("opening the lock {}", path.display())),
    }
}

/// Whether the file at `path` is a lock of this program's: its text, or empty (a run killed
/// between making the file and writing it).
fn is_a_lock(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file())
        && std::fs::read(path).is_ok_and(|b| b.is_empty() || b == LOCK_TEXT.as_bytes())
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
    install_of(staging, out, owned, REPRODUCE)
}

/// [`install`] for the folder `command` writes.
pub fn install_of(staging: &Path, out: &Path, owned: &Owned, command: &str) -> anyhow::Result<()> {
    let old = match Owned::read_of(out, command)? {
        Some(old) => old,
        None if command == REPRODUCE => Owned::from_results(out),
        None => Owned::default(),
    };
    let present = list_files(out)?;
    let foreign: Vec<&String> = present.iter().filter(|f| !old.contains(f)).collect();
    // What the messages call the finished files: reproduce's are a report.
    let finished = if command == REPRODUCE {
        "report"
    } else {
        "output"
    };
    let kept = |e: anyhow::Error| {
        e.context(format!(
            "the finished {finished} is in {}; {} is as it was",
            staging.display(),
            out.display()
        ))
    };
    // The working folder is never swapped away (a shell in it would be left in a removed
    // folder): its files go in one by one.
    if foreign.is_empty() && only_files_of(out, &old) && !is_working_folder(out) {
        return swap(staging, out);
    }
    if let Some(clash) = foreign.iter().find(|f| owned.contains(f)) {
        return Err(kept(anyhow::anyhow!(
            "{} in {} is not {}'s, and it wrote a file of that name; move that file \
             away, or choose another folder",
            clash,
            out.display(),
            if command == REPRODUCE {
                "the report".to_string()
            } else {
                format!("`classic-gpgpu {command}`")
            }
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
                    "the rest of the finished {finished} is in {}",
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

/// Whether everything in `out` is `old`'s (a folder of the user's, even empty, is not).
fn only_files_of(out: &Path, old: &Owned) -> bool {
    let Ok(entries) = std::fs::read_dir(out) else {
        return true;
    };
    entries.flatten().all(|e| {
        let name = e.file_name().to_string_lossy().into_owned();
        let under = format!("{name}/");
        name == MARKER || old.files().any(|(_, f)| f == name || f.starts_with(&under))
    })
}

fn is_working_folder(out: &Path) -> bool {
    std::env::current_dir().is_ok_and(|cwd| same_folder(&cwd, out))
}

fn same_folder(a: &Path, b: &Path) -> bool {
    matches!(
        (std::fs::canonicalize(a), std::fs::canonicalize(b)),
        (Ok(a), Ok(b)) if a == b
    )
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

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("cg-staged-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// One run of a writer of `files` into `out`.
    fn write(out: &Path, force: bool, files: &[&str]) -> anyhow::Result<Vec<String>> {
        let staged = Staged::begin("--dump", "test --dump", out, force)?;
        for f in files {
            crate::files::write_bytes(&staged.path().join(f), f.as_bytes())?;
        }
        staged.finish()
    }

    fn names(dir: &Path) -> Vec<String> {
        list_files(dir).unwrap()
    }

    #[test]
    fn a_folder_writer_owns_only_what_it_wrote() {
        let dir = scratch("rule");
        let out = dir.join("dump");
        write(&out, false, &["peel0.png", "peel1.png", "sub/peel2.png"]).unwrap();
        assert_eq!(names(&out), ["peel0.png", "peel1.png", "sub/peel2.png"]);
        // A rerun that writes fewer files removes the earlier run's others.
        write(&out, false, &["peel0.png"]).unwrap();
        assert_eq!(names(&out), ["peel0.png"]);
        // A folder of the user's (no marker): refused without --force, nothing touched.
        let theirs = dir.join("theirs");
        std::fs::create_dir_all(&theirs).unwrap();
        std::fs::write(theirs.join("notes.txt"), "mine").unwrap();
        let err = format!("{:#}", write(&theirs, false, &["peel0.png"]).unwrap_err());
        assert!(
            err.contains("notes.txt") && err.contains("--force"),
            "{err}"
        );
        assert_eq!(names(&theirs), ["notes.txt"]);
        // With --force the note stays, and the writer's files go in beside it.
        write(&theirs, true, &["peel1.png"]).unwrap();
        assert_eq!(names(&theirs), ["notes.txt", "peel1.png"]);
        assert_eq!(
            std::fs::read_to_string(theirs.join("notes.txt")).unwrap(),
            "mine"
        );
        std::fs::remove_dir_all(&theirs).unwrap();
        // A file put later into a folder that has the writer's marker is kept too (the
        // marker does not list it), and a rerun needs no --force.
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        write(&out, false, &["peel1.png"]).unwrap();
        assert_eq!(names(&out), ["notes.txt", "peel1.png"]);
        assert_eq!(
            std::fs::read_to_string(out.join("notes.txt")).unwrap(),
            "mine"
        );
        // A file of the user's with a name the writer writes is never replaced: the new
        // files stay in the staging folder the message names.
        let err = format!("{:#}", write(&out, true, &["notes.txt"]).unwrap_err());
        assert!(
            err.contains("notes.txt") && err.contains("move that file"),
            "{err}"
        );
        assert_eq!(
            std::fs::read_to_string(out.join("notes.txt")).unwrap(),
            "mine"
        );
        let staging = staging_of(&out, std::process::id()).unwrap();
        assert!(err.contains(&staging.display().to_string()), "{err}");
        assert_eq!(
            std::fs::read(staging.join("notes.txt")).unwrap(),
            b"notes.txt"
        );
        std::fs::remove_dir_all(&staging).unwrap();
        // Another command's folder is not this one's.
        let theirs = Staged::begin("--out", "other --out", &out, false).err();
        assert!(format!("{theirs:?}").contains("--force"), "{theirs:?}");
        // Nothing is left beside the folder: no staging folder, no lock.
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "{:?}",
            std::fs::read_dir(&dir).unwrap().collect::<Vec<_>>()
        );
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_failed_writer_leaves_the_folder_as_it_was() {
        let dir = scratch("failed");
        let out = dir.join("dump");
        write(&out, false, &["a.png", "b.png"]).unwrap();
        let staged = Staged::begin("--dump", "test --dump", &out, false).unwrap();
        crate::files::write_bytes(&staged.path().join("a.png"), b"new").unwrap();
        drop(staged); // an error before finish
        assert_eq!(names(&out), ["a.png", "b.png"]);
        assert_eq!(std::fs::read(out.join("a.png")).unwrap(), b"a.png");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_linked_destination_is_followed_and_a_dangling_link_refused() {
        let dir = scratch("link");
        let real = dir.join("real");
        std::fs::create_dir_all(&real).unwrap();
        let link = dir.join("link");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write(&link, false, &["a.png"]).unwrap();
        write(&link, false, &["b.png"]).unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(names(&real), ["b.png"]);
        let dangling = dir.join("dangling");
        std::os::unix::fs::symlink(dir.join("nowhere"), &dangling).unwrap();
        let err = format!("{:#}", write(&dangling, true, &["a.png"]).unwrap_err());
        assert!(
            err.contains("does not exist") && err.contains("nowhere"),
            "{err}"
        );
        assert!(!dir.join("nowhere").exists());
        let file = dir.join("file");
        std::fs::write(&file, "x").unwrap();
        let err = format!("{:#}", write(&file, true, &["a.png"]).unwrap_err());
        assert!(err.contains("not a folder"), "{err}");
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "x");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn one_run_holds_the_lock_and_leaves_no_file() {
        let dir = std::env::temp_dir().join(format!("cg-lock-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let out = dir.join("report");
        let lock_file = dir.join(".report.classic-gpgpu-lock");
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

    #[test]
    fn another_commands_folder_is_refused_even_with_force_and_its_marker_kept() {
        let dir = scratch("others");
        let out = dir.join("dump");
        write(&out, false, &["a.png"]).unwrap();
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        let marker = std::fs::read(out.join(MARKER)).unwrap();
        let err = format!(
            "{:#}",
            Staged::begin("--png", "other --png", &out, true)
                .err()
                .unwrap()
        );
        assert!(
            err.contains("is `classic-gpgpu test --dump`'s")
                && err.contains("not even with --force"),
            "{err}"
        );
        // The refusal names whose folder it is, never the marker as a file of someone else's.
        assert!(!err.contains("e.g."), "{err}");
        assert_eq!(std::fs::read(out.join(MARKER)).unwrap(), marker);
        // A report is `reproduce`'s; a page `compare` wrote with the report's marker (its
        // files all of section "compare") is `compare`'s, refused to `reproduce`.
        let report = dir.join("report");
        std::fs::create_dir_all(&report).unwrap();
        let mut owned = Owned::default();
        owned.add("paper1", "fig.png");
        owned.write(&report).unwrap();
        assert_eq!(owner(&report).unwrap().as_deref(), Some(REPRODUCE));
        let page = dir.join("page");
        std::fs::create_dir_all(&page).unwrap();
        let mut owned = Owned::default();
        owned.add(COMPARE, "comparison.json");
        owned.write(&page).unwrap();
        assert_eq!(owner(&page).unwrap().as_deref(), Some(COMPARE));
        let err = format!("{:#}", check_out(&page, true).unwrap_err());
        assert!(err.contains("is `classic-gpgpu compare`'s"), "{err}");
        assert!(Owned::read(&page).unwrap().is_none());
        // A file at the marker's name that this program did not write is never replaced.
        let theirs = dir.join("theirs");
        std::fs::create_dir_all(&theirs).unwrap();
        std::fs::write(theirs.join(MARKER), "my notes").unwrap();
        let err = format!("{:#}", write(&theirs, true, &["a.png"]).unwrap_err());
        assert!(err.contains("not a marker this program wrote"), "{err}");
        assert_eq!(
            std::fs::read_to_string(theirs.join(MARKER)).unwrap(),
            "my notes"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn the_lock_has_a_name_of_its_own_and_never_removes_a_users_file() {
        let dir = scratch("lock-name");
        let out = dir.join("dump");
        // The name the lock had before: a user's file, untouched by a run.
        std::fs::write(dir.join(".dump.lock"), "mine").unwrap();
        write(&out, false, &["a.png"]).unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.join(".dump.lock")).unwrap(),
            "mine"
        );
        assert!(!dir.join(".dump.classic-gpgpu-lock").exists());
        // A file at the lock's own name that is not a lock: refused, kept.
        let lock = dir.join(".other.classic-gpgpu-lock");
        std::fs::write(&lock, "mine").unwrap();
        let err = format!(
            "{:#}",
            write(&dir.join("other"), false, &["a.png"]).unwrap_err()
        );
        assert!(err.contains("in the way"), "{err}");
        assert_eq!(std::fs::read_to_string(&lock).unwrap(), "mine");
        assert!(!dir.join("other").exists());
        // A lock a killed run left (its text, or empty) is taken over and removed.
        std::fs::write(&lock, LOCK_TEXT).unwrap();
        write(&dir.join("other"), false, &["a.png"]).unwrap();
        assert!(!lock.exists());
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_mount_point_is_refused_before_any_work() {
        // /proc is where the kernel's file system is mounted, on every Linux.
        let proc = Path::new("/proc");
        if crate::files::is_mount_point(proc) {
            let err = format!(
                "{:#}",
                check_folder("--out", REPRODUCE, proc, true).unwrap_err()
            );
            assert!(err.contains("a mount point"), "{err}");
        }
    }
}
