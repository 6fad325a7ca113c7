//! The teaser (paper 4.1.5, Figure 1): two flanges converging and crossing
//! at 0.866c over a mirrored background, in three bands: infinite light
//! speed (the lab slice at t = 0), classical and relativistic (the camera
//! advanced 18.675 t.units, the light time from the stage centre).
//!
//! Measured in each band: where each flange's leading and trailing edges
//! stand on the stage, and the apparent width between them, against the
//! instantaneous (infinite band) or retarded (finite bands) positions of
//! the feet of those edges.

use super::{
    background, difference, is_background, motion_of, trace_rows, Edge, Effort, FixtureReport,
    Reading, Row, Setup,
};
use crate::fixture::{Fixture, Overrides};
use crate::measure::{edge, Plane};
use crate::oracle::{body_point, instantaneous, retarded};
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

pub fn run(effort: &Effort) -> Result<FixtureReport, String> {
    let f = Fixture::load(NAME).map_err(|e| e.to_string())?;
    let advanced = f.spec.camera.t;
    let base = f
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let bands = [
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
    ];
    let bg = background(&f);
    let mut rows = Vec::new();
    let mut views = Vec::new();
    for (band, model, tc) in bands {
        let setup = Setup {
            fixture: &f,
            model,
            camera_t: tc,
        };
        let cam = setup.camera_x();
        let mut marks = Vec::new();
        for fl in &FLANGES {
            let (start, v, lorentz) = motion_of(&f, fl.front, model)?;
            let keep = [fl.front, fl.side];
            let (look, vfov) = setup.aim(&keep, 0.1)?;
            let (img, camera) =
                setup.probe(&keep, look, vfov, effort.probe, effort.probe, effort.spp)?;
            let plane = Plane::z(start.x.z + DEPTH);
            let local = |p: DVec3| (p.y - start.x.y, p.x);
            let heights = (0.05 * HEIGHT, 0.95 * HEIGHT);
            // The leading edge faces the direction of motion: scan in from that side.
            let (from, step) = if v.x > 0.0 {
                (i64::from(img.width()) - 1, -1)
            } else {
                (0, 1)
            };
            let lead = trace_rows(
                &img,
                &camera,
                plane,
                |s| edge(&img, s, from, step, |c| is_background(c, bg)),
                local,
                heights,
            );
            let trail = trace_rows(
                &img,
                &camera,
                plane,
                |s| edge(&img, s, from, step, fl.is_front),
                local,
                heights,
            );
            let fail =
                |what: &str, e: String| format!("{NAME} {band} flange {}: {what}: {e}", fl.tag);
            let lead = Edge::fit(&lead, 3, effort)
                .map_err(|e| fail("leading edge", e))?
                .at(0.0);
            let trail = Edge::fit(&trail, 3, effort)
                .map_err(|e| fail("trailing edge", e))?
                .at(0.0);
            let seen = |x: f64| -> Result<DVec3, String> {
                let p = body_point(start.t, start.x, v, DVec3::new(x, 0.0, DEPTH), lorentz);
                match model.light_speed {
                    LightSpeed::Infinite => Ok(instantaneous(&p, tc, cam).x),
                    LightSpeed::Finite => retarded(&p, tc, cam)
                        .map(|r| r.x)
                        .ok_or_else(|| fail("oracle", "never seen".into())),
                }
            };
            let (e_lead, e_trail) = (seen(fl.leading_x)?, seen(0.0)?);
            marks.extend([e_lead, e_trail].map(|p| (p - cam).normalize()));
            let row = |q: &str, m: &Reading, e: f64| {
                Row::new(
                    NAME,
                    &format!("{band}: flange {} {q}", fl.tag),
                    m.value,
                    e,
                    None,
                    m.tolerance,
                    "l.units",
                )
            };
            rows.push(row("leading edge on the stage (x)", &lead, e_lead.x));
            rows.push(row("trailing edge on the stage (x)", &trail, e_trail.x));
            // Widths along the flange's own motion, so both come out positive.
            let along = v.x.signum();
            let width = difference(&lead, &trail);
            let width = Reading {
                value: width.value * along,
                tolerance: width.tolerance,
            };
            rows.push(row(
                "apparent width on the stage",
                &width,
                (e_lead.x - e_trail.x) * along,
            ));
        }
        views.push(setup.full_view(band, &marks)?);
    }
    Ok(FixtureReport::new(NAME, &f.spec.description, views, rows))
}
