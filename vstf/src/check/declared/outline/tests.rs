use super::*;
use glam::DQuat;

/// The `sphere-above` fixture's scene: a sphere of radius 1 at 0.95c from
/// (-30, 2.5, 0) at t = 0, seen from (0, 0, 10) at t = 40.
fn scene() -> (Event, DVec3, f64, Event) {
    (
        Event::new(0.0, DVec3::new(-30.0, 2.5, 0.0)),
        DVec3::new(0.95, 0.0, 0.0),
        1.0,
        Event::new(40.0, DVec3::new(0.0, 0.0, 10.0)),
    )
}

/// Every reading the expected outline gives, degrees (and the ratio): the
/// three extents, then the four of the fitted circle.
fn readings(e: &Expected) -> [f64; 7] {
    [
        e.width,
        e.height,
        e.height / e.width,
        e.circle.radius.to_degrees(),
        e.circle.rms.to_degrees(),
        azimuth(&e.circle.centre),
        elevation(&e.circle.centre),
    ]
}

/// One curve sampled two ways: 720 parameters evenly spaced, and 150
/// crowded towards the start.
fn two_samplings(curve: &Curve) -> [Expected; 2] {
    let even: Vec<f64> = (0..720).map(|k| f64::from(k) / 720.0).collect();
    let crowded: Vec<f64> = (0..150)
        .map(|k| 0.01 + 0.98 * (f64::from(k) / 150.0).powi(2))
        .collect();
    [even, crowded].map(|at| Expected::of(curve, &at).unwrap())
}

#[test]
fn every_expected_reading_of_a_circle_is_the_curves_own() {
    let (start, u, radius, cam) = scene();
    let curve = expected_relativistic(start, u, radius, cam).unwrap();
    let [a, b] = two_samplings(&curve);
    for (x, y) in readings(&a).into_iter().zip(readings(&b)) {
        assert!((x - y).abs() < 1e-9, "{x} against {y}");
    }
    // Aberration along u keeps the plane of u and the cone's axis, so the
    // cone's two rays in that plane bound a diameter of the image circle.
    let rest = to_frame_of(start.t - cam.t, start.x - cam.x, u).unwrap().1;
    let (c, half) = (rest.normalize(), (radius / rest.length()).asin());
    let e = (u - c * c.dot(u)).normalize();
    let [p, q] = [1.0, -1.0].map(|k| aberrate_lorentz(c * half.cos() + e * (k * half.sin()), -u));
    let diameter_mid = (p + q).normalize();
    assert!(a.circle.centre.cross(diameter_mid).length() < 1e-11);
    assert!((a.circle.radius - p.cross(q).length().atan2(p.dot(q)) / 2.0).abs() < 1e-11);
    // The stereographic fit's centre expected -10.83701 degrees; the circle's own is 7e-4 left of it.
    assert!((azimuth(&a.circle.centre) + 10.837710).abs() < 1e-6);
    // A circle's extents in closed form: sin(half width) = sin(rho) / cos(elevation of its centre).
    let (rho, el) = (a.circle.radius, elevation(&a.circle.centre).to_radians());
    assert!((a.height - 2.0 * rho.to_degrees()).abs() < 1e-9);
    assert!((a.width - 2.0 * (rho.sin() / el.cos()).asin().to_degrees()).abs() < 1e-9);
    // The best of the 720 samples alone falls short of the extreme.
    assert!(a.width - span(&a.dirs, azimuth) > 1e-9);
}

#[test]
fn every_expected_reading_of_a_decoupled_outline_is_the_curves_own() {
    let (start, u, radius, cam) = scene();
    let curve = expected_classical(start.x, start.t, u, radius, cam);
    let [a, b] = two_samplings(&curve);
    let ([extents_a @ .., _, _, _, _], [extents_b @ .., _, _, _, _]) = (readings(&a), readings(&b));
    for (x, y) in extents_a.into_iter().zip(extents_b) {
        assert!((x - y).abs() < 1e-9, "{x} against {y}");
    }
    assert!(a.width - span(&a.dirs, azimuth) > 1e-9);
    // No circle: a circle fitted to it moves with the sampling, and is not read.
    assert!(a.circle.rms.to_degrees() > 0.01);
    assert!((a.circle.radius - b.circle.radius).to_degrees().abs() > 1e-3);
}

#[test]
fn the_measured_circle_is_read_in_degrees_beside_the_expected() {
    let (start, u, radius, cam) = scene();
    let curve = expected_relativistic(start, u, radius, cam).unwrap();
    let [a, _] = two_samplings(&curve);
    let mut off = a.circle;
    off.centre = DQuat::from_rotation_y(1e-4) * off.centre;
    let rows = circle(&off, &a.circle, (0.01, 1.0), 100.0);
    let (_, moved, expected) = rows[2];
    assert_eq!(rows[2].0, OutlineRead::CentreAzimuth);
    assert!(((moved.value - expected).abs() - 1e-4f64.to_degrees()).abs() < 1e-9);
    assert!(
        (moved.value - expected).abs() > moved.tolerance,
        "a wrong axis fails"
    );
}
