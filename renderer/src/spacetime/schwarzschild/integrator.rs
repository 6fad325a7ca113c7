//! The integration of a geodesic's path: the central acceleration
//! a = -3 M h^2 x / r^5 and the coordinate time, stepped by classical
//! Runge-Kutta (chords near geometry) or Dormand-Prince 5(4) with its error
//! estimate (steps clear of all geometry).
//!
//! Each step is written once over a [`Lane`]: one geodesic's `f64`, or four
//! geodesics side by side in `f64x4`, taking the same operations in the
//! same order lane by lane, so that every lane is its geodesic's own step
//! to the bit.

use super::Geodesic;
use glam::DVec3;
use std::ops::{Add, Div, Mul, Sub};
use wide::f64x4;

/// What the steps compute in: IEEE additions, multiplications, divisions
/// and square roots, each correctly rounded, lane by lane.
pub(super) trait Lane:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    fn splat(x: f64) -> Self;
    fn sqrt(self) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
}

impl Lane for f64x4 {
    #[inline(always)]
    fn splat(x: f64) -> f64x4 {
        f64x4::splat(x)
    }
    #[inline(always)]
    fn sqrt(self) -> f64x4 {
        f64x4::sqrt(self)
    }
}

/// A vector of lanes, its operations those of glam's `DVec3` in the same
/// order (a dot product sums x, then y, then z).
#[derive(Clone, Copy)]
pub(super) struct V3<L> {
    pub(super) x: L,
    pub(super) y: L,
    pub(super) z: L,
}

impl<L: Lane> V3<L> {
    #[inline(always)]
    fn dot(self, o: V3<L>) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    fn scaled(self, s: L) -> V3<L> {
        V3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    #[inline(always)]
    fn plus(self, o: V3<L>) -> V3<L> {
        V3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl From<DVec3> for V3<f64> {
    #[inline(always)]
    fn from(d: DVec3) -> V3<f64> {
        V3 {
            x: d.x,
            y: d.y,
            z: d.z,
        }
    }
}

impl From<V3<f64>> for DVec3 {
    #[inline(always)]
    fn from(v: V3<f64>) -> DVec3 {
        DVec3::new(v.x, v.y, v.z)
    }
}

/// What stays the same along a geodesic's path: M, h^2 = |x cross v|^2
/// and sqrt(C), C = v^2 - 2 M h^2 / r^3 (the central acceleration's
/// angular momentum and energy).
#[derive(Clone, Copy)]
pub(super) struct Invariants<L = f64> {
    m: L,
    h2: L,
    root_c: L,
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
}

impl<L: Lane> Invariants<L> {
    /// d/d(lambda) of (x, v, t) (t's with `time_sign` applied by the
    /// caller): a = -3 M h^2 x / r^5, and from the null condition
    /// dt/dlambda = sqrt(v_r^2 / f^2 + v_t^2 / f) = sqrt(C) / f, since
    /// v_r^2 + f v_t^2 = v^2 - (2M / r) h^2 / r^2 = C.
    #[inline(always)]
    pub(super) fn derivative(&self, x: V3<L>, v: V3<L>) -> (V3<L>, V3<L>, L) {
        let r2 = x.dot(x);
        let r = r2.sqrt();
        let a = x.scaled(L::splat(-3.0) * self.m * self.h2 / (r2 * r2 * r));
        let dt = self.root_c * r / (r - L::splat(2.0) * self.m);
        (v, a, dt)
    }
}

/// What every trial step from one state shares: the state, the orbit's
/// invariants there and the derivative at the state itself (every
/// Runge-Kutta method's first stage), found once however many step lengths
/// are tried.
#[derive(Clone, Copy)]
pub(super) struct Outset<L = f64> {
    x: V3<L>,
    v: V3<L>,
    orbit: Invariants<L>,
    slope: (V3<L>, V3<L>, L),
}

/// A trial's end in lanes: x, v and the coordinate time it took.
pub(super) type LaneEnd<L> = (V3<L>, V3<L>, L);

/// A trial's end: x, v (relative to the centre) and the coordinate time
/// it took.
pub(super) type End = (DVec3, DVec3, f64);

/// A Dormand-Prince trial's end and its error estimate in x and in v.
pub(super) type Trial = (End, DVec3, DVec3);

impl Geodesic {
    /// The shared start of the trial steps from the geodesic's state.
    pub(super) fn outset(&self) -> Outset {
        let orbit = Invariants::of(self.mass, self.x, self.v);
        let (x, v) = (self.x.into(), self.v.into());
        Outset {
            x,
            v,
            orbit,
            slope: orbit.derivative(x, v),
        }
    }
}

impl Outset {
    /// dt/dlambda at the state itself (without `time_sign`).
    pub(super) fn time_rate(&self) -> f64 {
        self.slope.2
    }

    /// [`Outset::rk4`] of one geodesic, in glam vectors.
    #[inline(always)]
    pub(super) fn rk4_trial(&self, h: f64) -> End {
        let (x, v, dt) = self.rk4(h);
        (x.into(), v.into(), dt)
    }

    /// [`Outset::dopri`] of one geodesic, in glam vectors.
    #[inline(always)]
    pub(super) fn dopri_trial(&self, h: f64) -> Trial {
        let ((x, v, dt), ex, ev) = self.dopri(h);
        ((x.into(), v.into(), dt), ex.into(), ev.into())
    }
}

impl<L: Lane> Outset<L> {
    /// One classical Runge-Kutta step of `h` in lambda from this state.
    #[inline(always)]
    pub(super) fn rk4(&self, h: L) -> LaneEnd<L> {
        let (x, v) = (self.x, self.v);
        let orbit = self.orbit;
        let half = h / L::splat(2.0);
        let (k1x, k1v, k1t) = self.slope;
        let (k2x, k2v, k2t) = orbit.derivative(x.plus(k1x.scaled(half)), v.plus(k1v.scaled(half)));
        let (k3x, k3v, k3t) = orbit.derivative(x.plus(k2x.scaled(half)), v.plus(k2v.scaled(half)));
        let (k4x, k4v, k4t) = orbit.derivative(x.plus(k3x.scaled(h)), v.plus(k3v.scaled(h)));
        let sixth = h / L::splat(6.0);
        let two = L::splat(2.0);
        let dx = k1x.plus(k2x.plus(k3x).scaled(two)).plus(k4x).scaled(sixth);
        let dv = k1v.plus(k2v.plus(k3v).scaled(two)).plus(k4v).scaled(sixth);
        let dt = (k1t + two * (k2t + k3t) + k4t) * sixth;
        (x.plus(dx), v.plus(dv), dt)
    }

    /// One Dormand-Prince step of `h` in lambda from this state: the
    /// fifth order solution, and the difference from the embedded fourth
    /// order one in x and in v.
    #[inline(always)]
    pub(super) fn dopri(&self, h: L) -> (LaneEnd<L>, V3<L>, V3<L>) {
        let zero = V3 {
            x: L::splat(0.0),
            y: L::splat(0.0),
            z: L::splat(0.0),
        };
        let mut k = Stages {
            x: [zero; 7],
            v: [zero; 7],
            t: [L::splat(0.0); 7],
        };
        (k.x[0], k.v[0], k.t[0]) = self.slope;
        // Stage by stage, each summing a fixed number of terms, so that
        // every sum is unrolled.
        let start = (self.x, self.v);
        let orbit = &self.orbit;
        k.stage::<1>(start, &A[0], h, orbit);
        k.stage::<2>(start, &A[1], h, orbit);
        k.stage::<3>(start, &A[2], h, orbit);
        k.stage::<4>(start, &A[3], h, orbit);
        k.stage::<5>(start, &A[4], h, orbit);
        let end = k.stage::<6>(start, &A[5], h, orbit);
        let (mut ex, mut ev) = (zero, zero);
        for ((&kx, &kv), &e) in k.x.iter().zip(&k.v).zip(&E) {
            ex = ex.plus(kx.scaled(h * L::splat(e)));
            ev = ev.plus(kv.scaled(h * L::splat(e)));
        }
        (end, ex, ev)
    }
}

/// Four geodesics' trial steps side by side: lane j of each argument is
/// geodesic j's, and so is lane j of each result, to the bit.
pub(super) struct Outsets4(Outset<f64x4>);

impl Outsets4 {
    /// The lanes' starts: `each[j]` for lane j.
    pub(super) fn of(each: [&Outset; 4]) -> Outsets4 {
        let lanes = |f: fn(&Outset) -> f64| f64x4::new(each.map(f));
        let v3 = |f: fn(&Outset) -> V3<f64>| V3 {
            x: f64x4::new(each.map(|o| f(o).x)),
            y: f64x4::new(each.map(|o| f(o).y)),
            z: f64x4::new(each.map(|o| f(o).z)),
        };
        Outsets4(Outset {
            x: v3(|o| o.x),
            v: v3(|o| o.v),
            orbit: Invariants {
                m: lanes(|o| o.orbit.m),
                h2: lanes(|o| o.orbit.h2),
                root_c: lanes(|o| o.orbit.root_c),
            },
            slope: (v3(|o| o.slope.0), v3(|o| o.slope.1), lanes(|o| o.slope.2)),
        })
    }

    /// [`Outset::rk4_trial`] of each lane's start, lane j stepping `h[j]`.
    pub(super) fn rk4(&self, h: [f64; 4]) -> [End; 4] {
        let (x, v, dt) = self.0.rk4(f64x4::new(h));
        let (x, v, dt) = (split(x), split(v), dt.to_array());
        std::array::from_fn(|j| (x[j], v[j], dt[j]))
    }

    /// [`Outset::dopri_trial`] of each lane's start, lane j stepping `h[j]`.
    pub(super) fn dopri(&self, h: [f64; 4]) -> [Trial; 4] {
        let ((x, v, dt), ex, ev) = self.0.dopri(f64x4::new(h));
        let (x, v, dt, ex, ev) = (split(x), split(v), dt.to_array(), split(ex), split(ev));
        std::array::from_fn(|j| ((x[j], v[j], dt[j]), ex[j], ev[j]))
    }
}

/// Each lane's vector.
fn split(v: V3<f64x4>) -> [DVec3; 4] {
    let (x, y, z) = (v.x.to_array(), v.y.to_array(), v.z.to_array());
    std::array::from_fn(|j| DVec3::new(x[j], y[j], z[j]))
}

/// The Dormand-Prince tableau's rows.
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

/// The fifth order weights less the embedded fourth order ones.
const E: [f64; 7] = [
    35.0 / 384.0 - 5179.0 / 57600.0,
    0.0,
    500.0 / 1113.0 - 7571.0 / 16695.0,
    125.0 / 192.0 - 393.0 / 640.0,
    -2187.0 / 6784.0 + 92097.0 / 339200.0,
    11.0 / 84.0 - 187.0 / 2100.0,
    -1.0 / 40.0,
];

/// The derivatives of a Dormand-Prince step's stages, in x, v and t.
struct Stages<L> {
    x: [V3<L>; 7],
    v: [V3<L>; 7],
    t: [L; 7],
}

impl<L: Lane> Stages<L> {
    /// Stage `N`: the state `start` moved by the first `N` stages'
    /// derivatives weighted by `row` (the tableau's row N - 1) over `h`,
    /// whose derivative becomes stage N's; returns that state, with its
    /// time.
    #[inline(always)]
    fn stage<const N: usize>(
        &mut self,
        (x0, v0): (V3<L>, V3<L>),
        row: &[f64; 6],
        h: L,
        orbit: &Invariants<L>,
    ) -> LaneEnd<L> {
        let (mut x, mut v, mut t) = (x0, v0, L::splat(0.0));
        let terms = self.x.iter().zip(&self.v).zip(&self.t).zip(row);
        for (((&kx, &kv), &kt), &a) in terms.take(N) {
            let w = h * L::splat(a);
            x = x.plus(kx.scaled(w));
            v = v.plus(kv.scaled(w));
            t = t + kt * w;
        }
        (self.x[N], self.v[N], self.t[N]) = orbit.derivative(x, v);
        (x, v, t)
    }
}
