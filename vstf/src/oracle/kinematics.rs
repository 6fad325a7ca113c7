//! Special-relativistic kinematics written from the formulas: the
//! Lorentz factor, the boost of a displacement between events, length
//! contraction, and the aberration of light for a moving observer
//! (relativistic and Galilean).

use glam::DVec3;

/// Lorentz factor, paper eq. (2), of the speed `beta`.
pub fn gamma(beta: f64) -> f64 {
    gamma_of_squared(beta * beta)
}

/// Lorentz factor, paper eq. (2), of the squared speed beta^2 = v.v
/// (for a velocity vector, without the square root of a square).
pub fn gamma_of_squared(beta_squared: f64) -> f64 {
    1.0 / (1.0 - beta_squared).sqrt()
}

/// A lab-frame displacement (`dt`, `dx`) between two events, in the frame
/// moving with lab velocity `u` (|u| < 1): the pure Lorentz boost
/// t' = gamma (t - u.x), x' = x + ((gamma - 1) (u.x) / u^2 - gamma t) u
/// (paper 3, item 2c, in vector form). `None` at or above light speed.
pub fn to_frame_of(dt: f64, dx: DVec3, u: DVec3) -> Option<(f64, DVec3)> {
    let u2 = u.length_squared();
    if !u.is_finite() || u2 >= 1.0 {
        return None;
    }
    if u2 == 0.0 {
        return Some((dt, dx));
    }
    let g = gamma_of_squared(u2);
    let ux = u.dot(dx);
    Some((g * (dt - ux), dx + u * ((g - 1.0) * ux / u2 - g * dt)))
}

/// Length contraction of a rest-frame offset `r` of a body moving with
/// lab velocity `v`: its lab-simultaneous offset, the component along `v`
/// divided by gamma (written out here, independently of the ray tracer's boost).
pub fn contract(r: DVec3, v: DVec3) -> DVec3 {
    let speed = v.length();
    if speed == 0.0 {
        return r;
    }
    let n = v / speed;
    let along = r.dot(n);
    r + n * (along / gamma(speed) - along)
}

/// The direction, in the frame of an observer moving with lab velocity `v`,
/// of light that reaches it from lab direction `n` (unit, from the observer
/// towards the source). Relativistic aberration: the photon's 4-momentum
/// (1, -n) is boosted, k'^0 = gamma (1 + v.n), k' = -n + (gamma - 1)(-n.v^)v^
/// - gamma v, and n' = -k' / k'^0 (paper eq. 3-5 in vector form).
pub fn aberrate_lorentz(n: DVec3, v: DVec3) -> DVec3 {
    let b = v.length();
    if b == 0.0 {
        return n;
    }
    let vh = v / b;
    let g = gamma(b);
    let k = -n;
    let k0 = g * (1.0 - v.dot(k));
    let kv = k + vh * ((g - 1.0) * k.dot(vh)) - v * g;
    (-kv / k0).normalize()
}

/// The same for Galilean kinematics: light moving at c in the lab has
/// velocity -n - v relative to the observer, who sees it coming from n + v.
pub fn aberrate_galilean(n: DVec3, v: DVec3) -> DVec3 {
    (n + v).normalize()
}

/// The relativistic Doppler factor D = nu_seen / nu_emitted of light
/// leaving a source that moves with lab velocity `u` along the unit vector
/// `k`, seen by an observer at rest in the lab: D = 1 / (gamma (1 - u.k)).
pub fn doppler_factor(u: DVec3, k: DVec3) -> f64 {
    1.0 / (gamma_of_squared(u.length_squared()) * (1.0 - u.dot(k)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn aberration_matches_the_paper_half_angle_formula() {
        // Eq. (9): tan(a'/2) = sqrt((1 - b)/(1 + b)) tan(a/2), angles from the observer's velocity.
        let b = 0.6;
        for a_deg in [10.0f64, 60.0, 116.565, 170.0] {
            let a = a_deg.to_radians();
            let n = DVec3::new(a.cos(), a.sin(), 0.0);
            let got = aberrate_lorentz(n, DVec3::new(b, 0.0, 0.0));
            let want = 2.0 * (((1.0 - b) / (1.0 + b)).sqrt() * (a / 2.0).tan()).atan();
            assert_relative_eq!(got.y.atan2(got.x), want, max_relative = 1e-12);
        }
    }

    #[test]
    fn doppler_factor_head_on_receding_and_transverse() {
        let b = 0.6;
        let u = DVec3::new(b, 0.0, 0.0);
        // Head-on: sqrt((1 + b) / (1 - b)) = 2; receding: 1/2; transverse
        // (k perpendicular to u in the lab): 1/gamma = 0.8.
        assert_relative_eq!(doppler_factor(u, DVec3::X), 2.0, max_relative = 1e-12);
        assert_relative_eq!(doppler_factor(u, -DVec3::X), 0.5, max_relative = 1e-12);
        assert_relative_eq!(doppler_factor(u, DVec3::Y), 0.8, max_relative = 1e-12);
        // A wrong sign of u.k would swap head-on and receding.
        assert!((doppler_factor(-u, DVec3::X) - 2.0).abs() > 1.0);
    }
}
