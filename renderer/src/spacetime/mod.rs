//! Flat spacetime in natural units (c = 1): events, 4-vectors, straight
//! worldlines, and the Lorentz boosts between an object's rest frame and
//! the lab (paper 2.1 and 3, item 2).

mod boost;
mod event;
mod ray;
mod schwarzschild;
mod waypoints;

pub use boost::Boost;
pub(crate) use event::Worldline;
pub use event::{Event, FourVector};
pub use ray::{LightSpeed, Ray};
pub use schwarzschild::{
    Geodesic, Leg, Schwarzschild, Spacetime, CHORD_TOLERANCE, MAX_CHORDS, SKY_TOLERANCE,
};
pub use waypoints::{Waypoint, WaypointWindow, MAX_WINDOW_WAYPOINTS};

use glam::DVec3;

/// The Lorentz factor gamma = 1 / sqrt(1 - |v|^2) of lab velocity `velocity`
/// (paper eq. 2); NaN or infinite at and above light speed.
#[inline]
pub fn gamma(velocity: DVec3) -> f64 {
    lorentz_factor(velocity.length_squared())
}

/// The Lorentz factor from the squared speed `b2`.
#[inline]
pub(crate) fn lorentz_factor(b2: f64) -> f64 {
    1.0 / (1.0 - b2).sqrt()
}
