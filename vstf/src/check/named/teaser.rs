//! The teaser (paper 4.1.5, Figure 1): two flanges converging and crossing
//! at 0.866c over a mirrored background, in three bands: infinite light
//! speed (the lab slice at t = 0), classical and relativistic (the camera
//! advanced 18.675 t.units, the light time from the stage centre).
//!
//! Measured in each band: where each flange's leading and trailing edges
//! stand on the stage, and the apparent width between them, against the
//! instantaneous (infinite band) or retarded (finite bands) positions of
//! the feet of those edges.

use crate::check::findings::CheckOutcome;
use crate::check::named::view::NamedView;
use crate::check::probe::Effort;
use crate::check::row::{difference, Quantity, Reading, Unit};
use crate::check::traced_edge::{OnPlane, ProbeImage};
use crate::fixture::Fixture;
use crate::measure::Plane;
use crate::observer::{fixture_model, motion_of, Observer};
use crate::oracle::{instantaneous, retarded};
use glam::DVec3;
use renderer::{LightSpeed, Model};

const NAME: &str = "teaser";
const HEIGHT: f64 = 4.0;
const DEPTH: f64 = 2.0;

/// One of the two flanges: its objects, the local x of its leading edge
/// (the trailing edge is at local x = 0), and the colour test for its front.
struct Flange {
    tag: &'static str,
    front: &'static str,
    side: &'static str,
    leading_x: f64,
    is_front: fn(DVec3) -> bool,
}

const FLANGES: [Flange; 2] = [
    Flange {
        tag: "A",
        front: "flange A front",
        side: "flange A side",
        leading_x: 2.0,
        is_front: |c| c.z > 0.2 && c.z > c.x + 0.15 && c.z > c.y,
    },
    Flange {
        tag: "B",
        front: "flange B front",
        side: "flange B side",
        leading_x: -2.0,
        is_front: |c| c.y > 0.2 && c.y > c.x + 0.15 && c.y > c.z + 0.15,
    },
];

/// The three bands of the teaser: (label, model, camera time); the finite
/// bands' camera is advanced by the fixture's camera time.
fn bands(f: &Fixture) -> Result<[(&'static str, Model, f64); 3], String> {
    let advanced = f.spec.camera.t;
    let base = fixture_model(f);
    Ok([
        ("infinite", Model::INFINITE, 0.0),
        ("classical", Model::CLASSICAL, advanced),
        (
            "relativistic",
            Model {
                lorentz: true,
                ..base
            },
            advanced,
        ),
    ])
}

/// The bands [`run`] renders, for `--view`.
pub(super) fn views(f: &Fixture) -> Result<Vec<NamedView>, String> {
    Ok(bands(f)?
        .into_iter()
        .map(|(band, model, tc)| NamedView {
            name: band.into(),
            fixture: f.clone(),
            model,
            camera_t: tc,
        })
        .collect())
}

/// Each flange's edges on the stage in each band, against the feet of
/// those edges: instantaneous (infinite light speed) or retarded.
pub(super) fn run(f: &Fixture, effort: &Effort) -> Result<CheckOutcome, String> {
    let mut quantities = Vec::new();
    let mut views = Vec::new();
    for (band, model, tc) in bands(f)? {
        let setup = Observer {
            fixture: f,
            model,
            camera_t: tc,
        };
        let cam = setup.camera_x();
        let mut marks = Vec::new();
        for fl in &FLANGES {
            let feet = flange_feet(&setup, band, fl, effort)?;
            marks.extend([feet.expected_lead, feet.expected_trail].map(|p| (p - cam).normalize()));
            // Widths along the flange's own motion, so both come out positive.
            let width = difference(&feet.lead, &feet.trail);
            let table = [
                (
                    "leading edge on the stage (x)",
                    feet.lead,
                    feet.expected_lead.x,
                ),
                (
                    "trailing edge on the stage (x)",
                    feet.trail,
                    feet.expected_trail.x,
                ),
                (
                    "apparent width on the stage",
                    Reading {
                        value: width.value * feet.along,
                        tolerance: width.tolerance,
                    },
                    (feet.expected_lead.x - feet.expected_trail.x) * feet.along,
                ),
            ];
            quantities.extend(table.map(|(q, measured, expected)| Quantity {
                name: format!("{band}: flange {} {q}", fl.tag),
                measured,
                expected,
                paper: None,
                unit: Unit::LUnits,
                error: None,
            }));
        }
        let mut view = setup.full_view(band, &marks)?;
        let prefix = format!("{band}: ");
        view.measured = quantities
            .iter()
            .filter(|q| q.name.starts_with(&prefix))
            .map(|q| q.name.clone())
            .collect();
        views.push(view);
    }
    Ok(CheckOutcome { views, quantities })
}

/// Where a flange's leading and trailing edges stand on the stage,
/// measured and expected.
struct Feet {
    lead: Reading,
    trail: Reading,
    expected_lead: DVec3,
    expected_trail: DVec3,
    /// The sign of the flange's motion along x.
    along: f64,
}

/// Measures the feet of one flange's edges on a probe aimed at it, and
/// computes where first principles put them.
fn flange_feet(setup: &Observer, band: &str, fl: &Flange, effort: &Effort) -> Result<Feet, String> {
    let (model, tc, cam) = (setup.model, setup.camera_t, setup.camera_x());
    let m = motion_of(setup.fixture, fl.front, model)?;
    let (start, v) = (m.start, m.velocity);
    let probe = ProbeImage::aimed_lazy(setup, &[fl.front, fl.side], 0.1, effort)?;
    let front = OnPlane {
        plane: Plane::z(start.x.z + DEPTH),
        coords: |p: DVec3| (p.y - start.x.y, p.x),
        range: (0.05 * HEIGHT, 0.95 * HEIGHT),
        degree: 3,
    };
    // The leading edge faces the direction of motion: scan in from that side.
    let sweep = if v.x > 0.0 {
        probe.sweep_leftwards()
    } else {
        probe.sweep_rightwards()
    };
    let fail = |what: &str, e: String| format!("{NAME} {band} flange {}: {what}: {e}", fl.tag);
    let lead = probe
        .fit(&front, sweep, probe.background(), effort)
        .map_err(|e| fail("leading edge", e))?
        .at(0.0);
    let trail = probe
        .fit(&front, sweep, fl.is_front, effort)
        .map_err(|e| fail("trailing edge", e))?
        .at(0.0);
    let seen = |x: f64| -> Result<DVec3, String> {
        let p = m.point(DVec3::new(x, 0.0, DEPTH));
        match model.light_speed {
            LightSpeed::Infinite => Ok(instantaneous(&p, tc, cam).x),
            LightSpeed::Finite => retarded(&p, tc, cam)
                .map(|r| r.x)
                .ok_or_else(|| fail("oracle", "never seen".into())),
        }
    };
    Ok(Feet {
        lead,
        trail,
        expected_lead: seen(fl.leading_x)?,
        expected_trail: seen(0.0)?,
        along: v.x.signum(),
    })
}
