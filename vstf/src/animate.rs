//! Animations (paper 3, item 6): frames differ only by the camera's t; the
//! 4D database is built once and never touched between frames.

mod behind;
mod clock;

pub use clock::{lab_times, parse_frames, Clock, FrameRange};

use crate::fixture::{Fixture, View};
use crate::output::video::{self, VideoFormat};
use crate::output::write_atomic;
use crate::shard::Shard;
use image::RgbImage;
use renderer::Database;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Most frames one animation may have.
pub const MAX_FRAMES: usize = 100_000;

/// The camera times t = a, a + step, ... up to b (inclusive, within 1e-9 of a step).
pub fn frame_times(a: f64, b: f64, step: f64) -> Result<Vec<f64>, String> {
    if !(a.is_finite() && b.is_finite() && step.is_finite()) {
        return Err("--frames and --step must be finite numbers".into());
    }
    if step <= 0.0 {
        return Err(format!("--step {step}: must be positive"));
    }
    if b < a {
        return Err(format!("--frames {a}..{b}: the end is before the start"));
    }
    let n = ((b - a) / step + 1e-9).floor() + 1.0;
    if n > MAX_FRAMES as f64 {
        return Err(format!("{n} frames: at most {MAX_FRAMES} (raise --step)"));
    }
    Ok((0..n as usize).map(|i| a + step * i as f64).collect())
}

/// Parses `A..B`.
pub fn parse_range(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once("..")
        .ok_or_else(|| format!("{s:?}: expected A..B"))?;
    let num = |x: &str| {
        x.trim()
            .parse::<f64>()
            .map_err(|_| format!("{s:?}: expected A..B with numbers"))
    };
    Ok((num(a)?, num(b)?))
}

/// Where frames go.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// A folder of `frame-NNNNN.png`.
    Sequence(PathBuf),
    /// An animated GIF.
    Gif(PathBuf),
    /// An animated PNG.
    Apng(PathBuf),
    /// A video, encoded by ffmpeg.
    Video(PathBuf, VideoFormat),
}

/// What an animation's `--out` may name.
pub const ANIMATION_OUTPUTS: &str =
    "a folder (PNG frames), FILE.gif, FILE.png (APNG), FILE.mp4 or FILE.webm";

impl Output {
    /// A `.gif`, `.png`/`.apng`, `.mp4` or `.webm` file, else a folder of
    /// PNG frames; a path ending in the extension of another kind of file
    /// (`.jpg`, `.mov`, ...) is refused, never made a folder.
    pub fn from_path(p: &Path) -> Result<Output, String> {
        let ext = crate::output::extension(p);
        match ext.as_deref() {
            Some("gif") => Ok(Output::Gif(p.into())),
            Some("png") | Some("apng") => Ok(Output::Apng(p.into())),
            Some(e) => match VideoFormat::of_extension(e) {
                Some(v) => Ok(Output::Video(p.into(), v)),
                None if crate::output::names_a_file(p) => Err(format!(
                    "--out {}: an animation is written as {ANIMATION_OUTPUTS}, not .{e}",
                    p.display()
                )),
                None => Ok(Output::Sequence(p.into())),
            },
            None => Ok(Output::Sequence(p.into())),
        }
    }

    /// Refuses, before any frame is rendered, an output that could not be
    /// written at the end: a folder (or FIFO, device) where the file goes;
    /// for a video, no ffmpeg on PATH, unless `encode` is false (a shard's
    /// frames need ffmpeg only when `vstf merge` encodes them).
    pub fn preflight(&self, encode: bool) -> Result<(), String> {
        match self {
            Output::Sequence(_) => Ok(()),
            Output::Gif(f) | Output::Apng(f) => Ok(crate::output::writable_file(f)?),
            Output::Video(f, _) => {
                crate::output::writable_file(f)?;
                if encode {
                    video::find_ffmpeg()?;
                }
                Ok(())
            }
        }
    }

    /// The folder where finished frames are written as PNGs as they are
    /// done: the sequence itself, or `<file>.frames/` beside an animation
    /// file (removed once the file is written), so that an interrupted run
    /// leaves every finished frame on disk.
    pub fn frames_dir(&self) -> PathBuf {
        match self {
            Output::Sequence(d) => d.clone(),
            Output::Gif(f) | Output::Apng(f) | Output::Video(f, _) => {
                let mut name = f.file_name().map(|n| n.to_os_string()).unwrap_or_default();
                name.push(".frames");
                f.with_file_name(name)
            }
        }
    }
}

/// The PNG of frame `i` in a frames folder.
pub fn frame_path(dir: &Path, i: usize) -> PathBuf {
    dir.join(format!("frame-{i:05}.png"))
}

/// What an animation's frames are, written beside them so that a resumed
/// run only keeps frames of the same animation (and merged shards only
/// frames of one animation).
pub fn manifest(f: &Fixture, view: &View, times: &[f64], label: bool) -> String {
    // Everything a frame depends on: the scene as loaded, the camera and
    // every render setting (colour effects, shutter, seed, depth, shadows).
    let scene = format!("{:?}{:?}{:?}", f.spec, view.camera, view.settings);
    format!(
        "vstf animation\nfixture {}\nmodel {}\nsize {}x{}\nspp {}\nscene and settings {}\ntimes {:?}\nlabelled {label}\n",
        f.file.display(),
        view.model,
        view.camera.width,
        view.camera.height,
        view.settings.spp,
        crate::shard::hash_hex(scene.as_bytes()),
        times
    )
}

/// The frame index of a frame file's name (`frame-00012.png`).
fn frame_index(name: &str) -> Option<usize> {
    name.strip_prefix("frame-")?
        .strip_suffix(".png")?
        .parse()
        .ok()
}

/// Removes the frames of `shard` an earlier animation left in `dir`, so
/// that a later `--resume` can never keep one of them (other shards'
/// frames in a shared folder are theirs).
fn remove_old_frames(dir: &Path, shard: Shard) -> Result<(), String> {
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = e.file_name();
        let owned = frame_index(&name.to_string_lossy()).is_some_and(|i| shard.owns_frame(i));
        if owned && e.file_type().is_ok_and(|t| t.is_file()) {
            std::fs::remove_file(e.path())
                .map_err(|err| format!("cannot remove {}: {err}", e.path().display()))?;
        }
    }
    Ok(())
}

/// The resume manifest's file in a frames folder (one per shard).
fn manifest_path(dir: &Path, shard: Shard) -> PathBuf {
    if shard == Shard::WHOLE {
        dir.join("animation.txt")
    } else {
        dir.join(format!("animation-{}.txt", shard.tag()))
    }
}

/// Whether frame `i` is already in `dir`, whole: a PNG of the view's size.
fn frame_is_whole(dir: &Path, i: usize, view: &View) -> bool {
    image::open(frame_path(dir, i))
        .is_ok_and(|im| (im.width(), im.height()) == (view.camera.width, view.camera.height))
}

/// How frames are rendered: kept from an interrupted run (`resume`),
/// labelled with their camera time, and which shard's frames.
#[derive(Clone, Copy, Debug)]
pub struct FrameOptions {
    /// Keep frames already written whole by a run of the same animation.
    pub resume: bool,
    /// Write each frame's camera time ("t = 12.5") at its top left.
    pub label: bool,
    /// Render only this shard's frames, and write its manifest.
    pub shard: Shard,
}

/// Checks that a resumed run continues the same animation in `dir`.
fn can_resume(dir: &Path, mpath: &Path, wanted: &str) -> Result<(), String> {
    match std::fs::read_to_string(mpath) {
        Ok(found) if found == wanted => Ok(()),
        Ok(_) => Err(format!(
            "cannot resume: the frames in {} belong to another animation (see {})",
            dir.display(),
            mpath.display()
        )),
        Err(_) => Err(format!(
            "cannot resume: {} has no animation to resume ({} is missing)",
            dir.display(),
            mpath.display()
        )),
    }
}

/// Renders every frame of `opts.shard` with one database, calling `done`
/// with the count finished after each; stops early (returning how many
/// were finished) when `stop` is raised. A sharded run ends by writing the
/// shard's manifest (`shard-I-of-N.json`) beside its frames.
pub fn render_frames(
    (f, view, db): (&Fixture, &View, &Database),
    times: &[f64],
    out: &Output,
    stop: &AtomicBool,
    opts: FrameOptions,
    mut done: impl FnMut(usize),
) -> Result<usize, String> {
    let dir = out.frames_dir();
    let wanted = manifest(f, view, times, opts.label);
    let mpath = manifest_path(&dir, opts.shard);
    // A resumed run checks before making anything, so that a refusal
    // leaves no folder behind.
    if opts.resume {
        can_resume(&dir, &mpath, &wanted)?;
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    if !opts.resume {
        remove_old_frames(&dir, opts.shard)?;
    }
    write_atomic(&mpath, wanted.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", mpath.display()))?;
    let owned: Vec<usize> = (0..times.len())
        .filter(|&i| opts.shard.owns_frame(i))
        .collect();
    let kept = |i: usize| opts.resume && frame_is_whole(&dir, i, view);
    let frames = behind::Frames {
        scene: (f, view, db),
        dir: &dir,
        label: opts.label,
        kept: &kept,
    };
    let finished = frames.run((&owned, times), stop, &mut done)?;
    if finished < owned.len() {
        return Ok(finished);
    }
    if opts.shard != Shard::WHOLE {
        let scene = crate::shard::hash_hex(wanted.as_bytes());
        let mut m = crate::shard::Manifest::new("animation", scene, opts.shard, times.len());
        for &i in &owned {
            let file = frame_path(Path::new(""), i);
            m.add(&dir, i.to_string(), &file.to_string_lossy())?;
        }
        m.write(&dir)?;
    }
    Ok(owned.len())
}

/// Assembles the frames of a sharded animation, found through the shards'
/// manifests (`found`, [`crate::shard::read_manifests`]), into `out` (a
/// folder of frames, a GIF or an APNG), once every shard is there, of one
/// animation and unchanged; returns the number of frames.
pub fn merge(found: Vec<crate::shard::Found>, out: &Output, fps: u32) -> Result<usize, String> {
    let shards = crate::shard::complete(found, "animation")?;
    let n = shards[0].manifest.items;
    let mut files: Vec<Option<PathBuf>> = vec![None; n];
    for s in &shards {
        for w in &s.manifest.outputs {
            let i: usize = w
                .item
                .parse()
                .ok()
                .filter(|&i| i < n && s.manifest.shard.owns_frame(i))
                .ok_or_else(|| {
                    format!(
                        "shard {}: frame {:?} is not one of its frames",
                        s.manifest.shard, w.item
                    )
                })?;
            files[i] = Some(s.dir.join(&w.file));
        }
    }
    if let Some(gap) = files.iter().position(Option::is_none) {
        return Err(format!("frame {gap} is in no shard's manifest"));
    }
    let files: Vec<PathBuf> = files.into_iter().flatten().collect();
    let frames = || -> Result<Vec<RgbImage>, String> {
        files
            .iter()
            .map(|p| {
                image::open(p)
                    .map(|im| im.to_rgb8())
                    .map_err(|e| format!("cannot read {}: {e}", p.display()))
            })
            .collect()
    };
    let (file, bytes) = match out {
        Output::Sequence(d) => {
            std::fs::create_dir_all(d)
                .map_err(|e| format!("cannot create {}: {e}", d.display()))?;
            for (i, p) in files.iter().enumerate() {
                let to = frame_path(d, i);
                if to.canonicalize().ok() != p.canonicalize().ok() {
                    let bytes = std::fs::read(p)
                        .map_err(|e| format!("cannot read {}: {e}", p.display()))?;
                    write_atomic(&to, &bytes)
                        .map_err(|e| format!("cannot write {}: {e}", to.display()))?;
                }
            }
            return Ok(n);
        }
        Output::Gif(file) => (file, encode_gif(&frames()?, fps)?),
        Output::Apng(file) => (file, encode_apng(&frames()?, fps)?),
        Output::Video(file, format) => {
            video::encode_files(&files, fps, file, *format)?;
            return Ok(n);
        }
    };
    write_atomic(file, &bytes).map_err(|e| format!("cannot write {}: {e}", file.display()))?;
    Ok(n)
}

/// A camera time for a frame's label: at most 4 decimals, trailing zeros dropped.
pub fn time_label(t: f64) -> String {
    let s = format!("{t:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn load_frames(dir: &Path, n: usize) -> Result<Vec<RgbImage>, String> {
    (0..n)
        .map(|i| {
            let p = frame_path(dir, i);
            image::open(&p)
                .map(|im| im.to_rgb8())
                .map_err(|e| format!("cannot read {}: {e}", p.display()))
        })
        .collect()
}

/// Assembles the finished frames into the GIF, APNG or video file
/// (atomically), then removes the frames folder; a video that ffmpeg could
/// not encode leaves neither the file nor the frames. A sequence needs
/// nothing more.
pub fn finish(out: &Output, n: usize, fps: u32) -> Result<(), String> {
    let (file, bytes) = match out {
        Output::Sequence(_) => return Ok(()),
        Output::Video(file, format) => {
            let dir = out.frames_dir();
            let encoded = video::encode(&dir, n, fps, file, *format);
            remove_frames_dir(&dir)?;
            return encoded;
        }
        Output::Gif(file) => (file, encode_gif(&load_frames(&out.frames_dir(), n)?, fps)?),
        Output::Apng(file) => (file, encode_apng(&load_frames(&out.frames_dir(), n)?, fps)?),
    };
    write_atomic(file, &bytes).map_err(|e| format!("cannot write {}: {e}", file.display()))?;
    remove_frames_dir(&out.frames_dir())
}

/// Removes the frames and shard manifests vstf wrote into `dir`, file by
/// file (never a recursive delete, so nothing else there and nothing behind
/// a link is touched), then `dir` if it is left empty.
fn remove_frames_dir(dir: &Path) -> Result<(), String> {
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = e.file_name();
        let name = name.to_string_lossy();
        let ours = frame_index(&name).is_some()
            || (name.starts_with("animation") && name.ends_with(".txt"));
        if ours && e.file_type().is_ok_and(|t| t.is_file()) {
            std::fs::remove_file(e.path())
                .map_err(|err| format!("cannot remove {}: {err}", e.path().display()))?;
        }
    }
    let _ = std::fs::remove_dir(dir);
    Ok(())
}

fn encode_gif(frames: &[RgbImage], fps: u32) -> Result<Vec<u8>, String> {
    use image::codecs::gif::{GifEncoder, Repeat};
    let mut bytes = Vec::new();
    {
        let mut enc = GifEncoder::new_with_speed(&mut bytes, 10);
        enc.set_repeat(Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        let delay = image::Delay::from_numer_denom_ms(1000, fps.max(1));
        for f in frames {
            let rgba = image::DynamicImage::ImageRgb8(f.clone()).to_rgba8();
            enc.encode_frame(image::Frame::from_parts(rgba, 0, 0, delay))
                .map_err(|e| format!("cannot encode GIF: {e}"))?;
        }
    }
    Ok(bytes)
}

fn encode_apng(frames: &[RgbImage], fps: u32) -> Result<Vec<u8>, String> {
    let first = frames.first().ok_or("no frames to encode")?;
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, first.width(), first.height());
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_animated(frames.len() as u32, 0)
            .map_err(|e| format!("cannot encode APNG: {e}"))?;
        enc.set_frame_delay(1, fps.clamp(1, u16::MAX as u32) as u16)
            .map_err(|e| format!("cannot encode APNG: {e}"))?;
        let mut w = enc
            .write_header()
            .map_err(|e| format!("cannot encode APNG: {e}"))?;
        for f in frames {
            w.write_image_data(f.as_raw())
                .map_err(|e| format!("cannot encode APNG: {e}"))?;
        }
        w.finish().map_err(|e| format!("cannot encode APNG: {e}"))?;
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_times_are_inclusive_and_checked() {
        assert_eq!(
            frame_times(940.0, 942.0, 1.0).unwrap(),
            vec![940.0, 941.0, 942.0]
        );
        assert_eq!(frame_times(0.0, 1.0, 0.3).unwrap().len(), 4);
        assert_eq!(
            frame_times(0.0, 0.9, 0.3).unwrap().len(),
            4,
            "0.9/0.3 is 3 steps despite rounding"
        );
        assert!(frame_times(2.0, 1.0, 1.0).is_err());
        assert!(frame_times(0.0, 1.0, 0.0).is_err());
        assert!(frame_times(0.0, 1e9, 1.0).is_err());
        assert_eq!(parse_range("940..1171").unwrap(), (940.0, 1171.0));
        assert_eq!(parse_range("-5..5").unwrap(), (-5.0, 5.0));
        assert!(parse_range("940-1171").is_err());
    }

    #[test]
    fn outputs_by_extension() {
        let of = |p: &str| Output::from_path(Path::new(p));
        assert_eq!(of("a.gif"), Ok(Output::Gif("a.gif".into())));
        assert_eq!(of("a.PNG"), Ok(Output::Apng("a.PNG".into())));
        assert_eq!(of("frames"), Ok(Output::Sequence("frames".into())));
        assert_eq!(of("run.v2"), Ok(Output::Sequence("run.v2".into())));
        assert_eq!(
            of("a.MP4"),
            Ok(Output::Video("a.MP4".into(), VideoFormat::Mp4))
        );
        assert_eq!(
            of("a.webm"),
            Ok(Output::Video("a.webm".into(), VideoFormat::Webm))
        );
        for file in ["a.jpg", "a.exr", "a.mov", "a.mkv"] {
            let e = of(file).unwrap_err();
            assert!(e.contains(file) && e.contains("FILE.mp4"), "{e}");
        }
        assert_eq!(
            Output::Gif("x/a.gif".into()).frames_dir(),
            PathBuf::from("x/a.gif.frames")
        );
    }
}
