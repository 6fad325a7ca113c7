//! Acceleration: which prisms a ray is tested against. Bounding volume
//! hierarchies over 4D boxes, in two levels (per stretch of an object's
//! path, and over all stretches). Never changes which hit is found.

mod bvh;
mod packet;
mod two_level;
mod wide;

pub(crate) use bvh::rounding_margin;
pub(crate) use packet::{Lanes, PACKET};
pub(crate) use two_level::{StretchPrisms, TwoLevel};
