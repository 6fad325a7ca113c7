//! A fast sphere (issue 6, item 4): an analytic sphere crossing the view at
//! 0.9c. Lorentz-contracted, its outline on the sky stays a circle
//! (Penrose 1959, Terrell 1959); Lorentz-decoupled, it does not.
//!
//! Measured, in angle space: the outline's edge points from the image as
//! directions, projected stereographically about their mean (circles on the
//! sky stay circles) and fitted by a circle. Reported: its angular radius,
//! and the outline's RMS deviation from it.
//!
//! Expected. Contracted: in the sphere's rest frame the camera event sees a
//! cone of half-angle asin(R / D') about the centre; aberration into the
//! camera's frame ([`aberrate_lorentz`], with the camera moving at -u) maps
//! it to the outline. Decoupled: in the sphere's comoving coordinates
//! x' = x - u t the sphere is static and a light ray a straight line, so an
//! outline direction is one whose ray is tangent to it, found by bisection
//! along each direction from the centre.

use super::{background, is_background, Effort, FixtureReport, Row, Setup};
use crate::fixture::{Fixture, Overrides};
use crate::measure::{edge, Scan};
use crate::oracle::aberrate_lorentz;
use glam::{DVec2, DVec3};
use renderer::{Boost, Event};

const SPHERE: &str = "sphere";

/// A circle fitted on the sky: its angular radius, and the RMS deviation of
/// the points from it (both degrees).
struct SkyCircle {
    radius_deg: f64,
    rms_deg: f64,
}

/// Stereographic projection about `m` (circles on the sphere stay circles).
fn project(d: DVec3, m: DVec3, e1: DVec3, e2: DVec3) -> DVec2 {
    let k = 2.0 / (1.0 + d.dot(m));
    DVec2::new(d.dot(e1), d.dot(e2)) * k
}

fn unproject(p: DVec2, m: DVec3, e1: DVec3, e2: DVec3) -> DVec3 {
    let r2 = p.length_squared() / 4.0;
    ((e1 * p.x + e2 * p.y) + m * (1.0 - r2)) / (1.0 + r2)
}

/// Fits a circle on the sky to unit directions (algebraic circle fit in the
/// stereographic plane about their mean).
fn fit_sky_circle(dirs: &[DVec3]) -> Option<SkyCircle> {
    let m = dirs
        .iter()
        .fold(DVec3::ZERO, |a, d| a + *d)
        .try_normalize()?;
    let e1 = m.any_orthonormal_vector();
    let e2 = m.cross(e1);
    let pts: Vec<DVec2> = dirs.iter().map(|d| project(*d, m, e1, e2)).collect();
    // x^2 + y^2 + D x + E y + F = 0, least squares in (D, E, F).
    let (mut ata, mut atb) = (glam::DMat3::ZERO, DVec3::ZERO);
    for p in &pts {
        let row = DVec3::new(p.x, p.y, 1.0);
        ata += glam::DMat3::from_cols(row * row.x, row * row.y, row * row.z);
        atb += row * -(p.length_squared());
    }
    let sol = ata.inverse() * atb;
    let c = DVec2::new(-sol.x / 2.0, -sol.y / 2.0);
    let r = (c.length_squared() - sol.z).sqrt();
    if !r.is_finite() {
        return None;
    }
    let u = c.try_normalize().unwrap_or(DVec2::X);
    let (d1, d2) = (
        unproject(c + u * r, m, e1, e2),
        unproject(c - u * r, m, e1, e2),
    );
    let radius = d1.angle_between(d2) / 2.0;
    // Plane distances to angles: d(angle)/d(plane) = 1 / (1 + |p|^2 / 4).
    let rms = (pts
        .iter()
        .map(|p| ((p.distance(c) - r) / (1.0 + p.length_squared() / 4.0)).powi(2))
        .sum::<f64>()
        / pts.len() as f64)
        .sqrt();
    Some(SkyCircle {
        radius_deg: radius.to_degrees(),
        rms_deg: rms.to_degrees(),
    })
}

/// Edge points of the outline from a probe, as lab directions: from every
/// row scanned from both sides, and from every column; and the angular size
/// of a pixel.
fn measured_outline(
    setup: &Setup,
    effort: &Effort,
) -> Result<(Vec<DVec3>, Vec<DVec3>, f64), String> {
    let (look, hfov) = setup.aim(&[SPHERE], 0.15)?;
    let (img, camera) = setup.probe(
        &[SPHERE],
        look,
        hfov,
        effort.probe,
        effort.probe,
        effort.spp,
    )?;
    let bg = background(setup.fixture);
    let outside = |c: DVec3| is_background(c, bg);
    let (w, h) = (i64::from(img.width()), i64::from(img.height()));
    let (mut rows, mut cols) = (Vec::new(), Vec::new());
    for horizontal in [true, false] {
        let dirs = if horizontal { &mut rows } else { &mut cols };
        let (n, len) = if horizontal {
            (img.height(), w)
        } else {
            (img.width(), h)
        };
        for at in 0..n {
            let scan = Scan { horizontal, at };
            for (from, step) in [(0, 1), (len - 1, -1)] {
                if let Some(u) = edge(&img, scan, from, step, outside) {
                    let (px, py) = scan.point(u);
                    dirs.push(camera.direction(px, py));
                }
            }
        }
    }
    let px = crate::measure::angular_footprint(
        &camera,
        f64::from(img.width()) / 2.0,
        f64::from(img.height()) / 2.0,
        true,
    )
    .to_degrees();
    Ok((rows, cols, px))
}

/// The outline expected for the contracted sphere: the rest-frame cone,
/// aberrated into the camera's frame.
fn expected_relativistic(
    centre: Event,
    u: DVec3,
    radius: f64,
    cam: Event,
) -> Result<Vec<DVec3>, String> {
    let rest = Boost::new(u)
        .ok_or("sphere at light speed")?
        .to_rest(centre - cam)
        .x;
    let (dist, c) = (rest.length(), rest.normalize());
    let half = (radius / dist).asin();
    let (e1, e2) = (
        c.any_orthonormal_vector(),
        c.cross(c.any_orthonormal_vector()),
    );
    Ok((0..720)
        .map(|k| {
            let phi = std::f64::consts::TAU * f64::from(k) / 720.0;
            let n = c * half.cos() + (e1 * phi.cos() + e2 * phi.sin()) * half.sin();
            aberrate_lorentz(n, -u)
        })
        .collect())
}

/// The outline expected for the decoupled sphere: directions d whose light
/// ray, a straight line o + s (d + u) in comoving coordinates, grazes the
/// static sphere of centre c.
fn expected_classical(centre0: DVec3, t0: f64, u: DVec3, radius: f64, cam: Event) -> Vec<DVec3> {
    // Comoving origin of the camera ray, relative to the sphere's centre.
    let o = cam.x - u * (cam.t - t0) - centre0;
    let inside = |d: DVec3| {
        let w = d + u;
        o.cross(w).length_squared() < radius * radius * w.length_squared() && o.dot(w) < 0.0
    };
    // The apparent centre: a direction inside; then bisect outwards along 720 directions.
    let mut centre = (-o).normalize();
    for _ in 0..50 {
        if inside(centre) {
            break;
        }
        centre = (centre - u * 0.05).normalize();
    }
    let (e1, e2) = (
        centre.any_orthonormal_vector(),
        centre.cross(centre.any_orthonormal_vector()),
    );
    (0..720)
        .map(|k| {
            let phi = std::f64::consts::TAU * f64::from(k) / 720.0;
            let side = e1 * phi.cos() + e2 * phi.sin();
            let at = |a: f64| (centre * a.cos() + side * a.sin()).normalize();
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if inside(at(mid)) {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            at(0.5 * (lo + hi))
        })
        .collect()
}

pub fn relativistic(effort: &Effort) -> Result<FixtureReport, String> {
    run("sphere-relativistic", effort)
}

pub fn classical(effort: &Effort) -> Result<FixtureReport, String> {
    run("sphere-classical", effort)
}

fn run(name: &str, effort: &Effort) -> Result<FixtureReport, String> {
    let f = Fixture::load(name).map_err(|e| e.to_string())?;
    let model = f
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let obj = f
        .scene
        .objects
        .iter()
        .find(|o| o.name == SPHERE)
        .ok_or("no sphere")?;
    let radius = obj
        .shape
        .sphere_radius()
        .ok_or("the sphere must be analytic")?;
    let (start, u) = obj
        .motion
        .uniform()
        .ok_or("the sphere must move uniformly")?;
    let contracted = model.lorentz && obj.kind == renderer::ObjectKind::VObj;
    let setup = Setup {
        fixture: &f,
        model,
        camera_t: f.spec.camera.t,
    };
    let cam = Event::new(f.spec.camera.t, f.spec.camera.position);
    let (row_dirs, col_dirs, px) = measured_outline(&setup, effort)?;
    let dirs: Vec<DVec3> = row_dirs.iter().chain(&col_dirs).copied().collect();
    let measured = fit_sky_circle(&dirs).ok_or("cannot fit the measured outline")?;
    let expected_dirs = if contracted {
        expected_relativistic(start, u, radius, cam)?
    } else {
        expected_classical(start.x, start.t, u, radius, cam)
    };
    let expected = fit_sky_circle(&expected_dirs).ok_or("cannot fit the expected outline")?;
    // Each edge point is known to the area method's resolution (1/n pixel,
    // uniform: / sqrt 12); the radius is a mean over N points, the RMS a
    // spread of them.
    let sigma = px / effort.strata() / 12f64.sqrt();
    let n = dirs.len() as f64;
    let tol_radius = 3.0 * sigma / n.sqrt() * 2.0;
    let tol_rms = 3.0 * sigma;
    // The outline's extent: width along the motion (azimuth) and height
    // across it (elevation), from its extreme points, which do not depend
    // on how the outline is sampled. Each extreme is one edge point, taken
    // from scans that cross the outline squarely there: rows for the width,
    // columns for the height.
    let az = |v: &DVec3| v.x.atan2(-v.z).to_degrees();
    let el = |v: &DVec3| v.y.atan2(v.x.hypot(v.z)).to_degrees();
    let span = |d: &[DVec3], f: &dyn Fn(&DVec3) -> f64| {
        let (lo, hi) = d
            .iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        hi - lo
    };
    let (mw, mh) = (span(&row_dirs, &az), span(&col_dirs, &el));
    let (ew, eh) = (span(&expected_dirs, &az), span(&expected_dirs, &el));
    let tol_extent = 3.0 * sigma * 2f64.sqrt();
    let mut rows = vec![
        Row::new(
            name,
            "angular width of the outline along the motion",
            mw,
            ew,
            None,
            tol_extent,
            "deg",
        ),
        Row::new(
            name,
            "angular height of the outline across the motion",
            mh,
            eh,
            None,
            tol_extent,
            "deg",
        ),
    ];
    if contracted {
        // A circle: the fitted circle does not depend on the sampling.
        rows.push(Row::new(
            name,
            "angular radius of the outline (fitted circle)",
            measured.radius_deg,
            expected.radius_deg,
            None,
            tol_radius,
            "deg",
        ));
        rows.push(Row::new(
            name,
            "RMS deviation of the outline from a circle",
            measured.rms_deg,
            expected.rms_deg,
            None,
            tol_rms,
            "deg",
        ));
    }
    let marks: Vec<DVec3> = expected_dirs.iter().step_by(45).copied().collect();
    let views = vec![setup.full_view("view", &marks)?];
    Ok(FixtureReport::new(name, &f.spec.description, views, rows))
}
