//! Writing files so that a reader never sees a half-written one: write a
//! temporary file beside the target, then rename it over the target.
//!
//! Only regular files are ever replaced. A symbolic link is written through:
//! the file it names is replaced, atomically, by a temporary file beside it.
//! A directory, FIFO, device or socket at the path is refused. Temporary
//! files are named `.<name>.vstf-tmp-<pid>`, so that they can be recognised
//! (`.gitignore` ignores them) and removed by a later run once the process
//! that wrote them is gone ([`remove_stale`]).

use crate::error::Error;
use std::io::Write;
use std::path::{Path, PathBuf};

mod exr_file;
mod still;
pub mod video;

pub use exr_file::{write_exr, ExrMeta, AOV_CHANNELS};
pub use still::{write_8bit, write_jpeg, StillFormat, JPEG_QUALITY, STILL_EXTENSIONS};

/// Extensions of files that vstf does not write but that name a file, not
/// a folder: an `--out` ending in one is refused rather than made a folder
/// of frames.
const FILE_EXTENSIONS: &[&str] = &[
    "jpg", "jpeg", "exr", "tif", "tiff", "bmp", "webp", "avif", "heic", "heif", "tga", "ppm",
    "pgm", "pnm", "hdr", "svg", "pdf", "mov", "mkv", "avi", "m4v", "ogv", "ogg", "mpg", "mpeg",
    "wmv", "flv", "3gp", "h264", "hevc", "y4m", "mjpeg", "json", "txt", "html", "zip", "tar", "gz",
];

/// The lower-case extension of `path`'s file name, if it has one.
pub(crate) fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// Whether `path` ends in the extension of a kind of file (one vstf writes
/// or not): such a path must never become a folder.
pub(crate) fn names_a_file(path: &Path) -> bool {
    extension(path).is_some_and(|e| {
        FILE_EXTENSIONS.contains(&e.as_str())
            || matches!(e.as_str(), "png" | "apng" | "gif" | "mp4" | "webm")
    })
}

/// Refuses now, before any work, an output that could not be written at
/// the end: something at `path` that is not a regular file (a folder, a
/// FIFO, a device).
pub fn writable_file(path: &Path) -> Result<(), String> {
    regular_target(path)
        .map(drop)
        .map_err(|e| format!("--out {}: {e}", path.display()))
}

/// The marker in every temporary file's name.
pub(crate) const TEMP_MARK: &str = ".vstf-tmp-";

/// Most symbolic links followed from one output path.
const MAX_LINKS: usize = 40;

/// Writes `bytes` to `path` atomically, creating parent folders; through a
/// symbolic link to the file it names; never over anything but a regular file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let target = regular_target(path)?;
    if let Some(dir) = target.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    remove_stale_beside(&target);
    let tmp = temp_path(&target);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, &target)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// The file a write to `path` replaces: `path` itself, or the end of the
/// chain of symbolic links it starts; an error if that is not a regular file
/// (or nothing yet).
fn regular_target(path: &Path) -> std::io::Result<PathBuf> {
    let mut target = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        let Ok(meta) = std::fs::symlink_metadata(&target) else {
            return Ok(target);
        };
        let kind = meta.file_type();
        if kind.is_symlink() {
            let link = std::fs::read_link(&target)?;
            target = match target.parent() {
                Some(dir) if link.is_relative() => dir.join(link),
                _ => link,
            };
            continue;
        }
        if kind.is_file() {
            return Ok(target);
        }
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "{} is {}, not a regular file: vstf replaces only regular files",
                target.display(),
                describe(&kind)
            ),
        ));
    }
    Err(std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("{}: more than {MAX_LINKS} symbolic links", path.display()),
    ))
}

/// What kind of file system entry this is, in words.
fn describe(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_dir() {
        "a directory"
    } else if kind.is_fifo() {
        "a FIFO"
    } else if kind.is_char_device() || kind.is_block_device() {
        "a device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "not a regular file"
    }
}

/// Writes so far by this process: each temporary file gets its own number,
/// so that two threads writing the same target never share one.
static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// A temporary file beside `target` for one write of this process:
/// `.<name>.vstf-tmp-<pid>-<n>`.
fn temp_path(target: &Path) -> PathBuf {
    let name = target.file_name().and_then(|n| n.to_str()).unwrap_or("out");
    let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    target.with_file_name(format!(".{name}{TEMP_MARK}{}-{n}", std::process::id()))
}

/// The writer's process id of a temporary file of ours (this naming, or the
/// `.<name>.<pid>.tmp` of earlier versions).
fn temp_owner(name: &str) -> Option<u32> {
    if let Some((_, rest)) = name.rsplit_once(TEMP_MARK) {
        return rest.split('-').next()?.parse().ok();
    }
    let rest = name.strip_prefix('.')?.strip_suffix(".tmp")?;
    rest.rsplit_once('.')?.1.parse().ok()
}

/// Whether a process with this id may be running (Linux: `/proc/<pid>`).
/// Where `/proc` cannot tell (no `/proc/self`), every writer counts as
/// running, so that no one's temporary file is removed.
fn is_running(pid: u32) -> bool {
    let proc = Path::new("/proc");
    pid == std::process::id() || !proc.join("self").exists() || proc.join(pid.to_string()).exists()
}

/// The temporary files under `dir` (recursively) left by processes that
/// are no longer running.
pub(crate) fn stale_temps(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return found;
    };
    for e in entries.flatten() {
        let p = e.path();
        let Ok(kind) = e.file_type() else { continue };
        if kind.is_dir() {
            found.extend(stale_temps(&p));
        } else if let Some(pid) = p.file_name().and_then(|n| n.to_str()).and_then(temp_owner) {
            if kind.is_file() && !is_running(pid) {
                found.push(p);
            }
        }
    }
    found.sort();
    found
}

/// Folders already swept by this process ([`remove_stale_beside`]).
static SWEPT: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Removes the stale temporary files beside `target` (those of writes that
/// were interrupted, their writers gone), once per folder per process: a
/// long animation writes many frames into one folder, and listing it for
/// every frame would cost as much as the frames' number squared.
fn remove_stale_beside(target: &Path) {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    {
        let mut swept = SWEPT.lock().unwrap_or_else(|e| e.into_inner());
        if swept.iter().any(|d| d == dir) {
            return;
        }
        swept.push(dir.to_path_buf());
    }
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let n = e.file_name();
        let Some(n) = n.to_str() else { continue };
        let is_file = e.file_type().is_ok_and(|t| t.is_file());
        // Only this naming: the older `.<name>.<pid>.tmp` could be anyone's
        // in a folder of the user's (golden/ and target/vstf/ are swept of
        // both by `remove_stale`).
        let ours = n.contains(TEMP_MARK) && temp_owner(n).is_some_and(|pid| !is_running(pid));
        if is_file && ours {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Removes the stale temporary files under `dir`; returns those removed.
pub(crate) fn remove_stale(dir: &Path) -> Vec<PathBuf> {
    stale_temps(dir)
        .into_iter()
        .filter(|p| std::fs::remove_file(p).is_ok())
        .collect()
}

/// An 8-bit RGB image encoded as PNG, as [`write_png`] writes it.
pub fn encode_png(img: &image::RgbImage) -> Result<Vec<u8>, image::ImageError> {
    let mut bytes = Vec::new();
    img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )?;
    Ok(bytes)
}

/// Encodes an 8-bit RGB image as PNG and writes it atomically.
pub fn write_png(path: &Path, img: &image::RgbImage) -> Result<(), Error> {
    let bytes = encode_png(img).map_err(|e| Error::io(path, format!("cannot encode PNG: {e}")))?;
    write_atomic(path, &bytes)
        .map_err(|e| Error::io(path, format!("cannot write {}: {e}", path.display())))
}

/// A rendered image as 8-bit RGB, the form PNGs are written and compared
/// in (the renderer's own bytes, [`renderer::Image::to_rgb8_bytes`]).
pub fn rgb8(image: &renderer::Image) -> image::RgbImage {
    image::RgbImage::from_raw(image.width, image.height, image.to_rgb8_bytes())
        .expect("an image has width * height pixels")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::FileTypeExt;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("vstf-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_symbolic_link_is_written_through_and_stays_a_link() {
        let dir = scratch("link");
        let (real, link) = (dir.join("real.txt"), dir.join("link.txt"));
        std::fs::write(&real, "old").unwrap();
        std::os::unix::fs::symlink("real.txt", &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
        // A dangling link creates the file it names.
        let dangling = dir.join("dangling.txt");
        std::os::unix::fs::symlink("made.txt", &dangling).unwrap();
        write_atomic(&dangling, b"made").unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.join("made.txt")).unwrap(),
            "made"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn directories_fifos_and_devices_are_refused_and_left_alone() {
        let dir = scratch("special");
        let e = write_atomic(&dir, b"x").unwrap_err();
        assert!(
            e.to_string().contains("is a directory, not a regular file"),
            "{e}"
        );
        let fifo = dir.join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let e = write_atomic(&fifo, b"x").unwrap_err();
            assert!(e.to_string().contains("is a FIFO"), "{e}");
            assert!(std::fs::symlink_metadata(&fifo)
                .unwrap()
                .file_type()
                .is_fifo());
        }
        let e = write_atomic(Path::new("/dev/null"), b"x").unwrap_err();
        assert!(e.to_string().contains("/dev/null is a device"), "{e}");
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().flatten().collect();
        assert_eq!(leftovers.len(), usize::from(fifo.exists()), "{leftovers:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn temps_of_dead_writers_are_found_and_removed_but_not_live_ones() {
        let dir = scratch("stale");
        std::fs::create_dir_all(dir.join("flange")).unwrap();
        // No process has id u32::MAX - 1; this one is alive.
        let dead = dir.join(format!("flange/.frame-920.png{TEMP_MARK}{}", u32::MAX - 1));
        let old_style = dir.join(format!("flange/.frame-1151.png.{}.tmp", u32::MAX - 1));
        let live = dir.join(format!(".view.png{TEMP_MARK}{}-0", std::process::id()));
        // Another running process's temporary file is kept too (pid 1 runs).
        let other_live = dir.join(format!(".init.png{TEMP_MARK}1-0"));
        std::fs::write(&other_live, "x").unwrap();
        let golden = dir.join("flange/frame-920.png");
        for p in [&dead, &old_style, &live, &golden] {
            std::fs::write(p, "x").unwrap();
        }
        assert_eq!(stale_temps(&dir), vec![old_style.clone(), dead.clone()]);
        assert_eq!(remove_stale(&dir).len(), 2);
        assert!(!dead.exists() && !old_style.exists());
        assert!(live.exists() && golden.exists() && other_live.exists());
        // A write cleans up after an earlier, interrupted write of the same file.
        std::fs::write(&dead, "x").unwrap();
        write_atomic(&golden, b"y").unwrap();
        assert!(!dead.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
