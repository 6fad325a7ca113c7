//! Debug mode (paper section 4): every variable along a pixel's rays, for a
//! person to read or as JSON lines to compare later. The variables come from
//! the renderer's own functions with recording switched on
//! (`renderer::Trace`), so what is logged is what is rendered.

mod diff;

pub use diff::{diff_logs, diff_streams, Comparison, DiffOptions, Difference, STEP_KINDS};

use crate::fixture::{Fixture, View};
use glam::DVec3;
use renderer::Database;
use renderer::{Outcome, Recorder, Step};
use serde::Serialize;
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
    let mut rec = Recorder::default();
    let frame = renderer::Frame {
        camera: &view.camera,
        camera_t: view.camera_t,
        model: view.model,
        settings: &view.settings,
    };
    let shader = renderer::shader(db, &f.scene, &frame);
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
            Step::Gravitational { emitter_r, observer_r, factor } => format!(
                "gravitational shift: static emitter at r = {emitter_r:.6}, static camera at r = {observer_r:.6}; nu_o/nu_e = sqrt(f(r_e)/f(r_o)) = {factor:.9}"
            ),
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
