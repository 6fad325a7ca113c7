//! How long each step of a geodesic is: chords within their tolerance of
//! the arc near geometry (their bending and their time's curvature
//! bounded, docs/physics.md "Chords"), longer steps where the arc keeps
//! clear of the box holding every object.

use super::integrator::{End, Outset, Trial};
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

/// A step clear of all geometry is tried at most this many times, each
/// shorter, before a chord is taken instead.
const CLEAR_TRIES: u32 = 3;

/// A chord's length is halved at most this many times; a step that has
/// not found one within its bound by then is taken as captured.
const CHORD_TRIES: u32 = 40;

/// One step of a geodesic under way ([`Geodesic::step`]): what it found
/// of the state it starts from, and the trial it is at.
pub(super) struct Step {
    r: f64,
    speed: f64,
    /// h^2 = |x cross v|^2 and C = v^2 - 2 M h^2 / r^3.
    h2: f64,
    c: f64,
    /// How far its chord may stray from the geodesic.
    tol: f64,
    pub(super) outset: Outset,
    phase: Phase,
}

impl Step {
    /// The longest chord allowed where the least radius it passes is
    /// `nearest` (measured the tolerance nearer), and never longer than
    /// [`LONGEST_STEP`] of the radius.
    fn allowed(&self, m: f64, nearest: f64) -> f64 {
        longest_chord(m, nearest - self.tol, self.h2, self.c, self.tol).min(LONGEST_STEP * self.r)
    }
}

/// Where a step is.
#[derive(Clone, Copy)]
enum Phase {
    /// Trying a step `clear` long (its `tries`-th try) along which nothing
    /// can be met: its arc keeps more than the tolerance outside the box
    /// holding all geometry and turns by at most [`CLEAR_TURN`]
    /// ([`Geodesic::meets_geometry`]). It is one Dormand-Prince 5(4) step
    /// of at most [`CLEAR_STEP`] of the radius, taken when its error
    /// estimate is within [`CLEAR_ERROR`] of the chord tolerance in
    /// position and of the pixel's angle in direction, and shortened (by
    /// the estimate's fourth root, [`CLEAR_TRIES`] tries) where it is not;
    /// the length that passed is tried first next time (and, where it was
    /// no longer than a chord, half as long again). Not tried where no
    /// such step is longer than [`LONGEST_STEP`] of the radius, where the
    /// straight line ahead meets the box, or for a geodesic not sized to a
    /// pixel.
    Clear { clear: f64, tries: u32 },
    /// A chord of `h` in lambda, after `tries` halvings.
    Chord { h: f64, tries: u32 },
}

/// What a step needs next: a Dormand-Prince or Runge-Kutta trial of `h` in
/// lambda from its start, or nothing more, its ray taken as captured (no
/// chord within the bound after [`CHORD_TRIES`] halvings).
#[derive(Clone, Copy)]
pub(super) enum Ask {
    Dopri(f64),
    Rk4(f64),
    Captured,
}

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
    /// [`LONGEST_STEP`] of the radius can be taken ([`Phase::Clear`]);
    /// otherwise one step, as long as the chord bound allows at the least
    /// radius the straight line along v would pass, halved until the chord
    /// is within the tolerance of the arc it cuts (measured at the least
    /// radius it passes, less the tolerance itself), and never longer than
    /// [`LONGEST_STEP`] of the radius.
    pub(super) fn step(&mut self) -> Leg {
        let mut step = self.begin_step();
        loop {
            let ended = match self.ask(&mut step) {
                Ask::Dopri(h) => {
                    let found = step.outset.dopri_trial(h);
                    self.after_dopri(&mut step, found)
                }
                Ask::Rk4(h) => {
                    let found = step.outset.rk4_trial(h);
                    self.after_rk4(&mut step, found)
                }
                Ask::Captured => Some(Leg::Captured),
            };
            if let Some(leg) = ended {
                return leg;
            }
        }
    }

    /// A step from the geodesic's present state, before any trial.
    #[inline]
    pub(super) fn begin_step(&self) -> Step {
        let m = self.mass;
        let r = self.x.length();
        let speed = self.v.length();
        let h2 = self.x.cross(self.v).length_squared();
        let c = speed * speed - 2.0 * m * h2 / (r * r * r);
        Step {
            r,
            speed,
            h2,
            c,
            tol: self.tolerance(),
            outset: self.outset(),
            phase: Phase::Clear {
                clear: self.clear_fraction * r,
                tries: 0,
            },
        }
    }

    /// The trial `step` needs next, or its leg: the clear step's tries
    /// ([`Phase::Clear`]) while they may pass, then the chord's halvings.
    #[inline]
    pub(super) fn ask(&mut self, step: &mut Step) -> Ask {
        if let Phase::Clear { clear, tries } = step.phase {
            if tries < CLEAR_TRIES && self.may_clear(step, clear) {
                return Ask::Dopri(clear / step.speed);
            }
            step.phase = self.chord_phase(step);
        }
        match step.phase {
            Phase::Chord { h, tries } if tries < CHORD_TRIES => Ask::Rk4(h),
            _ => Ask::Captured,
        }
    }

    /// Whether a step clear of all geometry `clear` long is worth trying:
    /// longer than a chord may be here, its straight line clear of the box.
    /// Where it is no longer than a chord, the next step's first try is
    /// made longer (`clear_fraction`).
    #[inline]
    fn may_clear(&mut self, step: &Step, clear: f64) -> bool {
        let turning = self.pixel_angle * CLEAR_ERROR;
        if !(clear > LONGEST_STEP * step.r && turning > 0.0) {
            // No longer than a chord here: try longer again later.
            self.clear_fraction = (self.clear_fraction * 1.5).min(CLEAR_STEP);
            return false;
        }
        let ahead = self.x + self.v * (clear / step.speed);
        let (lo, hi) = self.geometry;
        let margin = DVec3::splat(step.tol);
        !segment_meets_box(self.x, ahead, (lo - margin, hi + margin))
    }

    /// The first trial of a chord near geometry: as long as the chord
    /// bound allows at the least radius the straight line along v passes.
    #[inline]
    fn chord_phase(&self, step: &Step) -> Phase {
        let ahead = self.v / step.speed;
        let mut len = step.allowed(self.mass, step.r);
        for _ in 0..2 {
            len = step.allowed(self.mass, distance_to_segment(self.x, self.x + ahead * len));
        }
        Phase::Chord {
            h: 0.95 * len / step.speed,
            tries: 0,
        }
    }

    /// The verdict on a Dormand-Prince trial of `step` ([`Ask::Dopri`]):
    /// its chord where it is taken, `None` where the step goes on.
    #[inline]
    pub(super) fn after_dopri(&mut self, step: &mut Step, found: Trial) -> Option<Leg> {
        let Phase::Clear { clear, tries } = step.phase else {
            unreachable!("a Dormand-Prince trial is asked for in the clear phase");
        };
        let ((x, v, dt), ex, ev) = found;
        let turning = self.pixel_angle * CLEAR_ERROR;
        let error =
            (ex.length() / (step.tol * CLEAR_ERROR)).max(ev.length() / (step.speed * turning));
        let scale = (0.9 / error.sqrt().sqrt()).clamp(0.2, 2.0);
        self.clear_fraction = (self.clear_fraction * scale).min(CLEAR_STEP);
        let turn = match self.meets_geometry(x, step.h2, step.c, step.tol) {
            Some(turn) if x.is_finite() => turn,
            _ => {
                step.phase = self.chord_phase(step);
                return None;
            }
        };
        if error <= 1.0 && turn <= CLEAR_TURN && x != self.x {
            self.cleared = true;
            return Some(self.advance(x, v, dt, (x - self.x).length()));
        }
        step.phase = Phase::Clear {
            clear: clear * scale.min(0.9 * CLEAR_TURN / turn),
            tries: tries + 1,
        };
        None
    }

    /// The verdict on a Runge-Kutta trial of `step` ([`Ask::Rk4`]): its
    /// chord where it is within the bound, `None` (and half the length
    /// next) where it is not.
    #[inline]
    pub(super) fn after_rk4(&mut self, step: &mut Step, (x, v, dt): End) -> Option<Leg> {
        let Phase::Chord { h, tries } = step.phase else {
            unreachable!("a Runge-Kutta trial is asked for in the chord phase");
        };
        let len = (x - self.x).length();
        let bound = step.allowed(self.mass, distance_to_segment(self.x, x));
        if len > 0.0 && len <= bound && x.is_finite() {
            self.cleared = false;
            return Some(self.advance(x, v, dt, len));
        }
        step.phase = Phase::Chord {
            h: h / 2.0,
            tries: tries + 1,
        };
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
