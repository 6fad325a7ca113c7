//! A minimal spacetime ray tracer after Black et al., "Viewing Classical and
//! Relativistic Spacetime Geometry".
//!
//! Data flows one way:
//! scene ([`scene`], [`mesh`]) -> temporal extrusion ([`extrude`], with
//! [`boost`] for V_obj objects and [`keyframe`] for accelerated ones) -> static 4D database ([`database`], searched
//! through [`bvh`]) -> light-cone rays ([`lightcone`]) -> barycentric solve
//! ([`intersect`]) -> shading with shadow and mirror rays ([`shade`]; colour
//! effects of motion by [`doppler`] on [`spectrum`]s) ->
//! image ([`render`]).
//!
//! Natural units throughout (c = 1); events are lab-frame (t, x, y, z) in f64,
//! y up, the stage in the x-z plane.

pub mod boost;
pub mod bvh;
pub mod database;
pub mod doppler;
pub mod extrude;
pub mod intersect;
pub mod keyframe;
pub mod lightcone;
pub mod mesh;
pub mod model;
pub mod render;
pub mod rng;
pub mod scene;
pub mod shade;
pub mod spacetime;
pub mod spectrum;
pub mod trace;

pub use boost::Boost;
pub use database::{Database, SceneError, Surface, Traversal};
pub use doppler::Effects;
pub use extrude::{Prism, Tetrahedron};
pub use intersect::Hit;
pub use keyframe::{Hyperbolic, Keyframe};
pub use lightcone::{Attitude, Camera, Kinematics, LightSpeed, Ray};
pub use mesh::Mesh;
pub use model::Model;
pub use render::{render, Image, RenderSettings};
pub use scene::{Motion, ObjectKind, Scene, SceneObject};
pub use shade::{Light, Material};
pub use spacetime::{Event, FourVector, Worldline};
