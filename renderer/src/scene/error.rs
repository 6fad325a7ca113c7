//! Why a scene cannot be inserted into the database: the object, the part
//! of its description at fault, and what is wrong, as data. The fixture
//! layer turns the field into a location in its file.

use super::MeshError;
use std::fmt;

/// A scene that cannot be inserted.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// Index of the object in the scene.
    pub object: usize,
    /// The object's name.
    pub name: String,
    /// The part of the object's description at fault.
    pub field: SceneField,
    /// What is wrong.
    pub kind: SceneErrorKind,
}

/// The part of an object's description an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneField {
    /// Its mesh or analytic sphere.
    Shape,
    /// Its motion as a whole.
    Motion,
    /// The start event of uniform or hyperbolic motion.
    Start,
    /// The lab 4-vector of a straight temporal extrusion.
    Extrusion,
    /// The velocity of motion given by velocity.
    Velocity,
    /// The proper lifetime of motion given by velocity.
    ProperLifetime,
    /// The keyframe list as a whole.
    Keyframes,
    /// One keyframe (or, after generation, one pose) by index.
    Keyframe(usize),
    /// The lab time of a keyframe.
    KeyframeTime(usize),
    /// The reference point's position at a keyframe.
    KeyframePosition(usize),
    /// The vertex list of a keyframe.
    KeyframeVertices(usize),
    /// One vertex of a keyframe.
    KeyframeVertex {
        /// Index of the keyframe.
        keyframe: usize,
        /// Index of the vertex.
        vertex: usize,
    },
    /// A parameter of hyperbolic motion.
    Hyperbolic(HyperbolicField),
}

/// A parameter of [`super::Hyperbolic`] motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HyperbolicField {
    /// The start event.
    Start,
    /// The direction of the acceleration.
    Direction,
    /// The proper acceleration.
    Acceleration,
    /// The initial velocity.
    InitialVelocity,
    /// The lab duration.
    Duration,
    /// The polyline tolerance.
    Tolerance,
}

/// What is wrong with a scene object.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneErrorKind {
    /// The mesh cannot be extruded.
    Mesh(MeshError),
    /// The mesh degenerates under Lorentz contraction.
    ContractedMesh(MeshError),
    /// The mesh degenerates at one pose (lab time `t`).
    PoseMesh {
        /// Lab time of the pose.
        t: f64,
        /// What is wrong with the mesh there.
        error: MeshError,
    },
    /// A triangle extrudes to a tetrahedron with no 3-volume.
    FlatTetrahedron {
        /// Index of the triangle in the mesh.
        triangle: u32,
    },
    /// An analytic sphere's radius is not a positive length.
    SphereRadius(f64),
    /// A triangle naming a material the object does not have.
    MaterialIndex {
        /// Index of the triangle in the mesh.
        triangle: usize,
        /// The material index it gives.
        index: u32,
        /// How many materials the object has (`material` and its
        /// `face_materials`).
        materials: usize,
    },
    /// An analytic sphere was given non-uniform motion.
    SphereNotUniform,
    /// The velocity of uniform motion is not finite.
    VelocityNotFinite,
    /// A V_obj at or above light speed.
    VObjTooFast {
        /// Its speed, fraction of c.
        speed: f64,
    },
    /// Non-finite numbers.
    NotFinite,
    /// A temporal extrusion of zero duration.
    ZeroDuration,
    /// A proper lifetime that is not a positive finite time.
    ProperLifetime,
    /// Fewer than two keyframes.
    TooFewKeyframes(usize),
    /// A keyframe's time or position is not finite.
    KeyframeNotFinite,
    /// A keyframe not after the one before.
    KeyframesOutOfOrder {
        /// Its time.
        t: f64,
        /// The time of the keyframe before.
        previous: f64,
    },
    /// A keyframe's vertex list does not match the mesh.
    VertexCount {
        /// Vertices given.
        given: usize,
        /// Vertices of the mesh.
        mesh: usize,
    },
    /// A V_obj's reference point at or above light speed at a keyframe.
    KeyframeTooFast {
        /// Its speed, fraction of c.
        speed: f64,
    },
    /// A V_obj's vertex at or above light speed between two poses.
    VertexTooFast {
        /// Index of the vertex.
        vertex: usize,
        /// Its speed, fraction of c.
        speed: f64,
        /// Lab times of the two poses.
        between: (f64, f64),
    },
    /// A V_obj's reference point at or above light speed over a stretch.
    StretchTooFast {
        /// Its speed, fraction of c.
        speed: f64,
    },
    /// The direction of hyperbolic motion is not a unit vector.
    NotUnit,
    /// The proper acceleration is not positive and finite.
    AccelerationNotPositive,
    /// The initial velocity is not below light speed.
    InitialVelocity,
    /// The duration is not a positive finite lab time.
    Duration,
    /// The tolerance is not a positive finite length.
    Tolerance,
    /// A Born-rigid body reaching beyond its Rindler horizon.
    BeyondHorizon {
        /// The proper acceleration of the reference point.
        acceleration: f64,
        /// How far behind the reference point the body reaches.
        behind: f64,
    },
    /// The tolerance would take too many keyframes.
    TooManyKeyframes {
        /// The tolerance asked for.
        tolerance: f64,
        /// The keyframes it would take.
        count: f64,
        /// The most allowed.
        max: usize,
    },
    /// A Born-rigid vertex too near its Rindler horizon for the curved
    /// surface to be cut within the tolerance.
    NearHorizon {
        /// The tolerance asked for.
        tolerance: f64,
        /// How far in front of the horizon the vertex is (its 1/a + xi).
        ahead: f64,
        /// The tolerance below which it is allowed.
        limit: f64,
    },
    /// Cutting a Born-rigid surface within the tolerance would add too
    /// many triangles.
    TooManyPieces {
        /// The tolerance asked for.
        tolerance: f64,
        /// The triangles it would add.
        count: u64,
        /// The most allowed.
        max: usize,
    },
}

impl fmt::Display for SceneErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use SceneErrorKind as K;
        match self {
            K::Mesh(e) => write!(f, "{e}"),
            K::ContractedMesh(e) => write!(f, "after Lorentz contraction: {e}"),
            K::PoseMesh { t, error } => write!(f, "at t = {t}: {error}"),
            K::FlatTetrahedron { triangle } => write!(f, "triangle {triangle} extrudes to a tetrahedron with no 3-volume"),
            K::SphereRadius(r) => write!(f, "sphere radius {r}: expected a positive length"),
            K::MaterialIndex { triangle, index, materials } => write!(f, "triangle {triangle} names material {index}; the object has {materials} (0 to {})", materials - 1),
            K::SphereNotUniform => write!(f, "an analytic sphere moves uniformly (extrusion or velocity); give a tessellated sphere keyframes or hyperbolic motion"),
            K::VelocityNotFinite => write!(f, "the velocity is not finite (zero-duration extrusion?)"),
            K::VObjTooFast { speed } => write!(f, "a V_obj moves at {speed:.6}c; it must be slower than light (use an H_obj for a Lorentz-decoupled, superluminal object)"),
            K::NotFinite => write!(f, "must be finite numbers"),
            K::ZeroDuration => write!(f, "zero-duration extrusion (dt = 0): the object would exist for no time"),
            K::ProperLifetime => write!(f, "must be a positive finite time"),
            K::TooFewKeyframes(n) => write!(f, "{n} keyframe(s): at least 2 are needed"),
            K::KeyframeNotFinite => write!(f, "t and position must be finite numbers"),
            K::KeyframesOutOfOrder { t, previous } => write!(f, "keyframes out of time order: t = {t} follows t = {previous}"),
            K::VertexCount { given, mesh } => write!(f, "{given} vertices given; the mesh has {mesh}"),
            K::KeyframeTooFast { speed } => write!(f, "a V_obj's reference point moves at {speed:.6}c here; it must be slower than light"),
            K::VertexTooFast { vertex, speed, between } => write!(f, "vertex {vertex} of a V_obj moves at {speed:.6}c between t = {} and t = {}; a V_obj's vertices must be slower than light (use an H_obj for a Lorentz-decoupled object)", between.0, between.1),
            K::StretchTooFast { speed } => write!(f, "the reference point moves at {speed:.6}c; a V_obj must be slower than light"),
            K::NotUnit => write!(f, "must be a unit vector (the acceleration's direction)"),
            K::AccelerationNotPositive => write!(f, "must be a positive proper acceleration (1/l.units); for uniform motion use a velocity worldline"),
            K::InitialVelocity => write!(f, "must be slower than light (|v| < 1)"),
            K::Duration => write!(f, "must be a positive finite lab time"),
            K::Tolerance => write!(f, "must be a positive finite length"),
            K::BeyondHorizon { acceleration, behind } => write!(f, "a Born-rigid object under proper acceleration {acceleration} must lie within 1/a = {} behind its reference point (the Rindler horizon); a vertex is {behind} behind it", 1.0 / acceleration),
            K::TooManyKeyframes { tolerance, count, max } => write!(f, "tolerance {tolerance} would take {count} keyframes (at most {max}); loosen it"),
            K::NearHorizon { tolerance, ahead, limit } => write!(f, "a Born-rigid vertex {ahead} l.units in front of its Rindler horizon is too near it for the curved surface to be kept within tolerance {tolerance}; a tolerance below {limit} allows it"),
            K::TooManyPieces { tolerance, count, max } => write!(f, "tolerance {tolerance} would cut the Born-rigid surface into {count} more triangles (at most {max}); loosen it"),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "object {:?}: {}", self.name, self.kind)
    }
}

impl std::error::Error for SceneError {}

/// A fault found below the object level: the field and what is wrong,
/// before the object is known.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Fault {
    pub(crate) field: SceneField,
    pub(crate) kind: SceneErrorKind,
}

impl Fault {
    /// The fault at `field`.
    pub(crate) fn new(field: SceneField, kind: SceneErrorKind) -> Fault {
        Fault { field, kind }
    }

    /// The fault as an error of object `object` named `name`.
    pub(crate) fn of(self, object: usize, name: &str) -> SceneError {
        SceneError {
            object,
            name: name.to_string(),
            field: self.field,
            kind: self.kind,
        }
    }
}
