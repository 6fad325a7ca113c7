//! The scene as given: 3D objects with their motion and materials, a light
//! and a background. [`crate::Database::build`] turns it into the
//! static 4D database.

mod error;
mod material;
mod mesh;
mod motion;
mod obj;
mod texture;

pub(crate) use error::Fault;
pub use error::{HyperbolicField, SceneError, SceneErrorKind, SceneField};
pub use material::{Blink, Light, Material};
pub use mesh::{Mesh, MeshError};
pub(crate) use motion::MAX_KEYFRAMES;
pub use motion::{Hyperbolic, Keyframe, Motion};
pub(crate) use texture::SurfacePoint;
pub use texture::{Axes, Texels, Texture, UvMapping};

/// The mesh of an object without one (an analytic sphere).
pub(crate) static NO_MESH: Mesh = Mesh {
    vertices: Vec::new(),
    triangles: Vec::new(),
    materials: Vec::new(),
};

use crate::spacetime::Spacetime;
use glam::DVec3;
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The two object classes of paper 3.1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
pub enum ObjectKind {
    /// Lorentz-decoupled: the mesh is already in lab-frame dimensions and is
    /// inserted as is. May be superluminal.
    #[cfg_attr(feature = "serde", serde(rename = "H_obj"))]
    HObj,
    /// Given in rest-frame dimensions plus a lab velocity; Lorentz-transformed
    /// on insertion (contraction along the velocity, dilation of its clock).
    /// Must be slower than light.
    #[cfg_attr(feature = "serde", serde(rename = "V_obj"))]
    VObj,
}

/// What an object is made of, relative to its reference point; rest-frame
/// dimensions for a V_obj.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// Triangles.
    Mesh(Mesh),
    /// An analytic sphere centred on the reference point.
    Sphere {
        /// Rest-frame radius, l.units.
        radius: f64,
    },
}

impl Shape {
    /// The radius of an analytic sphere.
    pub fn sphere_radius(&self) -> Option<f64> {
        match self {
            Shape::Sphere { radius } => Some(*radius),
            Shape::Mesh(_) => None,
        }
    }
}

/// One 3D object of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneObject {
    /// Name, unique in the scene.
    pub name: String,
    /// H_obj or V_obj.
    pub kind: ObjectKind,
    /// Its mesh or analytic sphere.
    pub shape: Shape,
    /// How its reference point moves.
    pub motion: Motion,
    /// Surface appearance: material 0, of every triangle unless its mesh
    /// gives it another ([`Mesh::materials`]), and of an analytic sphere.
    pub material: Material,
    /// Materials 1, 2, ... that a mesh's triangles may name
    /// ([`Mesh::materials`]); usually empty.
    pub face_materials: Vec<Material>,
}

/// Everything in the lab: objects, the one point light (at rest), and the
/// colour seen where a ray meets nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The objects.
    pub objects: Vec<SceneObject>,
    /// The one point light, at rest in the lab.
    pub light: Light,
    /// Colour where a ray meets nothing (when there is no `sky`).
    pub background: DVec3,
    /// An equirectangular image of the sky at infinity, in the lab's
    /// directions ([`Texels::toward`]): where a ray meets nothing, the
    /// direction its light came from at infinity shows this instead of the
    /// background colour.
    pub sky: Option<Arc<Texels>>,
    /// The spacetime light crosses: flat, or curved by a mass at rest.
    pub spacetime: Spacetime,
}
