//! Shading (paper 3, item 5): one point light at rest in the lab, Lambert
//! plus Phong specular on two-sided faces, with shadow and reflection rays
//! that, like primary rays, travel on past light cones from the hit event:
//! the light a surface receives left the light source, or the reflected
//! object, earlier.

use crate::database::Database;
use crate::intersect::Hit;
use crate::lightcone::{LightSpeed, Ray};
use crate::spacetime::Event;
use crate::trace::{NoTrace, RayKind, Step, Trace};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A point light at rest in the lab frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    /// Lab position, l.units.
    pub position: DVec3,
    /// Linear RGB intensity.
    #[serde(default = "white")]
    pub color: DVec3,
    /// Fraction of a material's colour seen without direct light.
    #[serde(default = "default_ambient")]
    pub ambient: f64,
}

fn white() -> DVec3 {
    DVec3::ONE
}
fn default_ambient() -> f64 {
    0.25
}
fn default_diffuse() -> f64 {
    0.75
}
fn default_shininess() -> f64 {
    32.0
}

/// A colour that alternates with the object's own (proper) time, so that
/// time dilation is visible (paper 3, item 2d).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Blink {
    /// Period in the object's proper time, t.units.
    pub period: f64,
    /// Colour during the first half of each period (the base colour the rest).
    pub color: DVec3,
}

/// Surface appearance. Colours are linear RGB in [0, 1].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    pub color: DVec3,
    #[serde(default = "default_diffuse")]
    pub diffuse: f64,
    #[serde(default)]
    pub specular: f64,
    #[serde(default = "default_shininess")]
    pub shininess: f64,
    /// Fraction of the colour taken from the mirror reflection, 0..=1.
    #[serde(default)]
    pub mirror: f64,
    #[serde(default)]
    pub blink: Option<Blink>,
}

impl Material {
    pub fn matte(color: DVec3) -> Material {
        Material {
            color,
            diffuse: default_diffuse(),
            specular: 0.0,
            shininess: default_shininess(),
            mirror: 0.0,
            blink: None,
        }
    }

    /// The colour at the object's proper time `tau`.
    pub fn color_at(&self, tau: f64) -> DVec3 {
        match self.blink {
            Some(b) if (tau / b.period).rem_euclid(1.0) < 0.5 => b.color,
            _ => self.color,
        }
    }
}

/// The start of the searched stretch of a secondary ray leaving `event`:
/// far enough to step off the surface it leaves, relative to the scale of
/// the coordinates.
pub fn self_hit_margin(event: Event) -> f64 {
    1e-9 * (1.0 + event.x.abs().max_element() + event.t.abs())
}

/// Everything fixed for one render: the database and how light travels.
pub struct Shader<'a> {
    pub db: &'a Database,
    pub light: &'a Light,
    pub background: DVec3,
    pub light_speed: LightSpeed,
    /// Number of mirror bounces followed.
    pub max_depth: u32,
    /// Whether shadow rays are traced.
    pub shadows: bool,
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
                self.background
            }
            Some(hit) => {
                if T::ENABLED {
                    trace.record(self.hit_step(kind, ray, &hit));
                }
                self.shade_traced(ray, &hit, depth, trace)
            }
        }
    }

    fn hit_step(&self, kind: RayKind, ray: &Ray, hit: &Hit) -> Step {
        let surface = self.db.surface(hit);
        let object = &self.db.objects()[surface.object as usize];
        Step::Hit {
            kind,
            tet: hit.tet,
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

    /// Lambert plus Phong at `hit`, plus the mirror term.
    pub fn shade(&self, ray: &Ray, hit: &Hit, depth: u32) -> DVec3 {
        self.shade_traced(ray, hit, depth, &mut NoTrace)
    }

    fn shade_traced<T: Trace>(&self, ray: &Ray, hit: &Hit, depth: u32, trace: &mut T) -> DVec3 {
        let object = &self.db.objects()[self.db.surface(hit).object as usize];
        let m = &object.material;
        let albedo = m.color_at(object.proper_time(hit.event));
        let n = self.facing_normal(ray, hit);
        let view = -ray.direction.x;
        let ambient = albedo * self.light.ambient;
        let to_light = self.light.position - hit.event.x;
        let l = to_light.normalize_or_zero();
        let lambert = n.dot(l);
        let (mut diffuse, mut specular, mut shadowed) = (DVec3::ZERO, 0.0, false);
        if lambert > 0.0 {
            shadowed = self.shadows && self.in_shadow_traced(hit.event, trace);
            if !shadowed {
                let r = 2.0 * lambert * n - l;
                specular = if m.specular > 0.0 {
                    m.specular * r.dot(view).max(0.0).powf(m.shininess)
                } else {
                    0.0
                };
                diffuse = albedo * (m.diffuse * lambert);
            }
        }
        let local = ambient + self.light.color * (diffuse + DVec3::splat(specular));
        let mut color = local;
        if m.mirror > 0.0 && depth < self.max_depth {
            let d = ray.direction.x;
            let reflected = Ray::backwards(hit.event, d - 2.0 * d.dot(n) * n, self.light_speed);
            color = local * (1.0 - m.mirror)
                + self.radiance_traced(&reflected, depth + 1, RayKind::Reflection, trace)
                    * m.mirror;
        }
        if T::ENABLED {
            trace.record(Step::Shading {
                depth,
                albedo,
                ambient,
                light_vector: l,
                light_distance: to_light.length(),
                lambert,
                in_shadow: shadowed,
                diffuse,
                specular,
                mirror: m.mirror,
                local,
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
