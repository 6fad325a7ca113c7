//! Videos out: `animate --out FILE.mp4 / .webm` through ffmpeg, counted
//! by `ffprobe`, sharded frames merged into one, and every failure leaving
//! nothing behind.
//!
//! Without ffmpeg/ffprobe the test that needs them says so and skips; with
//! `VSTF_REQUIRE_MEDIA` set their absence is a failure ([`media`]).

use crate::support::{media, vstf, RunExt, Scratch};
use std::path::{Path, PathBuf};
use std::process::Command;

/// `vstf animate` of six small teaser frames (48x27: an odd height) into `out`.
fn animate(out: &Path, extra: &[&str]) -> Command {
    let mut c = vstf();
    c.args(["animate", "teaser", "--frames", "10..20", "--step", "2"])
        .args(["--width", "48", "--height", "27", "--out"])
        .arg(out)
        .args(extra);
    c
}

/// What ffprobe counts in a video's first stream: codec, width, height and
/// frames decoded.
fn probe(video: &Path) -> String {
    let out = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=codec_name,width,height,nb_read_frames",
        ])
        .args(["-of", "csv=p=0"])
        .arg(video)
        .output()
        .unwrap();
    assert!(out.status.success(), "ffprobe: {out:?}");
    String::from_utf8(out.stdout).unwrap().trim().to_string()
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    n.sort();
    n
}

/// `.mp4` and `.webm` are playable videos of as many frames as asked
/// (ffprobe decodes them), the odd height padded to even; nothing else is
/// left beside them. Sharded frames merge into a video too.
#[test]
fn animate_encodes_videos_that_ffprobe_counts() {
    if !media(&["ffmpeg", "ffprobe"], "the video test") {
        return;
    }
    let dir = Scratch::new("videos");
    animate(&dir.join("a.mp4"), &[]).run().succeeds();
    assert_eq!(probe(&dir.join("a.mp4")), "h264,48,28,6");
    animate(&dir.join("a.webm"), &["--fps", "25"])
        .run()
        .succeeds();
    assert_eq!(probe(&dir.join("a.webm")), "vp9,48,28,6");
    assert_eq!(names(&dir), ["a.mp4", "a.webm"]);
    // Shards need no ffmpeg; the merge encodes.
    let shards = dir.join("shards");
    for s in ["1/2", "2/2"] {
        animate(&shards, &["--shard", s])
            .env("PATH", "/nonexistent")
            .run()
            .succeeds();
    }
    let merge = |out: &Path| vstf().args(["merge", "--out"]).arg(out).arg(&shards).run();
    merge(&dir.join("m.mov")).fails_with("not .mov");
    merge(&dir.join("m.mp4")).succeeds();
    assert_eq!(probe(&dir.join("m.mp4")), "h264,48,28,6");
    assert_eq!(names(&dir), ["a.mp4", "a.webm", "m.mp4", "shards"]);
}

/// A fake ffmpeg that writes half a file where it was told to and fails.
fn failing_ffmpeg(dir: &Path) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let script = bin.join("ffmpeg");
    std::fs::write(
        &script,
        "#!/bin/sh\nfor a; do last=$a; done\necho half > \"$last\"\necho 'Unknown encoder' >&2\nexit 1\n",
    )
    .unwrap();
    std::fs::set_permissions(&script, std::fs::Permissions::from_mode(0o755)).unwrap();
    bin
}

/// Without ffmpeg, or with one that fails, `animate --out x.mp4` says so,
/// exits non-zero and leaves nothing: no file, no frames, no folder named
/// like the file; other file extensions are refused, never made folders;
/// a resume with nothing to resume makes nothing either.
#[test]
fn video_failures_leave_nothing_behind() {
    let dir = Scratch::new("video-failures");
    let out = dir.join("out");
    std::fs::create_dir(&out).unwrap();
    let bin = failing_ffmpeg(&dir);
    let run = animate(&out.join("x.mp4"), &[])
        .env("PATH", "/nonexistent")
        .run();
    run.fails_with("ffmpeg is not on PATH");
    assert_eq!(run.code(), Some(2));
    assert!(names(&out).is_empty(), "{:?}", names(&out));
    animate(&out.join("x.webm"), &[])
        .env("PATH", &bin)
        .run()
        .fails_with("failed")
        .stderr_has("Unknown encoder");
    assert!(names(&out).is_empty(), "{:?}", names(&out));
    animate(&out.join("x.mp4"), &["--resume"])
        .env("PATH", &bin)
        .run()
        .fails_with("cannot resume");
    assert!(names(&out).is_empty(), "{:?}", names(&out));
    for file in ["x.jpg", "x.exr", "x.mov", "x.mkv"] {
        animate(&out.join(file), &[])
            .run()
            .fails_with("FILE.mp4 or FILE.webm");
    }
    assert!(names(&out).is_empty(), "{:?}", names(&out));
    // A folder where the video goes is refused before any frame.
    std::fs::create_dir(out.join("d.mp4")).unwrap();
    animate(&out.join("d.mp4"), &[])
        .env("PATH", &bin)
        .run()
        .fails_with("is a directory, not a regular file");
    assert_eq!(names(&out), ["d.mp4"]);
}
