//! The principle of relativity: a camera moving at v past a static cube, and
//! the camera at rest with the cube moving at -v, seen at the same event,
//! must give the same image in the relativistic model. The object-moving
//! scene is the Lorentz transform of the camera-moving one (classical model:
//! the Galilean transform). Measured from both images: where the cube's
//! silhouette crosses the horizon, as azimuths in the camera's frame.
//! Expected from first principles, for each scene on its own: the static
//! cube's directions aberrated into the moving camera's frame, or the moving
//! cube's retarded directions for the camera at rest.

use crate::check::findings::CheckOutcome;
use crate::check::named::view::NamedView;
use crate::check::probe::{Effort, Probe};
use crate::check::row::{difference, Quantity, Reading, Unit};
use crate::check::traced_edge::{Edge, EdgeTrace};
use crate::fixture::Fixture;
use crate::measure::edge;
use crate::observer::{background, is_background, Observer};
use crate::oracle::{
    aberrate_galilean, aberrate_lorentz, body_point, extremes_on_polygon, retarded, to_frame_of,
};
use glam::DVec3;
use renderer::{Event, FourVector, Model, Motion, ObjectKind};

const NAME: &str = "relativity";
const CUBE: &str = "cube";
const HALF: f64 = 1.5;
/// How long before and after the camera event the moving cube exists.
const SPAN: f64 = 1000.0;

/// The camera's rest-frame attitude: azimuth of a camera-frame direction.
fn azimuth(setup: &Observer, d: DVec3) -> f64 {
    let c = &setup.fixture.spec.camera;
    let forward = (c.look_at.unwrap_or(c.position + DVec3::NEG_Z) - c.position).normalize();
    let right = forward.cross(c.up).normalize();
    d.dot(right).atan2(d.dot(forward)).to_degrees()
}

/// The scene seen by a camera at rest at the same event, with the cube
/// moving at -v: its worldline is the camera-moving one transformed (Lorentz
/// or Galilean) into the camera's rest frame.
fn object_moving(f: &Fixture, model: Model) -> Result<Fixture, String> {
    let mut g = f.clone();
    let v = g.spec.camera.velocity.take().unwrap_or(DVec3::ZERO);
    let cam = Event::new(f.spec.camera.t, f.spec.camera.position);
    let cube = g
        .scene
        .objects
        .iter_mut()
        .find(|o| o.name == CUBE)
        .ok_or("relativity: no cube")?;
    let centre = crate::observer::uniform(&cube.motion)
        .ok_or("relativity: the cube must move uniformly")?
        .0
        .x;
    // The cube's centre at the camera's time, in the camera's rest frame.
    let at = if model.lorentz {
        let (t, x) =
            to_frame_of(0.0, centre - cam.x, v).ok_or("relativity: camera at light speed")?;
        cam + FourVector::new(t, x)
    } else {
        Event::new(cam.t, centre)
    };
    let u = -v;
    cube.kind = if model.lorentz {
        ObjectKind::VObj
    } else {
        ObjectKind::HObj
    };
    cube.motion = Motion::Extrusion {
        start: at + FourVector::new(-SPAN, -u * SPAN),
        extrusion: FourVector::new(2.0 * SPAN, u * 2.0 * SPAN),
    };
    Ok(g)
}

/// The silhouette's left and right crossings of the horizon (camera-frame
/// azimuths, degrees), measured on a probe render.
fn measure(setup: &Observer, effort: &Effort) -> Result<(Reading, Reading), String> {
    let c = &setup.fixture.spec.camera;
    let look = c.look_at.unwrap_or(c.position + DVec3::NEG_Z);
    let (img, camera) = setup.probe(&Probe {
        keep: &[CUBE],
        look_at: look,
        hfov_deg: 40.0,
        size: (effort.probe, effort.probe / 4),
        spp: effort.spp,
    })?;
    let bg = background(setup.fixture);
    let w = i64::from(img.width());
    // Rows as (row offset from the horizon, pixels; azimuth of the edge).
    let centre = f64::from(img.height()) / 2.0;
    let to_az = |px: f64| azimuth(setup, camera.rest_direction(px, centre));
    let mut traces = Vec::new();
    for (from, step) in [(0, 1), (w - 1, -1)] {
        let mut points = Vec::new();
        for y in 0..img.height() {
            let scan = crate::measure::Scan {
                horizontal: true,
                at: y,
            };
            if let Some(u) = edge(&img, scan, from, step, |c| is_background(c, bg)) {
                points.push((f64::from(y) + 0.5 - centre, u));
            }
        }
        // The edge in pixels, fitted against the row, read on the horizon;
        // its footprint in azimuth per pixel there.
        let dpx = (to_az(centre + 1.0) - to_az(centre - 1.0)).abs() / 2.0;
        let trace = EdgeTrace {
            points,
            footprint: 1.0,
        };
        let e = Edge::fit(&trace, 2, effort)
            .map_err(|e| format!("{NAME}: {e}"))?
            .at(0.0);
        traces.push(Reading {
            value: to_az(e.value),
            tolerance: e.tolerance * dpx,
        });
    }
    Ok((traces.remove(0), traces.remove(0)))
}

/// Lab directions of the points on the horizon at the given camera-frame
/// azimuths, for the report's markers.
fn horizon_marks(setup: &Observer, azimuths: &[f64]) -> Vec<DVec3> {
    let c = &setup.fixture.spec.camera;
    let forward = (c.look_at.unwrap_or(c.position + DVec3::NEG_Z) - c.position).normalize();
    let right = forward.cross(c.up).normalize();
    let camera = setup.pinhole((8, 8)).ok();
    azimuths
        .iter()
        .filter_map(|a| {
            let n = forward * a.to_radians().cos() + right * a.to_radians().sin();
            // The camera-frame direction, carried into the lab as the camera carries its rays.
            camera.map(|cam| cam.to_lab(n))
        })
        .collect()
}

/// The cube's horizon cross-section about its centre.
const SQUARE: [DVec3; 4] = [
    DVec3::new(-HALF, 0.0, -HALF),
    DVec3::new(HALF, 0.0, -HALF),
    DVec3::new(HALF, 0.0, HALF),
    DVec3::new(-HALF, 0.0, HALF),
];

/// Camera moving: the static cube's points are seen along their lab
/// directions, aberrated into the camera's frame (Lorentz or Galilean).
/// Returns the extreme azimuths (left, right).
fn expected_camera_moving(a: &Observer) -> Result<(f64, f64), String> {
    let c = &a.fixture.spec.camera;
    let v = c.velocity.unwrap_or(DVec3::ZERO);
    let centre = match a
        .fixture
        .scene
        .objects
        .iter()
        .find(|o| o.name == CUBE)
        .and_then(|o| crate::observer::uniform(&o.motion))
    {
        Some((start, _)) => start.x,
        None => return Err("relativity: no uniformly moving cube".into()),
    };
    let aberrate = |n: DVec3| {
        if a.model.lorentz {
            aberrate_lorentz(n, v)
        } else {
            aberrate_galilean(n, v)
        }
    };
    Ok(extremes_on_polygon(&SQUARE, |r| {
        azimuth(a, aberrate((centre + r - c.position).normalize()))
    }))
}

/// Cube moving: the moving cube's points at their retarded positions.
/// Returns the extreme azimuths (left, right).
fn expected_cube_moving(b: &Observer) -> Result<(f64, f64), String> {
    let c = &b.fixture.spec.camera;
    let cube = b
        .fixture
        .scene
        .objects
        .iter()
        .find(|o| o.name == CUBE)
        .ok_or("no cube")?;
    let (start, u) =
        crate::observer::uniform(&cube.motion).ok_or("relativity: the cube must move uniformly")?;
    let seen = |r: DVec3| {
        let p = body_point(start.t, start.x, u, r, b.model.lorentz);
        retarded(&p, c.t, c.position).map_or(f64::NAN, |s| azimuth(b, s.direction))
    };
    Ok(extremes_on_polygon(&SQUARE, seen))
}

/// The views [`run`] renders, for `--view`: in each model, the camera
/// moving past the cube and the cube moving past the camera.
pub(super) fn views(f: &Fixture) -> Result<Vec<NamedView>, String> {
    let t = f.spec.camera.t;
    let mut out = Vec::new();
    for model in [Model::RELATIVISTIC, Model::CLASSICAL] {
        let view = |name: String, fixture: Fixture| NamedView {
            name,
            fixture,
            model,
            camera_t: t,
        };
        out.push(view(format!("{model}, camera moving"), f.clone()));
        out.push(view(
            format!("{model}, cube moving"),
            object_moving(f, model)?,
        ));
    }
    Ok(out)
}

/// For each model, the cube's horizon edges seen by the moving camera and
/// by the camera at rest with the cube moving, each against its own first
/// principles, and their differences (zero under relativity; the classical
/// model's Galilean transform does not make them agree).
pub(super) fn run(f: &Fixture, effort: &Effort) -> Result<CheckOutcome, String> {
    let t = f.spec.camera.t;
    let mut quantities = Vec::new();
    let mut views = Vec::new();
    for model in [Model::RELATIVISTIC, Model::CLASSICAL] {
        let moving_object = object_moving(f, model)?;
        let a = Observer {
            fixture: f,
            model,
            camera_t: t,
        };
        let b = Observer {
            fixture: &moving_object,
            model,
            camera_t: t,
        };
        let (la, ra) = measure(&a, effort)?;
        let (lb, rb) = measure(&b, effort)?;
        let (ea_l, ea_r) = expected_camera_moving(&a)?;
        let (eb_l, eb_r) = expected_cube_moving(&b)?;
        let table = [
            ("left edge, camera moving", la, ea_l),
            ("left edge, cube moving", lb, eb_l),
            ("right edge, camera moving", ra, ea_r),
            ("right edge, cube moving", rb, eb_r),
            (
                "left edge: camera moving minus cube moving",
                difference(&la, &lb),
                ea_l - eb_l,
            ),
            (
                "right edge: camera moving minus cube moving",
                difference(&ra, &rb),
                ea_r - eb_r,
            ),
        ];
        let first = quantities.len();
        quantities.extend(table.map(|(q, measured, expected)| Quantity {
            name: format!("{model}: {q}"),
            measured,
            expected,
            paper: None,
            unit: Unit::Degrees,
            error: None,
        }));
        let rows: Vec<String> = quantities[first..].iter().map(|q| q.name.clone()).collect();
        for (setup, label, marks) in [
            (&a, "camera moving", [ea_l, ea_r]),
            (&b, "cube moving", [eb_l, eb_r]),
        ] {
            let mut view =
                setup.full_view(&format!("{model}, {label}"), &horizon_marks(setup, &marks))?;
            view.measured.clone_from(&rows);
            views.push(view);
        }
    }
    Ok(CheckOutcome { views, quantities })
}
