//! Choosing a camera time that sees something (`--camera-t auto`), and
//! noticing a render in which a moving object is nowhere in view: a fast
//! object is seen where its light left it, which at the wrong camera time
//! is off the image altogether.
//!
//! Both use the oracle's light-cone solve and the measurements' own camera
//! model, never the renderer's.

use crate::fixture::time::{lifetime, solve};
use crate::fixture::{CameraTime, Fixture, View};
use crate::observer::{uniform, Observer};
use crate::oracle::{instantaneous, retarded, PointWorldline};
use glam::DVec3;
use renderer::{LightSpeed, Model, Shape};

/// The lab time `t` (`--camera-t`) stands for in fixture `f` under `model`:
/// the same solve as a view's `t` ([`crate::fixture::time`]).
pub fn resolve_camera_time(f: &Fixture, t: &CameraTime, model: Model) -> Result<f64, String> {
    solve(f, t, model).map_err(|m| format!("--camera-t: {m}"))
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
        let (t0, t1) = lifetime(obj, view.model);
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
