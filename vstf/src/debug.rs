//! Debug mode (paper section 4): every variable along a pixel's rays, for a
//! person to read or as JSON lines to compare later. The variables come from
//! the renderer's own functions with recording switched on
//! (`renderer::Trace`), so what is logged is what is rendered.

use crate::fixture::{Fixture, View};
use glam::DVec3;
use renderer::Database;
use renderer::{Outcome, Recorder, Step};
use serde::Serialize;
use serde_json::Value;
use std::fmt::Write as _;

/// Everything recorded for one pixel.
#[derive(Clone, Debug, Serialize)]
pub struct PixelLog {
    /// Fixture name.
    pub fixture: String,
    /// Light-speed model of the view.
    pub model: String,
    /// Camera lab time, t.units.
    pub camera_t: f64,
    /// Camera lab position at `camera_t`.
    pub camera: DVec3,
    /// Pixel column and row.
    pub pixel: [u32; 2],
    /// Every variable recorded along the pixel's rays, in order.
    pub steps: Vec<Step>,
    /// Linear colour, and as stored in the 8-bit image.
    pub color: DVec3,
    /// The colour as stored in the 8-bit image.
    pub rgb8: [u8; 3],
}

impl PixelLog {
    /// Drops the prisms and tetrahedra tested but not kept (`candidate` steps): the
    /// compact log, one block per sample of rays, hits and shading.
    pub fn drop_candidates(&mut self) {
        self.steps.retain(|s| !matches!(s, Step::Candidate { .. }));
    }
}

/// Traces pixel (x, y) of `view`, with the database built for it.
pub fn trace_pixel(
    f: &Fixture,
    view: &View,
    db: &Database,
    x: u32,
    y: u32,
) -> Result<PixelLog, String> {
    if x >= view.camera.width || y >= view.camera.height {
        return Err(format!(
            "pixel {x},{y} is outside the {}x{} image",
            view.camera.width, view.camera.height
        ));
    }
    let shader = renderer::shader(db, &f.scene, view.model, &view.settings);
    let mut rec = Recorder::default();
    let frame = renderer::Frame {
        camera: &view.camera,
        camera_t: view.camera_t,
        model: view.model,
        settings: &view.settings,
    };
    let color = renderer::pixel_traced(&shader, &frame, x, y, &mut rec);
    let one = crate::output::rgb8(&renderer::Image {
        width: 1,
        height: 1,
        pixels: vec![color],
    });
    Ok(PixelLog {
        fixture: f.name.clone(),
        model: view.model.to_string(),
        camera_t: view.camera_t,
        camera: view.camera.position_at(view.camera_t),
        pixel: [x, y],
        steps: rec.steps,
        color,
        rgb8: one.get_pixel(0, 0).0,
    })
}

fn v3(v: DVec3) -> String {
    format!("({:.9}, {:.9}, {:.9})", v.x, v.y, v.z)
}

fn ev(e: renderer::Event) -> String {
    format!("t = {:.9}, x = {}", e.t, v3(e.x))
}

fn bary(b: &renderer::Barycentric) -> String {
    let each: Vec<String> = b.coordinates().iter().map(|x| format!("{x:.6}")).collect();
    format!("[{}]", each.join(", "))
}

/// A primitive as the log names it: a prism tested whole, a tetrahedron
/// with its prism and piece, or a sphere.
fn primitive(p: renderer::PrimitiveId) -> String {
    match p {
        renderer::PrimitiveId::Prism(p) => format!("prism {p} (whole)"),
        renderer::PrimitiveId::Tetrahedron(t) => {
            format!("tet {t} (prism {}, piece {})", t / 3, t % 3)
        }
        renderer::PrimitiveId::Sphere(k) => format!("sphere {k}"),
    }
}

/// The log as text for a person, one line per step, indented by ray.
pub fn describe(log: &PixelLog) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "pixel ({}, {}) of {}, {} model, camera at {} at t = {}",
        log.pixel[0],
        log.pixel[1],
        log.fixture,
        log.model,
        v3(log.camera),
        log.camera_t
    );
    // Lines are indented by mirror depth (a reflected ray and what it
    // meets one level in, the shading of the surface it left back out),
    // shadow rays and their blockers two further.
    let base = |depth: u32| "  ".repeat(depth as usize + 1);
    let mut indent = String::new();
    for step in &log.steps {
        let own = match step {
            Step::Shading { depth, .. }
            | Step::Doppler { depth, .. }
            | Step::Reflection { depth, .. } => Some(base(*depth)),
            _ => None,
        };
        let line = match step {
            Step::Sample { index, px, py, camera_t } => {
                indent = String::new();
                format!("sample {index} at image ({px:.4}, {py:.4}), camera t = {camera_t}")
            }
            Step::Ray { kind, depth, origin, direction, normalized, range } => {
                indent = match kind {
                    renderer::RayKind::Shadow => base(*depth) + "    ",
                    _ => base(*depth),
                };
                format!(
                    "{kind:?} ray (depth {depth}): origin {}; direction t = {}, x = {}; normalized t = {:.9}, x = {}; s in [{:e}, {:e}]",
                    ev(*origin),
                    direction.t,
                    v3(direction.x),
                    normalized.t,
                    v3(normalized.x),
                    range.0,
                    range.1
                )
            }
            Step::Candidate { primitive: p, object, triangle, prism: _, outcome } => {
                let what = match outcome {
                    Outcome::Accepted { s, event, bary: b } => format!("ACCEPTED s = {s:.9}, event {}, bary {}", ev(*event), bary(b)),
                    Outcome::Parallel => "rejected: parallel to its hyperplane".into(),
                    Outcome::OutOfRange { s } => format!("rejected: hyperplane met at s = {s:.6}, outside the searched range"),
                    Outcome::Outside { s, bary: b } => format!("rejected: outside it (s = {s:.6}, bary {})", bary(b)),
                    Outcome::OutOfSpan { s, t } => format!("rejected: triangle crossed at s = {s:.6}, t = {t:.6}, outside the prism's lab times"),
                };
                format!("  {} ({object:?} triangle {triangle}): {what}", primitive(*p))
            }
            Step::Hit { kind, primitive: p, object, triangle, event, surface_point, proper_time, start_t, normal, facing_normal } => format!(
                "{} {object:?} ({}, triangle {triangle}) at {}; in the object's frame {}; proper time {proper_time:.9} since its start at t = {start_t}; normal {}, facing {}",
                if *kind == renderer::RayKind::Shadow { "BLOCKED by" } else { "HIT" },
                primitive(*p),
                ev(*event),
                v3(*surface_point),
                v3(*normal),
                v3(*facing_normal)
            ),
            Step::Miss { kind, background } => format!("{kind:?} ray met nothing: background {}", v3(*background)),
            Step::Shading { .. } => shading_line(step),
            Step::Doppler { depth, surface_velocity, gamma, from_light, to_origin, from_mirror, surface_nm, surface_radiance } => {
                let mut line = format!(
                    "doppler (depth {depth}): surface velocity {} (gamma {gamma:.9}); nu_s/nu_lab from the light {from_light:.9}; D = nu_lab/nu_s towards the ray's origin {to_origin:.9}",
                    v3(*surface_velocity)
                );
                if let Some(f) = from_mirror {
                    line += &format!("; nu_s/nu_lab from the mirror ray {f:.9}");
                }
                if let (Some(nm), Some(r)) = (surface_nm, surface_radiance) {
                    line += &format!("; surface-frame spectrum {}", spectrum_line(nm, r));
                }
                line
            }
            Step::Reflection { .. } => reflection_line(step),
            Step::Observed { doppler, lab_nm, xyz, color } => {
                let mut line = format!("observed: nu_cam/nu_lab {doppler:.9}; colour {}", v3(*color));
                if let (Some(nm), Some(xyz)) = (lab_nm, xyz) {
                    line += &format!(
                        "; band {:.3}..{:.3} nm in the lab; XYZ {}",
                        nm[0],
                        nm[nm.len() - 1],
                        v3(*xyz)
                    );
                }
                line
            }
        };
        let _ = writeln!(out, "{}{line}", own.as_deref().unwrap_or(&indent));
    }
    let _ = writeln!(out, "colour {} -> 8-bit {:?}", v3(log.color), log.rgb8);
    out
}

/// The shading terms at a hit; for a moving surface, the directions it
/// shades with, in its own frame.
fn shading_line(step: &Step) -> String {
    let Step::Shading {
        depth,
        albedo,
        ambient,
        light_vector,
        light_distance,
        lambert,
        surface_frame,
        in_shadow,
        diffuse,
        specular,
        mirror,
        local,
        color,
    } = step
    else {
        return String::new();
    };
    let frame = surface_frame.map_or(String::new(), |[n, l, v]| {
        format!(
            " (in the surface's frame: normal {}, to the light {}, to the viewer {})",
            v3(n),
            v3(l),
            v3(v)
        )
    });
    format!(
        "shading (depth {depth}): albedo {}; ambient {}; light vector {} at {light_distance:.6}; n.l = {lambert:.9}{frame}; in shadow: {in_shadow}; diffuse {}; specular {specular:.9}; mirror {mirror}; local {}; colour {}",
        v3(*albedo),
        v3(*ambient),
        v3(*light_vector),
        v3(*diffuse),
        v3(*local),
        v3(*color)
    )
}

/// A moving mirror's reflection, with its rest-frame directions.
fn reflection_line(step: &Step) -> String {
    let Step::Reflection {
        depth,
        mirror_velocity,
        k_out,
        k_in,
        frequency_ratio,
        rest_frame,
    } = step
    else {
        return String::new();
    };
    let mut line = format!(
        "reflection (depth {depth}) by a mirror moving at {}: photon out along {}, in along {}; nu_out/nu_in {frequency_ratio:.9}",
        v3(*mirror_velocity),
        v3(*k_out),
        v3(*k_in)
    );
    if let Some([n, out, inc]) = rest_frame {
        line += &format!(
            "; in the mirror's rest frame: normal {}, out {}, in {}",
            v3(*n),
            v3(*out),
            v3(*inc)
        );
    }
    line
}

/// A spectrum in brief: every 10th sample as wavelength:value (the log
/// file has them all).
fn spectrum_line(nm: &[f64], values: &[f64]) -> String {
    nm.iter()
        .zip(values)
        .step_by(10)
        .map(|(l, v)| format!("{l:.1}:{v:.6}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The kinds of steps a log holds (the `step` tag of each), which
/// `debug-diff --ignore` may skip.
pub const STEP_KINDS: [&str; 9] = [
    "sample",
    "ray",
    "candidate",
    "hit",
    "miss",
    "shading",
    "doppler",
    "reflection",
    "observed",
];

/// The first field that differs between two logs' pixel, and how many did.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// Line number (1-based) in the logs.
    pub line: usize,
    /// The pixel, as written in the log (`[x,y]`).
    pub pixel: String,
    /// JSON path of the first differing field, with the kind of its step,
    /// e.g. `steps[4] (hit).event.t`.
    pub path: String,
    /// Its value in the first log.
    pub a: String,
    /// Its value in the second log.
    pub b: String,
    /// Every differing field of the pixel (path, first, second), the first
    /// of them included; only the first with `first_only`.
    pub fields: Vec<(String, String, String)>,
}

/// How two logs compare: the differing pixels kept (the first `keep`), how
/// many differ in all, and how many lines each log has.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Comparison {
    /// The first differing pixels, in order.
    pub shown: Vec<Difference>,
    /// All differing pixels (a different number of lines counts as one).
    pub differing: usize,
    /// Lines in the first and the second log.
    pub lines: (usize, usize),
}

/// How a comparison of logs treats numbers and steps: numbers agree when
/// |a - b| <= tol * max(1, |a|, |b|); steps of the kinds in `ignore` are
/// skipped; `first_only` keeps only each pixel's first differing field.
pub struct DiffOptions<'a> {
    /// The relative tolerance.
    pub tol: f64,
    /// Step kinds skipped (each one of [`STEP_KINDS`]).
    pub ignore: &'a [String],
    /// Only the first differing field of each pixel.
    pub first_only: bool,
    /// How many differing pixels to keep.
    pub keep: usize,
}

/// Compares two JSON-lines logs pixel by pixel, reading both a line at a
/// time (constant memory whatever their size).
pub fn diff_streams(
    a: impl std::io::BufRead,
    b: impl std::io::BufRead,
    o: &DiffOptions,
) -> Result<Comparison, String> {
    if let Some(bad) = o.ignore.iter().find(|k| !STEP_KINDS.contains(&k.as_str())) {
        return Err(format!(
            "--ignore {bad:?}: no such step kind (the kinds: {})",
            STEP_KINDS.join(", ")
        ));
    }
    let mut out = Comparison::default();
    let (mut la, mut lb) = (a.lines(), b.lines());
    let parse = |line: Option<std::io::Result<String>>,
                 which: &str,
                 n: usize|
     -> Result<Option<Value>, String> {
        match line {
            None => Ok(None),
            Some(Err(e)) => Err(format!("{which} line {n}: {e}")),
            Some(Ok(l)) => serde_json::from_str(&l)
                .map(Some)
                .map_err(|e| format!("{which} line {n}: {e}")),
        }
    };
    loop {
        let n = out.lines.0.max(out.lines.1) + 1;
        let (x, y) = (
            parse(la.next(), "first log", n)?,
            parse(lb.next(), "second log", n)?,
        );
        out.lines.0 += usize::from(x.is_some());
        out.lines.1 += usize::from(y.is_some());
        let (x, y) = match (x, y) {
            (Some(x), Some(y)) => (x, y),
            (None, None) => break,
            _ => {
                // One log ends: count the rest of the other.
                out.lines.0 += la.by_ref().count();
                out.lines.1 += lb.by_ref().count();
                out.differing += 1;
                if out.shown.len() < o.keep {
                    let (a, b) = (out.lines.0.to_string(), out.lines.1.to_string());
                    out.shown.push(Difference {
                        line: n,
                        pixel: "-".into(),
                        path: "(number of pixels)".into(),
                        fields: vec![("(number of pixels)".into(), a.clone(), b.clone())],
                        a,
                        b,
                    });
                }
                break;
            }
        };
        let (x, y) = (strip(&x, o.ignore), strip(&y, o.ignore));
        let mut fields = Vec::new();
        differences(&x, &y, "", o, &mut fields);
        if let Some((path, a, b)) = fields.first().cloned() {
            out.differing += 1;
            if out.shown.len() < o.keep {
                out.shown.push(Difference {
                    line: n,
                    pixel: x["pixel"].to_string(),
                    path,
                    a,
                    b,
                    fields,
                });
            }
        }
    }
    Ok(out)
}

/// Compares two JSON-lines logs held in memory: the first differing field
/// of every differing pixel (see [`diff_streams`]).
pub fn diff_logs(a: &str, b: &str, tol: f64, ignore: &[String]) -> Result<Vec<Difference>, String> {
    let o = DiffOptions {
        tol,
        ignore,
        first_only: true,
        keep: usize::MAX,
    };
    Ok(diff_streams(a.as_bytes(), b.as_bytes(), &o)?.shown)
}

fn strip(v: &Value, ignore: &[String]) -> Value {
    let mut v = v.clone();
    if let Some(steps) = v.get_mut("steps").and_then(Value::as_array_mut) {
        steps.retain(|s| {
            !s["step"]
                .as_str()
                .is_some_and(|k| ignore.iter().any(|i| i == k))
        });
    }
    v
}

/// The most fields of one pixel listed.
const MAX_FIELDS: usize = 64;

/// Appends every field where `a` and `b` differ (only the first with
/// `first_only`), with its path; a step's path names its kind.
fn differences(
    a: &Value,
    b: &Value,
    path: &str,
    o: &DiffOptions,
    out: &mut Vec<(String, String, String)>,
) {
    let full = |out: &Vec<_>| out.len() >= MAX_FIELDS || (o.first_only && !out.is_empty());
    if full(out) {
        return;
    }
    let here = |out: &mut Vec<(String, String, String)>| {
        let p = if path.is_empty() {
            ".".into()
        } else {
            path.to_string()
        };
        out.push((p, a.to_string(), b.to_string()));
    };
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            let agree = (x - y).abs() <= o.tol * 1f64.max(x.abs()).max(y.abs());
            if !agree {
                here(out);
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                let kind = match (path, p["step"].as_str(), q["step"].as_str()) {
                    ("steps", Some(k), Some(l)) if k != l => {
                        // Steps of different kinds: one difference, not their fields.
                        out.push((
                            format!("{path}[{i}] (kind of step)"),
                            k.to_string(),
                            l.to_string(),
                        ));
                        if full(out) {
                            return;
                        }
                        continue;
                    }
                    ("steps", Some(k), _) => format!(" ({k})"),
                    _ => String::new(),
                };
                differences(p, q, &format!("{path}[{i}]{kind}"), o, out);
                if full(out) {
                    return;
                }
            }
            if x.len() != y.len() {
                out.push((
                    format!("{path} (length)"),
                    x.len().to_string(),
                    y.len().to_string(),
                ));
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort();
            keys.dedup();
            for k in keys {
                let sub = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => differences(p, q, &sub, o, out),
                    (p, q) => out.push((sub, format!("{p:?}"), format!("{q:?}"))),
                }
                if full(out) {
                    return;
                }
            }
        }
        _ if a == b => {}
        _ => here(out),
    }
}
