//! The barycentric solve of a ray against one tetrahedron (paper 3.2).
//!
//! The ray `O + s D` meets the hyperplane of the tetrahedron `V0 + E b`
//! (E = [V1-V0, V2-V0, V3-V0]) where `N.(O + s D - V0) = 0`, N being the
//! 4D normal orthogonal to the three edges. The point's barycentric
//! coordinates come from the 3x3 system left after dropping the
//! coordinate along which N is largest (the 4D analogue of projecting a 3D
//! triangle onto its dominant plane), which keeps the solve well conditioned
//! even for tetrahedra thousands of t.units long and 1/20 l.unit wide.
//!
//! Near a face, edge or corner, where the solve's rounding could send a ray
//! between two neighbours (both rejecting it), inside or outside is decided
//! watertight in the manner of Woop, Benthin and Wald (2013): the corners
//! are projected along the ray, which becomes a point, and the point is
//! inside when the four signed volumes it spans with the faces agree in
//! sign. The signs are exact, of corners projected alike in every
//! tetrahedron, so neighbours decide as one: of two sharing a face exactly
//! one keeps the ray (both, when it lies exactly on the face), and around a
//! shared edge or corner at least one does. Signs do not depend on the
//! coordinates' scale.

use super::{piece, Barycentric, Hit, Miss, PrimitiveId, PrismCorners};
use crate::spacetime::Event;
use crate::spacetime::Ray;
use glam::{DMat3, DVec3, DVec4};

/// Barycentric coordinates this close to 0 (or below) leave inside or
/// outside to the watertight decision: far wider than the solve's rounding
/// (about 1e-11 for long, thin tetrahedra moving at 0.9c, larger at 100x
/// coordinates), far narrower than any pixel.
pub(crate) const EXACT_BAND: f64 = 1e-7;

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
    /// The solve of the tetrahedron with `corners`; `None` when it has no
    /// 3-volume (cannot be hit).
    pub fn new(corners: &[Event; 4]) -> Option<PreparedTet> {
        let v = corners.map(|e| e.to_xyzt());
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

    /// The barycentric solve of tetrahedron `tet`, piece `k` of the prism
    /// with `corners` (the piece it was prepared from). `range` bounds the
    /// ray parameter s (inclusive).
    pub fn intersect(
        &self,
        ray: &Ray,
        (tet, corners, k): (u32, &PrismCorners, usize),
        range: (f64, f64),
    ) -> Result<Hit, Miss> {
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
        let least = bary.iter().copied().fold(f64::INFINITY, f64::min);
        if !(least >= -EXACT_BAND && (least > EXACT_BAND || crosses(&piece(corners, k), o, d))) {
            return Err(Miss::Outside {
                s,
                bary: Barycentric::Tetrahedron(bary),
            });
        }
        let clamped = bary.map(|x| x.clamp(0.0, 1.0));
        Ok(Hit {
            s,
            event: Event::from_xyzt(p),
            primitive: PrimitiveId::Tetrahedron(tet),
            bary: Barycentric::Tetrahedron(clamped),
            stored: Hit::NOT_STORED,
        })
    }
}

/// Whether the line `o + s d` meets the tetrahedron with `corners`,
/// decided watertight (see the module's documentation): the corners
/// relative to `o` are sheared along `d` onto the three axes other than
/// `d`'s largest, where the line is the origin; the origin is inside when
/// the signed volumes it spans with the four faces (the barycentric
/// coordinates' numerators) all have one sign, zeros counting as either.
/// Each corner is projected by the same operations in every tetrahedron
/// that holds it, and each volume's sign is exact (Shewchuk's adaptive
/// orient3d), so the decisions of neighbours are those of one fixed set of
/// points: consistent across every shared face, edge and corner.
pub(crate) fn crosses(corners: &[Event; 4], o: DVec4, d: DVec4) -> bool {
    let k = (0..4).fold(
        0,
        |best, i| if d[i].abs() > d[best].abs() { i } else { best },
    );
    let projected = corners.map(|c| {
        let r = c.to_xyzt() - o;
        let mut p = [0.0; 3];
        for (j, i) in (0..4).filter(|&i| i != k).enumerate() {
            p[j] = r[i] - d[i] / d[k] * r[k];
        }
        robust::Coord3D {
            x: p[0],
            y: p[1],
            z: p[2],
        }
    });
    let origin = robust::Coord3D {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
    const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    let volumes =
        FACES.map(|[a, b, c]| robust::orient3d(projected[a], projected[b], projected[c], origin));
    let signed = [volumes[0], -volumes[1], volumes[2], -volumes[3]];
    let all = |f: fn(f64) -> bool| signed.iter().all(|&v| f(v));
    !all(|v| v == 0.0) && (all(|v| v >= 0.0) || all(|v| v <= 0.0))
}
