//! The barycentric solve of a ray against one tetrahedron (paper 3.2).
//!
//! The ray `O + s D` meets the hyperplane of the tetrahedron `V0 + E b`
//! (E = [V1-V0, V2-V0, V3-V0]) where `N.(O + s D - V0) = 0`, N being the
//! 4D normal orthogonal to the three edges. The point's barycentric
//! coordinates come from the 3x3 system left after dropping the
//! coordinate along which N is largest (the 4D analogue of projecting a 3D
//! triangle onto its dominant plane), which keeps the solve well conditioned
//! even for tetrahedra thousands of t.units long and 1/20 l.unit wide.

use super::{Hit, Miss, PrimitiveId, Tetrahedron};
use crate::spacetime::Event;
use crate::spacetime::Ray;
use glam::{DMat3, DVec3, DVec4};

/// Barycentric slack for hits exactly on a shared face, so that a ray
/// through a face or edge between two tetrahedra cannot slip through both.
pub(crate) const BARY_EPS: f64 = 1e-12;

/// A tetrahedron with its solve prepared once, when the database is built.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedTet {
    v0: DVec4,
    normal: DVec4,
    /// The rows of the inverse of the projected 3x3 edge matrix, spread back
    /// over (x, y, z, t) with a zero at the dropped axis: b_k = rows[k] . (p - v0).
    rows: [DVec4; 3],
}

/// Inserts a zero at `axis`, the inverse of [`drop_axis`].
fn spread(v: DVec3, axis: usize) -> DVec4 {
    let a = v.to_array();
    let mut out = [0.0; 4];
    let mut k = 0;
    for (i, o) in out.iter_mut().enumerate() {
        if i != axis {
            *o = a[k];
            k += 1;
        }
    }
    DVec4::from_array(out)
}

fn drop_axis(v: DVec4, axis: usize) -> DVec3 {
    let a = v.to_array();
    let mut out = [0.0; 3];
    let mut k = 0;
    for (i, x) in a.iter().enumerate() {
        if i != axis {
            out[k] = *x;
            k += 1;
        }
    }
    DVec3::from_array(out)
}

/// The vector orthogonal to `a`, `b`, `c` in 4D (generalised cross product).
fn normal4(a: DVec4, b: DVec4, c: DVec4) -> DVec4 {
    let m = |i: usize| {
        DMat3::from_cols(drop_axis(a, i), drop_axis(b, i), drop_axis(c, i)).determinant()
    };
    DVec4::new(-m(0), m(1), -m(2), m(3))
}

impl PreparedTet {
    /// `None` for a tetrahedron with no 3-volume (cannot be hit).
    pub fn new(tet: &Tetrahedron) -> Option<PreparedTet> {
        let v = tet.vertices.map(|e| e.to_xyzt());
        let (e1, e2, e3) = (v[1] - v[0], v[2] - v[0], v[3] - v[0]);
        let normal = normal4(e1, e2, e3);
        let drop = normal
            .abs()
            .to_array()
            .iter()
            .enumerate()
            .fold(0, |best, (i, x)| {
                if *x > normal.abs().to_array()[best] {
                    i
                } else {
                    best
                }
            });
        let m = DMat3::from_cols(
            drop_axis(e1, drop),
            drop_axis(e2, drop),
            drop_axis(e3, drop),
        );
        let det = m.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = m.inverse().transpose();
        Some(PreparedTet {
            v0: v[0],
            normal,
            rows: [
                spread(inv.x_axis, drop),
                spread(inv.y_axis, drop),
                spread(inv.z_axis, drop),
            ],
        })
    }

    /// The barycentric solve. `range` bounds the ray parameter s (inclusive).
    pub fn intersect(&self, ray: &Ray, tet: u32, range: (f64, f64)) -> Result<Hit, Miss> {
        let o = ray.origin.to_xyzt();
        let d = ray.direction.to_xyzt();
        let denom = self.normal.dot(d);
        let num = self.normal.dot(self.v0 - o);
        if denom == 0.0 || !(num / denom).is_finite() {
            return Err(Miss::Parallel);
        }
        let s = num / denom;
        if s < range.0 || s > range.1 {
            return Err(Miss::OutOfRange { s });
        }
        let p = o + d * s;
        let r = p - self.v0;
        let b = DVec3::new(
            self.rows[0].dot(r),
            self.rows[1].dot(r),
            self.rows[2].dot(r),
        );
        let bary = [1.0 - b.x - b.y - b.z, b.x, b.y, b.z];
        if bary.iter().any(|x| *x < -BARY_EPS) {
            return Err(Miss::Outside { s, bary });
        }
        let clamped = bary.map(|x| x.clamp(0.0, 1.0));
        Ok(Hit {
            s,
            event: Event::from_xyzt(p),
            primitive: PrimitiveId::Tetrahedron(tet),
            bary: clamped,
        })
    }
}
