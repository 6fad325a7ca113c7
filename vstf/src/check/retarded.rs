//! Retarded time (paper 4.1.2, Figures 9-10): the flange moving right at
//! 0.00866c, seen at frames 920 and 1151 (camera t = 940 and 1171, the
//! camera "moved ahead 20 frames" for the light to arrive). Measured: the
//! flange's right edge where it stands on the stage, in each frame, and the
//! apparent velocity between them.

use super::{
    background, is_background, motion_of, trace_rows, Edge, Effort, FixtureReport, Reading, Row,
    Setup,
};
use crate::fixture::{Fixture, Overrides};
use crate::measure::{edge, Plane};
use crate::oracle::{body_point, retarded};
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
    let (start, _, _) = motion_of(f, "flange", model)?;
    let setup = Setup {
        fixture: f,
        model,
        camera_t: tc,
    };
    let bg = background(f);
    let (look, vfov) = setup.aim(&["flange"], 0.15)?;
    let (img, camera) = setup.probe(
        &["flange"],
        look,
        vfov,
        effort.probe,
        effort.probe,
        effort.spp,
    )?;
    let w = i64::from(img.width());
    let trace = trace_rows(
        &img,
        &camera,
        Plane::z(start.x.z + DEPTH),
        |scan| edge(&img, scan, w - 1, -1, |c| is_background(c, bg)),
        |p| (p.y - start.x.y, p.x),
        (0.05 * HEIGHT, 0.95 * HEIGHT),
    );
    Ok(Edge::fit(&trace, 2, effort)
        .map_err(|e| format!("{NAME} at t_c = {tc}: {e}"))?
        .at(0.0))
}

/// Where first principles put the foot of the right edge at camera time
/// `tc`: its worldline against the camera's past light cone.
pub fn expected_foot(f: &Fixture, model: Model, tc: f64) -> Result<DVec3, String> {
    let (start, v, lorentz) = motion_of(f, "flange", model)?;
    let foot = body_point(start.t, start.x, v, DVec3::new(WIDTH, 0.0, DEPTH), lorentz);
    retarded(&foot, tc, f.spec.camera.position)
        .map(|r| r.x)
        .ok_or_else(|| "the right edge is never seen".into())
}

pub fn run(effort: &Effort) -> Result<FixtureReport, String> {
    let f = Fixture::load(NAME).map_err(|e| e.to_string())?;
    let model = f
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let (start, v, lorentz) = motion_of(&f, "flange", model)?;
    let mut rows = Vec::new();
    let mut views = Vec::new();
    let mut seen = Vec::new();
    for (frame, tc, paper) in [(920, 940.0, 0.0), (1151, 1171.0, 2.0)] {
        let setup = Setup {
            fixture: &f,
            model,
            camera_t: tc,
        };
        let cam = setup.camera_x();
        let reading = measure_foot(&f, model, tc, effort)?;
        let expected = expected_foot(&f, model, tc)?;
        rows.push(Row::new(
            NAME,
            &format!("right edge on the stage, frame {frame} (x)"),
            reading.value,
            expected.x,
            Some(paper),
            reading.tolerance,
            "l.units",
        ));
        seen.push((reading, expected.x));
        let corners = [
            (0.0, 0.0, DEPTH),
            (WIDTH, 0.0, DEPTH),
            (0.0, HEIGHT, DEPTH),
            (WIDTH, HEIGHT, DEPTH),
            (0.0, HEIGHT, 0.0),
        ];
        let marks: Vec<DVec3> = corners
            .iter()
            .filter_map(|&(x, y, z)| {
                retarded(
                    &body_point(start.t, start.x, v, DVec3::new(x, y, z), lorentz),
                    tc,
                    cam,
                )
            })
            .map(|r| r.direction)
            .collect();
        views.push(setup.full_view(&format!("frame {frame}"), &marks)?);
    }
    let dt = 1171.0 - 940.0;
    let (a, b) = (&seen[0], &seen[1]);
    rows.push(Row::new(
        NAME,
        "apparent velocity, frames 920 -> 1151",
        (b.0.value - a.0.value) / dt,
        (b.1 - a.1) / dt,
        Some(0.008658),
        (a.0.tolerance.powi(2) + b.0.tolerance.powi(2)).sqrt() / dt,
        "l.units/t.unit",
    ));
    Ok(FixtureReport::new(NAME, &f.spec.description, views, rows))
}
