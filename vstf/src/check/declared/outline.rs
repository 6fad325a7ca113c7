//! The outline of an analytic sphere on the sky. Lorentz-contracted, a
//! fast sphere's outline stays a circle (Penrose 1959, Terrell 1959);
//! Lorentz-decoupled, it does not.
//!
//! Measured, in angle space: the outline's edge points from the image as
//! lab directions, fitted by a circle on the sky ([`SkyCircle`]: the plane
//! a . d = cos(rho) nearest the directions d, its normal a the centre and
//! rho the angular radius, with no pole to depend on). Read off: the
//! outline's extents in azimuth and elevation and their ratio, the fitted
//! circle's angular radius and centre, and the outline's RMS angular
//! deviation from it.
//!
//! Expected. Contracted: in the sphere's rest frame the camera event sees a
//! cone of half-angle asin(R / D') about the centre; aberration into the
//! camera's frame ([`aberrate_lorentz`], with the camera moving at -u) maps
//! it to the outline. Decoupled: in the sphere's comoving coordinates
//! x' = x - u t the sphere is static and a light ray a straight line, so an
//! outline direction is one whose ray is tangent to it, found by bisection
//! along each direction from the centre. Either outline is a closed curve
//! of directions: the same circle fit is made to its samples, and its
//! extents are the curve's own extremes (refined between samples), so that
//! no expected reading depends on how the curve is sampled.

use crate::check::probe::Effort;
use crate::check::row::{Reading, Unit};
use crate::check::traced_edge::ProbeImage;
use crate::fixture::checks::OutlineRead;
use crate::fixture::Fixture;
use crate::measure::{azimuth, edge, elevation, Pixels, Scan, SkyCircle};
use crate::observer::Observer;
use crate::oracle::{aberrate_lorentz, extremes_on_loop, to_frame_of};
use glam::DVec3;
use renderer::Event;
use std::f64::consts::TAU;

/// A closed curve of directions: the direction at parameter s in [0, 1).
type Curve = Box<dyn Fn(f64) -> DVec3>;

/// Edge points of the outline from a probe, as lab directions: from every
/// row scanned from both sides, and from every column; and the angular size
/// of a pixel.
fn measured_outline(
    setup: &Observer,
    object: &str,
    effort: &Effort,
) -> Result<(Vec<DVec3>, Vec<DVec3>, f64), String> {
    let probe = ProbeImage::aimed_lazy(setup, &[object], 0.15, effort)?;
    let (img, camera) = (&probe.img, &probe.camera);
    let outside = probe.background();
    let (width, height) = img.dimensions();
    let (w, h) = (i64::from(width), i64::from(height));
    let (mut rows, mut cols) = (Vec::new(), Vec::new());
    for horizontal in [true, false] {
        let dirs = if horizontal { &mut rows } else { &mut cols };
        let (n, len) = if horizontal { (height, w) } else { (width, h) };
        for at in 0..n {
            let scan = Scan { horizontal, at };
            for (from, step) in [(0, 1), (len - 1, -1)] {
                if let Some(u) = edge(img, scan, from, step, &outside) {
                    let (px, py) = scan.point(u);
                    dirs.push(camera.direction(px, py));
                }
            }
        }
    }
    if let Some(failure) = img.failure() {
        return Err(failure);
    }
    let px = camera
        .angular_footprint(f64::from(width) / 2.0, f64::from(height) / 2.0, true)
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
) -> Result<Curve, String> {
    let rest = to_frame_of(centre.t - cam.t, centre.x - cam.x, u)
        .ok_or("sphere at light speed")?
        .1;
    let (dist, c) = (rest.length(), rest.normalize());
    let half = (radius / dist).asin();
    let (e1, e2) = (
        c.any_orthonormal_vector(),
        c.cross(c.any_orthonormal_vector()),
    );
    Ok(Box::new(move |s| {
        let phi = TAU * s;
        let n = c * half.cos() + (e1 * phi.cos() + e2 * phi.sin()) * half.sin();
        aberrate_lorentz(n, -u)
    }))
}

/// The outline expected for the decoupled sphere: directions d whose light
/// ray, a straight line o + s (d + u) in comoving coordinates, grazes the
/// static sphere of centre c.
fn expected_classical(centre0: DVec3, t0: f64, u: DVec3, radius: f64, cam: Event) -> Curve {
    // Comoving origin of the camera ray, relative to the sphere's centre.
    let o = cam.x - u * (cam.t - t0) - centre0;
    let inside = move |d: DVec3| {
        let w = d + u;
        o.cross(w).length_squared() < radius * radius * w.length_squared() && o.dot(w) < 0.0
    };
    // The apparent centre: a direction inside; then bisect outwards along each direction.
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
    Box::new(move |s| {
        let phi = TAU * s;
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
}

/// What the expected outline gives each reading, from its samples at the
/// parameters `at` (increasing, in [0, 1)): the circle fitted to them, and
/// the extents in azimuth and elevation (degrees), the curve's own
/// extremes. Azimuths are taken about the first sample's, so that an
/// outline across the azimuth's wrap at 180 degrees is measured across it.
struct Expected {
    circle: SkyCircle,
    width: f64,
    height: f64,
    dirs: Vec<DVec3>,
}

impl Expected {
    fn of(curve: &Curve, at: &[f64]) -> Option<Expected> {
        let dirs: Vec<DVec3> = at.iter().map(|s| curve(*s)).collect();
        let circle = SkyCircle::fit(&dirs)?;
        let reference = azimuth(dirs.first()?);
        let turn = |s: f64| (azimuth(&curve(s)) - reference + 180.0).rem_euclid(360.0) - 180.0;
        let (left, right) = extremes_on_loop(at, turn);
        let (low, high) = extremes_on_loop(at, |s| elevation(&curve(s)));
        Some(Expected {
            circle,
            width: right - left,
            height: high - low,
            dirs,
        })
    }
}

/// The angular extent (max - min) of directions under `f`, degrees; an
/// outline that straddles the azimuth's wrap at 180 degrees is measured
/// across it.
fn span(d: &[DVec3], f: impl Fn(&DVec3) -> f64) -> f64 {
    let extent = |values: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        hi - lo
    };
    let plain = extent(&mut d.iter().map(&f));
    if plain <= 180.0 {
        return plain;
    }
    extent(
        &mut d
            .iter()
            .map(&f)
            .map(|a| if a < 0.0 { a + 360.0 } else { a }),
    )
}

/// The sphere as the fixture gives it: radius and uniform motion, and
/// whether it is Lorentz-contracted under the model.
struct Sphere {
    radius: f64,
    start: Event,
    velocity: DVec3,
    contracted: bool,
}

impl Sphere {
    fn of(f: &Fixture, object: &str, model: renderer::Model) -> Result<Sphere, String> {
        let obj = f.object(object)?;
        let radius = obj
            .shape
            .sphere_radius()
            .ok_or("the sphere must be analytic")?;
        let (start, velocity) =
            crate::observer::uniform(&obj.motion).ok_or("the sphere must move uniformly")?;
        Ok(Sphere {
            radius,
            start,
            velocity,
            contracted: model.lorentz && obj.kind == renderer::ObjectKind::VObj,
        })
    }

    /// The outline first principles give, seen from the camera event `cam`.
    fn expected_outline(&self, cam: Event) -> Result<Curve, String> {
        let (start, u, radius) = (self.start, self.velocity, self.radius);
        Ok(if self.contracted {
            expected_relativistic(start, u, radius, cam)?
        } else {
            expected_classical(start.x, start.t, u, radius, cam)
        })
    }
}

/// An outline measured once and read by every check of it: each value
/// read off the measured outline with its uncertainty, beside the same
/// value read off the expected outline.
pub(super) struct Outline {
    values: Vec<(OutlineRead, Reading, f64)>,
    /// Whether the sphere is Lorentz-contracted (its outline a circle).
    contracted: bool,
    /// Expected outline directions to mark in the report.
    pub marks: Vec<DVec3>,
}

impl Outline {
    /// Measures the outline of the sphere `object` on a probe of
    /// `measuring`, and expects it from `described`'s scene data.
    pub(super) fn measure(
        measuring: &Observer,
        described: &Observer,
        object: &str,
        effort: &Effort,
    ) -> Result<Outline, String> {
        let f = described.fixture;
        let sphere = Sphere::of(f, object, described.model)?;
        let cam = Event::new(described.camera_t, described.camera_x());
        let (row_dirs, col_dirs, px) = measured_outline(measuring, object, effort)?;
        let dirs: Vec<DVec3> = row_dirs.iter().chain(&col_dirs).copied().collect();
        let measured = SkyCircle::fit(&dirs).ok_or("cannot fit the measured outline")?;
        let at: Vec<f64> = (0..720).map(|k| f64::from(k) / 720.0).collect();
        let expected = Expected::of(&sphere.expected_outline(cam)?, &at)
            .ok_or("cannot fit the expected outline")?;
        // Each edge point is known to the area method's resolution (1/n pixel,
        // uniform: / sqrt 12); the radius is a mean over N points, the RMS a
        // spread of them.
        let sigma = px / effort.strata() / 12f64.sqrt();
        // An azimuth step is the angle over the cosine of the elevation.
        let per_azimuth = 1.0 / elevation(&expected.circle.centre).to_radians().cos();
        let n = dirs.len() as f64;
        let mut values = extents(&row_dirs, &col_dirs, &expected, (sigma, per_azimuth));
        values.extend(circle(&measured, &expected.circle, (sigma, per_azimuth), n));
        Ok(Outline {
            values,
            contracted: sphere.contracted,
            marks: expected.dirs.iter().step_by(45).copied().collect(),
        })
    }

    /// The reading of `what`, its expectation and unit. The fitted circle
    /// (radius, RMS, centre) is read only for a Lorentz-contracted sphere,
    /// whose outline is a circle: another outline's circle fit depends on
    /// how its points are sampled.
    pub(super) fn read(&self, what: OutlineRead) -> Result<(Reading, f64, Unit), String> {
        let circular = matches!(
            what,
            OutlineRead::Radius
                | OutlineRead::Rms
                | OutlineRead::CentreAzimuth
                | OutlineRead::CentreElevation
        );
        if circular && !self.contracted {
            return Err(format!(
                "{what:?} reads the fitted circle, but this sphere is not Lorentz-contracted \
                 in the view: its outline is no circle (read its width, height or axis ratio)"
            ));
        }
        let (_, reading, expected) = self
            .values
            .iter()
            .find(|(r, _, _)| *r == what)
            .copied()
            .ok_or("every read is measured")?;
        let unit = if what == OutlineRead::AxisRatio {
            Unit::Ratio
        } else {
            Unit::Degrees
        };
        Ok((reading, expected, unit))
    }
}

/// The outline's extent: width along the motion (azimuth) and height
/// across it (elevation), from its extreme points, and their ratio. Each
/// measured extreme is one edge point (known to `sigma`, degrees; in
/// azimuth `per_azimuth` times that), taken from scans that cross the
/// outline squarely there: rows for the width, columns for the height. (The
/// nearest scan passes within h = 1/2 px of the extreme, where the outline
/// curves with radius R px: it falls short by at most h^2 / (2 R), under a
/// hundredth of a pixel for R of 13 px or more.)
fn extents(
    row_dirs: &[DVec3],
    col_dirs: &[DVec3],
    expected: &Expected,
    (sigma, per_azimuth): (f64, f64),
) -> Vec<(OutlineRead, Reading, f64)> {
    let tol_extent = 3.0 * sigma * 2f64.sqrt();
    let width = Reading {
        value: span(row_dirs, azimuth),
        tolerance: tol_extent * per_azimuth,
    };
    let height = Reading {
        value: span(col_dirs, elevation),
        tolerance: tol_extent,
    };
    let ratio = height.value / width.value;
    let (ew, eh) = (expected.width, expected.height);
    vec![
        (OutlineRead::Width, width, ew),
        (OutlineRead::Height, height, eh),
        (
            OutlineRead::AxisRatio,
            Reading {
                value: ratio,
                tolerance: ratio * (width.tolerance / width.value).hypot(tol_extent / height.value),
            },
            eh / ew,
        ),
    ]
}

/// The fitted circle: its radius (a mean over `n` edge points, each known
/// to `sigma`), its centre (known to sigma sqrt(2 / n) in each direction)
/// and the outline's RMS deviation from it, none depending on the sampling
/// (the fit has no pole).
fn circle(
    measured: &SkyCircle,
    expected: &SkyCircle,
    (sigma, per_azimuth): (f64, f64),
    n: f64,
) -> [(OutlineRead, Reading, f64); 4] {
    let centre = 3.0 * sigma * (2.0 / n).sqrt();
    let reading = |value, tolerance| Reading { value, tolerance };
    [
        (
            OutlineRead::Radius,
            reading(measured.radius.to_degrees(), 3.0 * sigma / n.sqrt() * 2.0),
            expected.radius.to_degrees(),
        ),
        (
            OutlineRead::Rms,
            reading(measured.rms.to_degrees(), 3.0 * sigma),
            expected.rms.to_degrees(),
        ),
        (
            OutlineRead::CentreAzimuth,
            reading(azimuth(&measured.centre), centre * per_azimuth),
            azimuth(&expected.centre),
        ),
        (
            OutlineRead::CentreElevation,
            reading(elevation(&measured.centre), centre),
            elevation(&expected.centre),
        ),
    ]
}

#[cfg(test)]
mod tests;
