//! The integration of a geodesic's path: the central acceleration
//! a = -3 M h^2 x / r^5 and the coordinate time, stepped by classical
//! Runge-Kutta (chords near geometry) or Dormand-Prince 5(4) with its error
//! estimate (steps clear of all geometry).

use super::Geodesic;
use glam::DVec3;

/// What stays the same along a geodesic's path: M, h^2 = |x cross v|^2
/// and sqrt(C), C = v^2 - 2 M h^2 / r^3 (the central acceleration's
/// angular momentum and energy).
#[derive(Clone, Copy)]
pub(super) struct Invariants {
    m: f64,
    h2: f64,
    root_c: f64,
}

impl Invariants {
    pub(super) fn of(m: f64, x: DVec3, v: DVec3) -> Invariants {
        let h2 = x.cross(v).length_squared();
        let r = x.length();
        let c = v.length_squared() - 2.0 * m * h2 / (r * r * r);
        Invariants {
            m,
            h2,
            root_c: c.max(0.0).sqrt(),
        }
    }

    /// d/d(lambda) of (x, v, t) (t's with `time_sign` applied by the
    /// caller): a = -3 M h^2 x / r^5, and from the null condition
    /// dt/dlambda = sqrt(v_r^2 / f^2 + v_t^2 / f) = sqrt(C) / f, since
    /// v_r^2 + f v_t^2 = v^2 - (2M / r) h^2 / r^2 = C.
    pub(super) fn derivative(&self, x: DVec3, v: DVec3) -> (DVec3, DVec3, f64) {
        let r2 = x.length_squared();
        let r = r2.sqrt();
        let a = x * (-3.0 * self.m * self.h2 / (r2 * r2 * r));
        let dt = self.root_c * r / (r - 2.0 * self.m);
        (v, a, dt)
    }
}

impl Geodesic {
    /// One classical Runge-Kutta step of `h` in lambda from (x, v).
    pub(super) fn rk4(&self, h: f64) -> (DVec3, DVec3, f64) {
        let (x, v) = (self.x, self.v);
        let orbit = Invariants::of(self.mass, x, v);
        let (k1x, k1v, k1t) = orbit.derivative(x, v);
        let (k2x, k2v, k2t) = orbit.derivative(x + k1x * (h / 2.0), v + k1v * (h / 2.0));
        let (k3x, k3v, k3t) = orbit.derivative(x + k2x * (h / 2.0), v + k2v * (h / 2.0));
        let (k4x, k4v, k4t) = orbit.derivative(x + k3x * h, v + k3v * h);
        let dx = (k1x + (k2x + k3x) * 2.0 + k4x) * (h / 6.0);
        let dv = (k1v + (k2v + k3v) * 2.0 + k4v) * (h / 6.0);
        let dt = (k1t + 2.0 * (k2t + k3t) + k4t) * (h / 6.0);
        (x + dx, v + dv, dt)
    }

    /// One Dormand-Prince step of `h` in lambda from (x, v): the fifth
    /// order solution, and the difference from the embedded fourth order
    /// one in x and in v (the step's error estimate).
    pub(super) fn dopri(&self, h: f64) -> ((DVec3, DVec3, f64), DVec3, DVec3) {
        const A: [[f64; 6]; 6] = [
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
                0.0,
                0.0,
            ],
            [
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
                0.0,
            ],
            [
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
        ];
        const E: [f64; 7] = [
            35.0 / 384.0 - 5179.0 / 57600.0,
            0.0,
            500.0 / 1113.0 - 7571.0 / 16695.0,
            125.0 / 192.0 - 393.0 / 640.0,
            -2187.0 / 6784.0 + 92097.0 / 339200.0,
            11.0 / 84.0 - 187.0 / 2100.0,
            -1.0 / 40.0,
        ];
        let orbit = Invariants::of(self.mass, self.x, self.v);
        let mut kx = [DVec3::ZERO; 7];
        let mut kv = [DVec3::ZERO; 7];
        let mut kt = [0.0; 7];
        (kx[0], kv[0], kt[0]) = orbit.derivative(self.x, self.v);
        let mut end = (self.x, self.v, 0.0);
        for (i, row) in A.iter().enumerate() {
            let (mut x, mut v, mut t) = (self.x, self.v, 0.0);
            for j in 0..=i {
                x += kx[j] * (h * row[j]);
                v += kv[j] * (h * row[j]);
                t += kt[j] * (h * row[j]);
            }
            (kx[i + 1], kv[i + 1], kt[i + 1]) = orbit.derivative(x, v);
            end = (x, v, t);
        }
        let (mut ex, mut ev) = (DVec3::ZERO, DVec3::ZERO);
        for j in 0..7 {
            ex += kx[j] * (h * E[j]);
            ev += kv[j] * (h * E[j]);
        }
        (end, ex, ev)
    }
}
