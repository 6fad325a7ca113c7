//! Events and 4-vectors of flat spacetime in natural units (c = 1).
//!
//! Coordinates are lab-frame (t, x, y, z): right-handed, y up, the stage in
//! the x-z plane (paper 2.1). The metric signature used for intervals is
//! (-, +, +, +): a null (light-like) displacement has interval zero.

use glam::{DVec3, DVec4};
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};
use std::ops::{Add, Mul, Neg, Sub};

/// A point of spacetime: lab time `t` and lab position `x` (paper 2.1).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
pub struct Event {
    /// Lab-frame time, t.units.
    pub t: f64,
    /// Lab-frame position, l.units.
    pub x: DVec3,
}

/// A displacement between two events (a 4-vector), lab frame.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
pub struct FourVector {
    /// Time component, t.units.
    pub t: f64,
    /// Spatial components, l.units.
    pub x: DVec3,
}

impl Event {
    /// The event at lab time `t` and lab position `x`.
    pub const fn new(t: f64, x: DVec3) -> Self {
        Self { t, x }
    }

    /// Packs the event as `(x, y, z, t)`: glam's `w` holds time.
    pub fn to_xyzt(self) -> DVec4 {
        self.x.extend(self.t)
    }

    /// Unpacks `(x, y, z, t)` as packed by `to_xyzt`.
    pub fn from_xyzt(v: DVec4) -> Self {
        Self {
            t: v.w,
            x: v.truncate(),
        }
    }

    /// Whether every component is finite.
    pub fn is_finite(self) -> bool {
        self.t.is_finite() && self.x.is_finite()
    }
}

impl FourVector {
    /// The 4-vector with time part `t` and spatial part `x`.
    pub const fn new(t: f64, x: DVec3) -> Self {
        Self { t, x }
    }

    /// Packs the 4-vector as `(x, y, z, t)`: glam's `w` holds time.
    pub fn to_xyzt(self) -> DVec4 {
        self.x.extend(self.t)
    }

    /// Unpacks `(x, y, z, t)` as packed by `to_xyzt`.
    pub fn from_xyzt(v: DVec4) -> Self {
        Self {
            t: v.w,
            x: v.truncate(),
        }
    }

    /// Minkowski interval |x|^2 - t^2: zero for light, negative inside the light cone.
    pub fn interval(self) -> f64 {
        self.x.length_squared() - self.t * self.t
    }

    /// Spatial velocity dx/dt of a worldline with this tangent (paper 3, item 2a).
    pub fn velocity(self) -> DVec3 {
        self.x / self.t
    }

    /// Whether every component is finite.
    pub fn is_finite(self) -> bool {
        self.t.is_finite() && self.x.is_finite()
    }
}

impl Sub for Event {
    type Output = FourVector;
    fn sub(self, rhs: Event) -> FourVector {
        FourVector::new(self.t - rhs.t, self.x - rhs.x)
    }
}

impl Add<FourVector> for Event {
    type Output = Event;
    fn add(self, rhs: FourVector) -> Event {
        Event::new(self.t + rhs.t, self.x + rhs.x)
    }
}

impl Add for FourVector {
    type Output = FourVector;
    fn add(self, rhs: FourVector) -> FourVector {
        FourVector::new(self.t + rhs.t, self.x + rhs.x)
    }
}

impl Sub for FourVector {
    type Output = FourVector;
    fn sub(self, rhs: FourVector) -> FourVector {
        FourVector::new(self.t - rhs.t, self.x - rhs.x)
    }
}

impl Mul<f64> for FourVector {
    type Output = FourVector;
    fn mul(self, k: f64) -> FourVector {
        FourVector::new(self.t * k, self.x * k)
    }
}

impl Neg for FourVector {
    type Output = FourVector;
    fn neg(self) -> FourVector {
        FourVector::new(-self.t, -self.x)
    }
}

/// A straight worldline: the reference point of an object starts at `start`
/// and moves along `extrusion` (paper 3.1: the velocity 4-vector whose `t`
/// is the object's lab lifetime). Positions of mesh vertices are given
/// relative to the reference point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
pub struct Worldline {
    /// Where and when the reference point starts.
    pub start: Event,
    /// The lab 4-vector from the start to the end of the worldline.
    pub extrusion: FourVector,
}

impl Worldline {
    /// Lab velocity dx/dt.
    pub fn velocity(&self) -> DVec3 {
        self.extrusion.velocity()
    }

    /// Where and when the reference point ends.
    pub fn end(&self) -> Event {
        self.start + self.extrusion
    }

    /// Lab position of the reference point at lab time `t` (extrapolated beyond the lifetime).
    pub fn position_at(&self, t: f64) -> DVec3 {
        self.start.x + self.velocity() * (t - self.start.t)
    }
}
