//! Where an accelerating camera sees a static marker (docs/physics.md,
//! "The accelerated observer"). Measured: the marker's outline on a render
//! of it alone through the fixture's own camera, each edge point turned
//! into a direction in the camera's own frame by the measurements'
//! pinhole at rest with the camera's attitude (a boost along the
//! acceleration keeps the camera's axes), fitted by a circle on the sky;
//! read: the angle between the circle's centre and the acceleration (a
//! camera on keyframes: its velocity at the view). Expected: the oracle's
//! worldline at the view's proper time (rapidity phi0 + a tau, position;
//! on keyframes, the oracle's own cubic at the view's lab time), the
//! marker's lab cone about angle theta of half-angle asin(R / d),
//! aberrated at beta = tanh(phi) (on keyframes |v|): the centre of the
//! seen circle ([`seen_circle`]).

use crate::check::probe::Effort;
use crate::check::row::{Reading, Unit};
use crate::fixture::checks::MarkerAngleSpec;
use crate::measure::{edge, Pinhole, Scan, SkyCircle};
use crate::observer::{camera_path, CameraPath, Observer};
use crate::oracle::rocket::seen_circle;
use glam::DVec3;
use image::RgbImage;
use renderer::Shape;

/// The reading, its expectation and unit (degrees), and a direction (lab)
/// to mark: the marker's centre.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    m: &MarkerAngleSpec,
    effort: &Effort,
) -> Result<((Reading, f64, Unit), DVec3), String> {
    let f = described.fixture;
    let path = camera_path(&f.spec.camera).ok_or("marker_angle: the camera has no worldline")?;
    let (at, v) = path
        .at(described.camera_t)
        .ok_or("marker_angle: the view is outside the camera's keyframes")?;
    // Angles from the acceleration (hyperbolic) or the velocity (keyframes).
    let (axis, beta) = match &path {
        CameraPath::Rocket(w) => (
            w.direction,
            w.rapidity(w.proper_time(described.camera_t)).tanh(),
        ),
        CameraPath::Keyframed(_) => (
            v.try_normalize().ok_or(
                "marker_angle: the camera on keyframes is at rest at this view, so no velocity to measure from",
            )?,
            v.length(),
        ),
    };
    let obj = f.object(&m.object)?;
    let Shape::Sphere { radius } = obj.shape else {
        return Err(format!("{:?} is not an analytic sphere", m.object));
    };
    let centre = obj.motion.uniform().ok_or("the marker moves")?.0.x;
    let to = centre - at;
    let theta = axis.angle_between(to);
    let alpha = (radius / to.length()).asin();
    let (expected, _) = seen_circle(theta, alpha, beta)
        .ok_or("the marker's outline holds the line of the camera's motion")?;
    let size = measuring.size(2 * effort.probe);
    let (img, _) = measuring.measuring_cropped(&[&m.object], size, effort.spp)?;
    let pinhole = rest_pinhole(measuring, size)?;
    let bg = measuring.fixture.spec.background;
    let dirs = outline(&img, &pinhole, |c| crate::observer::is_background(c, bg));
    let fit = SkyCircle::fit(&dirs).ok_or("cannot fit the marker's outline")?;
    // Each edge point is known to the area method's resolution (1/n pixel,
    // uniform: / sqrt 12); the centre of a circle through N of them to
    // sqrt(2 / N) of that; three sigma.
    let (cx, cy) = (f64::from(size.0) / 2.0, f64::from(size.1) / 2.0);
    let px = pinhole
        .rest_direction(cx, cy)
        .angle_between(pinhole.rest_direction(cx + 1.0, cy));
    let sigma = px / effort.strata() / 12f64.sqrt() * (2.0 / dirs.len() as f64).sqrt();
    let reading = Reading {
        value: axis.angle_between(fit.centre).to_degrees(),
        tolerance: 3.0 * sigma.to_degrees(),
    };
    Ok((
        (reading, expected.to_degrees(), Unit::Degrees),
        to.normalize(),
    ))
}

/// The measurements' pinhole of the fixture's camera at rest: lines of
/// sight in the camera's own frame.
pub(super) fn rest_pinhole(setup: &Observer, size: (u32, u32)) -> Result<Pinhole, String> {
    let c = &setup.fixture.spec.camera;
    let p = match c.look_at {
        Some(look_at) => Pinhole::looking_at(c.position, look_at, c.up, c.vfov_deg, size),
        None => Pinhole::yaw_pitch(
            c.position,
            (c.yaw_deg.unwrap_or(0.0), c.pitch_deg.unwrap_or(0.0)),
            c.vfov_deg,
            size,
        ),
    };
    p.ok_or_else(|| "degenerate camera".to_string())
}

/// The outline's edge points, scanned along every row and column from
/// both sides, as camera-frame directions.
fn outline(img: &RgbImage, pinhole: &Pinhole, outside: impl Fn(DVec3) -> bool) -> Vec<DVec3> {
    let (w, h) = (img.width(), img.height());
    let mut dirs = Vec::new();
    for horizontal in [true, false] {
        let (n, len) = if horizontal { (h, w) } else { (w, h) };
        for at in 0..n {
            let scan = Scan { horizontal, at };
            for (from, step) in [(0, 1), (i64::from(len) - 1, -1)] {
                if let Some(u) = edge(img, scan, from, step, &outside) {
                    let (px, py) = scan.point(u);
                    dirs.push(pinhole.rest_direction(px, py));
                }
            }
        }
    }
    dirs
}
