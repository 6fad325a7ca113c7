//! Images out: `render --out FILE.exr` (with `--aovs`, its layers) read
//! back by an independent reader, OpenImageIO's `oiiotool`, and checked
//! against a light-cone solve written here from the formulas; JPEG; and
//! what is refused, leaving nothing behind (videos in `videos`).
//!
//! Without oiiotool the tests that need it say so and skip; with
//! `VSTF_REQUIRE_MEDIA` set (as `.ci/run` does once it has installed it)
//! its absence is a failure ([`media`]).

use crate::support::{media, rgb, vstf, RunExt, Scratch};
use std::path::{Path, PathBuf};
use std::process::Command;

/// An EXR as OpenImageIO reads it: its channel names and each pixel's
/// values, row-major.
struct Oiio {
    channels: Vec<String>,
    width: usize,
    pixels: Vec<Vec<f32>>,
}

impl Oiio {
    /// Reads `file` with `oiiotool --info -v` (the channel list) and
    /// `oiiotool --dumpdata` (every pixel's values, in that order).
    fn read(file: &Path) -> Oiio {
        let run = |args: &[&str]| {
            let out = Command::new("oiiotool")
                .args(args)
                .arg(file)
                .output()
                .unwrap();
            assert!(out.status.success(), "oiiotool {args:?}: {out:?}");
            String::from_utf8(out.stdout).unwrap()
        };
        let info = run(&["--info", "-v"]);
        let list = info
            .lines()
            .find_map(|l| l.trim().strip_prefix("channel list:"))
            .unwrap_or_else(|| panic!("no channel list in {info}"));
        let channels: Vec<String> = list.split(',').map(|c| c.trim().to_string()).collect();
        let mut width = 0;
        let mut pixels = Vec::new();
        for line in run(&["--dumpdata"]).lines() {
            let Some(rest) = line.trim().strip_prefix("Pixel (") else {
                continue;
            };
            let (xy, values) = rest.split_once("):").unwrap();
            let (x, y) = xy.split_once(',').unwrap();
            let (x, y): (usize, usize) = (x.trim().parse().unwrap(), y.trim().parse().unwrap());
            if y == 0 {
                width = width.max(x + 1);
            }
            assert_eq!(pixels.len(), y * width.max(1) + x, "pixels out of order");
            let v: Vec<f32> = values
                .split_whitespace()
                .map(|s| s.parse().unwrap())
                .collect();
            assert_eq!(v.len(), channels.len(), "{line}");
            pixels.push(v);
        }
        Oiio {
            channels,
            width,
            pixels,
        }
    }

    /// Channel `name` at pixel (x, y).
    #[track_caller]
    fn at(&self, name: &str, (x, y): (usize, usize)) -> f64 {
        let k = self
            .channels
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no channel {name} in {:?}", self.channels));
        f64::from(self.pixels[y * self.width + x][k])
    }
}

/// The relative rounding of a value stored as f32 (half its unit in the
/// last place), the tolerance of every comparison with the oracle below
/// beside 1e-9 absolute: the f64 solves on both sides, and oiiotool's nine
/// printed decimals (5e-10).
const F32_ROUNDING: f64 = 1.0 / (1u64 << 24) as f64;

/// What the sphere of `sphere-relativistic` shows through the centre of
/// pixel (px, py) of a 96x72 image at camera time `tc`, solved here from
/// first principles: a sphere of radius 1 at rest in its frame, moving at
/// 0.9c along x, centre at lab time t at (-81 + 0.9 (t + 100), 0, -10),
/// Lorentz-contracted to x semi-axis 1/gamma (V_obj); the camera at rest
/// at the origin looking along -z, vfov 30 degrees. The light reaching the
/// camera at tc along -d left the event (tc - s, s d) for the smallest s
/// that puts it on the contracted sphere. Returns (s, t, proper time,
/// Doppler factor, unit normal), or None if the ray misses.
fn light_cone_solve(px: usize, py: usize, tc: f64) -> Option<(f64, f64, f64, f64, [f64; 3])> {
    let (w, h) = (96.0, 72.0);
    let beta: f64 = 0.9;
    let gamma = 1.0 / (1.0 - beta * beta).sqrt();
    let tan_half = (30f64.to_radians() / 2.0).tan();
    let u = ((px as f64 + 0.5) / w * 2.0 - 1.0) * tan_half * w / h;
    let v = (1.0 - (py as f64 + 0.5) / h * 2.0) * tan_half;
    let n = (u * u + v * v + 1.0).sqrt();
    let d = [u / n, v / n, -1.0 / n];
    // Point minus centre at s: s (d + beta x) - c0, with x stretched by gamma.
    let c0 = [-81.0 + beta * (tc + 100.0), 0.0, -10.0];
    let a = [gamma * (d[0] + beta), d[1], d[2]];
    let b = [-gamma * c0[0], -c0[1], -c0[2]];
    let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let (qa, qb, qc) = (dot(a, a), 2.0 * dot(a, b), dot(b, b) - 1.0);
    let disc = qb * qb - 4.0 * qa * qc;
    if disc <= 0.0 {
        return None;
    }
    let s = (-qb - disc.sqrt()) / (2.0 * qa);
    let t = tc - s;
    // The body's clocks read its rest-frame time since the start event
    // (t = -100, x = -81): gamma (dt - beta dx).
    let proper = gamma * ((t + 100.0) - beta * (s * d[0] + 81.0));
    // Light from the surface's rest frame along -d into the lab.
    let doppler = 1.0 / (gamma * (1.0 + beta * d[0]));
    let centre = [-81.0 + beta * (t + 100.0), 0.0, -10.0];
    let off = [s * d[0] - centre[0], s * d[1], s * d[2] - centre[2]];
    let g = [gamma * gamma * off[0], off[1], off[2]];
    let len = dot(g, g).sqrt();
    Some((s, t, proper, doppler, [g[0] / len, g[1] / len, g[2] / len]))
}

/// `vstf render sphere-relativistic` at 96x72, 1 sample, into `out`.
fn render_sphere(out: &Path, extra: &[&str]) {
    vstf()
        .args([
            "render",
            "sphere-relativistic",
            "--width",
            "96",
            "--height",
            "72",
        ])
        .args(["--spp", "1", "--out"])
        .arg(out)
        .args(extra)
        .run()
        .succeeds();
}

#[track_caller]
fn close(got: f64, want: f64, what: &str) {
    let tol = want.abs() * F32_ROUNDING + 1e-9;
    assert!(
        (got - want).abs() <= tol,
        "{what}: EXR {got}, oracle {want}, tolerance {tol:.3e} (f32 rounding + 1e-9)"
    );
}

const PIXELS: [(usize, usize); 8] = [
    (48, 36),
    (44, 30),
    (52, 40),
    (40, 36),
    (56, 36),
    (48, 33),
    (5, 5),
    (90, 60),
];

/// The EXR's radiance is the PNG's values before quantisation; its layers
/// at eight pixels (six on the sphere, two off) are the oracle's; a pixel
/// of nothing has object -1 and NaN elsewhere.
#[test]
fn exr_layers_agree_with_a_light_cone_solve() {
    if !media(&["oiiotool"], "the EXR layers test") {
        return;
    }
    let dir = Scratch::new("exr-layers");
    let (exr, png) = (dir.join("a.exr"), dir.join("a.png"));
    render_sphere(&exr, &["--aovs"]);
    render_sphere(&png, &[]);
    let read = Oiio::read(&exr);
    let names =
        "R G B event_t proper_time doppler searchlight object distance normal.X normal.Y normal.Z";
    for name in names.split(' ') {
        assert!(
            read.channels.iter().any(|c| c == name),
            "{name}: {:?}",
            read.channels
        );
    }
    assert_eq!((read.width, read.pixels.len()), (96, 96 * 72));
    // Radiance: the PNG holds round(255 clamp(v)); the EXR holds v as f32.
    let png = rgb(&png);
    let mut lit = 0;
    for (x, y, p) in png.enumerate_pixels() {
        for (k, c) in ["R", "G", "B"].iter().enumerate() {
            let v = read.at(c, (x as usize, y as usize));
            let tol = 0.5 + 255.0 * F32_ROUNDING;
            assert!(
                (255.0 * v.clamp(0.0, 1.0) - f64::from(p[k])).abs() <= tol,
                "({x}, {y}) {c}: EXR {v}, PNG {}",
                p[k]
            );
        }
        lit += usize::from(p.0 != [0, 0, 0]);
    }
    assert!(lit > 50, "the sphere covers {lit} pixels");
    let (mut hits, mut misses) = (0, 0);
    for px in PIXELS {
        let Some((s, t, proper, doppler, normal)) = light_cone_solve(px.0, px.1, 0.0) else {
            misses += 1;
            assert_eq!(read.at("object", px), -1.0, "{px:?}");
            for c in names.split(' ').skip(3).filter(|c| *c != "object") {
                assert!(read.at(c, px).is_nan(), "{px:?} {c}: {}", read.at(c, px));
            }
            assert_eq!(
                [read.at("R", px), read.at("G", px), read.at("B", px)],
                [0.0; 3]
            );
            continue;
        };
        hits += 1;
        let at = |c: &str| read.at(c, px);
        assert_eq!(at("object"), 0.0, "{px:?}");
        close(at("event_t"), t, "event_t");
        close(at("distance"), s, "distance");
        close(at("proper_time"), proper, "proper_time");
        close(at("doppler"), doppler, "doppler");
        close(at("searchlight"), doppler.powi(4), "searchlight");
        for (c, want) in ["normal.X", "normal.Y", "normal.Z"].iter().zip(normal) {
            close(at(c), want, c);
        }
    }
    assert!(hits >= 5 && misses >= 2, "{hits} hits, {misses} misses");
    // Negative controls: a layer that is not there is not found, and a
    // camera time one unit later gives other retarded times, which the same
    // solve at that time predicts.
    let out = Command::new("oiiotool")
        .arg(&exr)
        .args(["--ch", "event_time", "-o"])
        .arg(dir.join("none.exr"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("Unknown channel name \"event_time\""),
        "{said}"
    );
    let later = dir.join("later.exr");
    render_sphere(&later, &["--aovs", "--camera-t", "1"]);
    let later = Oiio::read(&later);
    let px = (48, 36);
    let (_, t0, ..) = light_cone_solve(px.0, px.1, 0.0).unwrap();
    let (_, t1, ..) = light_cone_solve(px.0, px.1, 1.0).unwrap();
    // The light of the receding surface takes longer: the retarded time
    // moves by 1 less the extra light time, a few hundredths, still
    // thousands of tolerances.
    let moved = (later.at("event_t", px) - t0).abs();
    assert!(
        moved > 1000.0 * (t0.abs() * F32_ROUNDING + 1e-9),
        "the time layer moved by {moved} only"
    );
    assert!((t1 - t0).abs() > 0.01, "the oracle's times {t0} and {t1}");
    close(later.at("event_t", px), t1, "event_t at t_c = 1");
}

/// JPEG for one image; what a single image cannot be written as is
/// refused before anything is rendered, and nothing is left.
#[test]
fn jpeg_output_and_refused_image_outputs() {
    let dir = Scratch::new("still-formats");
    let (jpg, png) = (dir.join("a.jpeg"), dir.join("a.png"));
    render_sphere(&jpg, &[]);
    render_sphere(&png, &[]);
    let (jpg, png) = (rgb(&jpg), rgb(&png));
    assert_eq!(jpg.dimensions(), (96, 72));
    let mean_error = jpg
        .as_raw()
        .iter()
        .zip(png.as_raw())
        .map(|(a, b)| f64::from(a.abs_diff(*b)))
        .sum::<f64>()
        / png.as_raw().len() as f64;
    assert!(mean_error < 2.0, "mean JPEG error {mean_error} levels");
    let refused = |out: &Path, extra: &[&str], message: &str| {
        vstf()
            .args([
                "render",
                "sphere-relativistic",
                "--width",
                "32",
                "--height",
                "24",
                "--out",
            ])
            .arg(out)
            .args(extra)
            .run()
            .fails_with(message);
    };
    refused(
        &dir.join("x.png"),
        &["--aovs"],
        "--aovs: the output variables are layers of an OpenEXR file",
    );
    refused(
        &dir.join("x.exr"),
        &["--models", "all"],
        "an EXR holds one view",
    );
    refused(&dir.join("x.mp4"), &[], "vstf animate writes it");
    std::fs::create_dir(dir.join("d.exr")).unwrap();
    refused(
        &dir.join("d.exr"),
        &[],
        "is a directory, not a regular file",
    );
    let mut left: Vec<PathBuf> = std::fs::read_dir(&*dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    left.sort();
    assert_eq!(
        left,
        [dir.join("a.jpeg"), dir.join("a.png"), dir.join("d.exr")]
    );
}

/// An EXR with its layers is the same file bit for bit whatever the thread
/// count, and a declared view (`--view`) is written as EXR too; the header
/// records the camera time of the view.
#[test]
fn exr_files_are_deterministic_and_take_declared_views() {
    let dir = Scratch::new("exr-determinism");
    let write = |name: &str, threads: &str, extra: &[&str]| {
        let out = dir.join(name);
        vstf()
            .env("RAYON_NUM_THREADS", threads)
            .args(["render", "sphere-relativistic", "--out"])
            .arg(&out)
            .arg("--aovs")
            .args(extra)
            .run()
            .succeeds();
        std::fs::read(out).unwrap()
    };
    let small = ["--width", "64", "--height", "48", "--spp", "2"];
    let one = write("one.exr", "1", &small);
    let two = write("two.exr", "2", &small);
    assert!(one == two, "the EXR differs between 1 and 2 threads");
    let later = write(
        "later.exr",
        "2",
        &[&small[..], &["--camera-t", "1"]].concat(),
    );
    assert!(one != later, "a later camera time wrote the same file");
    let view = write("view.exr", "2", &["--view", "view"]);
    assert!(
        view.starts_with(&[0x76, 0x2f, 0x31, 0x01]),
        "not an OpenEXR file"
    );
    let text = String::from_utf8_lossy(&view);
    assert!(text.contains("vstfCameraT") && text.contains("event_t"));
}
