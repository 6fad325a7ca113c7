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
    let one = renderer::Image {
        width: 1,
        height: 1,
        pixels: vec![color],
    }
    .to_rgb8();
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

fn bary(b: &[f64; 4]) -> String {
    format!("[{:.6}, {:.6}, {:.6}, {:.6}]", b[0], b[1], b[2], b[3])
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
    let mut indent = "";
    for step in &log.steps {
        let line = match step {
            Step::Sample { index, px, py, camera_t } => {
                indent = "";
                format!("sample {index} at image ({px:.4}, {py:.4}), camera t = {camera_t}")
            }
            Step::Ray { kind, depth, origin, direction, normalized, range } => {
                indent = match kind {
                    renderer::RayKind::Shadow => "      ",
                    _ => "  ",
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
            Step::Candidate { tet, object, triangle, prism, piece, outcome } => {
                let what = match outcome {
                    Outcome::Accepted { s, event, bary: b } => format!("ACCEPTED s = {s:.9}, event {}, bary {}", ev(*event), bary(b)),
                    Outcome::Parallel => "rejected: parallel to the tetrahedron's hyperplane".into(),
                    Outcome::OutOfRange { s } => format!("rejected: hyperplane met at s = {s:.6}, outside the searched range"),
                    Outcome::Outside { s, bary: b } => format!("rejected: outside the tetrahedron (s = {s:.6}, bary {})", bary(b)),
                };
                format!("  tet {tet} ({object:?} triangle {triangle}, prism {prism}, piece {piece}): {what}")
            }
            Step::Hit { kind, tet, object, triangle, event, surface_point, proper_time, normal, facing_normal } => format!(
                "{} {object:?} (tet {tet}, triangle {triangle}) at {}; in the object's frame {}; proper time {proper_time:.9}; normal {}, facing {}",
                if *kind == renderer::RayKind::Shadow { "BLOCKED by" } else { "HIT" },
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
        let _ = writeln!(out, "{indent}{line}");
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

/// One field that differs between two logs.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// Line number (1-based) in the logs.
    pub line: usize,
    /// The pixel, as written in the log (`[x,y]`).
    pub pixel: String,
    /// JSON path of the field, e.g. `steps[4].event.t`.
    pub path: String,
    /// The value in the first log.
    pub a: String,
    /// The value in the second log.
    pub b: String,
}

/// Compares two JSON-lines logs pixel by pixel. Numbers agree when
/// |a - b| <= tol * max(1, |a|, |b|); steps whose kind is listed in `ignore`
/// (e.g. `candidate`, which a change of traversal changes) are skipped.
/// Returns the first differing field of every differing pixel.
pub fn diff_logs(a: &str, b: &str, tol: f64, ignore: &[String]) -> Result<Vec<Difference>, String> {
    let parse = |text: &str, which: &str| -> Result<Vec<Value>, String> {
        text.lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty())
            .map(|(i, l)| {
                serde_json::from_str(l).map_err(|e| format!("{which} line {}: {e}", i + 1))
            })
            .collect()
    };
    let (la, lb) = (parse(a, "first log")?, parse(b, "second log")?);
    let mut out = Vec::new();
    for (i, (x, y)) in la.iter().zip(&lb).enumerate() {
        let (x, y) = (strip(x, ignore), strip(y, ignore));
        if let Some((path, va, vb)) = first_difference(&x, &y, "", tol) {
            out.push(Difference {
                line: i + 1,
                pixel: x["pixel"].to_string(),
                path,
                a: va,
                b: vb,
            });
        }
    }
    if la.len() != lb.len() {
        out.push(Difference {
            line: la.len().min(lb.len()) + 1,
            pixel: "-".into(),
            path: "(number of pixels)".into(),
            a: la.len().to_string(),
            b: lb.len().to_string(),
        });
    }
    Ok(out)
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

fn first_difference(
    a: &Value,
    b: &Value,
    path: &str,
    tol: f64,
) -> Option<(String, String, String)> {
    let here = || {
        Some((
            if path.is_empty() {
                ".".into()
            } else {
                path.to_string()
            },
            a.to_string(),
            b.to_string(),
        ))
    };
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64()?, y.as_f64()?);
            if (x - y).abs() <= tol * 1f64.max(x.abs()).max(y.abs()) {
                None
            } else {
                here()
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            if let Some(d) = x
                .iter()
                .zip(y)
                .enumerate()
                .find_map(|(i, (p, q))| first_difference(p, q, &format!("{path}[{i}]"), tol))
            {
                return Some(d);
            }
            if x.len() != y.len() {
                return Some((
                    format!("{path} (length)"),
                    x.len().to_string(),
                    y.len().to_string(),
                ));
            }
            None
        }
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort();
            keys.dedup();
            keys.into_iter().find_map(|k| {
                let sub = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => first_difference(p, q, &sub, tol),
                    (p, q) => Some((sub, format!("{p:?}"), format!("{q:?}"))),
                }
            })
        }
        _ if a == b => None,
        _ => here(),
    }
}
