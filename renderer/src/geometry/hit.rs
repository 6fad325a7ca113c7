//! What a ray meets, and which of two hits is seen.

use crate::spacetime::Event;

/// A ray meeting a tetrahedron.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter: spatial distance from the ray's origin.
    pub s: f64,
    /// Where the ray meets the tetrahedron.
    pub event: Event,
    /// Index of the tetrahedron in the database.
    pub tet: u32,
    /// Barycentric coordinates of `event` in the tetrahedron, each in [0, 1], summing to 1.
    pub bary: [f64; 4],
}

/// Why a tetrahedron was not hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Miss {
    /// The ray is parallel to the tetrahedron's hyperplane.
    Parallel,
    /// The hyperplane is met outside the searched stretch of the ray.
    OutOfRange { s: f64 },
    /// The hyperplane is met outside the tetrahedron.
    Outside { s: f64, bary: [f64; 4] },
}

/// The better of two hits: the smaller ray parameter, that is the most
/// recent event on a light-cone ray (paper 3, item 4); ties go to the lower
/// tetrahedron index so that every traversal order picks the same hit.
pub fn nearer(a: Option<Hit>, b: Hit) -> Hit {
    match a {
        Some(a) if (a.s, a.tet) <= (b.s, b.tet) => a,
        _ => b,
    }
}
