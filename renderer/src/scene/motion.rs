//! How an object's reference point moves through the lab: uniformly along a
//! straight worldline, through keyframes, or under constant proper
//! acceleration (paper 3.1, and the curved temporal extrusions of paper 6).

use super::{Fault, HyperbolicField as H, SceneErrorKind as K, SceneField};
use crate::math;
use crate::spacetime::{Event, FourVector};
use glam::DVec3;

/// How an object's reference point moves through the lab.
#[derive(Clone, Debug, PartialEq)]
pub enum Motion {
    /// From event `start` along the lab-frame 4-vector `extrusion`
    /// (paper 3.1: dt is the lab lifetime, dx the distance travelled in it).
    Extrusion {
        /// Where and when the reference point starts.
        start: Event,
        /// Lab 4-vector from the start to the end.
        extrusion: FourVector,
    },
    /// From event `start` with lab velocity `velocity`, for `proper_lifetime`
    /// of the object's own time. With the Lorentz transform on, a V_obj
    /// lives gamma * proper_lifetime in the lab; otherwise proper_lifetime.
    Velocity {
        /// Where and when the reference point starts.
        start: Event,
        /// Lab velocity (fraction of c).
        velocity: DVec3,
        /// Lifetime in the object's own time.
        proper_lifetime: f64,
    },
    /// Through keyframes at increasing lab times, straight between
    /// consecutive ones (paper 6, curved temporal extrusions): covers
    /// acceleration, rotation and deformation. The object exists from the
    /// first keyframe to the last.
    Keyframes(Vec<Keyframe>),
    /// Constant proper acceleration, generated into keyframes within its
    /// stated tolerance.
    Hyperbolic(Hyperbolic),
}

impl Motion {
    /// At rest at `position` for lab times [t0, t1].
    pub fn at_rest(position: DVec3, t0: f64, t1: f64) -> Motion {
        Motion::Extrusion {
            start: Event::new(t0, position),
            extrusion: FourVector::new(t1 - t0, DVec3::ZERO),
        }
    }

    /// The start event and lab velocity, for uniform motion.
    pub fn uniform(&self) -> Option<(Event, DVec3)> {
        match self {
            Motion::Extrusion { start, extrusion } => Some((*start, extrusion.velocity())),
            Motion::Velocity {
                start, velocity, ..
            } => Some((*start, *velocity)),
            Motion::Keyframes(_) | Motion::Hyperbolic(_) => None,
        }
    }

    /// Lab velocity, for uniform motion.
    pub fn velocity(&self) -> Option<DVec3> {
        match self {
            Motion::Extrusion { extrusion, .. } => Some(extrusion.velocity()),
            Motion::Velocity { velocity, .. } => Some(*velocity),
            Motion::Keyframes(_) | Motion::Hyperbolic(_) => None,
        }
    }
}

/// The object at one lab time.
#[derive(Clone, Debug, PartialEq)]
pub struct Keyframe {
    /// Lab time, t.units.
    pub t: f64,
    /// Lab position of the reference point, l.units.
    pub position: DVec3,
    /// Vertex positions relative to the reference point, rest-frame
    /// dimensions for a V_obj (turned or deformed mesh); `None` keeps the
    /// mesh's own vertices.
    pub offsets: Option<Vec<DVec3>>,
}

/// Constant proper acceleration along a straight line (hyperbolic motion).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyperbolic {
    /// Where and when the reference point starts.
    pub start: Event,
    /// Unit direction of the acceleration.
    pub direction: DVec3,
    /// Proper acceleration of the reference point, 1/l.units (c = 1).
    pub acceleration: f64,
    /// Lab velocity of the reference point at the start, along `direction`
    /// (negative: first moving against the acceleration).
    pub initial_velocity: f64,
    /// Lab time the motion lasts, t.units.
    pub duration: f64,
    /// Largest allowed lab distance, l.units, between any point of the
    /// object's generated surface and its exact position (a vertex's
    /// polyline and its hyperbola; for a Born-rigid V_obj every point of
    /// its curved surface too).
    pub tolerance: f64,
}

/// Most keyframes a hyperbolic motion may be cut into.
pub(crate) const MAX_KEYFRAMES: usize = 100_000;

impl Hyperbolic {
    /// Rapidity at the start, phi0 = atanh(initial_velocity).
    pub fn initial_rapidity(&self) -> f64 {
        math::atanh(self.initial_velocity)
    }

    /// The reference point's position along `direction` at lab time `t`,
    /// relative to the start, for a point whose rest-frame offset along the
    /// direction is `xi` (Born-rigid) or whose lab offset is fixed (`xi` = 0):
    /// on the hyperbola S^2 - T^2 = A^2 about the common centre, with
    /// A = 1/a + xi, S = s + cosh(phi0)/a and T = t - t0 + sinh(phi0)/a.
    pub fn along(&self, xi: f64, t: f64) -> f64 {
        let a = self.acceleration;
        let phi0 = self.initial_rapidity();
        let big_t = t - self.start.t + math::sinh(phi0) / a;
        math::hypot(1.0 / a + xi, big_t) - math::cosh(phi0) / a
    }

    /// The reference point's proper time at lab time `t`:
    /// tau = (asinh(a T) - phi0) / a.
    pub fn proper_time(&self, t: f64) -> f64 {
        let a = self.acceleration;
        let phi0 = self.initial_rapidity();
        (math::asinh(a * (t - self.start.t) + math::sinh(phi0)) - phi0) / a
    }

    /// Rapidity at lab time `t`: phi = asinh(a (t - t0) + sinh(phi0)), so
    /// that sinh(phi) = a T and the lab speed is tanh(phi).
    pub fn rapidity(&self, t: f64) -> f64 {
        math::asinh(self.acceleration * (t - self.start.t) + math::sinh(self.initial_rapidity()))
    }

    /// The lab time at which the reference point's proper time since the
    /// start is `tau` (the inverse of [`Hyperbolic::proper_time`]):
    /// t = t0 + (sinh(a tau + phi0) - sinh(phi0)) / a.
    pub fn lab_time(&self, tau: f64) -> f64 {
        let a = self.acceleration;
        let phi0 = self.initial_rapidity();
        self.start.t + (math::sinh(a * tau + phi0) - math::sinh(phi0)) / a
    }

    /// The reference point's event and lab velocity at lab time `t`: on
    /// the hyperbola ([`Hyperbolic::along`] with xi = 0), moving at
    /// dS/dt = T / sqrt(1/a^2 + T^2) = tanh(phi) along the direction.
    pub fn event_at(&self, t: f64) -> (Event, DVec3) {
        let x = self.start.x + self.direction * self.along(0.0, t);
        let a = self.acceleration;
        let a_big_t = a * (t - self.start.t) + math::sinh(self.initial_rapidity());
        let speed = a_big_t / math::hypot(1.0, a_big_t);
        (Event::new(t, x), self.direction * speed)
    }

    /// Rejects a motion that cannot be generated; the error names the field.
    pub(crate) fn validate(&self) -> Result<(), Fault> {
        let bad = |f: H, k: K| Err(Fault::new(SceneField::Hyperbolic(f), k));
        if !self.start.is_finite() {
            return bad(H::Start, K::NotFinite);
        }
        if !(self.direction.is_finite() && (self.direction.length() - 1.0).abs() < 1e-9) {
            return bad(H::Direction, K::NotUnit);
        }
        if !(self.acceleration > 0.0 && self.acceleration.is_finite()) {
            return bad(H::Acceleration, K::AccelerationNotPositive);
        }
        if self.initial_velocity.is_nan() || self.initial_velocity.abs() >= 1.0 {
            return bad(H::InitialVelocity, K::InitialVelocity);
        }
        if !(self.duration > 0.0 && self.duration.is_finite()) {
            return bad(H::Duration, K::Duration);
        }
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return bad(H::Tolerance, K::Tolerance);
        }
        Ok(())
    }
}
