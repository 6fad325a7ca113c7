//! The analytic sphere: a worldtube met by solving a quadratic, exact where
//! a tessellated sphere is faceted.

use super::{Barycentric, Hit, PrimitiveId};
use crate::spacetime::Event;
use crate::spacetime::Ray;
use glam::DVec3;

/// An analytic sphere: in its object's comoving coordinates
/// x' = x - v (t - t0) - x0 it is static; Lorentz-contracted (a V_obj) it is
/// the ellipsoid |S x'| = R, S stretching by gamma along v.
pub(crate) struct Sphere {
    pub(crate) object: u32,
    pub(crate) radius: f64,
    pub(crate) origin: Event,
    pub(crate) velocity: DVec3,
    /// 1 when not contracted.
    pub(crate) gamma: f64,
    /// Lab time the object's life ends.
    pub(crate) end: f64,
}

impl Sphere {
    /// S applied to a comoving offset: its component along v times gamma.
    fn stretch(&self, p: DVec3) -> DVec3 {
        let b2 = self.velocity.length_squared();
        if b2 == 0.0 || self.gamma == 1.0 {
            return p;
        }
        let along = self.velocity * (self.velocity.dot(p) / b2);
        p + along * (self.gamma - 1.0)
    }

    fn comoving(&self, e: Event) -> DVec3 {
        e.x - self.velocity * (e.t - self.origin.t) - self.origin.x
    }

    /// The nearest crossing of the sphere's worldtube within `range` and
    /// its lifetime: |S (o' + s d')| = R, a quadratic in s.
    pub(crate) fn intersect(&self, ray: &Ray, id: u32, range: (f64, f64)) -> Option<Hit> {
        let a = self.stretch(self.comoving(ray.origin));
        let b = self.stretch(ray.direction.x - self.velocity * ray.direction.t);
        let (qa, qb, qc) = (
            b.length_squared(),
            2.0 * a.dot(b),
            a.length_squared() - self.radius * self.radius,
        );
        let disc = qb * qb - 4.0 * qa * qc;
        if qa == 0.0 || disc < 0.0 {
            return None;
        }
        let q = -0.5 * (qb + qb.signum() * disc.sqrt());
        let (r1, r2) = (q / qa, if q != 0.0 { qc / q } else { q / qa });
        let alive = |s: f64| {
            let t = ray.origin.t + s * ray.direction.t;
            s >= range.0 && s <= range.1 && t >= self.origin.t && t <= self.end
        };
        let s = [r1.min(r2), r1.max(r2)].into_iter().find(|s| alive(*s))?;
        Some(Hit {
            s,
            event: ray.at(s),
            primitive: PrimitiveId::Sphere(id),
            bary: Barycentric::Sphere,
            stored: Hit::NOT_STORED,
        })
    }

    /// Outward unit normal at an event on the surface (lab frame): the
    /// gradient of |S x'|^2, S^T S x'.
    pub(crate) fn normal(&self, e: Event) -> DVec3 {
        self.stretch(self.stretch(self.comoving(e))).normalize()
    }
}
