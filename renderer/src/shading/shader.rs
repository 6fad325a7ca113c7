//! Shading (paper 3, item 5): one point light at rest in the lab, Lambert
//! plus Phong specular on two-sided faces, with shadow and reflection rays
//! that, like primary rays, travel on past light cones from the hit event:
//! the light a surface receives left the light source, or the reflected
//! object, earlier.

use super::carried::Carried;
use super::doppler::{self, Effects, Leg};
use crate::camera::{Camera, Kinematics};
use crate::color::{self, Spectrum, BAND_LEN};
use crate::database::Database;
use crate::geometry::Hit;
use crate::scene::Light;
use crate::spacetime::{gamma, Event};
use crate::spacetime::{LightSpeed, Ray};
use crate::trace::{NoTrace, RayKind, Step, Trace};
use glam::DVec3;

/// Values at the wavelengths of the observed band, carried into whatever
/// frame a leg of the path is in.
pub type Band = [f64; BAND_LEN];

pub(super) fn sample(s: &Spectrum, nm: &Band) -> Band {
    std::array::from_fn(|i| s.at(nm[i]))
}

fn scaled(nm: &Band, f: f64) -> Band {
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
    /// Colour where a ray meets nothing.
    pub background: DVec3,
    /// Whether rays lie on light cones or in constant-time slices.
    pub light_speed: LightSpeed,
    /// Number of mirror bounces followed.
    pub max_depth: u32,
    /// Whether shadow rays are traced.
    pub shadows: bool,
    /// Doppler shift and searchlight.
    pub effects: Effects,
}

/// What shading at a hit needs beyond the hit: the geometry of the light and
/// view, the shadow test, and the surface's motion for the colour effects.
struct Lit {
    object: u32,
    tau: f64,
    n: DVec3,
    l: DVec3,
    light_distance: f64,
    lambert: f64,
    shadowed: bool,
    /// m.specular (r.v)^shininess, 0 in shadow.
    specular: f64,
    /// Lab velocity of the surface and the gamma of its clock (1 when
    /// Lorentz-decoupled: classical Doppler).
    velocity: DVec3,
    gamma: f64,
    /// nu_surface / nu_lab for the light's leg, and nu_lab / nu_surface for
    /// the leg from the surface towards the ray's origin (1 when off).
    from_light: f64,
    out: f64,
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
        match self.db.closest_hit_traced(ray, range, trace) {
            None => {
                if T::ENABLED {
                    trace.record(Step::Miss {
                        kind,
                        background: self.background,
                    });
                }
                C::background(self, band)
            }
            Some(hit) => {
                if T::ENABLED {
                    trace.record(self.hit_step(kind, ray, &hit));
                }
                C::shade(self, ray, &hit, depth, band, trace)
            }
        }
    }

    fn hit_step(&self, kind: RayKind, ray: &Ray, hit: &Hit) -> Step {
        let surface = self.db.surface(hit);
        let object = &self.db.objects()[surface.object as usize];
        Step::Hit {
            kind,
            tet: self.db.primitive_number(hit.primitive),
            object: object.name.clone(),
            triangle: surface.triangle,
            event: hit.event,
            surface_point: object.local_point(hit.event),
            proper_time: object.proper_time(hit.event),
            normal: surface.normal,
            facing_normal: self.facing_normal(ray, hit),
        }
    }

    /// The unit normal of the hit surface, turned to face the ray's origin.
    pub fn facing_normal(&self, ray: &Ray, hit: &Hit) -> DVec3 {
        let n = self.db.surface(hit).normal;
        if n.dot(ray.direction.x) > 0.0 {
            -n
        } else {
            n
        }
    }

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

    /// The frequency ratio between the lab and the frame of a surface
    /// moving with `velocity` (clock `gamma`) for light propagating along
    /// `k`: nu_surface / nu_lab; 1 when light is instantaneous or the
    /// effects are off.
    fn to_surface(&self, velocity: DVec3, gamma: f64, k: DVec3) -> f64 {
        if !self.effects.any() || self.light_speed == LightSpeed::Infinite {
            return 1.0;
        }
        doppler::to_frame(velocity, gamma, k)
    }

    fn lit<T: Trace>(&self, ray: &Ray, hit: &Hit, trace: &mut T) -> Lit {
        let surface = self.db.surface(hit);
        let object = &self.db.objects()[surface.object as usize];
        let m = &object.material;
        let n = self.facing_normal(ray, hit);
        let view = -ray.direction.x;
        let to_light = self.light.position - hit.event.x;
        let l = to_light.normalize_or_zero();
        let lambert = n.dot(l);
        let (mut specular, mut shadowed) = (0.0, false);
        if lambert > 0.0 {
            shadowed = self.shadows && self.in_shadow_traced(hit.event, trace);
            if !shadowed && m.specular > 0.0 {
                let r = 2.0 * lambert * n - l;
                specular = m.specular * r.dot(view).max(0.0).powf(m.shininess);
            }
        }
        let stretch = object.stretch_at(hit.event.t);
        let (velocity, gamma) = (stretch.worldline.velocity(), stretch.clock.gamma());
        let from_light = self.to_surface(velocity, gamma, -l);
        let out = 1.0 / self.to_surface(velocity, gamma, view.normalize());
        Lit {
            object: surface.object,
            tau: object.proper_time(hit.event),
            n,
            l,
            light_distance: to_light.length(),
            lambert,
            shadowed,
            specular,
            velocity,
            gamma,
            from_light,
            out,
        }
    }

    /// The mirror ray leaving `hit`, and nu_surface / nu_lab for the light
    /// arriving along it.
    fn mirror_ray(&self, ray: &Ray, hit: &Hit, lit: &Lit) -> (Ray, f64) {
        let d = ray.direction.x;
        let reflected = Ray::backwards(hit.event, d - 2.0 * d.dot(lit.n) * lit.n, self.light_speed);
        let f = self.to_surface(lit.velocity, lit.gamma, -reflected.direction.x.normalize());
        (reflected, f)
    }

    /// Lambert plus Phong at `hit`, plus the mirror term.
    pub fn shade(&self, ray: &Ray, hit: &Hit, depth: u32) -> DVec3 {
        self.shade_traced(ray, hit, depth, &mut NoTrace)
    }

    /// RGB shading. With the searchlight on (and wavelengths unshifted) each
    /// leg scales the frequency-integrated intensity: the light's
    /// irradiance by (nu_s/nu_lab)^2, mirrored radiance by ^4, the radiance
    /// leaving towards the ray's origin by (nu_lab/nu_s)^4.
    pub(super) fn shade_traced<T: Trace>(
        &self,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        trace: &mut T,
    ) -> DVec3 {
        let lit = self.lit(ray, hit, trace);
        let m = &self.db.objects()[lit.object as usize].material;
        if self.effects.searchlight && (lit.out <= 0.0 || lit.from_light <= 0.0) {
            // A superluminal decoupled surface running into its own light:
            // no Doppler factor exists.
            return DVec3::ZERO;
        }
        let albedo = m.color_at(lit.tau);
        let ambient = albedo * self.light.ambient;
        let (mut diffuse, mut specular) = (DVec3::ZERO, 0.0);
        if lit.lambert > 0.0 && !lit.shadowed {
            specular = lit.specular;
            diffuse = albedo * (m.diffuse * lit.lambert);
        }
        let fx = self.effects;
        let mut local = if fx.searchlight {
            ambient
                + self.light.color
                    * (diffuse + DVec3::splat(specular))
                    * fx.intensity(lit.from_light, Leg::PointSource)
        } else {
            ambient + self.light.color * (diffuse + DVec3::splat(specular))
        };
        if let Some(e) = &m.emission {
            local += color::to_rgb(&e.sample_scaled(1.0));
        }
        let mut color = local;
        let mut mirror_factor = None;
        if m.mirror > 0.0 && depth < self.max_depth {
            let (reflected, f) = self.mirror_ray(ray, hit, &lit);
            mirror_factor = Some(f);
            let seen = self.radiance_traced(&reflected, depth + 1, RayKind::Reflection, trace);
            let seen = if fx.searchlight {
                seen * fx.intensity(f, Leg::Radiance)
            } else {
                seen
            };
            color = local * (1.0 - m.mirror) + seen * m.mirror;
        }
        if fx.searchlight {
            color *= fx.intensity(lit.out, Leg::Radiance);
        }
        if T::ENABLED {
            trace.record(Step::Shading {
                depth,
                albedo,
                ambient,
                light_vector: lit.l,
                light_distance: lit.light_distance,
                lambert: lit.lambert,
                in_shadow: lit.shadowed,
                diffuse,
                specular,
                mirror: m.mirror,
                local,
                color,
            });
            if fx.any() {
                trace.record(self.doppler_step(depth, &lit, mirror_factor, None));
            }
        }
        color
    }

    fn doppler_step(
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

    /// Spectral shading. In the surface's frame the lab wavelengths `nm`
    /// are nm * (nu_lab / nu_s); there the surface reflects the light (its
    /// spectrum evaluated at the wavelengths that left the lamp, times
    /// (nu_s/nu_lab)^3 with the searchlight), mirrors what reaches it, and
    /// emits; back in the lab the radiance scales by (nu_lab/nu_s)^5.
    pub(super) fn shade_spectral<T: Trace>(
        &self,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        nm: &Band,
        trace: &mut T,
    ) -> Band {
        let lit = self.lit(ray, hit, trace);
        let m = &self.db.objects()[lit.object as usize].material;
        if lit.out <= 0.0 || lit.from_light <= 0.0 {
            // A superluminal decoupled surface running into its own light.
            return [0.0; BAND_LEN];
        }
        let fx = self.effects;
        let surface_nm = scaled(nm, lit.out);
        let reflectance = sample(&m.reflectance_at(lit.tau), &surface_nm);
        let white = sample(&Spectrum::Rgb(DVec3::ONE), &surface_nm);
        let lamp = sample(&self.light.spectrum(), &scaled(&surface_nm, lit.from_light));
        let lamp_gain = fx.intensity(lit.from_light, Leg::PointSource);
        let direct = if lit.lambert > 0.0 && !lit.shadowed {
            (m.diffuse * lit.lambert, lit.specular)
        } else {
            (0.0, 0.0)
        };
        let emission = m.emission.as_ref().map(|e| sample(e, &surface_nm));
        let mut local: Band = std::array::from_fn(|i| {
            let lamp = lamp[i] * lamp_gain;
            reflectance[i] * (self.light.ambient * white[i] + direct.0 * lamp)
                + direct.1 * lamp
                + emission.map_or(0.0, |e| e[i])
        });
        let mut mirror_factor = None;
        if m.mirror > 0.0 && depth < self.max_depth {
            let (reflected, f) = self.mirror_ray(ray, hit, &lit);
            mirror_factor = Some(f);
            let seen = self.spectral_traced(
                &reflected,
                depth + 1,
                RayKind::Reflection,
                &scaled(&surface_nm, f),
                trace,
            );
            let gain = fx.intensity(f, Leg::Radiance);
            for (l, s) in local.iter_mut().zip(seen) {
                *l = *l * (1.0 - m.mirror) + s * gain * m.mirror;
            }
        }
        if T::ENABLED {
            trace.record(self.doppler_step(
                depth,
                &lit,
                mirror_factor,
                Some((&surface_nm, &local)),
            ));
        }
        let gain = fx.intensity(lit.out, Leg::Radiance);
        local.map(|l| l * gain)
    }

    /// The colour the camera records along `ray` (one of its rays, in the
    /// lab): the radiance, carried into the camera's frame when the colour
    /// effects are on (nu_cam / nu_lab = gamma_c (1 - v_c . k) for light
    /// propagating along k; classical without gamma, 1 for instantaneous
    /// light), then, for Doppler, integrated against the CIE 1931 matching
    /// functions into linear sRGB.
    pub fn observed_traced<T: Trace>(&self, camera: &Camera, ray: &Ray, trace: &mut T) -> DVec3 {
        let fx = self.effects;
        if !fx.any() {
            return self.radiance_traced(ray, 0, RayKind::Primary, trace);
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
            let seen = self.spectral_traced(ray, 0, RayKind::Primary, &lab_nm, trace);
            let xyz = color::xyz(&seen.map(|l| l * gain));
            (color::xyz_to_rgb(xyz), Some((lab_nm, xyz)))
        } else {
            (
                self.radiance_traced(ray, 0, RayKind::Primary, trace) * gain,
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

fn ray_step(kind: RayKind, depth: u32, ray: &Ray, range: (f64, f64)) -> Step {
    Step::Ray {
        kind,
        depth,
        origin: ray.origin,
        direction: ray.direction,
        normalized: ray.normalized_direction(),
        range,
    }
}
