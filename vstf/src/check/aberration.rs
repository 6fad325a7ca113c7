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
    background, fixture_model, is_background, trace_rows, Edge, Effort, Findings, Quantity,
    Reading, Setup, Unit, ViewReport,
};
use crate::fixture::Fixture;
use crate::measure::{edge, Plane};
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
    let camera = still(&camera);
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

/// The camera with its motion removed: its pixels' lines of sight are then
/// those of the camera's own frame.
fn still(camera: &renderer::Camera) -> renderer::Camera {
    renderer::Camera {
        velocity: DVec3::ZERO,
        kinematics: renderer::Kinematics::None,
        ..*camera
    }
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
fn measure_angular(camera: &renderer::Camera) -> f64 {
    let (cx, cy) = (
        f64::from(camera.width) / 2.0,
        f64::from(camera.height) / 2.0,
    );
    crate::measure::angular_footprint(camera, cx, cy, true).to_degrees()
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
    let camera = still(&camera);
    let az = |x: f64| azimuth_deg(camera.direction(x, f64::from(row) + 0.5));
    Ok((
        (az(f64::from(l)), l == 0),
        (az(f64::from(r) + 1.0), r + 1 == img.width()),
    ))
}

/// One view of the cube: the Earth's season at speed `beta` (None: the
/// control view, at rest) under `model`.
#[derive(Clone, Copy)]
struct Case {
    season: Option<Season>,
    beta: f64,
    model: Model,
}

impl Case {
    /// The view's name, prefixing its quantities.
    fn label(&self) -> String {
        match self.season {
            None => "at rest".into(),
            Some(s) => format!("{} {}c {}", s.name, self.beta, self.model),
        }
    }

    /// Every view in report order: at rest (under the fixture's model),
    /// then each speed, model and season.
    fn all(base: Model) -> Vec<Case> {
        let mut cases = vec![Case {
            season: None,
            beta: 0.0,
            model: base,
        }];
        for beta in [0.5, 0.866] {
            for model in [Model::CLASSICAL, Model::RELATIVISTIC] {
                for s in SEASONS {
                    cases.push(Case {
                        season: Some(s),
                        beta,
                        model,
                    });
                }
            }
        }
        cases
    }
}

/// The silhouette's edges on the horizon as measured, and the azimuths
/// (left, right) first principles expect for them.
struct Seen {
    left: Reading,
    right: Reading,
    expected: (f64, f64),
}

/// How a season is seen: as the cube moving past the camera at rest, or
/// (the paper's way) as the Earth moving past the cube at rest.
#[derive(Clone, Copy, PartialEq)]
enum Frame {
    CubeMoving,
    EarthMoving,
}

/// Where the control view's right edge lies, degrees: the near face's
/// corner, half a side across at one side's distance, atan(1/2).
fn rest_right() -> f64 {
    (0.5f64).atan().to_degrees()
}

/// Where the control view's right edge lies on the grid 10 l.units ahead:
/// 10 tan(atan 1/2) = 5 grid marks.
const REST_ON_GRID: f64 = 5.0;

/// An azimuth carried onto the grid 10 l.units ahead, grid marks.
fn on_grid(deg: f64) -> f64 {
    10.0 * deg.to_radians().tan()
}

/// A quantity derived from the silhouette's edges, as the paper reports them.
#[derive(Clone, Copy)]
enum Derived {
    /// The right edge on the grid 10 l.units ahead.
    OnGrid,
    /// How far the right edge has moved on the grid from the control view's 5 marks.
    GridShift,
    /// The angle between the left and right edges.
    Subtended,
    /// The right edge's angle from +z, the direction of the Earth's motion
    /// when receding: 180 degrees minus its azimuth.
    FromMotion,
    /// How far the right edge has moved from its control-view azimuth.
    Migration,
}

impl Derived {
    /// The derived value, measured (with its uncertainty) and expected.
    fn of(self, seen: &Seen) -> (Reading, f64) {
        let (right, (exp_l, exp_r)) = (seen.right, seen.expected);
        // d(on_grid)/d(deg) = 10 sec^2 * pi / 180.
        let slope =
            10.0 * (1.0 + right.value.to_radians().tan().powi(2)) * std::f64::consts::PI / 180.0;
        let grid = Reading {
            value: on_grid(right.value),
            tolerance: right.tolerance * slope,
        };
        let shifted = |value: f64, tolerance: f64| Reading { value, tolerance };
        match self {
            Derived::OnGrid => (grid, on_grid(exp_r)),
            Derived::GridShift => (
                shifted(REST_ON_GRID - grid.value, grid.tolerance),
                REST_ON_GRID - on_grid(exp_r),
            ),
            Derived::Subtended => (
                shifted(
                    right.value - seen.left.value,
                    right.tolerance.hypot(seen.left.tolerance),
                ),
                exp_r - exp_l,
            ),
            Derived::FromMotion => (shifted(180.0 - right.value, right.tolerance), 180.0 - exp_r),
            Derived::Migration => (
                shifted(rest_right() - right.value, right.tolerance),
                rest_right() - exp_r,
            ),
        }
    }

    /// The unit of the derived value.
    fn unit(self) -> Unit {
        match self {
            Derived::OnGrid | Derived::GridShift => Unit::GridMarks,
            _ => Unit::Degrees,
        }
    }
}

/// A figure the paper prints for one view: the view (season name, speed
/// and model; None for the control view, and for either model), the way
/// it is seen, the quantity's name and what it is, and the figure.
struct Figure {
    season: Option<&'static str>,
    beta: f64,
    model: Option<Model>,
    frame: Frame,
    name: &'static str,
    derived: Derived,
    paper: f64,
}

impl Figure {
    fn applies(&self, case: &Case, frame: Frame) -> bool {
        self.frame == frame
            && self.season == case.season.map(|s| s.name)
            && (case.season.is_none() || self.beta == case.beta)
            && self.model.is_none_or(|m| m == case.model)
    }
}

/// The paper's figures (4.1.3-4.1.4, Figures 11-16). The control view:
/// the right edge at 5 grid marks, a 45 degree silhouette, its right edge
/// 153.4 degrees from +z. Moving left at 0.5c, the right edge migrates by
/// 26.565 degrees (classical: 5 grid marks) or 30 degrees (relativistic:
/// 5.77 marks). Receding at 0.866c the paper prints 93.6 degrees from the
/// direction of motion for the relativistic view; first principles give it
/// to the classical one (docs/physics.md).
const FIGURES: &[Figure] = &[
    Figure {
        season: None,
        beta: 0.0,
        model: None,
        frame: Frame::CubeMoving,
        name: "right edge on the grid",
        derived: Derived::OnGrid,
        paper: 5.0,
    },
    Figure {
        season: None,
        beta: 0.0,
        model: None,
        frame: Frame::CubeMoving,
        name: "angle subtended by the silhouette",
        derived: Derived::Subtended,
        paper: 45.0,
    },
    Figure {
        season: None,
        beta: 0.0,
        model: None,
        frame: Frame::CubeMoving,
        name: "right edge angle from +z (receding motion)",
        derived: Derived::FromMotion,
        paper: 153.4,
    },
    Figure {
        season: Some("receding"),
        beta: 0.866,
        model: Some(Model::CLASSICAL),
        frame: Frame::EarthMoving,
        name: "Earth moving: right edge angle from the direction of motion",
        derived: Derived::FromMotion,
        paper: 93.6,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::CLASSICAL),
        frame: Frame::EarthMoving,
        name: "Earth moving: right edge migration",
        derived: Derived::Migration,
        paper: 26.565,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::EarthMoving,
        name: "Earth moving: right edge migration",
        derived: Derived::Migration,
        paper: 30.0,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::CLASSICAL),
        frame: Frame::CubeMoving,
        name: "right edge displacement on the grid",
        derived: Derived::GridShift,
        paper: 5.0,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::CLASSICAL),
        frame: Frame::CubeMoving,
        name: "right edge migration",
        derived: Derived::Migration,
        paper: 26.565,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::CubeMoving,
        name: "right edge displacement on the grid",
        derived: Derived::GridShift,
        paper: 5.77,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::CubeMoving,
        name: "right edge migration",
        derived: Derived::Migration,
        paper: 30.0,
    },
    Figure {
        season: Some("receding"),
        beta: 0.866,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::CubeMoving,
        name: "right edge angle from the direction of motion",
        derived: Derived::FromMotion,
        paper: 93.6,
    },
];

/// The quantities of one view of the cube: its edges and the paper's
/// figures for it.
struct ViewTable {
    label: String,
    quantities: Vec<Quantity>,
}

impl ViewTable {
    fn push(
        &mut self,
        name: &str,
        (measured, expected): (Reading, f64),
        paper: Option<f64>,
        unit: Unit,
    ) {
        self.quantities.push(Quantity {
            name: format!("{}: {name}", self.label),
            measured,
            expected,
            paper,
            unit,
        });
    }

    /// The paper's figures for `case` seen in `frame`.
    fn figures(&mut self, case: &Case, frame: Frame, seen: &Seen) -> usize {
        let mut n = 0;
        for fig in FIGURES.iter().filter(|f| f.applies(case, frame)) {
            self.push(
                fig.name,
                fig.derived.of(seen),
                Some(fig.paper),
                fig.derived.unit(),
            );
            n += 1;
        }
        n
    }
}

/// Measures both silhouette edges of a setup on the horizon.
fn measure_edges(setup: &Setup, effort: &Effort) -> Result<(Reading, Reading), String> {
    let (coarse_l, coarse_r) = coarse_edges(setup)?;
    Ok((
        measure_edge(setup, coarse_l, false, effort)?,
        measure_edge(setup, coarse_r, true, effort)?,
    ))
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
    let setup = Setup {
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
    let deg = |r: &Reading, e: f64| (*r, e);
    table.push(
        "left edge azimuth",
        deg(&cube.left, cube.expected.0),
        None,
        Unit::Degrees,
    );
    table.push(
        "right edge azimuth",
        deg(&cube.right, cube.expected.1),
        None,
        Unit::Degrees,
    );
    if let Some(s) = case.season {
        let w = s.earth * case.beta;
        let fe = earth_moving(control, w);
        let earth = Setup {
            fixture: &fe,
            model: case.model,
            camera_t: 0.0,
        };
        let (left, right) = measure_edges(&earth, effort)?;
        let seen = Seen {
            left,
            right,
            expected: expected_edges_earth_moving(rest_centre(control)?, w, case.model.lorentz),
        };
        let (xl, xr) = seen.expected;
        table.push(
            "Earth moving: left edge azimuth",
            deg(&seen.left, xl),
            None,
            Unit::Degrees,
        );
        table.push(
            "Earth moving: right edge azimuth",
            deg(&seen.right, xr),
            None,
            Unit::Degrees,
        );
        table.figures(&case, Frame::EarthMoving, &seen);
    }
    if table.figures(&case, Frame::CubeMoving, &cube) == 0 {
        table.push(
            "right edge on the grid",
            Derived::OnGrid.of(&cube),
            None,
            Unit::GridMarks,
        );
    }
    let marks: Vec<DVec3> = [cube.expected.0, cube.expected.1]
        .iter()
        .map(|a| DVec3::new(a.to_radians().sin(), 0.0, -a.to_radians().cos()))
        .collect();
    let report = setup.full_view(&table.label, &marks)?;
    Ok((table.quantities, report))
}

/// Every view of the cube: its edges against the retarded (cube moving) and
/// aberrated (Earth moving) azimuths, and the paper's figures.
pub fn run(control: &Fixture, effort: &Effort) -> Result<Findings, String> {
    let mut quantities = Vec::new();
    let mut views = Vec::new();
    for case in Case::all(fixture_model(control)?) {
        let (q, v) = view(control, case, effort)?;
        quantities.extend(q);
        views.push(v);
    }
    Ok(Findings { views, quantities })
}
