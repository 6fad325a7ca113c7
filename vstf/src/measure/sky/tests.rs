use super::*;
use crate::measure::{azimuth, elevation};
use glam::{DQuat, DVec2};
use std::f64::consts::{PI, TAU};

/// The unit direction at azimuth `az` and elevation `el` (degrees).
fn direction(az: f64, el: f64) -> DVec3 {
    let (az, el) = (az.to_radians(), el.to_radians());
    DVec3::new(el.cos() * az.sin(), el.sin(), -el.cos() * az.cos())
}

/// The points of the circle of centre `c` and angular radius `rho` at the
/// angles `phis` about it.
fn circle(c: DVec3, rho: f64, phis: impl Iterator<Item = f64>) -> Vec<DVec3> {
    let e1 = c.any_orthonormal_vector();
    let e2 = c.cross(e1);
    phis.map(|p| c * rho.cos() + (e1 * p.cos() + e2 * p.sin()) * rho.sin())
        .collect()
}

/// One circle sampled two ways: 720 points evenly spaced, and 150 crowded
/// towards one side (as a probe's rows and columns crowd where the outline
/// runs along them) on half the circle only.
fn two_samplings(c: DVec3, rho: f64) -> [Vec<DVec3>; 2] {
    [
        circle(c, rho, (0..720).map(|k| TAU * f64::from(k) / 720.0)),
        circle(
            c,
            rho,
            (0..150).map(|k| 0.3 + PI * (f64::from(k) / 150.0).powi(2)),
        ),
    ]
}

/// The circles tried: the `sphere-above` fixture's outline, a large one
/// and one near a great circle.
fn circles() -> [(DVec3, f64); 3] {
    [
        (direction(-10.837, 13.796), 5.473f64.to_radians()),
        (direction(30.0, -20.0), 40f64.to_radians()),
        (direction(150.0, 60.0), 85f64.to_radians()),
    ]
}

/// The readings the outline check takes off a circle, degrees.
fn readings(c: &SkyCircle) -> [f64; 4] {
    [
        azimuth(&c.centre),
        elevation(&c.centre),
        c.radius.to_degrees(),
        c.rms.to_degrees(),
    ]
}

#[test]
fn centre_radius_and_rms_do_not_depend_on_the_sampling() {
    for (c, rho) in circles() {
        let [a, b] = two_samplings(c, rho).map(|d| SkyCircle::fit(&d).unwrap());
        let truth = [azimuth(&c), elevation(&c), rho.to_degrees(), 0.0];
        for ((x, y), t) in readings(&a).into_iter().zip(readings(&b)).zip(truth) {
            assert!((x - y).abs() < 1e-9, "{x} against {y}");
            assert!((x - t).abs() < 1e-9, "{x} against the circle's {t}");
        }
    }
}

/// The fit this module replaced: the points projected stereographically
/// about their mean, a circle fitted in the plane and its centre projected
/// back.
fn stereographic_centre(dirs: &[DVec3]) -> DVec3 {
    let m = dirs.iter().fold(DVec3::ZERO, |a, d| a + *d).normalize();
    let e1 = m.any_orthonormal_vector();
    let e2 = m.cross(e1);
    let (mut ata, mut atb) = (DMat3::ZERO, DVec3::ZERO);
    for d in dirs {
        let p = DVec2::new(d.dot(e1), d.dot(e2)) * (2.0 / (1.0 + d.dot(m)));
        let row = DVec3::new(p.x, p.y, 1.0);
        ata += DMat3::from_cols(row * row.x, row * row.y, row * row.z);
        atb += row * -p.length_squared();
    }
    let sol = ata.inverse() * atb;
    let p = DVec2::new(-sol.x, -sol.y) / 2.0;
    let r2 = p.length_squared() / 4.0;
    ((e1 * p.x + e2 * p.y + m * (1.0 - r2)) / (1.0 + r2)).normalize()
}

#[test]
fn a_stereographic_centre_moves_with_the_sampling() {
    let (c, rho) = circles()[0];
    let [a, b] = two_samplings(c, rho).map(|d| stereographic_centre(&d));
    let moved = (azimuth(&a) - azimuth(&b)).abs();
    assert!(moved > 1e-3, "moved by {moved} degrees");
}

#[test]
fn another_circle_is_told_apart_at_1e_9() {
    let (c, rho) = circles()[0];
    let turned = DQuat::from_axis_angle(c.any_orthonormal_vector(), 1e-9) * c;
    let fit = |c| SkyCircle::fit(&two_samplings(c, rho)[0]).unwrap();
    assert!(fit(c).centre.cross(fit(turned).centre).length() > 0.5e-9);
    let wider = SkyCircle::fit(&two_samplings(c, rho + 1e-9)[0]).unwrap();
    assert!(wider.radius - fit(c).radius > 0.5e-9);
}

#[test]
fn rotating_the_points_rotates_the_fit() {
    let (c, rho) = circles()[1];
    let q = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 2.0);
    let dirs = &two_samplings(c, rho)[1];
    let turned: Vec<DVec3> = dirs.iter().map(|d| q * *d).collect();
    let (a, b) = (
        SkyCircle::fit(dirs).unwrap(),
        SkyCircle::fit(&turned).unwrap(),
    );
    assert!((q * a.centre).distance(b.centre) < 1e-12);
    assert!((a.radius - b.radius).abs() < 1e-12);
}

#[test]
fn the_rms_is_the_angular_scatter_off_the_circle() {
    let (c, rho) = circles()[0];
    let delta = 1e-3;
    let dirs: Vec<DVec3> = (0..720)
        .map(|k| {
            let side = if k % 2 == 0 { delta } else { -delta };
            circle(c, rho + side, std::iter::once(TAU * f64::from(k) / 720.0))[0]
        })
        .collect();
    let fit = SkyCircle::fit(&dirs).unwrap();
    assert!((fit.rms - delta).abs() < 1e-3 * delta, "{}", fit.rms);
    assert!(fit.centre.cross(c).length() < 1e-12);
    assert!((fit.off(c) + fit.radius).abs() < 1e-12);
    // The fitted radius is acos(cos(rho) cos(delta)), delta^2 / (2 tan rho) = 5e-6 wider.
    assert!((fit.off(dirs[0]) - delta).abs() < 1e-5 && (fit.off(dirs[1]) + delta).abs() < 1e-5);
}

#[test]
fn too_few_distinct_directions_fix_no_circle() {
    let (a, b) = (direction(0.0, 0.0), direction(10.0, 5.0));
    assert!(SkyCircle::fit(&[a, b]).is_none());
    assert!(SkyCircle::fit(&[a, b, a, b]).is_none());
    assert!(SkyCircle::fit(&[a, b, direction(-3.0, 4.0)]).is_some());
}

#[test]
fn jacobi_rotations_find_the_eigenvectors() {
    let m = DMat3::from_cols(
        DVec3::new(4.0, 1.0, -2.0),
        DVec3::new(1.0, 3.0, 0.5),
        DVec3::new(-2.0, 0.5, 1e-9),
    );
    let (values, vectors) = symmetric_eigen(m);
    for (l, v) in values.into_iter().zip(vectors) {
        assert!((v.length() - 1.0).abs() < 1e-14);
        assert!((m * v - v * l).length() < 1e-13, "{l} {v}");
    }
    let trace = m.col(0).x + m.col(1).y + m.col(2).z;
    assert!((values.iter().sum::<f64>() - trace).abs() < 1e-13);
}
