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

use super::{
    background, difference, is_background, motion_of, trace_rows, Edge, Effort, FixtureReport,
    Reading, Row, Setup,
};
use crate::fixture::{Fixture, Overrides};
use crate::measure::{edge, Plane};
use crate::oracle::{body_point, gamma, retarded};
use glam::DVec3;

const HEIGHT: f64 = 4.0;
const WIDTH: f64 = 2.0;
const DEPTH: f64 = 2.0;
const FRONT: &str = "flange front";
const SIDE: &str = "flange side";

pub fn decoupled(effort: &Effort) -> Result<FixtureReport, String> {
    run("terrell-decoupled", effort)
}

pub fn contracted(effort: &Effort) -> Result<FixtureReport, String> {
    run("terrell-contracted", effort)
}

/// The front face's blue, whatever its shading.
fn is_front(c: DVec3) -> bool {
    c.z > 0.2 && c.z > c.x + 0.15
}

fn run(name: &str, effort: &Effort) -> Result<FixtureReport, String> {
    let f = Fixture::load(name).map_err(|e| e.to_string())?;
    let model = f
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let (start, v, lorentz) = motion_of(&f, FRONT, model)?;
    let setup = Setup {
        fixture: &f,
        model,
        camera_t: f.spec.camera.t,
    };
    let (tc, cam) = (setup.camera_t, setup.camera_x());
    let keep = [FRONT, SIDE];
    let (look, vfov) = setup.aim(&keep, 0.1)?;
    let (img, camera) = setup.probe(&keep, look, vfov, effort.probe, effort.probe, effort.spp)?;
    let bg = background(&f);
    let w = i64::from(img.width());
    let (front_plane, far_plane) = (Plane::z(start.x.z + DEPTH), Plane::z(start.x.z));
    let heights = (0.05 * HEIGHT, 0.95 * HEIGHT);
    let local = |p: DVec3| (p.y - start.x.y, p.x);
    let fail = |what: &str, e: String| format!("{name}: {what}: {e}");
    let trailing = trace_rows(
        &img,
        &camera,
        front_plane,
        |s| edge(&img, s, w - 1, -1, is_front),
        local,
        heights,
    );
    let leading = trace_rows(
        &img,
        &camera,
        front_plane,
        |s| edge(&img, s, w - 1, -1, |c| is_background(c, bg)),
        local,
        heights,
    );
    let far = trace_rows(
        &img,
        &camera,
        far_plane,
        |s| edge(&img, s, 0, 1, |c| is_background(c, bg)),
        local,
        heights,
    );
    let trailing = Edge::fit(&trailing, 3, effort).map_err(|e| fail("trailing edge", e))?;
    let leading = Edge::fit(&leading, 3, effort).map_err(|e| fail("leading edge", e))?;
    let far = Edge::fit(&far, 3, effort).map_err(|e| fail("far edge", e))?;

    // First principles: each point's straight worldline against the camera's past light cone.
    let lab_width = if lorentz {
        WIDTH / gamma(v.length())
    } else {
        WIDTH
    };
    let seen = |x: f64, y: f64, z: f64| -> Result<DVec3, String> {
        let p = body_point(start.t, start.x, v, DVec3::new(x, y, z), lorentz);
        retarded(&p, tc, cam)
            .map(|r| r.x)
            .ok_or_else(|| format!("{name}: point ({x}, {y}, {z}) is never seen"))
    };
    let upper = seen(0.0, HEIGHT, DEPTH)?;
    let lower = seen(0.0, 0.0, DEPTH)?;
    let mid = seen(0.0, HEIGHT / 2.0, DEPTH)?;
    let far_top = seen(0.0, HEIGHT, 0.0)?;
    let lead_mid = seen(WIDTH, HEIGHT / 2.0, DEPTH)?;

    let m_upper = trailing.at(HEIGHT);
    let m_lower = trailing.at(0.0);
    let m_lag = trailing.combine(&[(1.0, HEIGHT), (-1.0, 0.0)]);
    let m_far_lag = difference(&m_upper, &far.at(HEIGHT));
    let m_sagitta = trailing.combine(&[(1.0, HEIGHT / 2.0), (-0.5, 0.0), (-0.5, HEIGHT)]);
    let (m_lead, m_trail) = (leading.at(HEIGHT / 2.0), trailing.at(HEIGHT / 2.0));
    let m_apparent = difference(&m_lead, &m_trail);
    let m_length = delay_removed_length(
        &m_lead,
        &m_trail,
        start.x.y + HEIGHT / 2.0,
        front_plane.point.z,
        v.x,
        tc,
        cam,
    );

    let row = |q: &str, m: &Reading, expected: f64, paper: Option<f64>, unit: &str| {
        Row::new(name, q, m.value, expected, paper, m.tolerance, unit)
    };
    let rows = vec![
        row(
            "trailing upper corner (x)",
            &m_upper,
            upper.x,
            Some(0.0),
            "l.units",
        ),
        row(
            "trailing lower corner (x)",
            &m_lower,
            lower.x,
            Some(-1.66),
            "l.units",
        ),
        row(
            "lag of the trailing lower corner behind the upper",
            &m_lag,
            upper.x - lower.x,
            Some(1.66),
            "l.units",
        ),
        row(
            "lag of the far top corner behind the near top corner",
            &m_far_lag,
            upper.x - far_top.x,
            Some(1.66),
            "l.units",
        ),
        row(
            "bow of the trailing edge at mid-height (Boas)",
            &m_sagitta,
            mid.x - (upper.x + lower.x) / 2.0,
            None,
            "l.units",
        ),
        row(
            "apparent front length at mid-height",
            &m_apparent,
            lead_mid.x - mid.x,
            None,
            "l.units",
        ),
        row(
            "front length with light delay removed / proper length",
            &Reading {
                value: m_length.value / WIDTH,
                tolerance: m_length.tolerance / WIDTH,
            },
            lab_width / WIDTH,
            lorentz.then_some(0.5),
            "ratio",
        ),
    ];
    let corners = [
        (0.0, 0.0, DEPTH),
        (0.0, HEIGHT, DEPTH),
        (WIDTH, 0.0, DEPTH),
        (WIDTH, HEIGHT, DEPTH),
        (0.0, HEIGHT, 0.0),
        (0.0, 0.0, 0.0),
    ];
    let marks: Vec<DVec3> = corners
        .iter()
        .filter_map(|&(x, y, z)| seen(x, y, z).ok())
        .map(|p| (p - cam).normalize())
        .collect();
    let views = vec![setup.full_view("view", &marks)?];
    Ok(FixtureReport::new(name, &f.spec.description, views, rows))
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
    y: f64,
    z: f64,
    vx: f64,
    tc: f64,
    cam: DVec3,
) -> Reading {
    let at = |x: f64| DVec3::new(x, y, z);
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
