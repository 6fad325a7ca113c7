//! Light in the field of a mass M at rest (Schwarzschild), from the
//! conserved quantities of a null geodesic, by quadrature of the orbit:
//! with u = 1/r and impact parameter b = L / E, (du/dphi)^2 = G(u) =
//! 1/b^2 - u^2 (1 - 2 M u), so the polar angle swept between two radii is
//! the integral of du / sqrt(G(u)) (docs/physics.md, "Light bent by a
//! mass"). Nothing here integrates the orbit's differential equation, as
//! the ray tracer does: the angles are quadratures of the closed form.

use std::f64::consts::PI;

/// Gauss-Legendre nodes and weights on [-1, 1], 8 points.
const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// Panels of the composite quadrature.
const PANELS: usize = 256;

/// The angular radius of the shadow seen by an observer at rest at radius
/// r > 3M: sin(alpha) = 3 sqrt(3) M / r * sqrt(1 - 2M/r) (the edge is light
/// with the critical impact parameter b_c = 3 sqrt(3) M, seen from a frame
/// whose radial lengths are dr / sqrt(1 - 2M/r)).
pub fn shadow_radius(m: f64, r: f64) -> f64 {
    (3.0 * 3f64.sqrt() * m / r * (1.0 - 2.0 * m / r).sqrt()).asin()
}

/// nu_o / nu_e for light from an emitter at rest at radius `r_e` to an
/// observer at rest at radius `r_o`: sqrt((1 - 2M/r_e) / (1 - 2M/r_o)).
/// The metric's g_tt = -(1 - 2M/r) does not depend on t, so E = -k.(d/dt)
/// is conserved along the light's geodesic, whatever its path; a static
/// observer's 4-velocity is u = (d/dt) / sqrt(1 - 2M/r), and the frequency
/// it measures is -k.u = E / sqrt(1 - 2M/r).
pub fn static_redshift(m: f64, r_e: f64, r_o: f64) -> f64 {
    ((1.0 - 2.0 * m / r_e) / (1.0 - 2.0 * m / r_o)).sqrt()
}

/// The same ratio with the Newtonian potential's clock rates, 1 - M/r
/// (the weak-field limit of sqrt(1 - 2M/r)): (1 - M/r_e) / (1 - M/r_o).
/// Near the mass it differs from [`static_redshift`] at second order in
/// M/r, enough to tell the two apart from the colour at r = 4M.
pub fn newtonian_redshift(m: f64, r_e: f64, r_o: f64) -> f64 {
    (1.0 - m / r_e) / (1.0 - m / r_o)
}

/// The impact parameter of light reaching an observer at rest at radius r
/// at angle `theta` from the direction of the centre:
/// b = r sin(theta) / sqrt(1 - 2M/r).
pub fn impact_parameter(m: f64, r: f64, theta: f64) -> f64 {
    r * theta.sin() / (1.0 - 2.0 * m / r).sqrt()
}

/// The angle from the centre's direction at which an observer at rest at
/// radius r sees light of impact parameter b (inverse of [`impact_parameter`]).
pub fn seen_angle(m: f64, r: f64, b: f64) -> f64 {
    (b * (1.0 - 2.0 * m / r).sqrt() / r).asin()
}

/// G(u) = 1/b^2 - u^2 + 2 M u^3.
fn g(m: f64, b: f64, u: f64) -> f64 {
    1.0 / (b * b) - u * u + 2.0 * m * u * u * u
}

/// u0 = 1 / r0 of the turning point of light with impact parameter b
/// above b_c: the root of G below 1/(3M), where u^2 (1 - 2Mu) increases.
pub fn turning_point(m: f64, b: f64) -> Option<f64> {
    let top = if m > 0.0 { 1.0 / (3.0 * m) } else { 2.0 / b };
    if g(m, b, top) >= 0.0 {
        return None;
    }
    bisect((0.0, top), 200, Slope::Falling, |u| Some(g(m, b, u)))
}

/// Where `f` changes sign in (lo, hi), rising (from negative to positive)
/// or falling as `Slope` says, after `steps` halvings: the middle of the
/// last interval; `None` when `f` cannot be evaluated on the way.
fn bisect(
    (mut lo, mut hi): (f64, f64),
    steps: u32,
    slope: Slope,
    f: impl Fn(f64) -> Option<f64>,
) -> Option<f64> {
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        if (f(mid)? > 0.0) == (slope == Slope::Rising) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// Which way a function crosses zero at the root [`bisect`] looks for.
#[derive(Clone, Copy, PartialEq)]
enum Slope {
    Rising,
    Falling,
}

/// The polar angle swept between u and the turning point u0: the integral
/// of du / sqrt(G(u)) from u to u0, with u = u0 - s^2 taking the inverse
/// square root at u0 away (composite 8-point Gauss-Legendre in s).
pub fn swept(m: f64, b: f64, u: f64, u0: f64) -> f64 {
    let top = (u0 - u).max(0.0).sqrt();
    let h = top / PANELS as f64;
    let mut sum = 0.0;
    for k in 0..PANELS {
        let mid = (k as f64 + 0.5) * h;
        for (x, w) in GL8 {
            let s = mid + 0.5 * h * x;
            let gu = g(m, b, u0 - s * s).max(0.0);
            sum += w * 0.5 * h * 2.0 * s / gu.sqrt();
        }
    }
    sum
}

/// The coordinate time light of impact parameter b takes between radius r
/// and its turning point r0: along the orbit dt = dr / (f sqrt(1 - b^2 f /
/// r^2)) (from E = f dt/dlambda, L = r^2 dphi/dlambda and the null
/// condition, f = 1 - 2M/r), integrated in r (smooth out to large r, where
/// the integrand tends to 1) with r = r0 + s^2 taking the inverse square
/// root at r0 away, by the rule of [`swept`].
pub fn elapsed(m: f64, b: f64, r: f64, r0: f64) -> f64 {
    let top = (r - r0).max(0.0).sqrt();
    let h = top / PANELS as f64;
    let mut sum = 0.0;
    for k in 0..PANELS {
        let mid = (k as f64 + 0.5) * h;
        for (x, w) in GL8 {
            let s = mid + 0.5 * h * x;
            let rr = r0 + s * s;
            let f = 1.0 - 2.0 * m / rr;
            let q = (1.0 - b * b * f / (rr * rr)).max(0.0);
            sum += w * 0.5 * h * 2.0 * s / (f * q.sqrt());
        }
    }
    sum
}

/// The coordinate time light of impact parameter b takes from radius r1
/// through its turning point out to radius r2 (both beyond it): the
/// Shapiro-delayed light time. With M = 0 it is the straight line's
/// sqrt(r1^2 - b^2) + sqrt(r2^2 - b^2).
pub fn light_time(m: f64, b: f64, r1: f64, r2: f64) -> Option<f64> {
    let u0 = turning_point(m, b)?;
    (1.0 / r1 <= u0 && 1.0 / r2 <= u0)
        .then(|| elapsed(m, b, r1, 1.0 / u0) + elapsed(m, b, r2, 1.0 / u0))
}

/// The impact parameter of the light from a point at radius `r2` that
/// reaches radius `r1` having swept the angle `psi` (< pi) about the
/// centre, passing it once on the near side (the primary image): the b
/// above b_c at which [`swept_between`] is `psi`.
pub fn impact_sweeping(m: f64, r1: f64, r2: f64, psi: f64) -> Option<f64> {
    let bc = 3.0 * 3f64.sqrt() * m;
    let (lo, hi) = (bc * (1.0 + 1e-9), r1.min(r2) * (1.0 - 1e-12));
    let over = |b: f64| swept_between(m, b, r1, r2).map(|a| a - psi);
    if !(over(lo)? > 0.0 && over(hi)? < 0.0) {
        return None;
    }
    bisect((lo, hi), 100, Slope::Falling, over)
}

/// The exact deflection of light of impact parameter b from infinity to
/// infinity: 2 * swept(0, u0) - pi.
pub fn deflection(m: f64, b: f64) -> Option<f64> {
    Some(2.0 * swept(m, b, 0.0, turning_point(m, b)?) - PI)
}

/// The weak-field series of the deflection to second order in M / b:
/// 4 M/b + 15 pi / 4 (M/b)^2.
pub fn deflection_series(m: f64, b: f64) -> f64 {
    let q = m / b;
    4.0 * q + 15.0 * PI / 4.0 * q * q
}

/// The polar angle light of impact parameter b sweeps from radius r1
/// through its turning point out to radius r2 (both beyond it).
pub fn swept_between(m: f64, b: f64, r1: f64, r2: f64) -> Option<f64> {
    let u0 = turning_point(m, b)?;
    (1.0 / r1 <= u0 && 1.0 / r2 <= u0)
        .then(|| swept(m, b, 1.0 / r1, u0) + swept(m, b, 1.0 / r2, u0))
}

/// The same angle along a straight line (M = 0) of impact parameter b:
/// pi - asin(b / r1) - asin(b / r2).
pub fn swept_straight(b: f64, r1: f64, r2: f64) -> f64 {
    PI - (b / r1).asin() - (b / r2).asin()
}

/// Where light seen at impact parameter b by an observer on an axis at
/// radius `r_obs` crosses the plane perpendicular to that axis at distance
/// `d` behind the centre, after passing its turning point: the signed
/// distance from the axis, positive on the side the light passed the
/// centre. `None` when the light is captured or turns before the plane.
pub fn plane_crossing(m: f64, b: f64, r_obs: f64, d: f64) -> Option<f64> {
    let u0 = turning_point(m, b)?;
    let first = swept(m, b, 1.0 / r_obs, u0);
    // On the way out, phi(u) = first + swept(u, u0); the plane is where
    // r cos(phi) = -d, between the turning point and infinity.
    let z = |u: f64| (first + swept(m, b, u, u0)).cos() / u + d;
    let (lo, hi) = (1e-12 * u0, u0);
    if z(hi) < 0.0 || z(lo) > 0.0 {
        return None;
    }
    let u = bisect((lo, hi), 60, Slope::Rising, |u| Some(z(u)))?;
    Some((first + swept(m, b, u, u0)).sin() / u)
}

/// The impact parameter of the light, seen from radius `r_obs` on the
/// axis, that crosses the plane at distance `d` behind the centre at the
/// signed distance `x` from the axis (the edge of a disc of radius |x|
/// centred on the axis: +x its outer image, -x its inner one), between b_c
/// and the observer's horizon of view.
pub fn impact_reaching(m: f64, r_obs: f64, d: f64, x: f64) -> Option<f64> {
    let bc = 3.0 * 3f64.sqrt() * m;
    let (lo, hi) = (
        bc * (1.0 + 1e-6),
        r_obs / (1.0 - 2.0 * m / r_obs).sqrt() * 0.999,
    );
    let at = |b: f64| plane_crossing(m, b, r_obs, d).map(|c| c - x);
    if !(at(lo)? < 0.0 && at(hi)? > 0.0) {
        return None;
    }
    bisect((lo, hi), 60, Slope::Rising, at)
}

/// The angle from the centre at which an observer at rest at radius r sees
/// the primary image of a star at infinity `beta` from the direction of the
/// centre (0 < beta < pi): light of impact parameter b arriving from the
/// star sweeps the polar angle phi(b) = swept_between(b, r, infinity), so
/// it comes from beta = pi - phi(b), which grows with b from minus
/// infinity at b_c, through 0 at the Einstein ring, towards pi; bisection
/// in b between b_c and the observer's horizon of view.
pub fn star_image(m: f64, r: f64, beta: f64) -> Option<f64> {
    let bc = 3.0 * 3f64.sqrt() * m;
    let (lo, hi) = (
        (bc * (1.0 + 1e-9)).max(1e-9 * r),
        r / (1.0 - 2.0 * m / r).sqrt() * 0.999_999,
    );
    let at = |b: f64| swept_between(m, b, r, f64::INFINITY).map(|phi| PI - phi - beta);
    if !(at(lo)? < 0.0 && at(hi)? > 0.0) {
        return None;
    }
    Some(seen_angle(m, r, bisect((lo, hi), 80, Slope::Rising, at)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Flat space gives the straight line's time; far out the light time is
    /// Weinberg's first-order d1 + d2 + 2M ln((r1 + d1)(r2 + d2) / r0^2) +
    /// M (sqrt((r1 - r0)/(r1 + r0)) + sqrt((r2 - r0)/(r2 + r0))),
    /// d = sqrt(r^2 - r0^2), r0 the turning point, and what is left is of
    /// the second order: it is quartered when M is halved (b held).
    #[test]
    fn the_light_time_is_the_straight_one_plus_shapiros_delay() {
        let (b, r1, r2): (f64, f64, f64) = (1e4, 1e6, 3e5);
        let flat = light_time(0.0, b, r1, r2).unwrap();
        let straight = (r1 * r1 - b * b).sqrt() + (r2 * r2 - b * b).sqrt();
        assert!((flat - straight).abs() < 1e-9 * straight, "{flat}");
        let left = |m: f64| {
            let r0 = 1.0 / turning_point(m, b).unwrap();
            let (d1, d2) = ((r1 * r1 - r0 * r0).sqrt(), (r2 * r2 - r0 * r0).sqrt());
            let first = d1
                + d2
                + 2.0 * m * ((r1 + d1) * (r2 + d2) / (r0 * r0)).ln()
                + m * (((r1 - r0) / (r1 + r0)).sqrt() + ((r2 - r0) / (r2 + r0)).sqrt());
            light_time(m, b, r1, r2).unwrap() - first
        };
        let (whole, half) = (left(1.0), left(0.5));
        assert!(whole.abs() < 0.01, "{whole}");
        assert!((whole / half - 4.0).abs() < 0.1, "{whole} {half}");
        let m = 1.0;
        assert!(light_time(m, b, r1, r2).unwrap() - straight > 20.0);
        let psi = swept_between(m, b, r1, r2).unwrap();
        let back = impact_sweeping(m, r1, r2, psi).unwrap();
        assert!((back - b).abs() < 1e-6 * b, "{back}");
    }

    #[test]
    fn the_quadrature_meets_the_weak_field_series() {
        // Far out the exact deflection is the series plus 128/3 (M/b)^3.
        let (m, b) = (1.0, 1000.0);
        let exact = deflection(m, b).unwrap();
        let q: f64 = m / b;
        let third = 128.0 / 3.0 * q * q * q;
        assert!(
            (exact - deflection_series(m, b) - third).abs() < 2e-9,
            "{exact}"
        );
        // A wrong coefficient of the second-order term (pi 15/16) is refused.
        assert!((exact - 4.0 * q - 15.0 * PI / 16.0 * q * q).abs() > 1e-6);
    }

    #[test]
    fn light_just_outside_the_critical_impact_parameter_circles_many_times() {
        let bc = 3.0 * 3f64.sqrt();
        assert!(turning_point(1.0, bc * 0.999).is_none());
        let near = deflection(1.0, bc * 1.0001).unwrap();
        assert!(near > 2.0 * PI, "{near}");
    }

    #[test]
    fn flat_space_crosses_the_plane_on_a_straight_line() {
        let (b, r, d): (f64, f64, f64) = (2.0, 10.0, 30.0);
        // The straight line at distance b from the centre, from (0, r): its
        // direction makes angle asin(b / r) with the axis.
        let t = (b / r).asin().tan();
        let x = plane_crossing(0.0, b, r, d).unwrap();
        assert!((x - t * (r + d)).abs() < 1e-9, "{x}");
    }

    #[test]
    fn the_einstein_ring_approaches_the_weak_field_angle() {
        // The thin lens with the series to second order:
        // theta^2 = theta_E^2 (1 + 15 pi / 16 M / b), theta_E^2 = 4 M D_ls / (D_l D_s).
        let (m, dl, dls) = (1.0, 1e5, 1e5);
        let b = impact_reaching(m, dl, dls, 0.0).unwrap();
        let theta = seen_angle(m, dl, b);
        let weak = (4.0 * m * dls / (dl * (dl + dls))).sqrt();
        let second = weak * (1.0 + 15.0 * PI / 32.0 * m / (dl * weak));
        assert!((theta / second - 1.0).abs() < 3e-5, "{theta} vs {second}");
        assert!((theta / weak - 1.0).abs() > 3e-3);
    }

    #[test]
    fn a_far_star_is_seen_where_the_thin_lens_puts_it() {
        // Source at infinity, observer at D: theta = (beta + sqrt(beta^2 +
        // 4 theta_E^2)) / 2, theta_E^2 = 4M / D, to first order.
        let (m, r, beta): (f64, f64, f64) = (1.0, 1e6, 3e-3);
        let theta = star_image(m, r, beta).unwrap();
        let thin = 0.5 * (beta + (beta * beta + 16.0 * m / r).sqrt());
        assert!((theta / thin - 1.0).abs() < 1e-3, "{theta} vs {thin}");
        // Without the mass, the star is where it is (the control).
        let flat = star_image(0.0, 30.0, 0.3).unwrap();
        assert!((flat - 0.3).abs() < 1e-9, "{flat}");
        assert!((theta - beta).abs() > 1e-3);
    }

    #[test]
    fn the_shadow_is_the_critical_impact_parameter_seen() {
        let (m, r) = (1.0, 30.0);
        let bc = 3.0 * 3f64.sqrt() * m;
        assert!((shadow_radius(m, r) - seen_angle(m, r, bc)).abs() < 1e-15);
    }
}
