//! What a ray meets, and which of two hits is seen.

use crate::spacetime::Event;

/// Which primitive of the database a hit is on. Tetrahedra order before
/// spheres, so that ties between hits go the same way in every traversal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum PrimitiveId {
    /// A tetrahedron, by index in [`crate::Database::tetrahedra`].
    Tetrahedron(u32),
    /// An analytic sphere, by index among the database's spheres.
    Sphere(u32),
}

impl PrimitiveId {
    /// The tetrahedron's index, if it is one.
    pub fn tetrahedron(self) -> Option<u32> {
        match self {
            PrimitiveId::Tetrahedron(i) => Some(i),
            PrimitiveId::Sphere(_) => None,
        }
    }
}

/// A ray meeting a primitive of the database.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter: spatial distance from the ray's origin.
    pub s: f64,
    /// Where the ray meets the tetrahedron.
    pub event: Event,
    /// The primitive met.
    pub primitive: PrimitiveId,
    /// Barycentric coordinates of `event` in the tetrahedron, each in [0, 1], summing to 1.
    pub bary: [f64; 4],
}

/// Why a tetrahedron was not hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Miss {
    /// The ray is parallel to the tetrahedron's hyperplane.
    Parallel,
    /// The hyperplane is met outside the searched stretch of the ray.
    OutOfRange {
        /// Ray parameter where the hyperplane is met.
        s: f64,
    },
    /// The hyperplane is met outside the tetrahedron.
    Outside {
        /// Ray parameter where the hyperplane is met.
        s: f64,
        /// Barycentric coordinates there, one of them negative.
        bary: [f64; 4],
    },
}

/// The better of two hits: the smaller ray parameter, that is the most
/// recent event on a light-cone ray (paper 3, item 4); ties go to the lower
/// primitive so that every traversal order picks the same hit.
pub fn nearer(a: Option<Hit>, b: Hit) -> Hit {
    match a {
        Some(a) if (a.s, a.primitive) <= (b.s, b.primitive) => a,
        _ => b,
    }
}
