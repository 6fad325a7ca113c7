//! How long each step of a geodesic is: chords within their tolerance of
//! the arc near geometry (their bending and their time's curvature
//! bounded, docs/physics.md "Chords"), longer steps where the arc keeps
//! clear of the box holding every object.

use super::integrator::Outset;
use super::{Geodesic, Leg, CHORD_TOLERANCE, PIXEL_FRACTION};
use crate::spacetime::{Event, FourVector, Ray};
use glam::DVec3;

/// A chord sized to the pixel strays by at most this fraction of its
/// start's height above the horizon.
const HEIGHT_FRACTION: f64 = 1.0 / 16.0;

/// No step of the integration is longer than this fraction of the radius
/// it starts at, however loose the chord tolerance: the accuracy of the
/// ray's direction, and so of where it goes, rests on it.
const LONGEST_STEP: f64 = 0.25;

/// Where the ray passes clear of every object, a step may be this
/// fraction of the radius it starts at, or less so that its path turns by
/// at most [`CLEAR_TURN`] radians: the chord can meet nothing, only the
/// integration's accuracy bounds it.
pub(super) const CLEAR_STEP: f64 = 0.5;

/// The most a ray's path turns over one step clear of every object.
const CLEAR_TURN: f64 = 0.2;

/// A step clear of every object is taken where its estimated error is at
/// most this fraction of the chord tolerance in position and of the pixel's
/// angle in direction.
const CLEAR_ERROR: f64 = 1.0 / 16.0;

/// The longest chord that strays by at most `tol` from a geodesic of
/// h = |x cross v| and C = v^2 - 2 M h^2 / r^3 (both conserved: the
/// central acceleration's angular momentum and energy) wherever its radius
/// is at least `r` (docs/physics.md, "Chords"). Its path curves by
/// kappa = 3 M h^2 / (r^4 v^2) = 3 M h^2 / (C r^4 + 2 M h^2 r), which
/// grows as r falls, and its dt/ds changes by at most
/// M cos(psi) (2 + 3 sin^2 psi) / (r^2 f^2) <= 2.485 M / (r^2 f^2) per unit
/// length; a chord of length L strays by L^2 / 8 times the larger of them.
fn longest_chord(m: f64, r: f64, h2: f64, c: f64, tol: f64) -> f64 {
    let f = 1.0 - 2.0 * m / r;
    if f <= 0.0 || r <= 0.0 {
        return 0.0;
    }
    let bending = bending(m, r, h2, c);
    let timing = 2.485 * m / (r * r * f * f);
    (8.0 * tol / bending.max(timing)).sqrt()
}
/// The curvature bound kappa = 3 M h^2 / (C r^4 + 2 M h^2 r) of the path
/// of a geodesic of h = |x cross v| and C = v^2 - 2 M h^2 / r^3 wherever
/// its radius is at least `r` ([`longest_chord`]).
fn bending(m: f64, r: f64, h2: f64, c: f64) -> f64 {
    3.0 * m * h2 / (c * r.powi(4) + 2.0 * m * h2 * r)
}

/// Whether the segment from `a` to `b` meets the box [`lo`, `hi`].
fn segment_meets_box(a: DVec3, b: DVec3, (lo, hi): (DVec3, DVec3)) -> bool {
    if lo.cmpgt(hi).any() {
        return false;
    }
    let d = b - a;
    let (mut enter, mut leave) = (0.0_f64, 1.0_f64);
    for i in 0..3 {
        if d[i] == 0.0 {
            if a[i] < lo[i] || a[i] > hi[i] {
                return false;
            }
            continue;
        }
        let inverse = 1.0 / d[i];
        let (near, far) = ((lo[i] - a[i]) * inverse, (hi[i] - a[i]) * inverse);
        enter = enter.max(near.min(far));
        leave = leave.min(near.max(far));
        if enter > leave {
            return false;
        }
    }
    true
}

/// The least radius an arc from `a` to `b` turning by at most CLEAR_TURN
/// can pass: the chord's, less the most the arc strays from it.
fn least_radius(a: DVec3, b: DVec3) -> f64 {
    distance_to_segment(a, b) - CLEAR_TURN * (b - a).length()
}

/// The distance from the origin to the segment from `a` to `b`.
fn distance_to_segment(a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let s = if len2 > 0.0 {
        (-a.dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * s).length()
}

impl Geodesic {
    /// How far the next chord may stray from the geodesic.
    /// However coarse the pixel, never more than [`HEIGHT_FRACTION`] of the
    /// height above the horizon, so that the bounds are taken outside it.
    fn tolerance(&self) -> f64 {
        let height = self.x.length() - 2.0 * self.mass;
        let footprint = PIXEL_FRACTION * self.pixel_angle * self.arc;
        (CHORD_TOLERANCE * self.mass).max(footprint.min(HEIGHT_FRACTION * height))
    }

    /// The next chord: a step clear of all geometry where one longer than
    /// [`LONGEST_STEP`] of the radius can be taken ([`Geodesic::clear_step`]);
    /// otherwise one step, as long as the chord bound allows at the least
    /// radius the straight line along v would pass, halved until the chord
    /// is within the tolerance of the arc it cuts (measured at the least
    /// radius it passes, less the tolerance itself), and never longer than
    /// [`LONGEST_STEP`] of the radius.
    pub(super) fn step(&mut self) -> Leg {
        let m = self.mass;
        let r = self.x.length();
        let speed = self.v.length();
        let h2 = self.x.cross(self.v).length_squared();
        let c = speed * speed - 2.0 * m * h2 / (r * r * r);
        let tol = self.tolerance();
        let allowed =
            |nearest: f64| longest_chord(m, nearest - tol, h2, c, tol).min(LONGEST_STEP * r);
        let outset = self.outset();
        if let Some(leg) = self.clear_step(&outset, LONGEST_STEP * r, h2, c, tol) {
            return leg;
        }
        let ahead = self.v / speed;
        let mut len = allowed(r);
        for _ in 0..2 {
            len = allowed(distance_to_segment(self.x, self.x + ahead * len));
        }
        let mut h = 0.95 * len / speed;
        for _ in 0..40 {
            let (x, v, dt) = self.rk4(&outset, h);
            let len = (x - self.x).length();
            if len > 0.0 && len <= allowed(distance_to_segment(self.x, x)) && x.is_finite() {
                self.cleared = false;
                return self.advance(x, v, dt, len);
            }
            h /= 2.0;
        }
        Leg::Captured
    }

    /// A step longer than `len` along which nothing can be met: its arc
    /// keeps more than `tol` outside the box holding all geometry and turns
    /// by at most [`CLEAR_TURN`] ([`Geodesic::meets_geometry`]). It is one
    /// Dormand-Prince 5(4) step of at most [`CLEAR_STEP`] of the radius,
    /// taken when its error estimate is within [`CLEAR_ERROR`] of the chord
    /// tolerance in position and of the pixel's angle in direction, and
    /// shortened (by the estimate's fourth root, three tries) where it is
    /// not; the length that passed is tried first next time (and, where it
    /// was no longer than a chord, half as long again). `None` where no
    /// such step is longer than `len`, where the straight line ahead
    /// meets the box, and for a geodesic not sized to a pixel.
    fn clear_step(&mut self, outset: &Outset, len: f64, h2: f64, c: f64, tol: f64) -> Option<Leg> {
        let turning = self.pixel_angle * CLEAR_ERROR;
        let r = self.x.length();
        let speed = self.v.length();
        let mut clear = self.clear_fraction * r;
        let (lo, hi) = self.geometry;
        let margin = DVec3::splat(tol);
        for _ in 0..3 {
            let ahead = self.x + self.v * (clear / speed);
            if !(clear > len && turning > 0.0) {
                // No longer than a chord here: try longer again later.
                self.clear_fraction = (self.clear_fraction * 1.5).min(CLEAR_STEP);
                return None;
            }
            if segment_meets_box(self.x, ahead, (lo - margin, hi + margin)) {
                return None;
            }
            let ((x, v, dt), ex, ev) = self.dopri(outset, clear / speed);
            let error = (ex.length() / (tol * CLEAR_ERROR)).max(ev.length() / (speed * turning));
            let scale = (0.9 / error.sqrt().sqrt()).clamp(0.2, 2.0);
            self.clear_fraction = (self.clear_fraction * scale).min(CLEAR_STEP);
            let turn = match self.meets_geometry(x, h2, c, tol) {
                Some(turn) if x.is_finite() => turn,
                _ => return None,
            };
            if error <= 1.0 && turn <= CLEAR_TURN && x != self.x {
                self.cleared = true;
                return Some(self.advance(x, v, dt, (x - self.x).length()));
            }
            clear *= scale.min(0.9 * CLEAR_TURN / turn);
        }
        None
    }

    /// How far the arc from here to `end` turns, if it keeps more than
    /// `tol` outside the box holding all geometry: it lies within the
    /// sagitta (1 - sqrt(1 - (kappa L / 2)^2)) / kappa of its chord of
    /// length L, kappa the bending at the least radius it can pass; `None`
    /// where it may come nearer (or the bound fails: kappa L >= 2, or the
    /// least radius inside the photon sphere).
    fn meets_geometry(&self, end: DVec3, h2: f64, c: f64, tol: f64) -> Option<f64> {
        let len = (end - self.x).length();
        let least = least_radius(self.x, end);
        let kappa = bending(self.mass, least, h2, c);
        let half = 0.5 * kappa * len;
        if !(least > 3.0 * self.mass && kappa >= 0.0 && half < 1.0) {
            return None;
        }
        let sagitta = 0.5 * len * half / (1.0 + (1.0 - half * half).sqrt());
        let margin = DVec3::splat(1.01 * sagitta + tol);
        let (lo, hi) = self.geometry;
        match segment_meets_box(self.x, end, (lo - margin, hi + margin)) {
            true => None,
            false => Some(2.0 * half),
        }
    }

    /// Moves on to (x, v), `dt` later in lambda's direction, giving the
    /// chord of length `len` from here.
    fn advance(&mut self, x: DVec3, v: DVec3, dt: f64, len: f64) -> Leg {
        let dt = dt * self.time_sign;
        let ray = Ray {
            origin: Event::new(self.t, self.centre + self.x),
            direction: FourVector::new(dt / len, (x - self.x) / len),
        };
        self.x = x;
        self.v = v;
        self.t += dt;
        self.arc += len;
        Leg::Chord(ray, len)
    }
}
