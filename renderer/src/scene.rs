//! The scene as given: 3D objects with their motion and materials, a light
//! and a background. [`crate::database::Database::build`] turns it into the
//! static 4D database.

use crate::keyframe::{Hyperbolic, Keyframe};
use crate::mesh::Mesh;
use crate::shade::{Light, Material};
use crate::spacetime::{Event, FourVector};
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

/// How an object's reference point moves through the lab.
#[derive(Clone, Debug, PartialEq)]
pub enum Motion {
    /// From event `start` along the lab-frame 4-vector `extrusion`
    /// (paper 3.1: dt is the lab lifetime, dx the distance travelled in it).
    Extrusion { start: Event, extrusion: FourVector },
    /// From event `start` with lab velocity `velocity`, for `proper_lifetime`
    /// of the object's own time. With the Lorentz transform on, a V_obj
    /// lives gamma * proper_lifetime in the lab; otherwise proper_lifetime.
    Velocity {
        start: Event,
        velocity: DVec3,
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
