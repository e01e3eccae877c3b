//! Every file the project writes goes through here, so that nothing of the user's is lost and
//! no file is ever left half-written:
//! - [`check_destination`] is the rule of every path written, file or folder: a link is
//!   followed to what it names, a link to nothing or a loop of links is refused (writing
//!   would replace the link), and so is a mount point (a finished output is put in place by a
//!   rename, which cannot replace one);
//! - [`check_output`] runs before any work: the rule above, and an input is never overwritten (not even with
//!   `--force`), an existing file only with `--force`, a folder is not a file, and the name's
//!   extension must be the format that will be written;
//! - [`write()`] writes to a temporary file in the same folder, flushes and syncs it, checks every
//!   error, and only then renames it into place: a full disk or a kill leaves the old file as it
//!   was (and at worst a `.NAME.tmp-PID` beside it), never an empty or truncated one;
//! - [`write_png`] and [`write_npy`] encode in memory first and write through [`write()`].

use anyhow::{bail, Context as _};
use std::io::Write;
use std::path::{Path, PathBuf};

/// An error and its causes on one line, as `{:#}` writes them, but without a cause that only
/// repeats what the line already says (some libraries' errors print their source too).
pub fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let cause = cause.to_string();
        if text.is_empty() {
            text = cause;
        } else if !text.contains(&cause) {
            text = format!("{text}: {cause}");
        }
    }
    text
}

/// Refuses `out` before anything is computed or touched: over one of `inputs` (ever), over an
/// existing file without `force`, over a folder, or with an extension other than one of
/// `extensions` (lower case, without the dot; empty accepts any). `what` names the option
/// (`--png`, `--out`) in the message.
pub fn check_output(
    what: &str,
    out: &Path,
    inputs: &[&Path],
    force: bool,
    extensions: &[&str],
) -> anyhow::Result<()> {
    check_destination(what, out)?;
    if let Some(input) = inputs.iter().find(|input| same_file(out, input)) {
        bail!(
            "{what} {} is the input {}; an input is never overwritten (not even with --force), \
             so write to another file",
            out.display(),
            input.display()
        );
    }
    if out.is_dir() {
        bail!("{what} {} is a folder; give a file name", out.display());
    }
    if !extensions.is_empty() {
        let ext = out
            .extension()
            .map(|e| e.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        if !extensions.contains(&ext.as_str()) {
            bail!(
                "{what} {}: the file is written as {}, so its name must end in .{}",
                out.display(),
                extensions[0].to_uppercase(),
                extensions.join(" or .")
            );
        }
    }
    if out.exists() && !force {
        bail!(
            "{what} {} exists; pass --force to replace it",
            out.display()
        );
    }
    Ok(())
}

/// The rule of every path the program writes (a file or a folder), before any work: a link to
/// nothing and a loop of links are refused, naming the link and where it leads; a mount point
/// is refused (outputs are put in place by a rename, which cannot replace a mount point, so the
/// run would fail after all its work). `what` names the option in the message.
pub fn check_destination(what: &str, path: &Path) -> anyhow::Result<()> {
    let real = follow(what, path)?;
    if is_mount_point(&real) {
        bail!(
            "{what} {}: a mount point (another file system is mounted there); an output is put \
             in place by renaming a finished copy over it, which cannot replace a mount point, \
             so give a path inside it (e.g. {})",
            path.display(),
            path.join("out").display()
        );
    }
    Ok(())
}

/// Where writing `path` writes: `path` itself, or what a link there names. A link to nothing
/// and a loop of links are refused: writing would replace the link with a file.
pub fn follow(what: &str, path: &Path) -> anyhow::Result<PathBuf> {
    let is_link = std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
    if !is_link {
        return Ok(path.to_path_buf());
    }
    let target = std::fs::read_link(path)
        .map(|t| t.display().to_string())
        .unwrap_or_else(|_| "?".into());
    let named = if what.is_empty() {
        path.display().to_string()
    } else {
        format!("{what} {}", path.display())
    };
    match std::fs::canonicalize(path) {
        Ok(real) => Ok(real),
        Err(e) if e.raw_os_error() == Some(rustix::io::Errno::LOOP.raw_os_error()) => bail!(
            "{named}: a link to {target}, which leads back to itself (a loop of links); nothing \
             is written through it: remove the loop, or give another path"
        ),
        Err(_) => bail!(
            "{named}: a link to {target}, which does not exist; nothing is written through a \
             link to nothing (the link would be replaced): create {target} first, or give \
             another path"
        ),
    }
}

/// Whether `path` (existing, links followed) is where a file system is mounted: its device
/// differs from its parent's, or /proc/self/mountinfo lists it (a bind mount of a folder of the
/// same file system). The root is one.
pub fn is_mount_point(path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    let Ok(real) = std::fs::canonicalize(path) else {
        return false;
    };
    let Some(parent) = real.parent() else {
        return true;
    };
    if let (Ok(a), Ok(b)) = (std::fs::metadata(&real), std::fs::metadata(parent)) {
        if a.dev() != b.dev() {
            return true;
        }
    }
    let Ok(mounts) = std::fs::read_to_string("/proc/self/mountinfo") else {
        return false;
    };
    // The fifth field is the mount point, with spaces and the like written as \040 etc.
    mounts
        .lines()
        .filter_map(|l| l.split(' ').nth(4))
        .any(|m| Path::new(&unescape_mount(m)) == real)
}

/// A mount point as mountinfo writes it (`\040` for a space) back as the path.
fn unescape_mount(text: &str) -> String {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let octal = bytes.get(i + 1..i + 4).and_then(|d| {
            std::str::from_utf8(d)
                .ok()
                .and_then(|d| u8::from_str_radix(d, 8).ok())
        });
        match (bytes[i], octal) {
            (b'\\', Some(byte)) => {
                out.push(byte);
                i += 4;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Refuses `dir` as a folder to write files into when it exists and is not a folder (checked
/// before any work, like [`check_output`]); the files in it are written through [`write()`].
pub fn check_folder(what: &str, dir: &Path) -> anyhow::Result<()> {
    check_destination(what, dir)?;
    if dir.exists() && !dir.is_dir() {
        bail!(
            "{what} {} is a file; give a folder to write the files into",
            dir.display()
        );
    }
    Ok(())
}

/// Whether two paths name one existing file (through links, `.`/`..`, or hard links).
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b || same_inode(&a, &b),
        _ => false,
    }
}

#[cfg(unix)]
fn same_inode(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => (a.dev(), a.ino()) == (b.dev(), b.ino()),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_inode(_: &Path, _: &Path) -> bool {
    false
}

/// Writes `path` whole or not at all: `contents` writes into a temporary file beside it, which
/// is flushed, synced and renamed over `path`. Missing parent folders are created. On any error
/// the temporary file is removed and `path` is as it was. A link is written through (the file
/// it names is replaced, the link stays); a link to nothing is refused ([`follow`]).
pub fn write(
    path: &Path,
    contents: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let path = &follow("", path)?;
    let dir = match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => {
            create_folder(dir)?;
            dir.to_path_buf()
        }
        None => PathBuf::from("."),
    };
    let tmp = temporary_name(path, &dir)?;
    let result = write_synced(&tmp, contents).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(e).with_context(|| format!("writing {}", path.display()));
    }
    // The rename itself is durable once the folder is synced (not every file system allows it).
    if let Ok(folder) = std::fs::File::open(&dir) {
        let _ = folder.sync_all();
    }
    remove_stale_temporaries(path, &dir);
    Ok(())
}

/// Makes `dir` and its parents; where a part of the path is a file, says which (not the
/// system's bare "File exists").
pub fn create_folder(dir: &Path) -> anyhow::Result<()> {
    let Err(e) = std::fs::create_dir_all(dir) else {
        return Ok(());
    };
    let file = dir
        .ancestors()
        .find(|a| !a.as_os_str().is_empty() && a.exists() && !a.is_dir());
    match file {
        Some(file) => bail!(
            "cannot create the folder {}: {} is a file, not a folder; give a path whose \
             folders are folders",
            dir.display(),
            file.display()
        ),
        None => Err(e).with_context(|| format!("creating the folder {}", dir.display())),
    }
}

/// Removes the temporary files of `path` that killed runs left (`.NAME.tmp-PID` whose process
/// is gone). Only where `/proc` says which processes live; a live PID's file is never touched.
fn remove_stale_temporaries(path: &Path, dir: &Path) {
    let Some(name) = path.file_name() else { return };
    if !Path::new("/proc/self").exists() {
        return;
    }
    let prefix = format!(".{}.tmp-", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let entry_name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = entry_name.strip_prefix(&prefix) else {
            continue;
        };
        let gone = pid.parse::<u32>().is_ok_and(|pid| {
            pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists()
        });
        if gone {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// `bytes` written to `path` through [`write()`].
pub fn write_bytes(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write(path, |w| w.write_all(bytes))
}

fn temporary_name(path: &Path, dir: &Path) -> anyhow::Result<PathBuf> {
    let name = path
        .file_name()
        .with_context(|| format!("{} names no file", path.display()))?;
    Ok(dir.join(format!(
        ".{}.tmp-{}",
        name.to_string_lossy(),
        std::process::id()
    )))
}

fn write_synced(
    tmp: &Path,
    contents: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let file = std::fs::File::create(tmp)?;
    let mut writer = std::io::BufWriter::new(file);
    contents(&mut writer)?;
    let file = writer.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()
}

/// An RGBA8 image, rows top first as images are stored, written to `path` as PNG.
pub fn write_png(path: &Path, rgba: &[u8], width: u32, height: u32) -> anyhow::Result<()> {
    write_bytes(path, &encode_png(rgba, width, height)?)
}

/// An RGBA8 image as the bytes of a PNG file.
pub fn encode_png(rgba: &[u8], width: u32, height: u32) -> anyhow::Result<Vec<u8>> {
    use image::ImageEncoder as _;
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(rgba, width, height, image::ExtendedColorType::Rgba8)
        .context("encoding a PNG")?;
    Ok(png)
}

/// Any image (`image`'s buffers: luma, RGB, RGBA) written to `path` as PNG through [`write()`].
pub fn write_image(path: &Path, image: &image::DynamicImage) -> anyhow::Result<()> {
    let mut png = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut png, image::ImageFormat::Png)
        .with_context(|| format!("encoding {} as PNG", path.display()))?;
    write_bytes(path, png.get_ref())
}

/// `data` (row-major, C order) with `shape` written to `path` in numpy's `.npy` format, float32
/// little-endian: `numpy.load(path)` gives the exact values.
pub fn write_npy(path: &Path, shape: &[usize], data: &[f32]) -> anyhow::Result<()> {
    use ndarray_npy::WriteNpyExt as _;
    let array =
        ndarray::ArrayViewD::from_shape(ndarray::IxDyn(shape), data).with_context(|| {
            format!(
                "{}: {} values do not fill shape {shape:?}",
                path.display(),
                data.len()
            )
        })?;
    let mut npy = Vec::new();
    array
        .write_npy(&mut npy)
        .with_context(|| format!("encoding {} as .npy", path.display()))?;
    write_bytes(path, &npy)
}

/// The most bytes an image may take decoded: the `image` crate's own default allocation
/// limit, said in the message with the size the file's header claims.
pub const IMAGE_DECODE_LIMIT: u64 = 512 << 20;

/// The image at `path` (the `what` in messages: "image", "height map"), decoded after its
/// header's size is checked against [`IMAGE_DECODE_LIMIT`]: a file claiming more pixels than
/// fit is refused with its size, not a bare "Memory limit exceeded".
pub fn read_image(path: &Path, what: &str) -> anyhow::Result<image::DynamicImage> {
    use image::ImageDecoder as _;
    let cannot = || format!("cannot read the {what} {}", path.display());
    let decoder = image::ImageReader::open(path)
        .with_context(cannot)?
        .with_guessed_format()
        .with_context(cannot)?
        .into_decoder()
        .with_context(cannot)?;
    let (width, height) = decoder.dimensions();
    let bytes = decoder.total_bytes();
    if bytes > IMAGE_DECODE_LIMIT {
        bail!(
            "the {what} {}: its header says {width} x {height} pixels, {:.1} GiB decoded, over \
             the {} MiB this program decodes an image into; give a smaller image",
            path.display(),
            bytes as f64 / (1u64 << 30) as f64,
            IMAGE_DECODE_LIMIT >> 20
        );
    }
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(IMAGE_DECODE_LIMIT.max(bytes) + (64 << 20));
    let mut decoder = decoder;
    decoder.set_limits(limits).with_context(cannot)?;
    image::DynamicImage::from_decoder(decoder).with_context(cannot)
}

/// A `.npy` file of float32 values: its shape and values (for tests and for checking dumps).
pub fn read_npy(path: &Path) -> anyhow::Result<(Vec<usize>, Vec<f32>)> {
    use ndarray_npy::ReadNpyExt as _;
    let file = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let array = ndarray::ArrayD::<f32>::read_npy(file)
        .with_context(|| format!("reading {} as a float32 .npy", path.display()))?;
    let shape = array.shape().to_vec();
    Ok((shape, array.iter().copied().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("classic-gpgpu-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = scratch("failed");
        let path = dir.join("kept.txt");
        std::fs::write(&path, "old").unwrap();
        let err = write(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert!(format!("{err:#}").contains("disk full"), "{err:#}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "temporary left behind"
        );
    }

    #[test]
    fn a_write_removes_what_killed_writers_left() {
        let dir = scratch("stale");
        let path = dir.join("out.json");
        // PID 0 is never a process of ours; a live PID (ours, in another name) stays.
        let stale = dir.join(".out.json.tmp-0");
        let foreign = dir.join(".other.json.tmp-0");
        let not_a_pid = dir.join(".out.json.tmp-x");
        for f in [&stale, &foreign, &not_a_pid] {
            std::fs::write(f, "left by a killed run").unwrap();
        }
        write_bytes(&path, b"new").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        assert_eq!(stale.exists(), !Path::new("/proc/self").exists());
        assert!(foreign.exists() && not_a_pid.exists());
    }

    #[test]
    fn a_write_replaces_whole() {
        let dir = scratch("whole");
        let path = dir.join("sub/new.txt");
        write_bytes(&path, b"one").unwrap();
        write_bytes(&path, b"two").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "two");
    }

    #[test]
    fn outputs_are_checked_before_anything_is_written() {
        let dir = scratch("check");
        let input = dir.join("in.png");
        std::fs::write(&input, "x").unwrap();
        let err = |out: &Path, force, ext: &[&str]| {
            check_output("--out", out, &[&input], force, ext)
                .unwrap_err()
                .to_string()
        };
        assert!(err(&input, true, &["png"]).contains("is the input"));
        assert!(err(&input, false, &[]).contains("is the input"));
        assert!(err(&dir.join("a.jpg"), false, &["png"]).contains("must end in .png"));
        assert!(err(&dir, true, &["png"]).contains("is a folder"));
        let other = dir.join("other.png");
        std::fs::write(&other, "y").unwrap();
        assert!(err(&other, false, &["png"]).contains("pass --force"));
        check_output("--out", &other, &[&input], true, &["png"]).unwrap();
        check_output("--out", &dir.join("new.PNG"), &[&input], false, &["png"]).unwrap();
    }

    #[test]
    fn a_cause_that_repeats_the_message_is_said_once() {
        let repeated = anyhow::anyhow!("Invalid PNG signature.")
            .context("Invalid PNG signature.")
            .context("cannot read the image a.png");
        assert_eq!(
            error_text(&repeated),
            "cannot read the image a.png: Invalid PNG signature."
        );
        let distinct = anyhow::anyhow!("disk full").context("writing a.png");
        assert_eq!(error_text(&distinct), "writing a.png: disk full");
    }

    #[test]
    fn a_file_is_not_a_folder_to_write_into() {
        let dir = scratch("folder");
        let file = dir.join("f");
        std::fs::write(&file, "x").unwrap();
        let err = check_folder("--dump", &file).unwrap_err().to_string();
        assert!(err.contains("--dump") && err.contains("is a file"), "{err}");
        check_folder("--dump", &dir).unwrap();
        check_folder("--dump", &dir.join("new")).unwrap();
    }

    #[test]
    fn a_hard_link_to_an_input_is_the_input() {
        let dir = scratch("link");
        let input = dir.join("in.png");
        std::fs::write(&input, "x").unwrap();
        let link = dir.join("link.png");
        std::fs::hard_link(&input, &link).unwrap();
        assert!(same_file(&link, &input));
        assert!(!same_file(&dir.join("other.png"), &input));
    }

    #[test]
    fn npy_round_trips_exact_values() {
        let dir = scratch("npy");
        let path = dir.join("a.npy");
        let data = [0.0f32, -1.5, f32::MIN_POSITIVE, 1e30, 3.25, -0.0];
        write_npy(&path, &[2, 3], &data).unwrap();
        let (shape, back) = read_npy(&path).unwrap();
        assert_eq!(shape, [2, 3]);
        assert_eq!(
            back.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            data.map(f32::to_bits)
        );
        assert!(write_npy(&path, &[4, 3], &data).is_err());
    }

    #[test]
    fn png_round_trips() {
        let dir = scratch("png");
        let path = dir.join("a.png");
        let rgba: Vec<u8> = (0..2 * 3 * 4).map(|i| (i * 10) as u8).collect();
        write_png(&path, &rgba, 2, 3).unwrap();
        let back = image::open(&path).unwrap().to_rgba8();
        assert_eq!(back.dimensions(), (2, 3));
        assert_eq!(back.into_raw(), rgba);
    }

    #[test]
    fn a_link_is_written_through_and_a_link_to_nothing_or_a_loop_refused() {
        let dir = scratch("links");
        let target = dir.join("target.txt");
        std::fs::write(&target, "old").unwrap();
        let link = dir.join("link.txt");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_bytes(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        let dangling = dir.join("dangling.txt");
        std::os::unix::fs::symlink(dir.join("nowhere.txt"), &dangling).unwrap();
        let err = check_output("--out", &dangling, &[], true, &["txt"])
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with(&format!("--out {}: a link to", dangling.display()))
                && err.contains("which does not exist"),
            "{err}"
        );
        let err = format!("{:#}", write_bytes(&dangling, b"x").unwrap_err());
        assert!(err.contains("does not exist"), "{err}");
        assert!(std::fs::symlink_metadata(&dangling).unwrap().is_symlink());
        assert!(!dir.join("nowhere.txt").exists());
        let (a, b) = (dir.join("a"), dir.join("b"));
        std::os::unix::fs::symlink(&b, &a).unwrap();
        std::os::unix::fs::symlink(&a, &b).unwrap();
        let err = check_destination("--png", &a).unwrap_err().to_string();
        assert!(err.contains("a loop of links"), "{err}");
    }

    #[test]
    fn mount_points_are_found() {
        assert_eq!(unescape_mount("/mnt/my\\040disk"), "/mnt/my disk");
        assert_eq!(unescape_mount("/plain"), "/plain");
        assert!(is_mount_point(Path::new("/")));
        let dir = scratch("mount");
        assert!(!is_mount_point(&dir));
        assert!(!is_mount_point(&dir.join("missing")));
        if is_mount_point(Path::new("/proc")) {
            let err = check_destination("--out", Path::new("/proc"))
                .unwrap_err()
                .to_string();
            assert!(err.contains("--out /proc: a mount point"), "{err}");
        }
    }
}
