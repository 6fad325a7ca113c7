//! The Shapiro delay, read from the pixels (the `lensing` kind's `delay`;
//! docs/physics.md, "The Shapiro delay"): a marker sphere at rest behind
//! the mass switches on at its worldline's start t_on; renders of it alone
//! through the view's camera (at rest) at camera times found by bisection
//! give the first camera time at which any pixel shows it and the first at
//! which it shows fully (as many pixels as at the end of the search, which
//! must show it), searched from just before light along a straight line
//! could bring it over [`WINDOW`]. The renders are square probes of
//! [`PROBE`] pixels, one sample each, aimed at where the marker is seen at
//! the window's end (in the view's measuring image at half the effort's
//! width); camera and mass at rest, it is seen there whenever it is seen.
//!
//! Expected: the coordinate time light takes from the marker's centre to
//! the camera along its primary image's null geodesic, by quadrature
//! ([`crate::oracle::schwarzschild::light_time`], the impact parameter from
//! the angle camera-mass-marker). Every point of the sphere is within its
//! radius rho of the centre, and the light time changes by at most
//! dt/ds <= 1 / f per unit of displacement (f = 1 - 2M/r at the sphere's
//! nearest radius), so both camera times lie within rho / f of
//! t_on + T: the reading is their mean less t_on, the tolerance rho / f
//! plus the bisection's step.

use super::lensing::{hole, Found};
use crate::check::probe::{Effort, Probe};
use crate::check::row::{Reading, Unit};
use crate::fixture::checks::LensingSpec;
use crate::measure;
use crate::observer::{background, is_background, Observer};
use crate::oracle::schwarzschild as gr;
use glam::DVec3;
use image::RgbImage;
use renderer::Shape;

/// The bisection's last step, t.units.
const STEP: f64 = 0.05;

/// How long after the straight line's light time the marker must be
/// shown fully, t.units: the delay searched for is within it.
const WINDOW: f64 = 64.0;

/// The width and height of the probes the bisection renders, pixels.
const PROBE: u32 = 32;

/// Measures the delay check `l` (see the module doc).
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    l: &LensingSpec,
    effort: &Effort,
) -> Result<Found, String> {
    let (m, centre) = hole(described)?;
    let name = l.marker.as_deref().ok_or("the delay needs a marker")?;
    let obj = described.fixture.object(name)?;
    let Shape::Sphere { radius } = obj.shape else {
        return Err(format!("{name:?} must be an analytic sphere"));
    };
    let (start, _) = obj.motion.uniform().ok_or("the marker must be at rest")?;
    let (t_on, at) = (start.t, start.x);
    let camera = described.camera_x();
    let (r1, r2) = ((camera - centre).length(), (at - centre).length());
    let psi = (camera - centre).angle_between(at - centre);
    let light = gr::impact_sweeping(m, r1, r2, psi)
        .and_then(|b| gr::light_time(m, b, r1, r2))
        .ok_or("no light from the marker's centre reaches the camera past the mass")?;
    let spread = radius / (1.0 - 2.0 * m / (r2 - radius));
    let straight = (at - camera).length();
    let lo = t_on + straight - radius - 1.0;
    let hi = lo + WINDOW;
    let (look_at, hfov_deg) = around(measuring, name, hi, effort)?;
    let shown = |t: f64| -> Result<usize, String> {
        let o = Observer {
            camera_t: t,
            ..*measuring
        };
        let (img, _) = o.probe(&Probe {
            keep: &[name],
            look_at,
            hfov_deg,
            size: (PROBE, PROBE),
            spp: 1,
        })?;
        Ok(lit(&img, background(measuring.fixture)))
    };
    if shown(lo)? > 0 {
        return Err(format!(
            "{name:?} is seen at camera time {lo}, before light on a straight line could bring it"
        ));
    }
    let all = shown(hi)?;
    if all == 0 {
        return Err(format!("{name:?} is not seen at camera time {hi}"));
    }
    let first = bisect(lo, hi, |t| Ok(shown(t)? > 0))?;
    let full = bisect(first - STEP, hi, |t| Ok(shown(t)? >= all))?;
    Ok((
        (
            Reading {
                value: 0.5 * (first + full) - t_on,
                tolerance: spread + STEP,
            },
            light,
            Unit::TUnits,
        ),
        (at - camera).normalize(),
    ))
}

/// The least t in (lo, hi] where `holds` turns true, within [`STEP`]
/// (it is false at lo and true at hi, and stays true once true).
fn bisect(
    mut lo: f64,
    mut hi: f64,
    mut holds: impl FnMut(f64) -> Result<bool, String>,
) -> Result<f64, String> {
    while hi - lo > STEP {
        let mid = 0.5 * (lo + hi);
        if holds(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

/// The pixels of `img` that show something other than the background `bg`.
fn lit(img: &RgbImage, bg: DVec3) -> usize {
    img.enumerate_pixels()
        .filter(|(x, y, _)| !is_background(measure::color(img, *x, *y), bg))
        .count()
}

/// Where the marker `name` is seen at camera time `t` (the camera and the
/// mass at rest, it is seen there at every time it is seen at all): the
/// point a square probe looks at and its field (degrees), covering the
/// marker's pixels in the view's measuring image, half the effort's width,
/// with half their extent to spare on each side.
fn around(
    measuring: &Observer,
    name: &str,
    t: f64,
    effort: &Effort,
) -> Result<(DVec3, f64), String> {
    let o = Observer {
        camera_t: t,
        ..*measuring
    };
    let (img, pinhole) = o.measuring_render(&[name], o.size(effort.probe / 2), 1)?;
    let bg = background(measuring.fixture);
    let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
    for (x, y, _) in img.enumerate_pixels() {
        if !is_background(measure::color(&img, x, y), bg) {
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
    }
    if x0 > x1 {
        return Err(format!("{name:?} is not seen at camera time {t}"));
    }
    let (fx0, fy0, fx1, fy1) = (
        f64::from(x0),
        f64::from(y0),
        f64::from(x1) + 1.0,
        f64::from(y1) + 1.0,
    );
    let centre = pinhole.direction(0.5 * (fx0 + fx1), 0.5 * (fy0 + fy1));
    let half = [(fx0, fy0), (fx1, fy0), (fx0, fy1), (fx1, fy1)]
        .iter()
        .map(|&(x, y)| pinhole.direction(x, y).angle_between(centre))
        .fold(0.0, f64::max);
    Ok((o.camera_x() + centre, 4.0 * half.to_degrees()))
}
