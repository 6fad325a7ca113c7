//! The accelerated observer (docs/physics.md, "The accelerated observer"):
//! a camera under constant proper acceleration a along a line, what it sees
//! of static markers (relativistic aberration at its rapidity), and the
//! Rindler horizon behind it.
//!
//! Written from first principles, independently of the ray tracer's
//! `Hyperbolic`: proper acceleration integrates to rapidity, phi = phi0 +
//! a tau; then dt/dtau = cosh(phi) and dx/dtau = sinh(phi).

use glam::DVec3;

/// A camera's hyperbolic worldline: from the event (t0, x0), where its
/// proper time is 0 and its speed `initial_velocity` along `direction`.
#[derive(Clone, Copy, Debug)]
pub struct RocketWorldline {
    /// Lab time of the start.
    pub t0: f64,
    /// Lab position at the start.
    pub x0: DVec3,
    /// Unit direction of the acceleration.
    pub direction: DVec3,
    /// Proper acceleration, 1/l.units.
    pub acceleration: f64,
    /// Signed lab speed along `direction` at the start.
    pub initial_velocity: f64,
}

impl RocketWorldline {
    fn phi0(&self) -> f64 {
        self.initial_velocity.atanh()
    }

    /// Rapidity at proper time `tau`: phi0 + a tau.
    pub fn rapidity(&self, tau: f64) -> f64 {
        self.phi0() + self.acceleration * tau
    }

    /// Lab time at proper time `tau`: t0 + (sinh(phi) - sinh(phi0)) / a.
    pub fn lab_time(&self, tau: f64) -> f64 {
        self.t0 + (self.rapidity(tau).sinh() - self.phi0().sinh()) / self.acceleration
    }

    /// Proper time at lab time `t` (the inverse of [`Self::lab_time`]).
    pub fn proper_time(&self, t: f64) -> f64 {
        let s = self.acceleration * (t - self.t0) + self.phi0().sinh();
        (s.asinh() - self.phi0()) / self.acceleration
    }

    /// Lab position at proper time `tau`: x0 + (cosh(phi) - cosh(phi0)) / a
    /// along the direction.
    pub fn position(&self, tau: f64) -> DVec3 {
        self.x0
            + self.direction
                * ((self.rapidity(tau).cosh() - self.phi0().cosh()) / self.acceleration)
    }

    /// Lab velocity at proper time `tau`: tanh(phi) along the direction.
    pub fn velocity(&self, tau: f64) -> DVec3 {
        self.direction * self.rapidity(tau).tanh()
    }
}

/// The angle from the observer's velocity at which it sees light arriving
/// from lab angle `theta` (radians, between the velocity and the direction
/// towards the source), moving at speed `beta`: relativistic aberration,
/// cos(theta') = (cos(theta) + beta) / (1 + beta cos(theta)).
pub fn aberrated_angle(theta: f64, beta: f64) -> f64 {
    let c = theta.cos();
    ((c + beta) / (1.0 + beta * c)).clamp(-1.0, 1.0).acos()
}

/// The same under Galilean addition (the classical model): the light seems
/// to come from n + v, tan(theta') = sin(theta) / (cos(theta) + beta).
pub fn aberrated_angle_galilean(theta: f64, beta: f64) -> f64 {
    theta.sin().atan2(theta.cos() + beta)
}

/// Where a sphere is seen by an observer moving at `beta`: the centre and
/// angular radius (radians, from the velocity) of its outline, a circle
/// in the observer's frame too (aberration maps circles on the sky to
/// circles). Its lab outline is the cone of half-angle alpha =
/// asin(R / distance) about lab angle `theta` from the velocity; by the
/// symmetry about the plane of the velocity and the centre, the diameter
/// in that plane, theta -+ alpha, maps to the seen circle's diameter.
/// `None` if the cone holds the velocity's line (theta < alpha or
/// theta > pi - alpha).
pub fn seen_circle(theta: f64, alpha: f64, beta: f64) -> Option<(f64, f64)> {
    if !(theta > alpha && theta + alpha < std::f64::consts::PI) {
        return None;
    }
    let (near, far) = (
        aberrated_angle(theta - alpha, beta),
        aberrated_angle(theta + alpha, beta),
    );
    Some(((near + far) / 2.0, (far - near) / 2.0))
}

/// The Rindler horizon. A camera starts from rest at lab time 0 with proper
/// acceleration `a`; a static point lies `behind` its start against the
/// acceleration and `aside` of its line. Light the point sends from lab
/// time 0 on first reaches the camera at the lab time returned; `None` if
/// it never does (behind >= 1/a: beyond the horizon). With u = 1/a + z(t) =
/// sqrt(1/a^2 + t^2) the camera's distance from the hyperbola's centre and
/// D = behind - 1/a, the light cone t^2 = aside^2 + (u + D)^2 and u^2 - t^2
/// = 1/a^2 give u = -(aside^2 + D^2 + 1/a^2) / (2 D), so t = sqrt(u^2 -
/// 1/a^2), real exactly when D < 0. The same time is when a point that
/// vanished at lab time 0 is last seen.
pub fn first_seen(a: f64, behind: f64, aside: f64) -> Option<f64> {
    let r = 1.0 / a;
    let d = behind - r;
    if d >= 0.0 {
        return None;
    }
    let u = -(aside * aside + d * d + r * r) / (2.0 * d);
    Some((u * u - r * r).max(0.0).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn the_worldline_is_the_hyperbola_and_its_clock_the_proper_time() {
        let w = RocketWorldline {
            t0: 2.0,
            x0: DVec3::new(1.0, 0.0, 0.0),
            direction: DVec3::NEG_Z,
            acceleration: 0.2,
            initial_velocity: 0.3,
        };
        for tau in [0.0, 1.0, 5.0, 12.0] {
            let (t, x) = (w.lab_time(tau), w.position(tau));
            // On the hyperbola about its centre: S^2 - T^2 = 1/a^2.
            let c = w.x0 - w.direction * (w.phi0().cosh() / w.acceleration);
            let big_t = t - w.t0 + w.phi0().sinh() / w.acceleration;
            let s = (x - c).length();
            assert_abs_diff_eq!(s * s - big_t * big_t, 25.0, epsilon = 1e-9);
            assert_abs_diff_eq!(w.proper_time(t), tau, epsilon = 1e-12);
            // Its velocity is dx/dt.
            let h = 1e-6;
            let v = (w.position(tau + h) - w.position(tau - h))
                / (w.lab_time(tau + h) - w.lab_time(tau - h));
            assert_abs_diff_eq!((v - w.velocity(tau)).length(), 0.0, epsilon = 1e-8);
        }
    }

    #[test]
    fn aberration_crowds_the_sky_forward_and_galilean_addition_less() {
        let theta = 100f64.to_radians();
        let rel = aberrated_angle(theta, 0.6);
        let gal = aberrated_angle_galilean(theta, 0.6);
        assert!(rel < gal && gal < theta, "{rel} {gal}");
        // Ahead and behind stay put; at rest nothing moves.
        assert_abs_diff_eq!(aberrated_angle(0.0, 0.9), 0.0);
        assert_abs_diff_eq!(
            aberrated_angle(std::f64::consts::PI, 0.9),
            std::f64::consts::PI
        );
        assert_abs_diff_eq!(aberrated_angle(theta, 0.0), theta, epsilon = 1e-15);
        // The same as the boosted photon's direction (kinematics.rs).
        let n = DVec3::new(theta.sin(), 0.0, theta.cos());
        let seen = super::super::aberrate_lorentz(n, DVec3::new(0.0, 0.0, 0.6));
        assert_abs_diff_eq!(seen.z.acos(), rel, epsilon = 1e-12);
    }

    #[test]
    fn a_point_inside_the_horizon_is_seen_at_the_closed_form_time_and_one_beyond_never() {
        let a = 0.1;
        let z = |t: f64| (1.0 / (a * a) + t * t).sqrt() - 1.0 / a;
        for (behind, aside) in [(6.0, 0.0), (6.0, 1.5), (2.0, 3.0), (9.9, 0.2)] {
            let t = first_seen(a, behind, aside).expect("inside the horizon");
            // On the light cone of the event (0, point).
            let dist = (aside * aside + (z(t) + behind).powi(2)).sqrt();
            assert_abs_diff_eq!(t, dist, epsilon = 1e-9 * t.max(1.0));
        }
        // Beyond: the light from t = 0 on never catches up with the camera.
        for behind in [10.0, 12.0] {
            assert_eq!(first_seen(a, behind, 0.5), None);
            for t in [1.0, 100.0, 1e4, 1e7] {
                assert!(t < (0.25 + (z(t) + behind).powi(2)).sqrt(), "{t}");
            }
        }
    }
}
