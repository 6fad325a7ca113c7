//! A primary ray in curved spacetime: its null geodesic, traced backwards
//! from the camera event, cut into straight 4D chords; each chord is
//! searched in the flat database as a ray of limited length, in order from
//! the camera, so the first chord with a hit gives the most recent event
//! the light met, as one straight ray does in flat spacetime. Shadow and
//! mirror rays leaving the hit stay straight. An escaping ray shows the sky
//! in the direction its light came from at infinity
//! ([`Geodesic::asymptote`]: the bending still left beyond its last chord
//! followed out), the background colour being the same in every direction.

use super::carried::Carried;
use super::shader::{ray_step, Shader};
use crate::spacetime::{Geodesic, Leg, Ray, Schwarzschild};
use crate::trace::{RayKind, Step, Trace};
use glam::DVec3;

impl Shader<'_> {
    /// The colour `C` of the light arriving along the camera's `ray` (its
    /// direction in the frame of an observer at rest there) through the
    /// field of `hole`: the first hit along its chords, the background if
    /// it escapes, black if it came out of the hole.
    pub(super) fn bent<C: Carried, T: Trace>(
        &self,
        hole: &Schwarzschild,
        ray: &Ray,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        let reach = self.db.reach_from(hole.centre);
        let mut geodesic =
            Geodesic::backwards(hole, ray.origin, ray.direction.x, self.light_speed, reach);
        while let Some(Leg::Chord(chord, length)) = geodesic.next() {
            let range = (0.0, length);
            if T::ENABLED {
                trace.record(ray_step(RayKind::Primary, 0, &chord, range));
            }
            let hit = self.db.closest_hit_traced(&chord, range, trace);
            if hit.is_some() {
                return self.carry_hit(&chord, hit, 0, RayKind::Primary, band, trace);
            }
            if length == f64::INFINITY {
                if self.sky.is_none() {
                    return self.carry_hit(&chord, None, 0, RayKind::Primary, band, trace);
                }
                if let Some(toward) = geodesic.asymptote() {
                    return self.escaped(RayKind::Primary, toward, band, trace);
                }
                break;
            }
        }
        if T::ENABLED {
            trace.record(Step::Miss {
                kind: RayKind::Primary,
                background: DVec3::ZERO,
            });
        }
        C::ZERO
    }
}
