//! First-principles expectations, computed without the ray tracer: where
//! points are seen on the camera's past light cone ([`seen`]), the
//! kinematics of special relativity and of Galilean addition
//! ([`kinematics`]), the quadratic solver both rest on ([`quadratic`]),
//! extremes over a body's outline or a closed curve ([`extremes`]), the point of an edge
//! seen at a given place ([`crossing`]), when a point is seen crossing an
//! azimuth ([`azimuth`]), light reflected by a moving
//! mirror ([`mirror`]), light bent by a mass at rest
//! ([`schwarzschild`]), and what an accelerating camera sees ([`rocket`],
//! and its worldline through keyframes, [`keyframed`]).
//!
//! Nothing here calls the ray tracer: each formula is written out so that
//! an error in the tracer's own cannot cancel.

pub mod azimuth;
pub mod crossing;
pub mod extremes;
pub mod keyframed;
pub mod kinematics;
pub mod mirror;
pub mod quadratic;
pub mod rocket;
pub mod schwarzschild;
pub mod seen;

pub use azimuth::{seen_at_azimuth, AzimuthCrossing, AzimuthMiss};
pub use crossing::first_root;
pub use extremes::{extremes_on_loop, extremes_on_polygon};
pub use kinematics::{
    aberrate_galilean, aberrate_lorentz, contract, doppler_factor, gamma, gamma_of_squared,
    to_frame_of,
};
pub use quadratic::quadratic_roots;
pub use seen::{
    body_point, instantaneous, retarded, retarded_hyperbolic, retarded_polyline, PointHyperbola,
    PointPolyline, PointWorldline, Retarded,
};
