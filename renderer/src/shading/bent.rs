//! A primary ray in curved spacetime: its null geodesic, traced backwards
//! from the camera event, cut into straight 4D chords; each chord is
//! searched in the flat database as a ray of limited length, in order from
//! the camera, so the first chord with a hit gives the most recent event
//! the light met, as one straight ray does in flat spacetime. The chords
//! stray from the geodesic by at most `CHORD_TOLERANCE` M, or where it is
//! more, an eighth of the footprint the pixel would have there in flat
//! spacetime (its angle times the arc from the camera); where the geodesic
//! passes clear of the box holding every object its steps are longer and
//! their chords, which can meet nothing, are not searched. Shadow and
//! mirror rays leaving the hit stay straight. An escaping ray shows the sky
//! in the direction its light came from at infinity
//! ([`Geodesic::asymptote`]: the bending still left beyond its last chord
//! followed out), the background colour being the same in every direction.
//!
//! With the colour effects on, the light climbing from the hit (or the
//! background or sky, at infinity) to the camera is shifted by the ratio of
//! the static observers' frequencies there, sqrt(f(r_e) / f(r_o)): the
//! spectrum is evaluated at the wavelengths the static observer at the
//! hit saw, and its radiance scaled with the searchlight, as across any
//! other leg (docs/physics.md, "Gravitational redshift").

use super::carried::Carried;
use super::doppler::Leg;
use super::shader::{ray_step, Shader};
use crate::geometry::Hit;
use crate::spacetime::{Geodesic, Leg as Piece, LightSpeed, Ray, Schwarzschild};
use crate::trace::{NoTrace, RayKind, Step, Trace};
use glam::DVec3;

/// Where a primary ray's search through a mass's field ended: the chord
/// that met something or escaped, or nothing (the light came out of the
/// hole, or the way out could not be followed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BentEnd {
    /// The chord searched last.
    Chord {
        /// The chord's ray: its origin the chord's later event.
        chord: Ray,
        /// Its closest hit (`None` on the last, infinite chord of an
        /// escaping ray).
        hit: Option<Hit>,
        /// Where the sky shows: the lab direction the light came from at
        /// infinity.
        toward: Option<DVec3>,
    },
    /// Black: captured, or lost on its way out to the sky.
    Dark,
}

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
        let end = self.bent_end(hole, ray, trace);
        self.bent_seen(hole, ray, &end, band, trace)
    }

    /// The chords of the geodesic along which light reaches `ray`'s origin.
    fn geodesic(&self, hole: &Schwarzschild, ray: &Ray) -> Geodesic {
        let reach = self.db.reach_from(hole.centre);
        let (lo, hi) = self.db.spatial_bounds();
        // The static observer's radial lengths are dr / sqrt(f): in the
        // coordinates the pixel's angle is at least sqrt(f) times its own.
        let angle = self.pixel_angle * hole.lapse_squared(ray.origin.x).max(0.0).sqrt();
        Geodesic::backwards(hole, ray.origin, ray.direction.x, self.light_speed, reach)
            .sized_to_pixel(angle)
            .with_geometry_in(lo, hi)
    }

    /// Where the search along `ray`'s chords ends, in order from the camera.
    fn bent_end<T: Trace>(&self, hole: &Schwarzschild, ray: &Ray, trace: &mut T) -> BentEnd {
        let mut geodesic = self.geodesic(hole, ray);
        while let Some(Piece::Chord(chord, length)) = geodesic.next() {
            if T::ENABLED {
                trace.record(ray_step(RayKind::Primary, 0, &chord, (0.0, length)));
            }
            if let Some(end) = self.chord_end(&mut geodesic, &chord, length, trace) {
                return end;
            }
        }
        BentEnd::Dark
    }

    /// Where the search ends on `chord` (`length` long) of `geodesic`,
    /// `None` where it goes on to the next.
    fn chord_end<T: Trace>(
        &self,
        geodesic: &mut Geodesic,
        chord: &Ray,
        length: f64,
        trace: &mut T,
    ) -> Option<BentEnd> {
        if geodesic.passed_clear() {
            return None;
        }
        let hit = self.db.closest_hit_traced(chord, (0.0, length), trace);
        if hit.is_none() && length < f64::INFINITY {
            return None;
        }
        let toward = match (hit, self.sky) {
            (None, Some(_)) => match geodesic.asymptote() {
                Some(toward) => Some(toward),
                None => return Some(BentEnd::Dark),
            },
            _ => None,
        };
        Some(BentEnd::Chord {
            chord: *chord,
            hit,
            toward,
        })
    }

    /// [`Shader::bent_end`] of each of `rays` (at most four) into `ends`,
    /// the same to the bit: their geodesics stepped side by side
    /// ([`Geodesic::next_each`]), each chord searched as it comes.
    pub(super) fn bent_ends(&self, hole: &Schwarzschild, rays: &[Ray], ends: &mut [BentEnd]) {
        let mut lanes: [Option<Geodesic>; 4] =
            std::array::from_fn(|j| rays.get(j).map(|ray| self.geodesic(hole, ray)));
        while lanes.iter().any(Option::is_some) {
            let legs = Geodesic::next_each(&mut lanes);
            for (j, leg) in legs.into_iter().enumerate() {
                let Some(geodesic) = &mut lanes[j] else {
                    continue;
                };
                let end = match leg {
                    Some(Piece::Chord(chord, length)) => {
                        self.chord_end(geodesic, &chord, length, &mut NoTrace)
                    }
                    _ => Some(BentEnd::Dark),
                };
                if let Some(end) = end {
                    ends[j] = end;
                    lanes[j] = None;
                }
            }
        }
    }

    /// The colour `C` seen along the camera's `ray` whose search through
    /// the field of `hole` ended at `end`.
    pub(super) fn bent_seen<C: Carried, T: Trace>(
        &self,
        hole: &Schwarzschild,
        ray: &Ray,
        end: &BentEnd,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        let &BentEnd::Chord { chord, hit, toward } = end else {
            if T::ENABLED {
                trace.record(Step::Miss {
                    kind: RayKind::Primary,
                    background: DVec3::ZERO,
                });
            }
            return C::ZERO;
        };
        let g = self.climb(hole, ray, hit.map(|h| h.event.x), trace);
        let at = C::emitted_band(band, g);
        let seen: C = match toward {
            Some(toward) => self.escaped(RayKind::Primary, toward, &at, trace),
            None => self.carry_hit(&chord, hit, 0, RayKind::Primary, &at, trace),
        };
        let factors = C::carries_factors(self.effects);
        seen.with_gain(factors.then(|| self.effects.intensity(g, Leg::Radiance)))
    }

    /// nu_camera_static / nu_emitter_static for light reaching the camera's
    /// event along `ray` from a static emitter at `from` (the background at
    /// infinity when `None`): sqrt(f(r_e) / f(r_o)), f = 1 - 2M/r
    /// ([`Schwarzschild::static_shift`]); 1 when the colour effects are off
    /// or light is instantaneous (as every Doppler factor is).
    fn climb<T: Trace>(
        &self,
        hole: &Schwarzschild,
        ray: &Ray,
        from: Option<DVec3>,
        trace: &mut T,
    ) -> f64 {
        if !self.effects.any() || self.light_speed == LightSpeed::Infinite {
            return 1.0;
        }
        let observer = ray.origin.x;
        let g = match from {
            Some(x) => hole.static_shift(x, observer),
            None => 1.0 / hole.lapse_squared(observer).sqrt(),
        };
        if T::ENABLED {
            trace.record(Step::Gravitational {
                emitter_r: from.map_or(f64::INFINITY, |x| (x - hole.centre).length()),
                observer_r: (observer - hole.centre).length(),
                factor: g,
            });
        }
        g
    }
}
