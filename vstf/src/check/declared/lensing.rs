//! Light bent by the fixture's mass, read from the pixels (the `lensing`
//! kind; docs/physics.md, "Light bent by a mass").
//!
//! Measured on a render through the view's own camera (at rest) at the
//! effort's width, one sample a pixel, keeping only the marker (none for
//! the shadow): the shadow is the black pixels, the ring the marker's
//! largest connected part, its outer edge the area it encloses and its
//! inner edge that area less the ring; each area is a circle about the
//! image centre (the camera looks at the mass), whose radius sqrt(A / pi)
//! is within sqrt(2)/2 pixel ([`RADIUS_FROM_AREA`]) and is turned into an
//! angle by the measurement's own pinhole. The deflection: the mean angle
//! from the mass of the marker's pixels (within half a pixel; the image is
//! an arc about the mass, so not its centroid's) is the angle theta it is
//! seen at, so its impact parameter b = r sin(theta) / sqrt(1 - 2M/r);
//! the angle the light turned through is the angle camera-mass-marker less
//! the angle a straight line of impact b sweeps between those radii. A
//! star of the sky: rendered with the sky alone, its primary image's mean
//! angle from the mass against the lens equation for a source at infinity.
//!
//! Expected: the closed form of the shadow, the rings by the exact lens
//! equation (quadrature of the orbit, [`crate::oracle::schwarzschild`]),
//! the deflection by 4M/b + 15 pi/4 (M/b)^2 with the tolerance widened by
//! what that series and the finite distances leave out (the quadrature's
//! value less the series, printed as part of the tolerance).

use crate::check::probe::Effort;
use crate::check::row::{Reading, Unit};
use crate::fixture::checks::{LensRead, LensingSpec};
use crate::measure::regions::{Mask, RADIUS_FROM_AREA};
use crate::measure::Pinhole;
use crate::observer::{background, Observer};
use crate::oracle::schwarzschild as gr;
use glam::DVec3;
use image::RgbImage;
use renderer::{Shape, Spacetime};

/// A row's reading, its expectation and unit, and the lab direction to mark.
pub(super) type Found = ((Reading, f64, Unit), DVec3);

/// The mass and centre of the fixture's spacetime.
pub(super) fn hole(o: &Observer) -> Result<(f64, DVec3), String> {
    match o.fixture.scene.spacetime {
        Spacetime::Schwarzschild(s) => Ok((s.mass, s.centre)),
        Spacetime::Flat => Err("the fixture has no mass".into()),
    }
}

/// The render a lensing check measures: through the view's own camera at
/// the effort's width, one sample a pixel, only the marker kept (none for
/// the shadow); shared by the checks of one view and marker.
pub(super) fn render(
    measuring: &Observer,
    l: &LensingSpec,
    effort: &Effort,
) -> Result<(RgbImage, Pinhole), String> {
    if l.read == LensRead::Star {
        return measuring.sky_render(measuring.size(effort.probe));
    }
    let keep: Vec<&str> = l.marker.iter().map(String::as_str).collect();
    measuring.measuring_render(&keep, measuring.size(effort.probe), 1)
}

/// Which render (see [`render`]) the check `l` shares with the view's
/// other lensing checks: its marker's, the sky's for a star (the shadow is
/// read without the sky), or the bare one.
pub(super) fn render_key(l: &LensingSpec) -> String {
    match (&l.marker, l.star) {
        (Some(name), _) => name.clone(),
        (None, Some(_)) => "\u{0}sky".into(),
        (None, None) => String::new(),
    }
}

/// Measures the lensing check `l` on `rendered` (see [`render`]), made
/// with `measuring`, expected from `described`.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    l: &LensingSpec,
    (img, pinhole): &(RgbImage, Pinhole),
) -> Result<Found, String> {
    let (m, centre) = hole(described)?;
    let camera = described.camera_x();
    let r = (camera - centre).length();
    let size = img.dimensions();
    let bg = background(measuring.fixture);
    if bg.max_element() < 0.1 {
        return Err("the background must not be black: the shadow would not show".into());
    }
    let to_mass = (centre - camera).normalize();
    if let (LensRead::Star, Some(star)) = (l.read, l.star) {
        return star_image(img, pinhole, (m, r, to_mass), star, measuring);
    }
    if l.read == LensRead::Deflection {
        return deflection(img, pinhole, (m, centre, camera), described, l, bg);
    }
    let middle = (f64::from(size.0) / 2.0, f64::from(size.1) / 2.0);
    if pinhole.direction(middle.0, middle.1).dot(to_mass) < 1.0 - 1e-12 {
        return Err("the camera must look at the mass (camera.look_at its position)".into());
    }
    let (area, expected) = match l.read {
        LensRead::Shadow => (
            Mask::of(img, |c| c.max_element() < 0.5 * bg.min_element().max(0.05)).count(),
            gr::shadow_radius(m, r),
        ),
        _ => {
            let ring = Mask::of(img, |c| marker_colour(c, bg)).largest_part();
            let outer = ring.enclosed();
            let area = match l.read {
                LensRead::RingOuter => outer.count(),
                _ => outer.without(&ring).count(),
            };
            let (expected, spread) = ring_edge(described, l, (m, centre, camera))?;
            return Ok((
                disc_reading(pinhole, middle, area, (expected, spread)),
                to_mass,
            ));
        }
    };
    Ok((
        disc_reading(pinhole, middle, area, (expected, 0.0)),
        to_mass,
    ))
}

/// A marker pixel: neither the background nor black.
fn marker_colour(c: DVec3, bg: DVec3) -> bool {
    (c - bg).abs().max_element() > 12.0 / 255.0 && c.max_element() > 0.1
}

/// The angular radius (degrees) of a circle of `area` pixels about the
/// image's `middle`, within [`RADIUS_FROM_AREA`] pixels, against
/// `expected` (radians) give or take `spread` (radians, from the
/// scene's own uncertainty).
fn disc_reading(
    pinhole: &Pinhole,
    middle: (f64, f64),
    area: usize,
    (expected, spread): (f64, f64),
) -> (Reading, f64, Unit) {
    let radius = (area as f64 / std::f64::consts::PI).sqrt();
    let axis = pinhole.direction(middle.0, middle.1);
    let angle = |r: f64| axis.angle_between(pinhole.direction(middle.0 + r, middle.1));
    let value = angle(radius);
    let tolerance = angle(radius + RADIUS_FROM_AREA) - value + spread;
    (
        Reading {
            value: value.to_degrees(),
            tolerance: tolerance.to_degrees(),
        },
        expected.to_degrees(),
        Unit::Degrees,
    )
}

/// The expected angle (radians) of the ring's edge `l.read` of the marker
/// disc, and half the difference between the polygon's inscribed and
/// circumscribed circles' rings.
fn ring_edge(
    o: &Observer,
    l: &LensingSpec,
    (m, centre, camera): (f64, DVec3, DVec3),
) -> Result<(f64, f64), String> {
    let name = l.marker.as_deref().ok_or("no marker")?;
    let obj = o.fixture.object(name)?;
    let Shape::Mesh(mesh) = &obj.shape else {
        return Err(format!("{name:?} is not a mesh"));
    };
    let position = obj.motion.uniform().ok_or("the marker moves")?.0.x;
    let points: Vec<DVec3> = mesh.vertices.iter().map(|v| *v + position).collect();
    let disc_centre = points.iter().sum::<DVec3>() / points.len() as f64;
    let axis = (centre - camera).normalize();
    let along = (disc_centre - centre).dot(axis);
    let off_axis = (disc_centre - centre - axis * along).length();
    let normal = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            (b - a).cross(c - a).normalize_or_zero()
        })
        .find(|n| *n != DVec3::ZERO)
        .ok_or("the marker has no triangle")?;
    let flat = points
        .iter()
        .all(|p| (*p - disc_centre).dot(normal).abs() < 1e-9 * along);
    if along <= 0.0 || off_axis > 1e-9 * along || normal.cross(axis).length() > 1e-9 || !flat {
        return Err(format!(
            "{name:?} must be a flat disc facing the camera, centred on the line from the camera through the mass, behind the mass"
        ));
    }
    let outer = points
        .iter()
        .map(|p| (*p - disc_centre).length())
        .fold(0.0, f64::max);
    let inner = rim_inscribed(mesh, &points, disc_centre);
    let sign = if l.read == LensRead::RingOuter {
        1.0
    } else {
        -1.0
    };
    let r = (camera - centre).length();
    let edge = |rho: f64| {
        gr::impact_reaching(m, r, along, sign * rho)
            .map(|b| gr::seen_angle(m, r, b))
            .ok_or_else(|| "no light from the disc's rim reaches the camera".to_string())
    };
    let (a, b) = (edge(inner)?, edge(outer)?);
    Ok((0.5 * (a + b), 0.5 * (a - b).abs()))
}

/// The least distance from `centre` to an edge of the mesh that only one
/// triangle has (the disc's rim): its inscribed circle's radius.
fn rim_inscribed(mesh: &renderer::Mesh, points: &[DVec3], centre: DVec3) -> f64 {
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for t in &mesh.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            edges.push((a.min(b), a.max(b)));
        }
    }
    let once = |e: &(u32, u32)| edges.iter().filter(|f| *f == e).count() == 1;
    edges
        .iter()
        .filter(|e| once(e))
        .map(|&(a, b)| {
            let (p, q) = (points[a as usize], points[b as usize]);
            let d = q - p;
            let s = ((centre - p).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            (p + d * s - centre).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The deflection row: see the module's doc.
fn deflection(
    img: &RgbImage,
    pinhole: &Pinhole,
    (m, centre, camera): (f64, DVec3, DVec3),
    described: &Observer,
    l: &LensingSpec,
    bg: DVec3,
) -> Result<Found, String> {
    let name = l.marker.as_deref().ok_or("no marker")?;
    let marker = described.fixture.object(name)?;
    let source = marker.motion.uniform().ok_or("the marker moves")?.0.x;
    let image = Mask::of(img, |c| marker_colour(c, bg)).largest_part();
    let (px, py) = image
        .centroid()
        .ok_or_else(|| format!("{name:?} is nowhere in the view"))?;
    let seen = pinhole.direction(px, py);
    let to_mass = (centre - camera).normalize();
    // The image is an arc about the mass: its pixels' mean angle from the
    // mass, not its centroid's (which lies inside the arc).
    let angles: Vec<f64> = image
        .centres()
        .map(|(x, y)| pinhole.direction(x, y).angle_between(to_mass))
        .collect();
    let theta = angles.iter().sum::<f64>() / angles.len() as f64;
    let (r, rs) = ((camera - centre).length(), (source - centre).length());
    let apart = (camera - centre).angle_between(source - centre);
    // Turned through, for light seen at angle theta from the mass.
    let turned = |theta: f64| {
        let b = gr::impact_parameter(m, r, theta);
        (apart - gr::swept_straight(b, r, rs), b)
    };
    let (value, b) = turned(theta);
    let expected = gr::deflection_series(m, b);
    // Half a pixel of the mean angle, carried through both sides.
    let dtheta = 0.5 * pinhole.angular_footprint(px, py, true);
    let (v2, b2) = turned(theta + dtheta);
    let measuring = ((v2 - gr::deflection_series(m, b2)) - (value - expected)).abs();
    let exact = gr::swept_between(m, b, r, rs)
        .ok_or("the light seen is captured (inside the critical impact parameter)")?;
    let left_out = (exact - gr::swept_straight(b, r, rs) - expected).abs();
    Ok((
        (
            Reading {
                value: value.to_degrees(),
                tolerance: (measuring + left_out).to_degrees(),
            },
            expected.to_degrees(),
            Unit::Degrees,
        ),
        seen,
    ))
}

/// The `star` row: the primary image of the sky's star in the direction
/// `star` is its pixels' largest connected part, a pixel counting when its
/// colour is the star's texel's within 10% of its direction in RGB and at
/// least a quarter of its brightness; the mean angle of its pixels from the
/// mass against the lens equation for a source at infinity at the star's
/// angle beta from the mass ([`gr::star_image`]). Tolerance: half a pixel,
/// plus half the spread of the angles at which the star's texel is seen
/// (beta give or take one texel, the reach of bilinear filtering).
fn star_image(
    img: &RgbImage,
    pinhole: &Pinhole,
    (m, r, to_mass): (f64, f64, DVec3),
    star: DVec3,
    o: &Observer,
) -> Result<Found, String> {
    let sky = o
        .fixture
        .scene
        .sky
        .as_ref()
        .ok_or("the fixture has no sky")?;
    let colour = sky.toward(star);
    let hue = colour.normalize_or_zero();
    let is_star = |c: DVec3| {
        c.length() >= 0.25 * colour.length() && (c.normalize_or_zero() - hue).length() < 0.1
    };
    let image = Mask::of(img, is_star).largest_part();
    let (px, py) = image
        .centroid()
        .ok_or("the star is nowhere in the view (no pixel of its colour)")?;
    let angles: Vec<f64> = image
        .centres()
        .map(|(x, y)| pinhole.direction(x, y).angle_between(to_mass))
        .collect();
    let theta = angles.iter().sum::<f64>() / angles.len() as f64;
    let beta = star.normalize().angle_between(to_mass);
    let seen = |beta: f64| {
        gr::star_image(m, r, beta)
            .ok_or_else(|| format!("no image of a star {beta} rad off the mass"))
    };
    let expected = seen(beta)?;
    let (w, h) = sky.size();
    let texel = (std::f64::consts::TAU / f64::from(w)).max(std::f64::consts::PI / f64::from(h));
    let spread = 0.5 * (seen(beta + texel)? - seen((beta - texel).max(1e-9))?).abs();
    let tolerance = 0.5 * pinhole.angular_footprint(px, py, true) + spread;
    Ok((
        (
            Reading {
                value: theta.to_degrees(),
                tolerance: tolerance.to_degrees(),
            },
            expected.to_degrees(),
            Unit::Degrees,
        ),
        pinhole.direction(px, py),
    ))
}
