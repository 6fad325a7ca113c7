//! Videos through Debian's `ffmpeg`, found on PATH: a folder of PNG frames
//! (`frame-00000.png`, ...) encoded into `.mp4` (H.264) or `.webm` (VP9),
//! both in 4:2:0 chroma (what every player plays; an odd width or height
//! is padded by one black column or row, as 4:2:0 needs even sizes).
//! ffmpeg writes a temporary file beside the output, renamed over it once
//! ffmpeg has succeeded; on any failure the temporary file is removed and
//! nothing is left.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// A video container and its codec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VideoFormat {
    /// MP4 with H.264 (libx264).
    Mp4,
    /// WebM with VP9 (libvpx-vp9).
    Webm,
}

impl VideoFormat {
    /// The format of an extension (lower case), if it is a video's.
    pub fn of_extension(ext: &str) -> Option<VideoFormat> {
        match ext {
            "mp4" => Some(VideoFormat::Mp4),
            "webm" => Some(VideoFormat::Webm),
            _ => None,
        }
    }

    /// ffmpeg's arguments for the muxer and the codec.
    fn codec_args(self) -> &'static [&'static str] {
        match self {
            VideoFormat::Mp4 => &[
                "-c:v",
                "libx264",
                "-crf",
                "16",
                "-pix_fmt",
                "yuv420p",
                "-movflags",
                "+faststart",
                "-f",
                "mp4",
            ],
            VideoFormat::Webm => &[
                "-c:v",
                "libvpx-vp9",
                "-crf",
                "24",
                "-b:v",
                "0",
                "-pix_fmt",
                "yuv420p",
                "-f",
                "webm",
            ],
        }
    }
}

/// The `ffmpeg` executable on PATH, or an error saying how to get one and
/// what vstf writes without it.
pub fn find_ffmpeg() -> Result<PathBuf, String> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .map(|dir| dir.join("ffmpeg"))
        .find(|p| is_executable(p))
        .ok_or_else(|| {
            "ffmpeg is not on PATH: vstf encodes .mp4 and .webm videos with it (Debian: \
             apt install ffmpeg); or write FILE.gif, FILE.png (APNG) or a folder of PNG frames"
                .to_string()
        })
}

/// Whether `p` is a file someone may execute.
fn is_executable(p: &Path) -> bool {
    use std::os::unix::fs::PermissionsExt;
    std::fs::metadata(p).is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
}

/// Encodes frames `frame-00000.png` .. of `dir` (`n` of them, at `fps`)
/// into `out`, atomically: through a temporary file beside it, renamed
/// over `out` only when ffmpeg succeeded.
pub fn encode(
    dir: &Path,
    n: usize,
    fps: u32,
    out: &Path,
    format: VideoFormat,
) -> Result<(), String> {
    let ffmpeg = find_ffmpeg()?;
    let target = super::regular_target(out).map_err(|e| e.to_string())?;
    let tmp = super::temp_path(&target);
    let result = run_ffmpeg(&ffmpeg, dir, n, fps, &tmp, format).and_then(|()| {
        std::fs::rename(&tmp, &target)
            .map_err(|e| format!("cannot write {}: {e}", target.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Runs ffmpeg once, its messages captured for the error.
fn run_ffmpeg(
    ffmpeg: &Path,
    dir: &Path,
    n: usize,
    fps: u32,
    tmp: &Path,
    format: VideoFormat,
) -> Result<(), String> {
    let output = Command::new(ffmpeg)
        .args(["-hide_banner", "-loglevel", "error", "-nostdin", "-y"])
        .args([
            "-framerate",
            &fps.max(1).to_string(),
            "-start_number",
            "0",
            "-i",
        ])
        .arg(dir.join("frame-%05d.png"))
        .args(["-frames:v", &n.to_string()])
        .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"])
        .args(format.codec_args())
        .arg(tmp)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", ffmpeg.display()))?;
    if output.status.success() {
        return Ok(());
    }
    let said = String::from_utf8_lossy(&output.stderr);
    let tail: Vec<&str> = said.lines().rev().take(6).collect();
    let tail: Vec<&str> = tail.into_iter().rev().collect();
    Err(format!(
        "{} failed ({}) encoding {} frames of {}: {}",
        ffmpeg.display(),
        output.status,
        n,
        dir.display(),
        tail.join(" / ")
    ))
}

/// Encodes the PNG frames `files` (in order, from anywhere: a merge's
/// shards) into `out`: copied into a temporary folder beside `out`
/// (`.<name>.vstf-frames-<pid>`), encoded, and the folder removed, whether
/// ffmpeg succeeded or not.
pub fn encode_files(
    files: &[PathBuf],
    fps: u32,
    out: &Path,
    format: VideoFormat,
) -> Result<(), String> {
    find_ffmpeg()?;
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let dir = out.with_file_name(format!(".{name}.vstf-frames-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let mut copied = Vec::with_capacity(files.len());
    let result = (|| {
        for (i, from) in files.iter().enumerate() {
            let to = dir.join(format!("frame-{i:05}.png"));
            std::fs::copy(from, &to)
                .map_err(|e| format!("cannot copy {} to {}: {e}", from.display(), to.display()))?;
            copied.push(to);
        }
        encode(&dir, files.len(), fps, out, format)
    })();
    for f in &copied {
        let _ = std::fs::remove_file(f);
    }
    let _ = std::fs::remove_dir(&dir);
    result
}
