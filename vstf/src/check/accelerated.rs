//! Accelerated motion: plates under constant proper acceleration, generated
//! into keyframes by the renderer and extruded interval by interval. Measured
//! at three camera times: where each plate's left and right edges appear at
//! mid-height, on the plates' plane. Expected from first principles: each
//! edge point's hyperbola against the camera's past light cone, a line
//! meeting a hyperbola ([`crate::oracle::retarded_hyperbolic`]). The
//! Lorentz-decoupled plate moves every point on the same hyperbola; the
//! Born-rigid one gives the point at rest-frame offset xi its own, A = 1/a +
//! xi about the same centre. The tolerance adds the keyframes' stated error
//! bound, as it moves the seen point, to the measurement's.

use super::{fixture_model, Effort, Findings, OnPlane, Probed, Quantity, Reading, Setup, Unit};
use crate::fixture::Fixture;
use crate::measure::Plane;
use crate::oracle::{retarded_hyperbolic, PointHyperbola, Retarded};
use glam::DVec3;
use renderer::{Hyperbolic, Motion, ObjectKind};

const NAME: &str = "accelerated";
/// Camera times of the measured frames.
const FRAMES: [f64; 3] = [18.0, 22.0, 26.0];
/// The plates' half width along the motion and height in the fixture; each
/// spans x in [-HALF_WIDTH, HALF_WIDTH] about its reference point.
const HALF_WIDTH: f64 = 0.5;
const HEIGHT: f64 = 2.0;
/// The measured plates and the height of their lower edge.
const PLATES: [(&str, f64); 2] = [("decoupled", 0.5), ("born-rigid", -2.5)];

/// The hyperbola of the plate point at offset `r` from the reference
/// point (rest-frame for a Born-rigid plate).
fn point(h: &Hyperbolic, r: DVec3, born_rigid: bool) -> PointHyperbola {
    let xi = if born_rigid { r.dot(h.direction) } else { 0.0 };
    let across = r - h.direction * xi;
    let p = PointHyperbola::starting(
        h.start.t,
        h.start.x + across,
        h.direction,
        h.acceleration,
        h.initial_velocity,
    );
    PointHyperbola {
        big_a: p.big_a + xi,
        ..p
    }
}

/// How far the seen point can move when the path is off by up to
/// `delta` along the motion: the light-cone intersection slides along the
/// worldline, so the seen position moves by delta / (1 - v.k), k the unit
/// vector from the emission towards the camera.
fn seen_shift(p: &PointHyperbola, seen: &Retarded, camera: DVec3, delta: f64) -> f64 {
    let k = (camera - seen.x).normalize();
    delta / (1.0 - p.velocity(seen.t).dot(k))
}

/// Each plate's left and right edges at mid-height in each frame, against
/// the retarded points of their hyperbolae.
pub fn run(f: &Fixture, effort: &Effort) -> Result<Findings, String> {
    let model = fixture_model(f);
    let mut quantities = Vec::new();
    let mut views = Vec::new();
    for tc in FRAMES {
        let setup = Setup {
            fixture: f,
            model,
            camera_t: tc,
        };
        let cam = setup.camera_x();
        let mut marks = Vec::new();
        for (name, y0) in PLATES {
            let obj = f
                .scene
                .objects
                .iter()
                .find(|o| o.name == name)
                .ok_or_else(|| format!("{NAME}: no plate {name:?}"))?;
            let Motion::Hyperbolic(h) = obj.motion else {
                return Err(format!("{NAME}: {name} must move hyperbolically"));
            };
            let born = model.lorentz && obj.kind == ObjectKind::VObj;
            quantities.extend(plate_edges(&setup, name, y0, &h, born, effort)?);
            for (x, y) in [
                (-HALF_WIDTH, y0),
                (HALF_WIDTH, y0),
                (-HALF_WIDTH, y0 + HEIGHT),
                (HALF_WIDTH, y0 + HEIGHT),
            ] {
                if let Some(r) =
                    retarded_hyperbolic(&point(&h, DVec3::new(x, y, 0.0), born), tc, cam)
                {
                    marks.push(r.direction);
                }
            }
        }
        views.push(setup.full_view(&format!("t_c = {tc}"), &marks)?);
    }
    Ok(Findings { views, quantities })
}

/// The left and right edges of the plate `name` (lower edge at `y0`) at
/// mid-height, measured on a probe aimed at it, against where its edge
/// points' hyperbolae `h` meet the camera's past light cone.
fn plate_edges(
    setup: &Setup,
    name: &str,
    y0: f64,
    h: &Hyperbolic,
    born: bool,
    effort: &Effort,
) -> Result<Vec<Quantity>, String> {
    let (tc, cam) = (setup.camera_t, setup.camera_x());
    let probe = Probed::aimed(setup, &[name], 0.15, effort)?;
    let mid = y0 + HEIGHT / 2.0;
    let plate = OnPlane {
        plane: Plane::z(h.start.x.z),
        coords: |p: DVec3| (p.y, p.x),
        range: (y0 + 0.05 * HEIGHT, y0 + 0.95 * HEIGHT),
        degree: 2,
    };
    let mut quantities = Vec::new();
    for (side, x, sweep) in [
        ("left", -HALF_WIDTH, probe.from_left()),
        ("right", HALF_WIDTH, probe.from_right()),
    ] {
        let reading = probe
            .fit(&plate, sweep, probe.background(), effort)
            .map_err(|e| format!("{NAME} {name} {side} at t_c = {tc}: {e}"))?
            .at(mid);
        let edge_point = point(h, DVec3::new(x, mid, 0.0), born);
        let expected = retarded_hyperbolic(&edge_point, tc, cam)
            .ok_or_else(|| format!("{NAME}: {name} is never seen at t_c = {tc}"))?;
        quantities.push(Quantity {
            name: format!("{name} {side} edge, t_c = {tc} (x)"),
            measured: Reading {
                value: reading.value,
                tolerance: reading.tolerance + seen_shift(&edge_point, &expected, cam, h.tolerance),
            },
            expected: expected.x.x,
            paper: None,
            unit: Unit::LUnits,
        });
    }
    Ok(quantities)
}
