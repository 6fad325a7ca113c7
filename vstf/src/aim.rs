//! Choosing a camera time that sees something (`--camera-t auto`), and
//! noticing a render in which a moving object is nowhere in view: a fast
//! object is seen where its light left it, which at the wrong camera time
//! is off the image altogether.
//!
//! Both use the oracle's light-cone solve and the measurements' own camera
//! model, never the renderer's.

use crate::fixture::{Fixture, View};
use crate::observer::{uniform, Observer};
use crate::oracle::{instantaneous, retarded, PointWorldline};
use glam::DVec3;
use renderer::{LightSpeed, Shape};
use std::str::FromStr;

/// A camera time as `--camera-t` gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraTime {
    /// This lab time, t.units.
    At(f64),
    /// When light leaving the looked-at point at t = 0 arrives: the light
    /// time from `camera.look_at` to the camera.
    Auto,
    /// When light leaving the named object's reference point, as it passes
    /// closest to the line of sight, arrives.
    AutoObject(String),
}

impl FromStr for CameraTime {
    type Err = String;
    fn from_str(s: &str) -> Result<CameraTime, String> {
        if s == "auto" {
            return Ok(CameraTime::Auto);
        }
        if let Some(name) = s.strip_prefix("auto:") {
            return Ok(CameraTime::AutoObject(name.to_string()));
        }
        match s.parse::<f64>() {
            Ok(t) if t.is_finite() => Ok(CameraTime::At(t)),
            _ => Err(format!(
                "{s:?}: expected a time in t.units, `auto` (the light time from the looked-at point) \
                 or `auto:OBJECT` (when the object is seen crossing the line of sight)"
            )),
        }
    }
}

/// The lab time `t` stands for in fixture `f`.
pub fn resolve_camera_time(f: &Fixture, t: &CameraTime) -> Result<f64, String> {
    let c = &f.spec.camera;
    if !matches!(t, CameraTime::At(_)) && c.velocity.is_some_and(|v| v != DVec3::ZERO) {
        return Err("--camera-t auto is for a camera at rest (camera.velocity is set)".into());
    }
    match t {
        CameraTime::At(t) => Ok(*t),
        CameraTime::Auto => {
            let look = c.look_at.ok_or(
                "--camera-t auto needs camera.look_at; or name an object: --camera-t auto:OBJECT",
            )?;
            Ok(look.distance(c.position))
        }
        CameraTime::AutoObject(name) => crossing_time(f, name),
    }
}

/// The unit direction the fixture's camera looks along.
fn line_of_sight(f: &Fixture) -> DVec3 {
    let c = &f.spec.camera;
    match c.look_at {
        Some(p) => (p - c.position).normalize_or_zero(),
        None => {
            let (yaw, pitch) = (
                c.yaw_deg.unwrap_or(0.0).to_radians(),
                c.pitch_deg.unwrap_or(0.0).to_radians(),
            );
            // libm, as the renderer's camera: the same bits on every platform.
            DVec3::new(
                -libm::sin(yaw) * libm::cos(pitch),
                libm::sin(pitch),
                -libm::cos(yaw) * libm::cos(pitch),
            )
        }
    }
}

/// The camera time at which the object `name`'s reference point is seen
/// where it passes closest to the camera's line of sight (within its
/// lifetime): t_c = t* + |x(t*) - camera|.
fn crossing_time(f: &Fixture, name: &str) -> Result<f64, String> {
    let obj = f.object(name)?;
    let (start, v) = uniform(&obj.motion).ok_or_else(|| {
        format!("--camera-t auto:{name}: {name:?} does not move uniformly (extrusion or velocity)")
    })?;
    let camera = f.spec.camera.position;
    let a = line_of_sight(f);
    let across = |w: DVec3| w - a * w.dot(a);
    // x(t) - camera = p0 + v t; its part across the line of sight is least at t*.
    let p0 = start.x - v * start.t - camera;
    let (p, w) = (across(p0), across(v));
    let t = if w.length_squared() > 0.0 {
        -p.dot(w) / w.length_squared()
    } else {
        start.t
    };
    let (t0, t1) = lifetime(f, obj);
    let t = t.clamp(t0, t1);
    Ok(t + (p0 + v * t).length())
}

/// An object's lab lifetime as the fixture gives it.
fn lifetime(f: &Fixture, obj: &renderer::SceneObject) -> (f64, f64) {
    match &obj.motion {
        renderer::Motion::Extrusion { start, extrusion } => {
            let (a, b) = (start.t, start.t + extrusion.t);
            (a.min(b), a.max(b))
        }
        renderer::Motion::Velocity {
            start,
            velocity,
            proper_lifetime,
        } => {
            let lorentz =
                obj.kind == renderer::ObjectKind::VObj && f.model(&Default::default()).lorentz;
            let g = if lorentz {
                1.0 / (1.0 - velocity.length_squared()).sqrt()
            } else {
                1.0
            };
            (start.t, start.t + g * proper_lifetime)
        }
        _ => (f64::NEG_INFINITY, f64::INFINITY),
    }
}

/// A warning for each moving object (uniform motion) that `view` does not
/// show at all: where its reference point is seen lies farther outside the
/// image than the object's size, or its light would have left before it
/// existed or after it ended.
pub fn out_of_view(f: &Fixture, view: &View) -> Vec<String> {
    let setup = Observer {
        fixture: f,
        model: view.model,
        camera_t: view.camera_t,
    };
    let Ok(pinhole) = setup.pinhole((view.camera.width, view.camera.height)) else {
        return Vec::new();
    };
    let camera = setup.camera_x();
    let (w, h) = (f64::from(view.camera.width), f64::from(view.camera.height));
    let mut warnings = Vec::new();
    for obj in &f.scene.objects {
        let Some((start, v)) = uniform(&obj.motion) else {
            continue;
        };
        if v == DVec3::ZERO {
            continue;
        }
        let p = PointWorldline {
            t0: start.t,
            x0: start.x,
            v,
        };
        let seen = match view.model.light_speed {
            LightSpeed::Finite => retarded(&p, view.camera_t, camera),
            LightSpeed::Infinite => Some(instantaneous(&p, view.camera_t, camera)),
        };
        let hint = if obj.name.contains(char::is_whitespace) {
            format!("try --camera-t \"auto:{}\"", obj.name)
        } else {
            format!("try --camera-t auto:{}", obj.name)
        };
        let Some(seen) = seen else {
            warnings.push(format!(
                "{:?} is never seen from the camera at t = {}; {hint}",
                obj.name, view.camera_t
            ));
            continue;
        };
        let (t0, t1) = lifetime(f, obj);
        if seen.t < t0 || seen.t > t1 {
            warnings.push(format!(
                "{:?} is not in view: light reaching the camera at t = {} would have had to leave it at t = {:.4}, outside its lifetime [{t0}, {t1}]; {hint}",
                obj.name, view.camera_t, seen.t
            ));
            continue;
        }
        let size = reach(obj) / seen.x.distance(camera).max(1e-300);
        let margin = size / pinhole.angular_footprint(w / 2.0, h / 2.0, true);
        let inside = pinhole
            .pixel_of(seen.direction)
            .is_some_and(|(x, y)| x > -margin && y > -margin && x < w + margin && y < h + margin);
        if !inside {
            warnings.push(format!(
                "{:?} is out of view: at t = {} the camera sees it where its light left it at t = {:.4}, at ({:.3}, {:.3}, {:.3}), outside the image; {hint}",
                obj.name, view.camera_t, seen.t, seen.x.x, seen.x.y, seen.x.z
            ));
        }
    }
    warnings
}

/// The radius about the reference point that holds the object.
fn reach(obj: &renderer::SceneObject) -> f64 {
    match &obj.shape {
        Shape::Mesh(m) => m.vertices.iter().map(|p| p.length()).fold(0.0, f64::max),
        Shape::Sphere { radius } => *radius,
    }
}
