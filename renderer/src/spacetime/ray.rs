//! Light rays: straight lines of spacetime along which light reaches an
//! event, on its past light cone (c = 1) or, for infinitely fast light, in
//! its slice of constant time (paper 3, item 3).

use super::{Event, FourVector};
use glam::DVec3;
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};

/// How fast light travels between events (paper 4.1.5, Figure 1 top band).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
pub enum LightSpeed {
    /// Conventional ray tracing: every ray stays in the slice t = const.
    Infinite,
    /// c = 1: rays lie on past light cones.
    Finite,
}

/// A straight line of spacetime, `origin + s * direction`, s >= 0.
/// The direction's spatial part is a unit vector, so `s` is the spatial
/// distance travelled; its time part is -1 for light at c = 1 (past-directed,
/// null) and 0 for infinitely fast light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// The event light arrives at.
    pub origin: Event,
    /// Spatial part a unit vector towards where the light came from.
    pub direction: FourVector,
}

impl Ray {
    /// The ray along which light reaches `origin` from spatial direction
    /// `towards` (unit vector), under the given light speed.
    pub fn backwards(origin: Event, towards: DVec3, light: LightSpeed) -> Ray {
        let t = match light {
            LightSpeed::Infinite => 0.0,
            LightSpeed::Finite => -1.0,
        };
        Ray {
            origin,
            direction: FourVector::new(t, towards),
        }
    }

    /// The event at ray parameter `s`.
    pub fn at(&self, s: f64) -> Event {
        self.origin + self.direction * s
    }

    /// The direction scaled to Euclidean unit length in 4D; for a light-cone
    /// ray its t component is -sqrt(2)/2 (paper 2.1).
    pub fn normalized_direction(&self) -> FourVector {
        let len = self.direction.to_xyzt().length();
        self.direction * (1.0 / len)
    }
}
