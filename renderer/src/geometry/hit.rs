//! What a ray meets, and which of two hits is seen.

use crate::spacetime::Event;

/// Which primitive of the database a hit is on. The order (prisms, then
/// tetrahedra, then spheres, each by index) breaks ties between hits the
/// same way in every traversal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum PrimitiveId {
    /// The prism of a triangle over a translation (uniform motion), tested
    /// whole as the triangle at rest in the comoving frame, by index in
    /// [`crate::Database::prism`].
    Prism(u32),
    /// A tetrahedron of a prism over a keyframe interval (which may turn or
    /// deform the triangle), by index in [`crate::Database::tetrahedra`]:
    /// piece `i % 3` of prism `i / 3`.
    Tetrahedron(u32),
    /// An analytic sphere, by index among the database's spheres.
    Sphere(u32),
}

impl PrimitiveId {
    /// The prism of a mesh's triangle the primitive is, or is a piece of.
    pub fn prism(self) -> Option<u32> {
        match self {
            PrimitiveId::Prism(p) => Some(p),
            PrimitiveId::Tetrahedron(i) => Some(i / 3),
            PrimitiveId::Sphere(_) => None,
        }
    }
}

/// Where a point lies in the primitive it is on: barycentric coordinates
/// over its corners.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize), serde(untagged))]
pub enum Barycentric {
    /// Over the corners of a prism's triangle where the triangle is at the
    /// point's lab time ([`crate::Database::triangle_at`]).
    Triangle([f64; 3]),
    /// Over the four corners of a tetrahedron.
    Tetrahedron([f64; 4]),
    /// None: an analytic sphere has no corners.
    Sphere,
}

impl Barycentric {
    /// The coordinates, one per corner.
    pub fn coordinates(&self) -> &[f64] {
        match self {
            Barycentric::Triangle(b) => b,
            Barycentric::Tetrahedron(b) => b,
            Barycentric::Sphere => &[],
        }
    }
}

/// A ray meeting a primitive of the database.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter: spatial distance from the ray's origin.
    pub s: f64,
    /// Where the ray meets the primitive.
    pub event: Event,
    /// The primitive met.
    pub primitive: PrimitiveId,
    /// Barycentric coordinates of `event` in the primitive, each in [0, 1],
    /// summing to 1 (none for a sphere).
    pub bary: Barycentric,
    /// Where the database keeps the comoving triangle of the translated
    /// prism met, the one its exact test has just read: the surface's
    /// normal is read there rather than looked up by the prism's index
    /// (a lookup that misses the cache once a hit). [`Hit::NOT_STORED`]
    /// for any other primitive.
    pub(crate) stored: u32,
}

impl Hit {
    /// [`Hit::stored`] of a primitive other than a translated prism.
    pub(crate) const NOT_STORED: u32 = u32::MAX;
}

/// Why a prism or tetrahedron was not hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Miss {
    /// The ray is parallel to the tetrahedron's hyperplane, or lies in the
    /// plane of the prism's triangle in the comoving frame.
    Parallel,
    /// The hyperplane (the triangle's plane) is met outside the searched
    /// stretch of the ray.
    OutOfRange {
        /// Ray parameter where the hyperplane is met.
        s: f64,
    },
    /// The hyperplane (the triangle's plane) is met outside the primitive.
    Outside {
        /// Ray parameter where the hyperplane is met.
        s: f64,
        /// Barycentric coordinates there, one of them negative.
        bary: Barycentric,
    },
    /// The prism's triangle is crossed before or after the prism's lab times.
    OutOfSpan {
        /// Ray parameter of the crossing.
        s: f64,
        /// Its lab time.
        t: f64,
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
