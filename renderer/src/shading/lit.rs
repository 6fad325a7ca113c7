//! The light at a hit: where the light is seen from the surface, whether
//! it is in shadow (a shadow ray on the past light cone), the Lambert and
//! Phong terms in the surface's frame, and the frequency ratios of the
//! light's leg and of the leg towards the ray's origin.

use super::doppler;
use super::frame::SurfaceFrame;
use super::shader::{ray_step, self_hit_margin, Shader};
use crate::database::Surface;
use crate::geometry::Hit;
use crate::math;
use crate::spacetime::{lorentz_factor, Event, LightSpeed, Ray, Spacetime};
use crate::trace::{NoTrace, RayKind, Trace};
use glam::DVec3;

/// What shading at a hit needs beyond the hit: the geometry of the light and
/// view, the shadow test, and the surface's motion for the colour effects.
pub(super) struct Lit {
    pub(super) object: u32,
    /// The triangle hit, which picks its material.
    pub(super) triangle: u32,
    pub(super) tau: f64,
    /// The texture's colour at the hit (`None` untextured).
    pub(super) texel: Option<DVec3>,
    pub(super) n: DVec3,
    pub(super) l: DVec3,
    pub(super) light_distance: f64,
    /// n . l, both in the surface's frame when it moves.
    pub(super) lambert: f64,
    /// For a moving surface under light cones: its facing normal, the
    /// direction towards the light and that towards the viewer, in its
    /// own frame (the directions shading uses).
    pub(super) surface_frame: Option<[DVec3; 3]>,
    pub(super) shadowed: bool,
    /// m.specular (r.v)^shininess, 0 in shadow.
    pub(super) specular: f64,
    /// Lab velocity of the surface and the gamma of its clock (1 when
    /// Lorentz-decoupled: classical Doppler).
    pub(super) velocity: DVec3,
    pub(super) gamma: f64,
    /// nu_surface / nu_lab for the light's leg, and nu_lab / nu_surface for
    /// the leg from the surface towards the ray's origin (1 when off).
    pub(super) from_light: f64,
    pub(super) out: f64,
}

impl Lit {
    /// Whether the surface faces the light (n . l > 0), or n . l is NaN: a
    /// NaN is shaded through, for the pixel's check to report, rather than
    /// dropped as unlit.
    pub(super) fn faces_light(&self) -> bool {
        self.lambert > 0.0 || self.lambert.is_nan()
    }
}

impl Shader<'_> {
    /// Whether the light source is hidden from `event`: the past light cone
    /// of the event, towards the light's (static) position, meets an object
    /// before reaching it. The blocker kept is the nearest (the most recent
    /// blocking event), so that it does not depend on the traversal.
    pub fn in_shadow(&self, event: Event) -> bool {
        self.in_shadow_traced(event, &mut NoTrace)
    }

    fn in_shadow_traced<T: Trace>(&self, event: Event, trace: &mut T) -> bool {
        let to_light = self.light.position - event.x;
        let dist = to_light.length();
        let shadow = Ray::backwards(event, to_light / dist, self.light_speed);
        let margin = self_hit_margin(event);
        if dist <= 2.0 * margin {
            return false;
        }
        let range = (margin, dist - margin);
        if T::ENABLED {
            trace.record(ray_step(RayKind::Shadow, 0, &shadow, range));
        }
        let blocker = self.db.closest_hit_traced(&shadow, range, trace);
        if T::ENABLED {
            if let Some(h) = &blocker {
                trace.record(self.hit_step(RayKind::Shadow, &shadow, h));
            }
        }
        blocker.is_some()
    }

    /// Whether light changes frequency between frames: the colour effects
    /// are on and light travels at a finite speed (every ratio of
    /// [`Shader::to_surface`] is 1 otherwise).
    pub(super) fn shifts_frequency(&self) -> bool {
        self.effects.any() && self.light_speed == LightSpeed::Finite
    }

    /// The frequency ratio between the lab and the frame of a surface
    /// at `at` moving with `velocity` (clock `gamma`) for light
    /// propagating along `k`: nu_surface / nu_lab; 1 when light is
    /// instantaneous or the effects are off. In a mass's field "the lab" is
    /// the observer at rest at `at`: the velocity and the light's direction
    /// are first taken into its frame ([`Schwarzschild::static_frame`]),
    /// and a Lorentz-transformed surface moving at light speed or faster
    /// there has no frame (0).
    ///
    /// [`Schwarzschild::static_frame`]: crate::Schwarzschild::static_frame
    pub(super) fn to_surface(&self, at: DVec3, velocity: DVec3, gamma: f64, k: DVec3) -> f64 {
        if !self.shifts_frequency() {
            return 1.0;
        }
        let Spacetime::Schwarzschild(hole) = &self.spacetime else {
            return doppler::to_frame(velocity, gamma, k);
        };
        let (u, k) = hole.static_frame(at, velocity, k);
        let b2 = u.length_squared();
        let lorentzian = gamma != 1.0;
        if lorentzian && b2 >= 1.0 {
            return 0.0;
        }
        let gamma = if lorentzian { lorentz_factor(b2) } else { 1.0 };
        doppler::to_frame(u, gamma, k)
    }

    /// The side of the surface hit that the ray's origin sees: its unit
    /// lab normal turned to that side, and the surface's frame (`None` at
    /// rest, under instantaneous light, or without a rest frame) with the
    /// normal turned the same way. The side is the one the light towards
    /// the origin leaves in the surface's own frame, where the local term
    /// is formed: n' . v' >= 0, v' the direction towards the viewer there
    /// (docs/physics.md, "Which side a moving surface shows"). A moving
    /// surface can show the side the lab would call hidden (n . v < 0);
    /// without a frame the side is the lab's, bit for bit.
    pub(super) fn facing(
        &self,
        ray: &Ray,
        surface: &Surface,
        velocity: DVec3,
    ) -> (DVec3, Option<SurfaceFrame>) {
        let n = surface.normal;
        let frame = match self.light_speed {
            LightSpeed::Finite => {
                let contracted = self.db.objects()[surface.object as usize].contracted;
                SurfaceFrame::of(n, velocity, contracted)
            }
            LightSpeed::Infinite => None,
        };
        let hidden = match &frame {
            Some(f) => f.normal().dot(f.propagation(-ray.direction.x.normalize())) < 0.0,
            None => n.dot(ray.direction.x) > 0.0,
        };
        if hidden {
            (-n, frame.map(SurfaceFrame::flipped))
        } else {
            (n, frame)
        }
    }

    pub(super) fn lit<T: Trace>(&self, ray: &Ray, hit: &Hit, trace: &mut T) -> Lit {
        let surface = self.db.surface(hit);
        let object = &self.db.objects()[surface.object as usize];
        let m = object.material_of(surface.triangle);
        let view = -ray.direction.x;
        let to_light = self.light.position - hit.event.x;
        let light_distance = to_light.length();
        // A light on the surface point lights nothing; a non-finite
        // direction stays NaN, for the pixel's check to report.
        let l = if to_light.is_finite() {
            unit_or_zero(to_light, light_distance)
        } else {
            DVec3::NAN
        };
        let (velocity, gamma) = self.db.motion_on(hit, &surface);
        let (n, frame) = self.facing(ray, &surface, velocity);
        let surface_frame =
            frame.map(|f| [f.normal(), f.towards(l), f.propagation(view.normalize())]);
        let [n_s, l_s, view_s] = surface_frame.unwrap_or([n, l, view]);
        let lambert = n_s.dot(l_s);
        let (mut specular, mut shadowed) = (0.0, false);
        // NaN passes these tests (not `x > 0` or `max(0)`), so that a
        // non-finite direction reaches the pixel's check rather than
        // shading as if unlit.
        if lambert > 0.0 || lambert.is_nan() {
            shadowed = self.shadows && self.in_shadow_traced(hit.event, trace);
            if !shadowed && m.specular > 0.0 {
                let r = 2.0 * lambert * n_s - l_s;
                let cos = r.dot(view_s);
                specular = m.specular * math::powf(if cos < 0.0 { 0.0 } else { cos }, m.shininess);
            }
        }
        let at = hit.event.x;
        let (from_light, out) = if self.shifts_frequency() {
            let from_light = self.to_surface(at, velocity, gamma, -l);
            let to_origin = self.to_surface(at, velocity, gamma, view.normalize());
            (from_light, 1.0 / to_origin)
        } else {
            (1.0, 1.0)
        };
        Lit {
            object: surface.object,
            triangle: surface.triangle,
            tau: object.proper_time(hit.event),
            texel: self.texel(hit, &surface, object),
            n,
            l,
            light_distance,
            lambert,
            surface_frame,
            shadowed,
            specular,
            velocity,
            gamma,
            from_light,
            out,
        }
    }
}

/// `v` over its `length`, or zero where that is not a finite positive
/// scale (a zero or overflowing length): `v.normalize_or_zero()` to the
/// bit, with the length found once for both.
fn unit_or_zero(v: DVec3, length: f64) -> DVec3 {
    let rcp = 1.0 / length;
    if rcp.is_finite() && rcp > 0.0 {
        v * rcp
    } else {
        DVec3::ZERO
    }
}
