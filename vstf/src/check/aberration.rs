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

use super::{
    background, is_background, trace_rows, Edge, Effort, FixtureReport, Reading, Row, Setup,
};
use crate::fixture::{Fixture, Overrides};
use crate::measure::{edge, Pinhole, Plane};
use crate::oracle::{
    aberrate_galilean, aberrate_lorentz, body_point, contract, extremes_on_polygon, retarded,
};
use glam::DVec3;
use renderer::{Event, FourVector, Model, Motion, ObjectKind};

const NAME: &str = "aberration";
const CUBE: &str = "cube";
const HALF: f64 = 5.0e4;
/// Lab times during which a moving cube exists: its light takes up to
/// ~1e6 t.units to arrive when it recedes at 0.866c.
const LIFE: (f64, f64) = (-3.0e6, 1.0e4);

/// A seasonal view: the Earth's direction of motion.
#[derive(Clone, Copy)]
struct Season {
    name: &'static str,
    /// Unit vector of the Earth's (observer's) velocity; the star is at -z.
    earth: DVec3,
}

const SEASONS: [Season; 4] = [
    Season {
        name: "approaching",
        earth: DVec3::NEG_Z,
    },
    Season {
        name: "moving left",
        earth: DVec3::NEG_X,
    },
    Season {
        name: "receding",
        earth: DVec3::Z,
    },
    Season {
        name: "moving right",
        earth: DVec3::X,
    },
];

fn azimuth_deg(d: DVec3) -> f64 {
    d.x.atan2(-d.z).to_degrees()
}

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
    let rest_centre = cube
        .motion
        .uniform()
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

/// Measures the silhouette edge on the horizon near azimuth `near_deg`:
/// a narrow probe aimed there, the edge traced over rows and fitted
/// against elevation, read at elevation 0.
fn measure_edge(
    setup: &Setup,
    near_deg: f64,
    right: bool,
    effort: &Effort,
) -> Result<Reading, String> {
    let a = near_deg.to_radians();
    let look = DVec3::new(a.sin(), 0.0, -a.cos());
    // A strip 3 degrees wide and 0.6 tall across the horizon, half the
    // probe's width: the angle targets (0.05 deg) are met ~100x over.
    let (img, camera) = setup.probe(
        &[CUBE],
        look,
        3.0,
        effort.probe / 2,
        effort.probe / 10,
        effort.spp,
    )?;
    let bg = background(setup.fixture);
    let w = i64::from(img.width());
    let (from, step) = if right { (w - 1, -1) } else { (0, 1) };
    // Angles are the observer's: lines of sight in the camera's own frame
    // (the same as the lab's when the camera is at rest).
    let camera = camera.still();
    // On the unit sphere of directions: elevation (deg) against azimuth (deg).
    let sphere = Plane::z(-1.0);
    let trace = trace_rows(
        &img,
        &camera,
        sphere,
        |s| edge(&img, s, from, step, |c| is_background(c, bg)),
        |p| (p.y.atan2(p.x.hypot(p.z)).to_degrees(), azimuth_deg(p)),
        (-0.25, 0.25),
    );
    let trace = super::EdgeTrace {
        footprint: measure_angular(&camera),
        ..trace
    };
    Ok(Edge::fit(&trace, 2, effort)
        .map_err(|e| format!("{NAME}: edge near {near_deg:.2} deg: {e}"))?
        .at(0.0))
}

/// Where the control fixture puts the cube's centre (at rest).
fn rest_centre(control: &Fixture) -> Result<DVec3, String> {
    match control
        .scene
        .objects
        .iter()
        .find(|o| o.name == CUBE)
        .and_then(|o| o.motion.uniform())
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

/// Angular size of a probe pixel at its centre, degrees.
fn measure_angular(camera: &Pinhole) -> f64 {
    let (cx, cy) = (
        f64::from(camera.width) / 2.0,
        f64::from(camera.height) / 2.0,
    );
    camera.angular_footprint(cx, cy, true).to_degrees()
}

/// Rough azimuths (left, right) of the silhouette on the horizon, from a
/// wide render.
fn coarse_edges(setup: &Setup) -> Result<(f64, f64), String> {
    // A wide strip across the horizon first; where the cube reaches its
    // border (beyond +-85 degrees), a second strip turned towards that side.
    let (l, r) = coarse_strip(setup, 0.0, 170.0)?;
    let l = if l.1 {
        coarse_strip(setup, -60.0, 60.0)?.0 .0
    } else {
        l.0
    };
    let r = if r.1 {
        coarse_strip(setup, 60.0, 60.0)?.1 .0
    } else {
        r.0
    };
    Ok((l, r))
}

/// A rough edge azimuth (degrees), and whether it lies on the probe's border.
type CoarseEdge = (f64, bool);

/// The azimuths of the leftmost and rightmost cube pixels on the horizon of
/// a strip centred on azimuth `centre_deg`, each with whether it lies on the
/// strip's border.
fn coarse_strip(
    setup: &Setup,
    centre_deg: f64,
    hfov_deg: f64,
) -> Result<(CoarseEdge, CoarseEdge), String> {
    let a = centre_deg.to_radians();
    let (img, camera) = setup.probe(
        &[CUBE],
        DVec3::new(a.sin(), 0.0, -a.cos()),
        hfov_deg,
        1441,
        3,
        1,
    )?;
    let bg = background(setup.fixture);
    let row = img.height() / 2;
    let xs: Vec<u32> = (0..img.width())
        .filter(|x| !is_background(crate::measure::color(&img, *x, row), bg))
        .collect();
    let (Some(&l), Some(&r)) = (xs.first(), xs.last()) else {
        return Err(format!("{NAME}: the cube is not on the horizon"));
    };
    let camera = camera.still();
    let az = |x: f64| azimuth_deg(camera.direction(x, f64::from(row) + 0.5));
    Ok((
        (az(f64::from(l)), l == 0),
        (az(f64::from(r) + 1.0), r + 1 == img.width()),
    ))
}

pub fn run(effort: &Effort) -> Result<FixtureReport, String> {
    let control = Fixture::load(NAME).map_err(|e| e.to_string())?;
    let base = control
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let mut rows = Vec::new();
    let mut views = Vec::new();
    let mut cases: Vec<(String, Option<Season>, f64, Model)> =
        vec![("at rest".into(), None, 0.0, base)];
    for beta in [0.5, 0.866] {
        for model in [Model::CLASSICAL, Model::RELATIVISTIC] {
            for s in SEASONS {
                cases.push((format!("{} {beta}c {model}", s.name), Some(s), beta, model));
            }
        }
    }
    let rest_right = (0.5f64).atan().to_degrees();
    for (label, season, beta, model) in cases {
        let u = season.map_or(DVec3::ZERO, |s| -s.earth * beta);
        let (f, centre) = moving(&control, u, model)?;
        let setup = Setup {
            fixture: &f,
            model,
            camera_t: 0.0,
        };
        let (coarse_l, coarse_r) = coarse_edges(&setup)?;
        let left = measure_edge(&setup, coarse_l, false, effort)?;
        let right = measure_edge(&setup, coarse_r, true, effort)?;
        let (exp_l, exp_r) = expected_edges(centre, u, model.lorentz);
        let row = |q: &str, m: &Reading, e: f64, paper: Option<f64>, unit: &str| {
            Row::new(
                NAME,
                &format!("{label}: {q}"),
                m.value,
                e,
                paper,
                m.tolerance,
                unit,
            )
        };
        rows.push(row("left edge azimuth", &left, exp_l, None, "deg"));
        rows.push(row("right edge azimuth", &right, exp_r, None, "deg"));
        if let Some(s) = season {
            // The same season seen the paper's way: the Earth moving, the star at rest.
            let w = s.earth * beta;
            let fe = earth_moving(&control, w);
            let earth = Setup {
                fixture: &fe,
                model,
                camera_t: 0.0,
            };
            let (cl, cr) = coarse_edges(&earth)?;
            let (el, er) = (
                measure_edge(&earth, cl, false, effort)?,
                measure_edge(&earth, cr, true, effort)?,
            );
            let (xl, xr) = expected_edges_earth_moving(rest_centre(&control)?, w, model.lorentz);
            rows.push(row("Earth moving: left edge azimuth", &el, xl, None, "deg"));
            rows.push(row(
                "Earth moving: right edge azimuth",
                &er,
                xr,
                None,
                "deg",
            ));
            if s.name == "receding" && beta == 0.866 && !model.lorentz {
                // The paper prints 93.6 for the relativistic view; it is this one's.
                let from_motion = Reading {
                    value: 180.0 - er.value,
                    tolerance: er.tolerance,
                };
                rows.push(row(
                    "Earth moving: right edge angle from the direction of motion",
                    &from_motion,
                    180.0 - xr,
                    Some(93.6),
                    "deg",
                ));
            }
            if s.name == "moving left" && beta == 0.5 {
                let paper = if model.lorentz { 30.0 } else { 26.565 };
                let migration = Reading {
                    value: rest_right - er.value,
                    tolerance: er.tolerance,
                };
                rows.push(row(
                    "Earth moving: right edge migration",
                    &migration,
                    rest_right - xr,
                    Some(paper),
                    "deg",
                ));
            }
        }
        // On the grid 10 l.units ahead, in grid marks (l.units).
        let on_grid = |deg: f64| 10.0 * deg.to_radians().tan();
        let slope =
            10.0 * (1.0 + right.value.to_radians().tan().powi(2)) * std::f64::consts::PI / 180.0;
        let grid = Reading {
            value: on_grid(right.value),
            tolerance: right.tolerance * slope,
        };
        let is = |name: &str, b: f64, m: Model| {
            season.is_some_and(|s| s.name == name) && beta == b && model == m
        };
        match () {
            _ if season.is_none() => {
                rows.push(row(
                    "right edge on the grid",
                    &grid,
                    on_grid(exp_r),
                    Some(5.0),
                    "grid marks",
                ));
                let width = Reading {
                    value: right.value - left.value,
                    tolerance: right.tolerance.hypot(left.tolerance),
                };
                rows.push(row(
                    "angle subtended by the silhouette",
                    &width,
                    exp_r - exp_l,
                    Some(45.0),
                    "deg",
                ));
                let from_motion = Reading {
                    value: 180.0 - right.value,
                    tolerance: right.tolerance,
                };
                rows.push(row(
                    "right edge angle from +z (receding motion)",
                    &from_motion,
                    180.0 - exp_r,
                    Some(153.4),
                    "deg",
                ));
            }
            _ if is("moving left", 0.5, Model::CLASSICAL)
                || is("moving left", 0.5, Model::RELATIVISTIC) =>
            {
                let (paper_marks, paper_deg) = if model.lorentz {
                    (5.77, 30.0)
                } else {
                    (5.0, 26.565)
                };
                let shift = Reading {
                    value: 5.0 - grid.value,
                    tolerance: grid.tolerance,
                };
                rows.push(row(
                    "right edge displacement on the grid",
                    &shift,
                    5.0 - on_grid(exp_r),
                    Some(paper_marks),
                    "grid marks",
                ));
                let migration = Reading {
                    value: rest_right - right.value,
                    tolerance: right.tolerance,
                };
                rows.push(row(
                    "right edge migration",
                    &migration,
                    rest_right - exp_r,
                    Some(paper_deg),
                    "deg",
                ));
            }
            _ if is("receding", 0.866, Model::RELATIVISTIC) => {
                let from_motion = Reading {
                    value: 180.0 - right.value,
                    tolerance: right.tolerance,
                };
                rows.push(row(
                    "right edge angle from the direction of motion",
                    &from_motion,
                    180.0 - exp_r,
                    Some(93.6),
                    "deg",
                ));
            }
            _ => rows.push(row(
                "right edge on the grid",
                &grid,
                on_grid(exp_r),
                None,
                "grid marks",
            )),
        }
        let marks: Vec<DVec3> = [exp_l, exp_r]
            .iter()
            .map(|a| DVec3::new(a.to_radians().sin(), 0.0, -a.to_radians().cos()))
            .collect();
        views.push(setup.full_view(&label, &marks)?);
    }
    Ok(FixtureReport::new(
        NAME,
        &control.spec.description,
        views,
        rows,
    ))
}
