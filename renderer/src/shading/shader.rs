//! Shading (paper 3, item 5): one point light at rest in the lab, Lambert
//! plus Phong specular on two-sided faces, with shadow and reflection rays
//! that, like primary rays, travel on past light cones from the hit event:
//! the light a surface receives left the light source, or the reflected
//! object, earlier.

use super::bent::BentEnd;
use super::carried::{Carried, Shaded};
use super::doppler::{self, Effects, Leg};
use super::lit::Lit;
use super::mirror;
use crate::accel::PACKET;
use crate::camera::{Camera, Kinematics};
use crate::color::{self, BAND_LEN};
use crate::database::Database;
use crate::geometry::Hit;
use crate::scene::Light;
use crate::spacetime::{gamma, Event};
use crate::spacetime::{LightSpeed, Ray, Spacetime};
use crate::trace::{NoTrace, RayKind, Step, Trace};
use glam::DVec3;

/// What a primary ray met, searched before it is shaded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Found {
    /// In flat spacetime: its closest hit from its origin on.
    Straight(Option<Hit>),
    /// In a mass's field: where the search along its chords ended.
    Bent(BentEnd),
}

/// Values at the wavelengths of the observed band, carried into whatever
/// frame a leg of the path is in.
pub type Band = [f64; BAND_LEN];

pub(super) fn scaled(nm: &Band, f: f64) -> Band {
    nm.map(|x| x * f)
}

/// The start of the searched stretch of a secondary ray leaving `event`:
/// far enough to step off the surface it leaves, relative to the scale of
/// the coordinates.
pub(crate) fn self_hit_margin(event: Event) -> f64 {
    1e-9 * (1.0 + event.x.abs().max_element() + event.t.abs())
}

/// Everything fixed for one render: the database and how light travels.
pub struct Shader<'a> {
    /// The static 4D database searched by every ray.
    pub db: &'a Database,
    /// The scene's point light.
    pub light: &'a Light,
    /// Colour where a ray meets nothing, when there is no sky.
    pub background: DVec3,
    /// The sky at infinity ([`crate::Scene::sky`]), seen where a ray
    /// escapes, by the lab direction its light came from.
    pub sky: Option<&'a crate::Texels>,
    /// Whether rays lie on light cones or in constant-time slices.
    pub light_speed: LightSpeed,
    /// Number of mirror bounces followed.
    pub max_depth: u32,
    /// Whether shadow rays are traced.
    pub shadows: bool,
    /// Doppler shift and searchlight.
    pub effects: Effects,
    /// The spacetime primary rays cross: straight lines, or bent by a mass.
    pub spacetime: Spacetime,
    /// The least angle between neighbouring pixels' lines of sight, radians
    /// ([`crate::Camera::pixel_angle`]): the chords of a bent ray stray
    /// from it by at most a fraction of the pixel's footprint.
    pub pixel_angle: f64,
    /// The background's spectrum at the observed band, found once for
    /// the render ([`crate::shader`] fills it in). `None` finds it ray by
    /// ray, the same values.
    pub background_band: Option<BackgroundBand>,
}

/// A uniform background's spectrum at the observed band's own wavelengths:
/// what every primary ray of a camera at rest that meets nothing carries,
/// since the light of a background at rest reaches a camera at rest
/// unshifted (paper 6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BackgroundBand {
    seen: DVec3,
    nm: Band,
    values: Band,
}

impl BackgroundBand {
    /// `background`'s spectrum at the observed band; `None` where rays
    /// carry no spectrum (the Doppler shift off) or see a sky rather than
    /// the background.
    pub fn of(
        background: DVec3,
        sky: Option<&crate::Texels>,
        effects: Effects,
    ) -> Option<BackgroundBand> {
        (effects.doppler && sky.is_none()).then(|| {
            let nm = color::band_nm();
            BackgroundBand {
                seen: background,
                nm,
                values: <Band as Carried>::background(background, &nm),
            }
        })
    }

    /// The spectrum of `seen` at `nm` where both are this one's to the bit.
    pub(super) fn at(&self, seen: DVec3, nm: &Band) -> Option<Band> {
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        (same(&self.seen.to_array(), &seen.to_array()) && same(&self.nm, nm)).then_some(self.values)
    }
}

impl Shader<'_> {
    /// Colour of the light arriving along `ray` (towards its origin).
    pub fn radiance(&self, ray: &Ray, depth: u32) -> DVec3 {
        self.radiance_traced(ray, depth, RayKind::Primary, &mut NoTrace)
    }

    /// [`Shader::radiance`], recording the variables along the way.
    pub fn radiance_traced<T: Trace>(
        &self,
        ray: &Ray,
        depth: u32,
        kind: RayKind,
        trace: &mut T,
    ) -> DVec3 {
        self.carry(ray, depth, kind, &(), trace)
    }

    /// The one path of every ray, primary, reflected or spectral: search
    /// the database from the ray's origin (stepping off the surface it
    /// leaves, for secondary rays), and shade the most recent event met in
    /// the colour type `C`, or return the background.
    pub(super) fn carry<C: Carried, T: Trace>(
        &self,
        ray: &Ray,
        depth: u32,
        kind: RayKind,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        let margin = if depth == 0 {
            0.0
        } else {
            self_hit_margin(ray.origin)
        };
        let range = (margin, f64::INFINITY);
        if T::ENABLED {
            trace.record(ray_step(kind, depth, ray, range));
        }
        let hit = self.db.closest_hit_traced(ray, range, trace);
        self.carry_hit(ray, hit, depth, kind, band, trace)
    }

    /// The rest of [`Shader::carry`], once the closest hit within its
    /// range is known: shade `hit`, or return the background.
    pub(super) fn carry_hit<C: Carried, T: Trace>(
        &self,
        ray: &Ray,
        hit: Option<Hit>,
        depth: u32,
        kind: RayKind,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        match hit {
            None => self.escaped(kind, ray.direction.x, band, trace),
            Some(hit) => {
                if T::ENABLED {
                    trace.record(self.hit_step(kind, ray, &hit));
                }
                self.shade_hit(ray, &hit, depth, band, trace)
            }
        }
    }

    /// The colour `C` of a ray of `kind` that met nothing, its light having
    /// come from the lab direction `toward` at infinity: the sky there, or
    /// the background colour.
    pub(super) fn escaped<C: Carried, T: Trace>(
        &self,
        kind: RayKind,
        toward: DVec3,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        let seen = match self.sky {
            Some(sky) => sky.toward(toward),
            None => self.background,
        };
        if T::ENABLED {
            trace.record(Step::Miss {
                kind,
                background: seen,
            });
        }
        C::background_known(self, seen, band).unwrap_or_else(|| C::background(seen, band))
    }

    pub(super) fn hit_step(&self, kind: RayKind, ray: &Ray, hit: &Hit) -> Step {
        let surface = self.db.surface(hit);
        let object = &self.db.objects()[surface.object as usize];
        Step::Hit {
            kind,
            primitive: hit.primitive,
            object: object.name.clone(),
            triangle: surface.triangle,
            event: hit.event,
            surface_point: object.local_point(hit.event),
            proper_time: object.proper_time(hit.event),
            start_t: object.lifetime().0,
            normal: surface.normal,
            facing_normal: self.facing_normal(ray, hit),
        }
    }

    /// The unit lab normal of the hit surface, turned to the side the ray's
    /// origin sees: the side the light towards it leaves in the surface's
    /// own frame (for a moving surface under light cones, not always the
    /// side facing the origin in the lab; see `Shader::facing`).
    pub fn facing_normal(&self, ray: &Ray, hit: &Hit) -> DVec3 {
        let surface = self.db.surface(hit);
        let (velocity, _) = self.db.motion_on(hit, &surface);
        self.facing(ray, &surface, velocity).0
    }

    /// The mirror ray leaving `hit`, and nu_surface / nu_lab for the light
    /// arriving along it. A static mirror, or any mirror under
    /// instantaneous light, reflects by d - 2 (d.n) n; a moving one by the
    /// law in its rest frame ([`mirror::incident`]). `None` when the mirror
    /// moves along its normal at light speed or faster: it has no rest
    /// frame and reflects nothing.
    fn mirror_ray<T: Trace>(
        &self,
        ray: &Ray,
        hit: &Hit,
        lit: &Lit,
        depth: u32,
        trace: &mut T,
    ) -> Option<(Ray, f64)> {
        let d = ray.direction.x;
        let towards = if lit.velocity == DVec3::ZERO || self.light_speed == LightSpeed::Infinite {
            d - 2.0 * d.dot(lit.n) * lit.n
        } else {
            let k_out = -d.normalize();
            let r = mirror::incident(k_out, lit.n, lit.velocity)?;
            if T::ENABLED {
                trace.record(Step::Reflection {
                    depth,
                    mirror_velocity: lit.velocity,
                    k_out,
                    k_in: r.k_in,
                    frequency_ratio: r.frequency_ratio,
                    rest_frame: mirror::in_rest_frame(k_out, r.k_in, lit.n, lit.velocity),
                });
            }
            -r.k_in
        };
        let reflected = Ray::backwards(hit.event, towards, self.light_speed);
        let f = self.to_surface(
            hit.event.x,
            lit.velocity,
            lit.gamma,
            -reflected.direction.x.normalize(),
        );
        Some((reflected, f))
    }

    /// Lambert plus Phong at `hit`, plus the mirror term.
    pub fn shade(&self, ray: &Ray, hit: &Hit, depth: u32) -> DVec3 {
        self.shade_hit(ray, hit, depth, &(), &mut NoTrace)
    }

    /// The colour `C` leaving `hit` towards the ray's origin. The surface
    /// forms its local term in its own frame, mirrors what reaches it along
    /// its mirror ray, and the light leaves towards the ray's origin. Where
    /// the colour carries the surface's frequency factors (paper 6), the
    /// mirrored radiance scales by (nu_s/nu_lab)^4 and the radiance leaving
    /// by (nu_lab/nu_s)^4 with the searchlight (frequency-integrated; a
    /// spectrum also shifts its wavelengths, see [`Leg`]).
    pub(super) fn shade_hit<C: Carried, T: Trace>(
        &self,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        let lit = self.lit(ray, hit, trace);
        let m = self.db.objects()[lit.object as usize].material_of(lit.triangle);
        let factors = C::carries_factors(self.effects);
        if factors && (lit.out <= 0.0 || lit.from_light <= 0.0) {
            // A superluminal decoupled surface running into its own light:
            // no Doppler factor exists.
            return C::ZERO;
        }
        let gain = |f: f64, leg: Leg| factors.then(|| self.effects.intensity(f, leg));
        let (local, detail) = C::local(self, m, &lit, band, gain(lit.from_light, Leg::PointSource));
        let mut mixed = local;
        let mut from_mirror = None;
        if m.mirror > 0.0 && depth < self.max_depth {
            let seen = match self.mirror_ray(ray, hit, &lit, depth, trace) {
                Some((reflected, f)) => {
                    from_mirror = Some(f);
                    let at = C::mirror_band(&detail, f);
                    let seen: C =
                        self.carry(&reflected, depth + 1, RayKind::Reflection, &at, trace);
                    seen.with_gain(gain(f, Leg::Radiance))
                }
                None => C::ZERO,
            };
            mixed = local.mix(seen, m.mirror);
        }
        let color = mixed.with_gain(gain(lit.out, Leg::Radiance));
        if T::ENABLED {
            let shaded = Shaded {
                depth,
                lit: &lit,
                mirror: m.mirror,
                from_mirror,
                local,
                detail: &detail,
                mixed,
                color,
            };
            C::record(self, &shaded, trace);
        }
        color
    }

    pub(super) fn doppler_step(
        &self,
        depth: u32,
        lit: &Lit,
        mirror: Option<f64>,
        spectral: Option<(&Band, &Band)>,
    ) -> Step {
        Step::Doppler {
            depth,
            surface_velocity: lit.velocity,
            gamma: lit.gamma,
            from_light: lit.from_light,
            to_origin: lit.out,
            from_mirror: mirror,
            surface_nm: spectral.map(|(nm, _)| nm.to_vec()),
            surface_radiance: spectral.map(|(_, r)| r.to_vec()),
        }
    }

    /// Spectral radiance arriving along `ray` at the wavelengths `nm`, both
    /// in the lab frame (wavelength tracking: each leg rescales the
    /// wavelengths at which the next is evaluated).
    pub fn spectral_traced<T: Trace>(
        &self,
        ray: &Ray,
        depth: u32,
        kind: RayKind,
        nm: &Band,
        trace: &mut T,
    ) -> Band {
        self.carry(ray, depth, kind, nm, trace)
    }

    /// The colour the camera records along `ray` (one of its rays, in the
    /// lab): the radiance, carried into the camera's frame when the colour
    /// effects are on (nu_cam / nu_lab = gamma_c (1 - v_c . k) for light
    /// propagating along k; classical without gamma, 1 for instantaneous
    /// light), then, for Doppler, integrated against the CIE 1931 matching
    /// functions into linear sRGB.
    pub fn observed_traced<T: Trace>(&self, camera: &Camera, ray: &Ray, trace: &mut T) -> DVec3 {
        self.observed_with(camera, ray, None, trace)
    }

    /// [`Shader::observed_traced`] of a primary ray whose search was made
    /// already (as a packet of neighbouring pixels' rays is, by
    /// [`Shader::search_primary`]): the same colour to the bit.
    pub fn observed_found(&self, camera: &Camera, ray: &Ray, found: &Found) -> DVec3 {
        self.observed_with(camera, ray, Some(found), &mut NoTrace)
    }

    /// What each of `rays` meets (neighbouring pixels' primary rays, at
    /// most four), into `found`, the same to the bit as each searched
    /// alone: in flat spacetime their closest hits, searched together
    /// (`Database::closest_hits`); in a mass's field where each search
    /// along its chords ends, their geodesics stepped side by side.
    pub fn search_primary(&self, rays: &[Ray], found: &mut [Found]) {
        assert!(
            rays.len() <= PACKET && rays.len() == found.len(),
            "a packet's rays"
        );
        match &self.spacetime {
            Spacetime::Flat => {
                let mut hits = [None; PACKET];
                let hits = &mut hits[..rays.len()];
                self.db.closest_hits(rays, (0.0, f64::INFINITY), hits);
                for (f, &hit) in found.iter_mut().zip(hits.iter()) {
                    *f = Found::Straight(hit);
                }
            }
            Spacetime::Schwarzschild(hole) => {
                let mut ends = [BentEnd::Dark; PACKET];
                let ends = &mut ends[..rays.len()];
                self.bent_ends(hole, rays, ends);
                for (f, &end) in found.iter_mut().zip(ends.iter()) {
                    *f = Found::Bent(end);
                }
            }
        }
    }

    /// The primary ray's colour in `C`: its search made now, or `found`
    /// already.
    fn primary<C: Carried, T: Trace>(
        &self,
        ray: &Ray,
        found: Option<&Found>,
        band: &C::At,
        trace: &mut T,
    ) -> C {
        if let Spacetime::Schwarzschild(hole) = &self.spacetime {
            return match found {
                Some(Found::Bent(end)) => self.bent_seen(hole, ray, end, band, trace),
                _ => self.bent(hole, ray, band, trace),
            };
        }
        let Some(&Found::Straight(hit)) = found else {
            return self.carry(ray, 0, RayKind::Primary, band, trace);
        };
        if T::ENABLED {
            trace.record(ray_step(RayKind::Primary, 0, ray, (0.0, f64::INFINITY)));
        }
        self.carry_hit(ray, hit, 0, RayKind::Primary, band, trace)
    }

    fn observed_with<T: Trace>(
        &self,
        camera: &Camera,
        ray: &Ray,
        found: Option<&Found>,
        trace: &mut T,
    ) -> DVec3 {
        let fx = self.effects;
        if !fx.any() {
            return self.primary(ray, found, &(), trace);
        }
        let k = -ray.direction.x.normalize();
        let f = match camera.kinematics {
            Kinematics::Lorentz => doppler::to_frame(camera.velocity, gamma(camera.velocity), k),
            Kinematics::Galilean => doppler::to_frame(camera.velocity, 1.0, k),
            Kinematics::None => 1.0,
        };
        let gain = fx.intensity(f, Leg::Radiance);
        let (color, spectral) = if fx.doppler {
            let lab_nm = scaled(&color::band_nm(), f);
            let seen: Band = self.primary(ray, found, &lab_nm, trace);
            let xyz = color::xyz(&seen.map(|l| l * gain));
            (color::xyz_to_rgb(xyz), Some((lab_nm, xyz)))
        } else {
            (
                self.primary::<DVec3, T>(ray, found, &(), trace) * gain,
                None,
            )
        };
        if T::ENABLED {
            trace.record(Step::Observed {
                doppler: f,
                lab_nm: spectral.map(|(nm, _)| nm.to_vec()),
                xyz: spectral.map(|(_, xyz)| xyz),
                color,
            });
        }
        color
    }
}

pub(super) fn ray_step(kind: RayKind, depth: u32, ray: &Ray, range: (f64, f64)) -> Step {
    Step::Ray {
        kind,
        depth,
        origin: ray.origin,
        direction: ray.direction,
        normalized: ray.normalized_direction(),
        range,
    }
}
