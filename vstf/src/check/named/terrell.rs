//! Terrell-Penrose-Boas rotation (paper 4.1.6, Figures 17-18): the flange
//! at 0.866c, camera at (0, 9, 15), at the camera time when the light from
//! the trailing upper corner, leaving it as it crosses x = 0, arrives.
//! Once Lorentz-decoupled (H_obj) and once contracted (V_obj).
//!
//! Measured on the images: where the trailing edge's corners appear and how
//! far the lower one lags the upper; how far the far top corner lags the near
//! one; how much the trailing edge bows (Boas: straight lines appear curved);
//! the front face's apparent length, and its length with the light delay
//! removed (the contraction, which Terrell rotation masks).

use crate::check::findings::CheckOutcome;
use crate::check::probe::Effort;
use crate::check::row::{difference, Quantity, Reading, Unit};
use crate::check::traced_edge::{Edge, OnPlane, ProbeImage};
use crate::fixture::Fixture;
use crate::measure::Plane;
use crate::observer::{fixture_model, motion_of, Observer, UniformMotion};
use crate::oracle::{gamma, retarded};
use glam::DVec3;

const HEIGHT: f64 = 4.0;
const WIDTH: f64 = 2.0;
const DEPTH: f64 = 2.0;
/// The flange's corners marked in the report: the front face's four and
/// the back face's trailing two (local coordinates).
const CORNERS: [(f64, f64, f64); 6] = [
    (0.0, 0.0, DEPTH),
    (0.0, HEIGHT, DEPTH),
    (WIDTH, 0.0, DEPTH),
    (WIDTH, HEIGHT, DEPTH),
    (0.0, HEIGHT, 0.0),
    (0.0, 0.0, 0.0),
];

/// The flange's two faces as the fixture declares them: the front (the
/// plane z = DEPTH of its local coordinates) and the side (x = 0).
pub(super) struct Faces<'a> {
    /// The front face's object.
    pub front: &'a str,
    /// The side face's object.
    pub side: &'a str,
}

/// The front face's blue, whatever its shading.
fn is_front(c: DVec3) -> bool {
    c.z > 0.2 && c.z > c.x + 0.15
}

/// The edges of the flange measured on one probe, each fitted against
/// height: the front face's trailing and leading edges, and the far
/// (back) face's trailing edge.
struct Edges {
    trailing: Edge,
    leading: Edge,
    far: Edge,
}

/// Traces and fits the flange's edges on a probe aimed at its front and side.
fn measure_edges(
    setup: &Observer,
    faces: &Faces,
    m: &UniformMotion,
    effort: &Effort,
) -> Result<Edges, String> {
    let name = &setup.fixture.name;
    let probe = ProbeImage::aimed_lazy(setup, &[faces.front, faces.side], 0.1, effort)?;
    let start = m.start;
    let face = |z: f64| OnPlane {
        plane: Plane::z(z),
        coords: move |p: DVec3| (p.y - start.x.y, p.x),
        range: (0.05 * HEIGHT, 0.95 * HEIGHT),
        degree: 3,
    };
    let (front, back) = (face(start.x.z + DEPTH), face(start.x.z));
    let fail = |what: &str, e: String| format!("{name}: {what}: {e}");
    Ok(Edges {
        trailing: probe
            .fit(&front, probe.sweep_leftwards(), is_front, effort)
            .map_err(|e| fail("trailing edge", e))?,
        leading: probe
            .fit(&front, probe.sweep_leftwards(), probe.background(), effort)
            .map_err(|e| fail("leading edge", e))?,
        far: probe
            .fit(&back, probe.sweep_rightwards(), probe.background(), effort)
            .map_err(|e| fail("far edge", e))?,
    })
}

/// Where a point of the flange (in its local coordinates) is seen from
/// the camera event: its straight worldline against the camera's past
/// light cone.
fn seen(setup: &Observer, m: &UniformMotion, x: f64, y: f64, z: f64) -> Result<DVec3, String> {
    retarded(
        &m.point(DVec3::new(x, y, z)),
        setup.camera_t,
        setup.camera_x(),
    )
    .map(|r| r.x)
    .ok_or_else(|| {
        format!(
            "{}: point ({x}, {y}, {z}) is never seen",
            setup.fixture.name
        )
    })
}

/// The Terrell-Penrose-Boas quantities of one flange fixture (H_obj or
/// V_obj): corner positions and lags, the trailing edge's bow, the front's
/// apparent length and its length with the light delay removed, which is
/// the Lorentz contraction 1/gamma (the paper: 0.5 at 0.866c) for the
/// V_obj and 1 for the H_obj.
pub(super) fn run(f: &Fixture, faces: &Faces, effort: &Effort) -> Result<CheckOutcome, String> {
    let model = fixture_model(f);
    let m = motion_of(f, faces.front, model)?;
    let setup = Observer {
        fixture: f,
        model,
        camera_t: f.spec.camera.t,
    };
    let edges = measure_edges(&setup, faces, &m, effort)?;
    let points = SeenPoints::of(&setup, &m)?;
    let quantities = quantities(&setup, &m, &edges, &points);
    let cam = setup.camera_x();
    let marks: Vec<DVec3> = CORNERS
        .iter()
        .filter_map(|&(x, y, z)| seen(&setup, &m, x, y, z).ok())
        .map(|p| (p - cam).normalize())
        .collect();
    Ok(CheckOutcome {
        views: vec![setup.full_view("view", &marks)?],
        quantities,
    })
}

/// Where first principles put the points of the flange that are measured:
/// the trailing edge's top, foot and middle, the far face's top trailing
/// corner and the leading edge's middle (front face).
struct SeenPoints {
    upper: DVec3,
    lower: DVec3,
    mid: DVec3,
    far_top: DVec3,
    lead_mid: DVec3,
}

impl SeenPoints {
    fn of(setup: &Observer, m: &UniformMotion) -> Result<SeenPoints, String> {
        let seen = |x: f64, y: f64, z: f64| seen(setup, m, x, y, z);
        Ok(SeenPoints {
            upper: seen(0.0, HEIGHT, DEPTH)?,
            lower: seen(0.0, 0.0, DEPTH)?,
            mid: seen(0.0, HEIGHT / 2.0, DEPTH)?,
            far_top: seen(0.0, HEIGHT, 0.0)?,
            lead_mid: seen(WIDTH, HEIGHT / 2.0, DEPTH)?,
        })
    }
}

/// The table: each quantity read off the fitted edges against the seen
/// points, with the paper's figure (Figures 17-18).
fn quantities(
    setup: &Observer,
    m: &UniformMotion,
    edges: &Edges,
    points: &SeenPoints,
) -> Vec<Quantity> {
    let Edges {
        trailing,
        leading,
        far,
    } = edges;
    let SeenPoints {
        upper,
        lower,
        mid,
        far_top,
        lead_mid,
    } = points;
    let (m_lead, m_trail) = (leading.at(HEIGHT / 2.0), trailing.at(HEIGHT / 2.0));
    let length = |name: &str, measured: Reading, expected: f64, paper: Option<f64>| Quantity {
        name: name.into(),
        measured,
        expected,
        paper,
        unit: Unit::LUnits,
        error: None,
    };
    vec![
        length(
            "trailing upper corner (x)",
            trailing.at(HEIGHT),
            upper.x,
            Some(0.0),
        ),
        length(
            "trailing lower corner (x)",
            trailing.at(0.0),
            lower.x,
            Some(-1.66),
        ),
        length(
            "lag of the trailing lower corner behind the upper",
            trailing.combine(&[(1.0, HEIGHT), (-1.0, 0.0)]),
            upper.x - lower.x,
            Some(1.66),
        ),
        length(
            "lag of the far top corner behind the near top corner",
            difference(&trailing.at(HEIGHT), &far.at(HEIGHT)),
            upper.x - far_top.x,
            Some(1.66),
        ),
        length(
            "bow of the trailing edge at mid-height (Boas)",
            trailing.combine(&[(1.0, HEIGHT / 2.0), (-0.5, 0.0), (-0.5, HEIGHT)]),
            mid.x - (upper.x + lower.x) / 2.0,
            None,
        ),
        length(
            "apparent front length at mid-height",
            difference(&m_lead, &m_trail),
            lead_mid.x - mid.x,
            None,
        ),
        contraction(setup, m, &m_lead, &m_trail),
    ]
}

/// The front's length with the light delay removed, over its proper
/// length, from the leading and trailing edges read at mid-height: the
/// Lorentz contraction 1/gamma for a V_obj, 1 for an H_obj.
fn contraction(setup: &Observer, m: &UniformMotion, lead: &Reading, trail: &Reading) -> Quantity {
    let (tc, cam) = (setup.camera_t, setup.camera_x());
    let lab_width = if m.contracted {
        WIDTH / gamma(m.velocity.length())
    } else {
        WIDTH
    };
    let m_length = delay_removed_length(
        lead,
        trail,
        DVec3::new(0.0, m.start.x.y + HEIGHT / 2.0, m.start.x.z + DEPTH),
        m.velocity.x,
        tc,
        cam,
    );
    Quantity {
        name: "front length with light delay removed / proper length".into(),
        measured: Reading {
            value: m_length.value / WIDTH,
            tolerance: m_length.tolerance / WIDTH,
        },
        expected: lab_width / WIDTH,
        paper: m.contracted.then_some(0.5),
        unit: Unit::Ratio,
        error: None,
    }
}

/// The lab length between the leading and trailing edges at one lab time,
/// from their apparent positions at height `y` on the plane z = `z`: each
/// apparent point was emitted one light time before t_c; moving the
/// leading point on to the trailing point's emission time at speed `vx`
/// compensates the delay (paper 1.1: "a rapidly moving object's physical
/// shape can be determined simply by compensating for the delay").
fn delay_removed_length(
    lead: &Reading,
    trail: &Reading,
    line: DVec3,
    vx: f64,
    tc: f64,
    cam: DVec3,
) -> Reading {
    let at = |x: f64| DVec3::new(x, line.y, line.z);
    let d = |x: f64| (at(x) - cam).length();
    let (xl, xt) = (lead.value, trail.value);
    let (tl, tt) = (tc - d(xl), tc - d(xt));
    let value = xl + vx * (tt - tl) - xt;
    // d value / d xl = 1 + vx (xl - cx) / d_l ; d value / d xt = -1 - vx (xt - cx) / d_t.
    let dl = 1.0 + vx * (xl - cam.x) / d(xl);
    let dt = 1.0 + vx * (xt - cam.x) / d(xt);
    Reading {
        value,
        tolerance: (lead.tolerance * dl).hypot(trail.tolerance * dt),
    }
}
