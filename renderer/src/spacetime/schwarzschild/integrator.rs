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

/// What every trial step from one state shares: the orbit's invariants
/// there and the derivative at the state itself (every Runge-Kutta
/// method's first stage), found once however many step lengths are tried.
#[derive(Clone, Copy)]
pub(super) struct Outset {
    orbit: Invariants,
    slope: (DVec3, DVec3, f64),
}

impl Geodesic {
    /// The shared start of the trial steps from the geodesic's state.
    pub(super) fn outset(&self) -> Outset {
        let orbit = Invariants::of(self.mass, self.x, self.v);
        Outset {
            orbit,
            slope: orbit.derivative(self.x, self.v),
        }
    }

    /// One classical Runge-Kutta step of `h` in lambda from (x, v), whose
    /// start is `outset`.
    pub(super) fn rk4(&self, outset: &Outset, h: f64) -> (DVec3, DVec3, f64) {
        let (x, v) = (self.x, self.v);
        let orbit = outset.orbit;
        let (k1x, k1v, k1t) = outset.slope;
        let (k2x, k2v, k2t) = orbit.derivative(x + k1x * (h / 2.0), v + k1v * (h / 2.0));
        let (k3x, k3v, k3t) = orbit.derivative(x + k2x * (h / 2.0), v + k2v * (h / 2.0));
        let (k4x, k4v, k4t) = orbit.derivative(x + k3x * h, v + k3v * h);
        let dx = (k1x + (k2x + k3x) * 2.0 + k4x) * (h / 6.0);
        let dv = (k1v + (k2v + k3v) * 2.0 + k4v) * (h / 6.0);
        let dt = (k1t + 2.0 * (k2t + k3t) + k4t) * (h / 6.0);
        (x + dx, v + dv, dt)
    }

    /// One Dormand-Prince step of `h` in lambda from (x, v), whose start is
    /// `outset`: the fifth order solution, and the difference from the
    /// embedded fourth order one in x and in v (the step's error estimate).
    pub(super) fn dopri(&self, outset: &Outset, h: f64) -> ((DVec3, DVec3, f64), DVec3, DVec3) {
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
        let orbit = outset.orbit;
        let mut k = Stages {
            x: [DVec3::ZERO; 7],
            v: [DVec3::ZERO; 7],
            t: [0.0; 7],
        };
        (k.x[0], k.v[0], k.t[0]) = outset.slope;
        // Stage by stage, each summing a fixed number of terms, so that
        // every sum is unrolled.
        let start = (self.x, self.v);
        k.stage::<1>(start, &A[0], h, &orbit);
        k.stage::<2>(start, &A[1], h, &orbit);
        k.stage::<3>(start, &A[2], h, &orbit);
        k.stage::<4>(start, &A[3], h, &orbit);
        k.stage::<5>(start, &A[4], h, &orbit);
        let end = k.stage::<6>(start, &A[5], h, &orbit);
        let (mut ex, mut ev) = (DVec3::ZERO, DVec3::ZERO);
        for ((&kx, &kv), &e) in k.x.iter().zip(&k.v).zip(&E) {
            ex += kx * (h * e);
            ev += kv * (h * e);
        }
        (end, ex, ev)
    }
}

/// The derivatives of a Dormand-Prince step's stages, in x, v and t.
struct Stages {
    x: [DVec3; 7],
    v: [DVec3; 7],
    t: [f64; 7],
}

impl Stages {
    /// Stage `N`: the state `start` moved by the first `N` stages'
    /// derivatives weighted by `row` (the tableau's row N - 1) over `h`,
    /// whose derivative becomes stage N's; returns that state, with its
    /// time.
    #[inline(always)]
    fn stage<const N: usize>(
        &mut self,
        (x0, v0): (DVec3, DVec3),
        row: &[f64; 6],
        h: f64,
        orbit: &Invariants,
    ) -> (DVec3, DVec3, f64) {
        let (mut x, mut v, mut t) = (x0, v0, 0.0);
        let terms = self.x.iter().zip(&self.v).zip(&self.t).zip(row);
        for (((&kx, &kv), &kt), &a) in terms.take(N) {
            x += kx * (h * a);
            v += kv * (h * a);
            t += kt * (h * a);
        }
        (self.x[N], self.v[N], self.t[N]) = orbit.derivative(x, v);
        (x, v, t)
    }
}
