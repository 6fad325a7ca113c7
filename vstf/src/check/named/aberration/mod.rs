//! Aberration (paper 4.1.3-4.1.4, Figures 11-16): a cube 1e5 on a side, its
//! near face 1e5 ahead of the camera, seen from the four seasonal positions
//! of an orbit at 0.5c and 0.866c, classical and relativistic, and at rest.
//!
//! The camera stays at rest (paper 2.1); the Earth's velocity w is given to
//! the cube as u = -w. The cube is placed so that, at the camera event, it
//! is where the control view has it: relativistic, in its own rest frame
//! (so its lab-simultaneous shape is the control cube contracted along u,
//! about the camera); classical, in the lab. Measured: the azimuth of the
//! silhouette's left and right edges on the horizon, and where the right
//! edge falls on the grid 10 l.units ahead.

use crate::check::findings::{CheckOutcome, ViewReport};
use crate::check::named::view::NamedView;
use crate::check::probe::Effort;
use crate::check::row::Quantity;
use crate::fixture::Fixture;
use crate::observer::{fixture_model, Observer};
use crate::oracle::{
    aberrate_galilean, aberrate_lorentz, body_point, contract, extremes_on_polygon, retarded,
};
use figures::{Derived, Figure, FIGURES};
use glam::DVec3;
use renderer::{Event, FourVector, Model, Motion, ObjectKind};
use silhouette::measure_edges;

mod cases;
mod figures;
mod silhouette;

use cases::{azimuth_deg, Case, Frame, Seen, CUBE, NAME};

const HALF: f64 = 5.0e4;
/// Lab times during which a moving cube exists: its light takes up to
/// ~1e6 t.units to arrive when it recedes at 0.866c.
const LIFE: (f64, f64) = (-3.0e6, 1.0e4);

/// The control fixture with the cube moving with `u`: a V_obj when the
/// model has the Lorentz transform, an H_obj otherwise, its centre at
/// `centre` at lab time 0.
fn moving(control: &Fixture, u: DVec3, model: Model) -> Result<(Fixture, DVec3), String> {
    let mut f = control.clone();
    let cube = f
        .scene
        .objects
        .iter_mut()
        .find(|o| o.name == CUBE)
        .ok_or("aberration: no cube")?;
    let rest_centre = crate::observer::uniform(&cube.motion)
        .ok_or("aberration: the cube must move uniformly")?
        .0
        .x;
    let centre = if model.lorentz {
        contract(rest_centre, u)
    } else {
        rest_centre
    };
    cube.kind = if model.lorentz {
        ObjectKind::VObj
    } else {
        ObjectKind::HObj
    };
    let dt = LIFE.1 - LIFE.0;
    cube.motion = Motion::Extrusion {
        start: Event::new(LIFE.0, centre + u * LIFE.0),
        extrusion: FourVector::new(dt, u * dt),
    };
    Ok((f, centre))
}

/// The extreme azimuths (left, right) of the cube's horizon cross-section as
/// seen from the camera at the origin at t = 0: every point of the square's
/// boundary is retarded in closed form.
fn expected_edges(centre: DVec3, u: DVec3, lorentz: bool) -> (f64, f64) {
    let corners = [
        DVec3::new(-HALF, 0.0, -HALF),
        DVec3::new(HALF, 0.0, -HALF),
        DVec3::new(HALF, 0.0, HALF),
        DVec3::new(-HALF, 0.0, HALF),
    ];
    let az = |r: DVec3| {
        let p = body_point(0.0, centre, u, r, lorentz);
        retarded(&p, 0.0, DVec3::ZERO).map_or(f64::NAN, |s| azimuth_deg(s.direction))
    };
    extremes_on_polygon(&corners, az)
}

/// Where the control fixture puts the cube's centre (at rest).
fn rest_centre(control: &Fixture) -> Result<DVec3, String> {
    match control
        .scene
        .objects
        .iter()
        .find(|o| o.name == CUBE)
        .and_then(|o| crate::observer::uniform(&o.motion))
    {
        Some((start, _)) => Ok(start.x),
        None => Err(format!("{NAME}: no uniformly moving cube")),
    }
}

/// The control fixture seen by a camera (the Earth) moving with `w`, the
/// cube at rest: the way the paper describes the seasonal views.
fn earth_moving(control: &Fixture, w: DVec3) -> Fixture {
    let mut f = control.clone();
    f.spec.camera.velocity = Some(w);
    f
}

/// The extreme azimuths (left, right), in the moving camera's frame, of the
/// static cube's horizon cross-section: each point's lab direction from the
/// camera, aberrated by the camera's velocity (Lorentz or Galilean).
fn expected_edges_earth_moving(centre: DVec3, w: DVec3, lorentz: bool) -> (f64, f64) {
    let corners = [
        DVec3::new(-HALF, 0.0, -HALF),
        DVec3::new(HALF, 0.0, -HALF),
        DVec3::new(HALF, 0.0, HALF),
        DVec3::new(-HALF, 0.0, HALF),
    ];
    extremes_on_polygon(&corners, |r| {
        let n = (centre + r).normalize();
        azimuth_deg(if lorentz {
            aberrate_lorentz(n, w)
        } else {
            aberrate_galilean(n, w)
        })
    })
}

/// The quantities of one view of the cube, named after it.
struct ViewTable {
    label: String,
    quantities: Vec<Quantity>,
}

impl ViewTable {
    /// The quantity `derived`, read off `seen`, with the paper's figure.
    fn row(&mut self, name: &str, derived: Derived, seen: &Seen, paper: Option<f64>) {
        let (measured, expected) = derived.of(seen);
        self.quantities.push(Quantity {
            name: format!("{}: {name}", self.label),
            measured,
            expected,
            paper,
            unit: derived.unit(),
            error: None,
        });
    }

    /// The paper's figures for `case` seen in `frame`; how many there are.
    fn figures(&mut self, case: &Case, frame: Frame, seen: &Seen) -> usize {
        let figures: Vec<&Figure> = FIGURES.iter().filter(|f| f.applies(case, frame)).collect();
        for fig in &figures {
            self.row(fig.name, fig.derived, seen, Some(fig.paper));
        }
        figures.len()
    }
}

/// A season seen the paper's way: the camera (the Earth) moving with `w`
/// past the cube at rest; the expected edges are the static cube's
/// directions aberrated into the camera's frame.
fn earth_seen(control: &Fixture, w: DVec3, model: Model, effort: &Effort) -> Result<Seen, String> {
    let fe = earth_moving(control, w);
    let earth = Observer {
        fixture: &fe,
        model,
        camera_t: 0.0,
    };
    let (left, right) = measure_edges(&earth, effort)?;
    Ok(Seen {
        left,
        right,
        expected: expected_edges_earth_moving(rest_centre(control)?, w, model.lorentz),
    })
}

/// One view: the cube moving with u = -w past the camera at rest, and
/// (for a season) the Earth moving with w past the cube at rest; their
/// edges, the paper's figures, and the full view.
fn view(
    control: &Fixture,
    case: Case,
    effort: &Effort,
) -> Result<(Vec<Quantity>, ViewReport), String> {
    let u = case.season.map_or(DVec3::ZERO, |s| -s.earth * case.beta);
    let (f, centre) = moving(control, u, case.model)?;
    let setup = Observer {
        fixture: &f,
        model: case.model,
        camera_t: 0.0,
    };
    let (left, right) = measure_edges(&setup, effort)?;
    let cube = Seen {
        left,
        right,
        expected: expected_edges(centre, u, case.model.lorentz),
    };
    let mut table = ViewTable {
        label: case.label(),
        quantities: Vec::new(),
    };
    table.row("left edge azimuth", Derived::LeftAzimuth, &cube, None);
    table.row("right edge azimuth", Derived::RightAzimuth, &cube, None);
    if let Some(s) = case.season {
        let earth = earth_seen(control, s.earth * case.beta, case.model, effort)?;
        let left = "Earth moving: left edge azimuth";
        table.row(left, Derived::LeftAzimuth, &earth, None);
        let right = "Earth moving: right edge azimuth";
        table.row(right, Derived::RightAzimuth, &earth, None);
        table.figures(&case, Frame::EarthMoving, &earth);
    }
    // Views the paper gives no figure for: the right edge on the grid.
    if table.figures(&case, Frame::CubeMoving, &cube) == 0 {
        table.row("right edge on the grid", Derived::OnGrid, &cube, None);
    }
    let marks: Vec<DVec3> = [cube.expected.0, cube.expected.1]
        .iter()
        .map(|a| DVec3::new(a.to_radians().sin(), 0.0, -a.to_radians().cos()))
        .collect();
    let mut report = setup.full_view(&table.label, &marks)?;
    report.measured = table.quantities.iter().map(|q| q.name.clone()).collect();
    Ok((table.quantities, report))
}

/// The views [`run`] renders, for `--view`: each case's fixture (the cube
/// moving, or at rest for the control), model and camera time 0.
pub(super) fn views(control: &Fixture, speeds: &[f64]) -> Result<Vec<NamedView>, String> {
    Case::all(fixture_model(control), speeds)
        .into_iter()
        .map(|case| {
            let u = case.season.map_or(DVec3::ZERO, |s| -s.earth * case.beta);
            let (fixture, _) = moving(control, u, case.model)?;
            Ok(NamedView {
                name: case.label(),
                fixture,
                model: case.model,
                camera_t: 0.0,
            })
        })
        .collect()
}

/// Every view of the cube at each of the orbital `speeds` (fractions of c):
/// its edges against the retarded (cube moving) and aberrated (Earth
/// moving) azimuths, and the paper's figures where it prints them.
pub(super) fn run(
    control: &Fixture,
    speeds: &[f64],
    effort: &Effort,
) -> Result<CheckOutcome, String> {
    let mut quantities = Vec::new();
    let mut views = Vec::new();
    for case in Case::all(fixture_model(control), speeds) {
        let (q, v) = view(control, case, effort)?;
        quantities.extend(q);
        views.push(v);
    }
    Ok(CheckOutcome { views, quantities })
}
