//! The 4D geometry of the database: temporal extrusion of triangles into
//! prisms of three tetrahedra (paper 3.1), keyframed and accelerated paths
//! resolved into poses (paper 6), and the ray tests: a translated prism
//! whole, as its triangle at rest in the comoving frame; the barycentric
//! solve against a tetrahedron (paper 3.2); and the analytic sphere.

mod born_rigid;
mod extrude;
mod filter;
mod hit;
mod poses;
mod sphere;
mod tetrahedron;
mod triangle;

pub(crate) use born_rigid::Pieces;
pub use extrude::Tetrahedron;
pub(crate) use extrude::{
    corner_order, corners_between, extrude_between, piece, Prism, PrismCorners,
};
pub(crate) use filter::{mesh_reach, CornerRows, FilterRay, LANES};
pub(crate) use hit::{nearer, Miss};
pub use hit::{Barycentric, Hit, PrimitiveId};
pub(crate) use poses::{resolve, Pose};
pub(crate) use sphere::Sphere;
pub(crate) use tetrahedron::PreparedTet;
pub(crate) use triangle::{comoving_line, intersect_prism, ComovingRay};
