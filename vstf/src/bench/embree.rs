//! Section 7 of `vstf bench`: this renderer against Intel Embree 3 (the
//! CPU ray-tracing limit) on the same triangles, camera and rays, measured
//! in the same run. Each side runs in a fresh process, alternately, and the
//! ratio is taken per round: CPU seconds per frame tracing the primary rays
//! (one at each pixel's centre, each ray's closest hit counted, as Embree's
//! side does; this renderer's whole render, shading and image included,
//! and the same with the frame encoded as PNG, as an animation delivers
//! it, are printed beside it), the build, peak memory, and the time from nothing
//! loaded to the first frame. The cost of motion (the tori at 0.9c against
//! their static frame) is taken both across two such processes and within
//! one, on one core ([`super::paired`]).
//!
//! Embree's side is `ebench.c`, compiled here against Debian's
//! `libembree-dev` when it is installed; without it the section prints this
//! renderer's own figures and how to install Embree.

use super::paired::{self, Paired};
use super::primary::{self, cpu_seconds, trace};
use super::tori;
use crate::fixture::{Fixture, Overrides};
use renderer::{Image, Traversal};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// Embree's side of the benchmark, as C.
const EBENCH: &str = include_str!("ebench.c");

/// What one side measured on one scene.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Measured {
    /// Reading the scene from disk (and validating it), wall seconds.
    pub load: f64,
    /// Building the acceleration structure, CPU seconds.
    pub build_cpu: f64,
    /// From the start to the first finished frame, wall seconds.
    pub first_frame: f64,
    /// The best frame's CPU seconds: for this renderer a whole render
    /// (shading and image included); for Embree, its tracing.
    pub frame_cpu: f64,
    /// The best frame's CPU seconds as an animation delivers it: the whole
    /// render, then the frame encoded as PNG (as `vstf animate` writes
    /// it). For Embree, its tracing.
    pub delivered_cpu: f64,
    /// The best frame's CPU seconds tracing the primary rays alone, as
    /// Embree's side does: each ray's closest hit, counted, no shading and
    /// no image.
    pub trace_cpu: f64,
    /// The process's peak resident memory, bytes.
    pub peak: u64,
    /// Pixels whose ray hit a triangle.
    pub hits: u64,
}

/// This renderer's side, run in this process: load the fixture at `path`,
/// build its database, render `frames` frames.
pub fn measure(path: &Path, frames: usize) -> Result<Measured, String> {
    let start = Instant::now();
    let f = Fixture::load(path).map_err(|e| e.to_string())?;
    let view = crate::run::view(&f, &Overrides::default())?;
    let load = start.elapsed().as_secs_f64();
    let c0 = cpu_seconds();
    let db = crate::run::database(&f, false, Traversal::Bvh)?;
    let build_cpu = cpu_seconds() - c0;
    let mut m = Measured {
        load,
        build_cpu,
        frame_cpu: f64::INFINITY,
        delivered_cpu: f64::INFINITY,
        trace_cpu: f64::INFINITY,
        ..Measured::default()
    };
    let mut spent = Image::default();
    for k in 0..frames.max(1) {
        let c = cpu_seconds();
        spent = crate::run::render_reusing(&db, &f, &view, spent)?;
        let img = crate::output::rgb8(&spent);
        m.frame_cpu = m.frame_cpu.min(cpu_seconds() - c);
        crate::output::encode_png(&img).map_err(|e| format!("cannot encode PNG: {e}"))?;
        m.delivered_cpu = m.delivered_cpu.min(cpu_seconds() - c);
        if k == 0 {
            m.first_frame = start.elapsed().as_secs_f64();
            m.hits = img.pixels().filter(|p| p.0 != [0, 0, 0]).count() as u64;
        }
    }
    for _ in 0..frames.max(1) {
        let c = cpu_seconds();
        let traced = trace(&db, &view);
        m.trace_cpu = m.trace_cpu.min(cpu_seconds() - c);
        // On a black background (the tori's) a pixel is lit when its ray
        // hits: the two counts must agree.
        if f.scene.background == glam::DVec3::ZERO && traced != m.hits {
            return Err(format!(
                "{}: {traced} primary rays hit, but {} pixels are lit",
                path.display(),
                m.hits
            ));
        }
        m.hits = traced;
    }
    m.peak = super::memory().1;
    Ok(m)
}

/// [`measure`] in a fresh `vstf` process (so that its peak memory is this
/// scene's alone), at this process's vector level.
fn measure_in_child(path: &Path, frames: usize) -> Result<Measured, String> {
    let frames = frames.to_string();
    primary::measure_in_child(&[path.as_ref(), "--frames".as_ref(), frames.as_ref()])
}

/// Compiles Embree's side into `dir`, or says why it cannot.
fn compile(dir: &Path) -> Result<PathBuf, String> {
    if !Path::new("/usr/include/embree3/rtcore.h").is_file() {
        return Err("Embree 3 is not installed (Debian: apt-get install libembree-dev)".into());
    }
    let src = dir.join("ebench.c");
    let exe = dir.join("ebench");
    crate::output::write_atomic(&src, EBENCH.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", src.display()))?;
    let out = Command::new("cc")
        .args(["-O2", "-o"])
        .arg(&exe)
        .arg(&src)
        .args(["-lembree3", "-lpthread", "-lm"])
        .output()
        .map_err(|e| format!("cannot run cc (apt-get install gcc): {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "cannot compile {}: {}",
            src.display(),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(exe)
}

/// The value of `key=` in Embree's output (the first, or with `best` the
/// smallest over its frames), seconds' `s` suffix dropped.
fn field(text: &str, key: &str, best: bool) -> Result<f64, String> {
    let values: Vec<f64> = text
        .split_whitespace()
        .filter_map(|w| w.strip_prefix(key)?.strip_prefix('='))
        .filter_map(|v| v.trim_end_matches('s').parse().ok())
        .collect();
    let v = if best {
        values.iter().copied().reduce(f64::min)
    } else {
        values.first().copied()
    };
    v.ok_or_else(|| format!("Embree's output has no {key}: {text}"))
}

/// Embree's side on `obj` at `w` x `h`, tracing with rtcIntersect`mode`.
fn embree(
    exe: &Path,
    obj: &Path,
    (w, h): (u32, u32),
    mode: u32,
    frames: usize,
) -> Result<Measured, String> {
    let threads = rayon::current_num_threads();
    let start = Instant::now();
    let out = Command::new(exe)
        .arg(obj)
        .args([w, h].map(|x| x.to_string()))
        .args([frames.to_string(), mode.to_string(), threads.to_string()])
        .output()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    let wall = start.elapsed().as_secs_f64();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    if !out.status.success() {
        return Err(format!("{} failed: {text}", exe.display()));
    }
    let (load, build) = (field(&text, "load", false)?, field(&text, "build", false)?);
    let trace = field(&text, "trace", false)?;
    Ok(Measured {
        load,
        build_cpu: field(&text, "build_cpu", false)?,
        first_frame: (load + build + trace).min(wall),
        frame_cpu: field(&text, "cpu", true)?,
        delivered_cpu: field(&text, "cpu", true)?,
        trace_cpu: field(&text, "cpu", true)?,
        peak: field(&text, "peak_rss_kb", false)? as u64 * 1024,
        hits: field(&text, "hits", false)? as u64,
    })
}

/// The sizes measured and how often.
struct Sizes {
    triangles: &'static [usize],
    image: (u32, u32),
    rounds: usize,
    frames: usize,
}

/// One scene's measurements, each side per round.
struct Scene {
    triangles: usize,
    ours: Vec<Measured>,
    /// This renderer on the same tori moving at 0.9c.
    moving: Vec<Measured>,
    /// The moving and the static tori traced in turn in one process.
    paired: Vec<Paired>,
    single: Vec<Measured>,
    packets: Vec<Measured>,
}

/// Section 7, appended to `out`.
pub fn section(dir: &Path, quick: bool, out: &mut String) -> Result<(), String> {
    let sizes = if quick {
        Sizes {
            triangles: &[10_000, 30_000],
            image: (480, 270),
            rounds: 1,
            frames: 1,
        }
    } else {
        Sizes {
            triangles: &[10_000, 1_000_000, 3_000_000],
            image: (1920, 1080),
            rounds: 2,
            frames: 3,
        }
    };
    let (w, h) = sizes.image;
    let _ = writeln!(out, "\n7. against Embree 3: the same tilted tori, camera and {w}x{h} primary rays (one at each pixel's centre), no shadows; CPU seconds per frame, best of {} frames: this renderer's whole render (shading and image included), the same with the frame encoded as PNG (frame+png: a frame as an animation delivers it) and its tracing alone (each ray's closest hit, counted: Embree's side's work), the ratios of each to Embree's tracing; each side in a fresh process, alternately, {} round(s), ratios per round", sizes.frames, sizes.rounds);
    let exe = compile(dir);
    if let Err(why) = &exe {
        let _ = writeln!(out, "   {why}: this renderer's figures only");
    }
    let mut scenes = Vec::new();
    for &n in sizes.triangles {
        let (obj, fixture, triangles) = tori::write(dir, n, sizes.image, tori::Motion::Static)?;
        let (_, moving, _) = tori::write(dir, n, sizes.image, tori::Motion::Moving)?;
        let mut s = Scene {
            triangles,
            ours: Vec::new(),
            moving: Vec::new(),
            paired: Vec::new(),
            single: Vec::new(),
            packets: Vec::new(),
        };
        for _ in 0..sizes.rounds {
            s.ours.push(measure_in_child(&fixture, sizes.frames)?);
            s.moving.push(measure_in_child(&moving, sizes.frames)?);
            s.paired
                .push(paired::measure_in_child(&moving, &fixture, sizes.frames)?);
            if let Ok(exe) = &exe {
                s.single
                    .push(embree(exe, &obj, sizes.image, 1, sizes.frames)?);
                s.packets
                    .push(embree(exe, &obj, sizes.image, 16, sizes.frames)?);
            }
        }
        scenes.push(s);
    }
    print_scenes(&scenes, out);
    Ok(())
}

/// The smallest and largest of the per-round ratios `ours / theirs` of `f`.
fn ratios(ours: &[Measured], theirs: &[Measured], f: impl Fn(&Measured) -> f64) -> String {
    ratios_of(ours, &f, theirs, &f)
}

/// The smallest and largest of the per-round ratios of `fo` of `ours` to
/// `ft` of `theirs`.
fn ratios_of(
    ours: &[Measured],
    fo: impl Fn(&Measured) -> f64,
    theirs: &[Measured],
    ft: impl Fn(&Measured) -> f64,
) -> String {
    range(ours.iter().zip(theirs).map(|(a, b)| fo(a) / ft(b)))
}

/// The smallest and largest of `ratios` to two decimals (one figure
/// where they print the same), or `-` for none.
fn range(ratios: impl Iterator<Item = f64>) -> String {
    let (lo, hi, n) = ratios.fold((f64::INFINITY, 0.0_f64, 0), |(l, h, n), x| {
        (l.min(x), h.max(x), n + 1)
    });
    let (lo, hi) = (format!("{lo:.2}"), format!("{hi:.2}"));
    if n == 0 {
        "-".into()
    } else if lo == hi {
        format!("{lo}x")
    } else {
        format!("{lo}-{hi}x")
    }
}

/// The best of a side's rounds for `f`.
fn best(m: &[Measured], f: impl Fn(&Measured) -> f64) -> f64 {
    m.iter().map(f).fold(f64::INFINITY, f64::min)
}

/// The best of a side's rounds for `f` to 3 decimals, or `-` without
/// rounds (Embree not installed).
fn best_or_dash(m: &[Measured], f: impl Fn(&Measured) -> f64) -> String {
    if m.is_empty() {
        "-".into()
    } else {
        format!("{:.3}", best(m, f))
    }
}

/// The table of section 7, its goals in a row under the header.
fn print_scenes(scenes: &[Scene], out: &mut String) {
    let row = |out: &mut String, c: [&str; 12]| {
        let line = format!(
            "   {:>10} {:>10} {:>13} {:>9} {:>7} {:>10} {:>7} {:>10} {:>10} {:>12} {:>10} {:>11}",
            c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10], c[11]
        );
        let _ = writeln!(out, "{}", line.trim_end());
    };
    row(
        out,
        [
            "triangles",
            "render (s)",
            "frame+png (s)",
            "trace (s)",
            "x1 (s)",
            "trace/x1",
            "x16 (s)",
            "trace/x16",
            "render/x1",
            "frame+png/x1",
            "hits vstf",
            "hits embree",
        ],
    );
    row(
        out,
        [
            "goal", "", "", "", "", "<= 1.2x", "", "<= 1.3x", "<= 1.5x", "<= 2x", "", "",
        ],
    );
    for s in scenes {
        let trace = |m: &Measured| m.trace_cpu;
        let render = |m: &Measured| m.frame_cpu;
        let delivered = |m: &Measured| m.delivered_cpu;
        let hits = s.single.first().map_or("-".into(), |m| m.hits.to_string());
        let cells = [
            s.triangles.to_string(),
            format!("{:.3}", best(&s.ours, render)),
            format!("{:.3}", best(&s.ours, delivered)),
            format!("{:.3}", best(&s.ours, trace)),
            best_or_dash(&s.single, trace),
            ratios(&s.ours, &s.single, trace),
            best_or_dash(&s.packets, trace),
            ratios(&s.ours, &s.packets, trace),
            ratios_of(&s.ours, render, &s.single, trace),
            ratios_of(&s.ours, delivered, &s.single, trace),
            s.ours.first().map_or(0, |m| m.hits).to_string(),
            hits,
        ];
        row(out, cells.each_ref().map(String::as_str));
    }
    for s in scenes {
        let _ = writeln!(
            out,
            "   {} triangles moving at 0.9c (V_obj, Lorentz-contracted, relativistic; {} rays hit): trace {:.3} s, {} its static frame each in its own process on every thread, {} both in one process on one bound core, frames in turn (goal <= 1.1x)",
            s.triangles,
            s.moving.first().map_or(0, |m| m.hits),
            best(&s.moving, |m| m.trace_cpu),
            ratios(&s.moving, &s.ours, |m| m.trace_cpu),
            range(s.paired.iter().map(Paired::ratio)),
        );
    }
    let Some(large) = scenes.last() else { return };
    let theirs = !large.single.is_empty();
    let pair = |ours: f64, their: f64, unit: &str| {
        if theirs {
            format!(
                "vstf {ours:.2} {unit}, Embree {their:.2} {unit} ({:.1}x)",
                ours / their
            )
        } else {
            format!("vstf {ours:.2} {unit}")
        }
    };
    let build = |m: &Measured| m.build_cpu;
    let first = |m: &Measured| m.first_frame;
    let _ = writeln!(
        out,
        "   at {} triangles: build {}; first frame (load, build, one frame) {} (goal <= 1.2x)",
        large.triangles,
        pair(
            best(&large.ours, build),
            best(&large.single, build),
            "CPU s"
        ),
        pair(best(&large.ours, first), best(&large.single, first), "s"),
    );
    if let [.., a, b] = scenes {
        let slope = |ma: &[Measured], mb: &[Measured]| {
            let peak = |m: &[Measured]| m.iter().map(|x| x.peak as f64).fold(0.0, f64::max);
            (peak(mb) - peak(ma)) / (b.triangles - a.triangles) as f64
        };
        let _ = writeln!(
            out,
            "   peak memory per triangle ({} -> {} triangles): {} (goal <= 1.2x)",
            a.triangles,
            b.triangles,
            pair(slope(&a.ours, &b.ours), slope(&a.single, &b.single), "B")
        );
    }
}

#[cfg(test)]
mod tests {
    use super::range;

    /// A range of ratios prints as one figure where both ends round to
    /// the same hundredth, as two otherwise, and `-` when empty.
    #[test]
    fn a_range_prints_its_ends_unless_they_round_alike() {
        assert_eq!(range([1.0651, 1.0699].into_iter()), "1.07x");
        assert_eq!(range([1.0649, 1.0651].into_iter()), "1.06-1.07x");
        assert_eq!(range([1.2, 0.95, 1.1].into_iter()), "0.95-1.20x");
        assert_eq!(range(std::iter::empty()), "-");
    }
}
