//! Choosing a camera time that sees something (`--camera-t auto`), and
//! noticing a render in which an object, or everything, is nowhere in view:
//! a fast object is seen where its light left it, which at the wrong camera
//! time is off the image altogether; a camera looking away, or a field of
//! view given in radians, shows nothing at any time.
//!
//! All of it uses the oracle's light-cone solve and the measurements' own
//! camera model, never the renderer's.

use crate::fixture::solve::{lifetime, line_of_sight, solve};
use crate::fixture::{CameraTime, Fixture, View};
use crate::measure::Pinhole;
use crate::observer::{uniform, Observer};
use crate::oracle::{body_point, instantaneous, retarded};
use glam::DVec3;
use renderer::{LightSpeed, Model, ObjectKind, SceneObject, Shape};

/// Below this vertical field of view (degrees) a value is more likely
/// radians than a telephoto lens.
const NARROW_VFOV_DEG: f64 = 5.0;

/// Most body points of a mesh sampled for visibility.
const MAX_POINTS: usize = 4096;

/// The lab time `t` (`--camera-t`) stands for in fixture `f` under `model`:
/// the same solve as a view's `t` ([`crate::fixture::time`]).
pub fn resolve_camera_time(f: &Fixture, t: &CameraTime, model: Model) -> Result<f64, String> {
    solve(&f.spec, &f.scene, t, model).map_err(|m| format!("--camera-t: {m}"))
}

/// A warning if the camera's field of view is under 5 degrees: more likely
/// radians, it fills the image with one colour and leaves no edge to measure.
pub(crate) fn narrow_field_of_view(f: &Fixture) -> Option<String> {
    let vfov = f.spec.camera.vfov_deg;
    (vfov < NARROW_VFOV_DEG).then(|| {
        format!(
            "camera.vfov_deg is {vfov}: a field of view under {NARROW_VFOV_DEG} degrees; it is in degrees (radians {vfov} would be {:.1} degrees)",
            vfov.to_degrees()
        )
    })
}

/// How much of an object a camera sees at one camera time.
#[derive(Clone, Debug, PartialEq)]
enum Sight {
    /// Some part of it lies in the image.
    InView {
        /// Its largest extent in the image, pixels.
        pixels: f64,
    },
    /// Its light would have left it outside its lifetime (at this lab time).
    NotAlive(f64),
    /// Its worldline never meets the camera's past light cone.
    Never,
    /// Seen, but wholly outside the image (its reference point seen there).
    Outside(DVec3),
    /// Not judged (accelerated or keyframed motion).
    Unknown,
}

/// Where the camera of `view` sees `obj` at camera time `tc`: the seen
/// directions of its body points (a mesh's vertices, or points all over
/// a sphere), each on the camera's past light cone (or its instant, with
/// infinitely fast light) and within the object's lifetime; in view if
/// the box of their pixels overlaps the image.
fn sight(f: &Fixture, obj: &SceneObject, view: &View, tc: f64) -> Sight {
    let Some((start, v)) = uniform(&obj.motion) else {
        return Sight::Unknown;
    };
    let setup = Observer {
        fixture: f,
        model: view.model,
        camera_t: tc,
    };
    let (w, h) = (view.camera.width, view.camera.height);
    let Ok(pinhole) = setup.pinhole((w, h)) else {
        return Sight::Unknown;
    };
    let camera = setup.camera_x();
    let contracted = view.model.lorentz && obj.kind == ObjectKind::VObj;
    let (t0, t1) = lifetime(obj, view.model);
    let centre = body_point(start.t, start.x, v, DVec3::ZERO, contracted);
    let seen_at = |r: DVec3| {
        let p = body_point(start.t, start.x, v, r, contracted);
        match view.model.light_speed {
            LightSpeed::Finite => retarded(&p, tc, camera),
            LightSpeed::Infinite => Some(instantaneous(&p, tc, camera)),
        }
    };
    let Some(middle) = seen_at(DVec3::ZERO) else {
        return Sight::Never;
    };
    let alive: Vec<DVec3> = body_points(obj)
        .into_iter()
        .filter_map(seen_at)
        .filter(|s| s.t >= t0 && s.t <= t1)
        .map(|s| s.direction)
        .collect();
    if alive.is_empty() {
        return Sight::NotAlive(middle.t);
    }
    match pixel_box(&pinhole, &alive) {
        Some([x0, y0, x1, y1])
            if x1 > 0.0 && y1 > 0.0 && x0 < f64::from(w) && y0 < f64::from(h) =>
        {
            Sight::InView {
                pixels: (x1 - x0).max(y1 - y0),
            }
        }
        Some(_) => Sight::Outside(centre.at(middle.t)),
        // Some points behind the camera, some ahead: it may straddle the view.
        None if alive.iter().any(|d| pinhole.pixel_of(*d).is_some()) => Sight::InView {
            pixels: f64::INFINITY,
        },
        None => Sight::Outside(centre.at(middle.t)),
    }
}

/// The box of the pixels of lines of sight `dirs`, if all are ahead of
/// the camera.
fn pixel_box(pinhole: &Pinhole, dirs: &[DVec3]) -> Option<[f64; 4]> {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for d in dirs {
        let (x, y) = pinhole.pixel_of(*d)?;
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    Some(b)
}

/// Body points (object coordinates) whose seen directions bound the
/// object's image: a mesh's vertices (at most [`MAX_POINTS`], evenly
/// taken), or 128 points spread evenly over a sphere (a Fibonacci
/// lattice; its extent falls short of the sphere's by under 2 %).
fn body_points(obj: &SceneObject) -> Vec<DVec3> {
    match &obj.shape {
        Shape::Mesh(m) => {
            let stride = m.vertices.len().div_ceil(MAX_POINTS).max(1);
            m.vertices.iter().step_by(stride).copied().collect()
        }
        Shape::Sphere { radius } => {
            let n = 128;
            let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
            (0..n)
                .map(|i| {
                    let y = 1.0 - 2.0 * (f64::from(i) + 0.5) / f64::from(n);
                    let r = (1.0 - y * y).sqrt();
                    let phi = golden * f64::from(i);
                    DVec3::new(r * phi.cos(), y, r * phi.sin()) * *radius
                })
                .collect()
        }
    }
}

/// Warnings about `view`: each moving object (uniform motion) of which no
/// part is in the image, with the camera time that shows it or, if none
/// does, what to change; the whole image empty; a field of view under 5
/// degrees; every object in view smaller than a pixel. Each names the
/// field or flag to change.
pub fn out_of_view(f: &Fixture, view: &View) -> Vec<String> {
    let mut warnings: Vec<String> = narrow_field_of_view(f).into_iter().collect();
    let sights = sights(f, view);
    for (obj, s) in f.scene.objects.iter().zip(&sights) {
        let moving = uniform(&obj.motion).is_some_and(|(_, v)| v != DVec3::ZERO);
        if let (true, Some(w)) = (moving, missing(f, obj, view, s)) {
            warnings.push(w);
        }
    }
    let judged = sights.iter().all(|s| *s != Sight::Unknown);
    let sizes: Vec<f64> = sights
        .iter()
        .filter_map(|s| match s {
            Sight::InView { pixels } => Some(*pixels),
            _ => None,
        })
        .collect();
    if judged && !f.scene.objects.is_empty() && sizes.is_empty() {
        warnings.push(nothing_in_view(f, view));
    } else if judged && !sizes.is_empty() && sizes.iter().all(|p| *p < 1.0) {
        warnings.push(format!(
            "every object in view is smaller than a pixel (at most {:.2} pixels across): move camera.position closer, narrow camera.vfov_deg or render larger (--width, --height)",
            sizes.iter().fold(0.0, |a: f64, b| a.max(*b))
        ));
    }
    warnings
}

/// What `view` shows of each object of `f`, at its camera time.
fn sights(f: &Fixture, view: &View) -> Vec<Sight> {
    f.scene
        .objects
        .iter()
        .map(|o| sight(f, o, view, view.camera_t))
        .collect()
}

/// Whether the image of `view` shows no part of any object (every object
/// judged), as [`out_of_view`] warns.
pub fn nothing_in_view_at_all(f: &Fixture, view: &View) -> bool {
    let sights = sights(f, view);
    !sights.is_empty()
        && sights
            .iter()
            .all(|s| matches!(s, Sight::NotAlive(_) | Sight::Outside(_) | Sight::Never))
}

/// The warning for a moving object that `view` does not show, if it does
/// not, with a hint: the camera time at which it is seen crossing the line
/// of sight if that shows it, else the camera's aim and field of view.
fn missing(f: &Fixture, obj: &SceneObject, view: &View, s: &Sight) -> Option<String> {
    let name = &obj.name;
    let what = match s {
        Sight::InView { .. } | Sight::Unknown => return None,
        Sight::Never => format!("{name:?} is never seen from the camera at t = {}", view.camera_t),
        Sight::NotAlive(t) => {
            let (t0, t1) = lifetime(obj, view.model);
            format!(
                "{name:?} is not in view: light reaching the camera at t = {} would have had to leave it at t = {t:.4}, outside its lifetime [{t0}, {t1}]",
                view.camera_t
            )
        }
        Sight::Outside(x) => format!(
            "{name:?} is out of view: at t = {} the camera sees it where its light left it, about ({:.3}, {:.3}, {:.3}), and no part of it is in the image",
            view.camera_t, x.x, x.y, x.z
        ),
    };
    Some(format!("{what}; {}", hint(f, obj, view)))
}

/// What to change so that `view` shows `obj`: its `auto:OBJECT` camera
/// time, if the object is in view then, else the camera's aim.
fn hint(f: &Fixture, obj: &SceneObject, view: &View) -> String {
    let auto = CameraTime::AutoObject(obj.name.clone());
    let flag = if obj.name.contains(char::is_whitespace) {
        format!("--camera-t \"auto:{}\"", obj.name)
    } else {
        format!("--camera-t auto:{}", obj.name)
    };
    match solve(&f.spec, &f.scene, &auto, view.model) {
        Ok(t) if matches!(sight(f, obj, view, t), Sight::InView { .. }) => {
            format!(
                "try {flag} (t = {t:.4}; or \"t\": \"auto:{}\" in a view)",
                obj.name
            )
        }
        Ok(_) => format!(
            "it is not in view at {flag} either, so no camera time shows it: {}",
            aim_advice(f)
        ),
        Err(m) => format!("{m}; {}", aim_advice(f)),
    }
}

/// Where the camera looks and how wide, with the fields that change them.
fn aim_advice(f: &Fixture) -> String {
    let c = &f.spec.camera;
    let aim = if c.look_at.is_some() {
        "camera.look_at"
    } else {
        "camera.yaw_deg / camera.pitch_deg"
    };
    let d = line_of_sight(&f.spec.camera);
    format!(
        "the camera at ({}, {}, {}) looks along ({:.3}, {:.3}, {:.3}) with camera.vfov_deg = {}; point {aim} at the object's path or widen camera.vfov_deg",
        c.position.x, c.position.y, c.position.z, d.x, d.y, d.z, c.vfov_deg
    )
}

/// The warning for an image that shows nothing: whether any object is
/// seen at its `auto:OBJECT` time (then that is the hint) or none at any
/// (then the camera's aim and field of view are).
fn nothing_in_view(f: &Fixture, view: &View) -> String {
    let shown = f.scene.objects.iter().find_map(|o| {
        let t = solve(
            &f.spec,
            &f.scene,
            &CameraTime::AutoObject(o.name.clone()),
            view.model,
        )
        .ok()?;
        matches!(sight(f, o, view, t), Sight::InView { .. }).then(|| (o.name.clone(), t))
    });
    match shown {
        Some((name, t)) => format!(
            "nothing is in view at t = {}: the image is empty; {name:?} is seen at t = {t:.4} (--camera-t \"auto:{name}\")",
            view.camera_t
        ),
        None => format!(
            "nothing is in view at t = {}, nor at any object's auto time: {}",
            view.camera_t,
            aim_advice(f)
        ),
    }
}
