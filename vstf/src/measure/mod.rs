//! Measuring an image: sub-pixel edges along scanlines ([`scan`]), mapped
//! back through an independent model of the camera ([`pinhole`]) to
//! positions on known planes or to directions, fitted along the edge
//! ([`fit`]), or as directions fitted by a circle on the sky ([`sky`]); and
//! colours turned back into chromaticities ([`colorimetry`]); areas and
//! centroids of regions of a colour ([`regions`]).
//!
//! Nothing here calls the ray tracer: a measurement that shared its
//! camera or colour code would cancel that code's errors instead of
//! revealing them. The camera model and the colorimetry are written from the
//! formulas and standards they implement.

pub mod colorimetry;
pub mod fit;
pub mod pinhole;
pub mod regions;
pub mod scan;
pub mod sky;

pub use fit::PolyFit;
pub use pinhole::{azimuth, elevation, Kinematics, Pinhole, Plane};
pub use scan::{color, color_of, edge, Pixels, Scan};
pub use sky::SkyCircle;
