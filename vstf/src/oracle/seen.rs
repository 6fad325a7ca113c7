//! Where a point is seen: the emission event on the camera's past light cone.
//!
//! The central closed form: a point moving on the straight worldline
//! x(t) = x0 + v (t - t0) is seen by a camera at event (tc, c) where that
//! worldline meets the camera's past light cone, |x(t) - c| = tc - t, t <= tc.
//! With a = x0 - v t0 - c this is the quadratic
//! (v.v - 1) t^2 + 2 (a.v + tc) t + (a.a - tc^2) = 0. A point under
//! constant proper acceleration (a hyperbola) meets the cone where another
//! quadratic says ([`retarded_hyperbolic`]); a point moving straight between
//! keyframes meets it on one of its segments ([`retarded_polyline`]); one
//! with infinitely fast light is seen where it is at the camera's time
//! ([`instantaneous`]).

use super::kinematics::{contract, gamma};
use super::quadratic::quadratic_roots;
use glam::DVec3;

/// A point's straight worldline: at lab time `t0` it is at `x0`, moving with `v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointWorldline {
    /// Lab time at which the point is at `x0`.
    pub t0: f64,
    /// Lab position at `t0`.
    pub x0: DVec3,
    /// Lab velocity (fraction of c).
    pub v: DVec3,
}

impl PointWorldline {
    /// Lab position at lab time `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.x0 + self.v * (t - self.t0)
    }
}

/// Where a point is seen: the emission event on the camera's past light cone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Retarded {
    /// Lab time of emission.
    pub t: f64,
    /// Lab position at emission.
    pub x: DVec3,
    /// Unit direction from the camera to `x`.
    pub direction: DVec3,
}

/// The latest emission event of `p` on the past light cone of the camera at
/// (`tc`, `camera`) (for a subluminal point there is exactly one); `None` if
/// the worldline never meets it.
pub fn retarded(p: &PointWorldline, tc: f64, camera: DVec3) -> Option<Retarded> {
    let a = p.x0 - p.v * p.t0 - camera;
    let qa = p.v.length_squared() - 1.0;
    let qb = 2.0 * (a.dot(p.v) + tc);
    let qc = a.length_squared() - tc * tc;
    let times = quadratic_roots(qa, qb, qc, 1e-15).into_iter();
    latest(times, tc, |t| p.at(t), camera)
}

/// The latest of the candidate emission times not after the camera's `tc`
/// (within rounding), with where the point `at` is then, as seen from
/// `camera`; `None` without one.
fn latest(
    times: impl Iterator<Item = f64>,
    tc: f64,
    at: impl Fn(f64) -> DVec3,
    camera: DVec3,
) -> Option<Retarded> {
    let t = times
        .filter(|t| *t <= tc + 1e-12 * tc.abs().max(1.0))
        .fold(f64::NEG_INFINITY, f64::max);
    if !t.is_finite() {
        return None;
    }
    let x = at(t);
    Some(Retarded {
        t,
        x,
        direction: (x - camera).normalize(),
    })
}

/// The worldline of a body point with rest-frame offset `r` from a reference
/// point that is at `x0` at lab time `t0` and moves with `v`; contracted
/// when `lorentz` (a V_obj with the Lorentz transform on).
pub fn body_point(t0: f64, x0: DVec3, v: DVec3, r: DVec3, lorentz: bool) -> PointWorldline {
    let offset = if lorentz { contract(r, v) } else { r };
    PointWorldline {
        t0,
        x0: x0 + offset,
        v,
    }
}

/// Where a point would be seen with infinite light speed: its position at
/// the camera's time.
pub fn instantaneous(p: &PointWorldline, tc: f64, camera: DVec3) -> Retarded {
    let x = p.at(tc);
    Retarded {
        t: tc,
        x,
        direction: (x - camera).normalize(),
    }
}

/// A point under constant proper acceleration along the unit vector `n`:
/// the hyperbola S^2 - T^2 = A^2 about the centre event (`centre_t`,
/// `centre`), where S is the distance from `centre` along `n` and
/// T = t - centre_t. A = 1/a is its own proper acceleration's inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointHyperbola {
    /// Lab time of the hyperbola's centre event (the turning point's time).
    pub centre_t: f64,
    /// Lab position of the centre event.
    pub centre: DVec3,
    /// Unit direction of the acceleration.
    pub n: DVec3,
    /// A = 1 / a, the distance from the centre at the turning point.
    pub big_a: f64,
}

impl PointHyperbola {
    /// A point that starts at `x0` at lab time `t0` with velocity
    /// `v0` along `n` (|v0| < 1) and keeps the proper acceleration `a`.
    pub fn starting(t0: f64, x0: DVec3, n: DVec3, a: f64, v0: f64) -> PointHyperbola {
        let g0 = gamma(v0);
        // S = cosh(phi0)/a = gamma0/a and T = sinh(phi0)/a = gamma0 v0/a at the start.
        PointHyperbola {
            centre_t: t0 - g0 * v0 / a,
            centre: x0 - n * (g0 / a),
            n,
            big_a: 1.0 / a,
        }
    }

    /// Lab position at lab time `t`: S = sqrt(A^2 + T^2) along `n`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.centre + self.n * self.big_a.hypot(t - self.centre_t)
    }

    /// Lab velocity at lab time `t`: n T / sqrt(A^2 + T^2).
    pub fn velocity(&self, t: f64) -> DVec3 {
        let big_t = t - self.centre_t;
        self.n * (big_t / self.big_a.hypot(big_t))
    }
}

/// Where the camera at (`tc`, `camera`) sees a point under hyperbolic
/// motion: its worldline meets the past light cone where
/// (Tc - T)^2 = |D|^2 - 2 Dn S + S^2 with D = camera - centre, Dn = D.n and
/// Tc = tc - centre_t. With S^2 - T^2 = A^2 this is the straight line
/// 2 Dn S - 2 Tc T = |D|^2 + A^2 - Tc^2 =: K, which meets the hyperbola
/// S = A cosh(eta), T = A sinh(eta) where u = e^eta solves
/// A (Dn - Tc) u^2 - K u + A (Dn + Tc) = 0. The latest root with T <= Tc
/// is the one seen.
pub fn retarded_hyperbolic(p: &PointHyperbola, tc: f64, camera: DVec3) -> Option<Retarded> {
    let d = camera - p.centre;
    let (dn, big_tc, a) = (d.dot(p.n), tc - p.centre_t, p.big_a);
    let k = d.length_squared() + a * a - big_tc * big_tc;
    let (qa, qb, qc) = (a * (dn - big_tc), -k, a * (dn + big_tc));
    let times = quadratic_roots(qa, qb, qc, 1e-15 * (qb.abs() + qc.abs()))
        .into_iter()
        .filter(|u| *u > 0.0)
        .map(|u| p.centre_t + a * (u - 1.0 / u) / 2.0);
    latest(times, tc, |t| p.at(t), camera)
}

/// A point moving straight between positions at increasing lab times
/// (keyframes): its worldline is a polyline of events (t, x).
#[derive(Clone, Debug, PartialEq)]
pub struct PointPolyline {
    /// The keyframes, in increasing lab time.
    pub events: Vec<(f64, DVec3)>,
}

impl PointPolyline {
    /// The segment holding lab time `t` and the point's straight worldline on
    /// it; `None` outside the keyframes' span.
    pub fn segment_at(&self, t: f64) -> Option<(usize, PointWorldline)> {
        let k = self
            .events
            .windows(2)
            .position(|w| w[0].0 <= t && t <= w[1].0)?;
        Some((k, self.segment(k)))
    }

    /// The straight worldline through keyframes k and k + 1.
    pub fn segment(&self, k: usize) -> PointWorldline {
        let ((t0, x0), (t1, x1)) = (self.events[k], self.events[k + 1]);
        PointWorldline {
            t0,
            x0,
            v: (x1 - x0) / (t1 - t0),
        }
    }

    /// Lab position at lab time `t`, inside the keyframes' span.
    pub fn at(&self, t: f64) -> Option<DVec3> {
        self.segment_at(t).map(|(_, w)| w.at(t))
    }
}

/// Where the camera at (`tc`, `camera`) sees a point moving straight
/// between keyframes: on each segment the straight-worldline quadratic of
/// [`retarded`], kept where its root lies within the segment's times; the
/// latest such emission not after `tc` is seen (a subluminal polyline
/// meets the past light cone once).
pub fn retarded_polyline(p: &PointPolyline, tc: f64, camera: DVec3) -> Option<Retarded> {
    let slack = |t: f64| 1e-12 * t.abs().max(1.0);
    (0..p.events.len().saturating_sub(1))
        .rev()
        .filter_map(|k| {
            let (t0, t1) = (p.events[k].0, p.events[k + 1].0);
            retarded(&p.segment(k), tc, camera)
                .filter(|r| r.t >= t0 - slack(t0) && r.t <= t1 + slack(t1))
        })
        .max_by(|a, b| a.t.total_cmp(&b.t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;
    use approx::assert_relative_eq;

    #[test]
    fn static_point_is_seen_one_light_time_ago() {
        let p = PointWorldline {
            t0: 0.0,
            x0: DVec3::new(3.0, 4.0, 0.0),
            v: DVec3::ZERO,
        };
        let r = retarded(&p, 10.0, DVec3::ZERO).unwrap();
        assert_relative_eq!(r.t, 5.0, max_relative = 1e-14);
    }

    #[test]
    fn retarded_event_is_on_the_light_cone() {
        let p = PointWorldline {
            t0: 2.0,
            x0: DVec3::new(-5.0, 1.0, 2.0),
            v: DVec3::new(0.866, 0.1, -0.2),
        };
        let c = DVec3::new(0.0, 9.0, 15.0);
        let r = retarded(&p, 40.0, c).unwrap();
        assert_relative_eq!((r.x - c).length(), 40.0 - r.t, max_relative = 1e-12);
        assert!(r.t < 40.0);
    }
    /// The hyperbolic closed form against bisection on the light-cone
    /// condition, and the emission event lies on both the cone and the
    /// hyperbola.
    #[test]
    fn hyperbolic_retarded_solve_matches_bisection() {
        let p = PointHyperbola::starting(2.0, DVec3::new(-3.0, 1.0, 0.5), DVec3::X, 0.3, -0.4);
        let cam = DVec3::new(1.0, 2.0, 9.0);
        for tc in [5.0, 12.0, 30.0, 60.0] {
            let r = retarded_hyperbolic(&p, tc, cam).unwrap();
            let gap = |t: f64| (tc - t) - (p.at(t) - cam).length();
            assert!(gap(r.t).abs() < 1e-9, "on the cone: {}", gap(r.t));
            let (mut lo, mut hi) = (tc - 1e3, tc);
            for _ in 0..200 {
                let m = 0.5 * (lo + hi);
                if gap(m) > 0.0 {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            assert!((r.t - lo).abs() < 1e-9, "tc {tc}: {} vs {lo}", r.t);
        }
        // The start: at t0 the point is at x0 moving at v0.
        let v = (p.at(2.0 + 1e-6).x - p.at(2.0 - 1e-6).x) / 2e-6;
        assert_abs_diff_eq!(p.at(2.0).x, -3.0, epsilon = 1e-12);
        assert_abs_diff_eq!(v, -0.4, epsilon = 1e-8);
    }

    /// The polyline solve against bisection on a zig-zag path: the emission
    /// it finds lies on the past light cone and no later one does.
    #[test]
    fn a_polyline_is_seen_where_it_meets_the_past_light_cone() {
        let events: Vec<(f64, DVec3)> = (0..=20)
            .map(|k| {
                let t = -30.0 + 1.5 * f64::from(k);
                let wiggle = if k % 2 == 0 { 0.0 } else { 0.6 };
                (t, DVec3::new(0.5 * t, wiggle, -8.0))
            })
            .collect();
        let p = PointPolyline { events };
        let camera = DVec3::new(1.0, 0.5, 2.0);
        for tc in [-5.3, -3.0, 0.0, 4.2] {
            let r = retarded_polyline(&p, tc, camera).unwrap();
            assert_abs_diff_eq!((r.x - camera).length(), tc - r.t, epsilon = 1e-9);
            assert_abs_diff_eq!(r.x.distance(p.at(r.t).unwrap()), 0.0, epsilon = 1e-9);
            let cone = |t: f64| (p.at(t).unwrap() - camera).length() - (tc - t);
            // After the emission the point is outside the past light cone
            // (it grows at 1 + d|x - c|/dt > 0): no later emission.
            let mut t = r.t + 1e-6;
            while t < tc.min(0.0) {
                assert!(cone(t) > 0.0, "a later emission near t = {t}");
                t += 0.01;
            }
        }
        assert!(retarded_polyline(&p, -40.0, camera).is_none());
    }
}
