//! Retarded time (paper 4.1.2, Figures 9-10): the flange moving right at
//! 0.00866c, seen at frames 920 and 1151 (camera t = 940 and 1171, the
//! camera "moved ahead 20 frames" for the light to arrive). Measured: the
//! flange's right edge where it stands on the stage, in each frame, and the
//! apparent velocity between them.

use super::{
    fixture_model, motion_of, Effort, Findings, OnPlane, Probed, Quantity, Reading, Setup, Unit,
};
use crate::fixture::Fixture;
use crate::measure::Plane;
use crate::oracle::retarded;
use glam::DVec3;
use renderer::Model;

const NAME: &str = "flange";
/// The flange primitive's size in this fixture (rest frame): height, width, depth.
const HEIGHT: f64 = 4.0;
const WIDTH: f64 = 2.0;
const DEPTH: f64 = 2.0;

/// Where the flange's right edge stands on the stage in the view at camera
/// time `tc`, measured from a probe render.
pub fn measure_foot(
    f: &Fixture,
    model: Model,
    tc: f64,
    effort: &Effort,
) -> Result<Reading, String> {
    let start = motion_of(f, "flange", model)?.start;
    let setup = Setup {
        fixture: f,
        model,
        camera_t: tc,
    };
    let probe = Probed::aimed(&setup, &["flange"], 0.15, effort)?;
    let front = OnPlane {
        plane: Plane::z(start.x.z + DEPTH),
        coords: |p: DVec3| (p.y - start.x.y, p.x),
        range: (0.05 * HEIGHT, 0.95 * HEIGHT),
        degree: 2,
    };
    Ok(probe
        .fit(&front, probe.from_right(), probe.background(), effort)
        .map_err(|e| format!("{NAME} at t_c = {tc}: {e}"))?
        .at(0.0))
}

/// Where first principles put the foot of the right edge at camera time
/// `tc`: its worldline against the camera's past light cone.
pub fn expected_foot(f: &Fixture, model: Model, tc: f64) -> Result<DVec3, String> {
    let m = motion_of(f, "flange", model)?;
    let foot = m.point(DVec3::new(WIDTH, 0.0, DEPTH));
    retarded(&foot, tc, f.spec.camera.position)
        .map(|r| r.x)
        .ok_or_else(|| "the right edge is never seen".into())
}

/// The frames measured: (frame number, camera time, the paper's figure for
/// where the right edge stands on the stage).
const FRAMES: [(u32, f64, f64); 2] = [(920, 940.0, 0.0), (1151, 1171.0, 2.0)];

/// The paper's apparent velocity of the flange between the two frames.
const PAPER_VELOCITY: f64 = 0.008658;

/// The flange's right edge on the stage in both frames, and its apparent
/// velocity between them, against the retarded positions of its foot.
pub fn run(f: &Fixture, effort: &Effort) -> Result<Findings, String> {
    let model = fixture_model(f);
    let mut quantities = Vec::new();
    let mut views = Vec::new();
    let mut seen = Vec::new();
    for (frame, tc, paper) in FRAMES {
        let setup = Setup {
            fixture: f,
            model,
            camera_t: tc,
        };
        let reading = measure_foot(f, model, tc, effort)?;
        let expected = expected_foot(f, model, tc)?;
        quantities.push(Quantity {
            name: format!("right edge on the stage, frame {frame} (x)"),
            measured: reading,
            expected: expected.x,
            paper: Some(paper),
            unit: Unit::LUnits,
        });
        seen.push((reading, expected.x));
        views.push(setup.full_view(&format!("frame {frame}"), &corner_marks(&setup)?)?);
    }
    let dt = FRAMES[1].1 - FRAMES[0].1;
    let (a, b) = (&seen[0], &seen[1]);
    quantities.push(Quantity {
        name: "apparent velocity, frames 920 -> 1151".into(),
        measured: Reading {
            value: (b.0.value - a.0.value) / dt,
            tolerance: (a.0.tolerance.powi(2) + b.0.tolerance.powi(2)).sqrt() / dt,
        },
        expected: (b.1 - a.1) / dt,
        paper: Some(PAPER_VELOCITY),
        unit: Unit::LUnitsPerTUnit,
    });
    Ok(Findings { views, quantities })
}

/// Where the flange's corners are seen from the camera event of `setup`:
/// the lab directions of their retarded positions.
fn corner_marks(setup: &Setup) -> Result<Vec<DVec3>, String> {
    let m = motion_of(setup.fixture, "flange", setup.model)?;
    let corners = [
        (0.0, 0.0, DEPTH),
        (WIDTH, 0.0, DEPTH),
        (0.0, HEIGHT, DEPTH),
        (WIDTH, HEIGHT, DEPTH),
        (0.0, HEIGHT, 0.0),
    ];
    Ok(corners
        .iter()
        .filter_map(|&(x, y, z)| {
            retarded(
                &m.point(DVec3::new(x, y, z)),
                setup.camera_t,
                setup.camera_x(),
            )
        })
        .map(|r| r.direction)
        .collect())
}
