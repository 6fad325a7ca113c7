//! The scene as given: 3D objects with their motion and materials, a light
//! and a background. [`crate::Database::build`] turns it into the
//! static 4D database.

mod material;
mod mesh;
mod motion;

pub use material::{Blink, Light, Material};
pub use mesh::{Mesh, MeshError};
pub(crate) use motion::MAX_KEYFRAMES;
pub use motion::{Hyperbolic, Keyframe, Motion};

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The two object classes of paper 3.1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum ObjectKind {
    /// Lorentz-decoupled: the mesh is already in lab-frame dimensions and is
    /// inserted as is. May be superluminal.
    #[serde(rename = "H_obj")]
    HObj,
    /// Given in rest-frame dimensions plus a lab velocity; Lorentz-transformed
    /// on insertion (contraction along the velocity, dilation of its clock).
    /// Must be slower than light.
    #[serde(rename = "V_obj")]
    VObj,
}

/// One 3D object of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneObject {
    pub name: String,
    pub kind: ObjectKind,
    /// Triangles relative to the reference point; rest-frame dimensions for a V_obj.
    pub mesh: Mesh,
    /// When set, the object is instead an analytic sphere of this (rest-frame)
    /// radius centred on the reference point, and `mesh` is ignored.
    pub sphere: Option<f64>,
    pub motion: Motion,
    pub material: Material,
}

/// Everything in the lab: objects, the one point light (at rest), and the
/// colour seen where a ray meets nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub objects: Vec<SceneObject>,
    pub light: Light,
    pub background: DVec3,
}
