//! A prism of a straight stretch tested whole (paper 3.1-3.2, in the
//! stretch's comoving frame).
//!
//! Over a translation every point of the object moves with the reference
//! point, so in the sheared coordinates x' = x - v (t - t0) - x0 (the
//! Galilean comoving frame of the lab-frame worldline, exact for H_obj and
//! for a Lorentz-contracted V_obj alike) the prism is its triangle at rest,
//! times the stretch's lab time span. A ray `o + s d` stays a straight line
//! there with the same parameter s: x'(s) = o' + s (d.x - v d.t). It meets
//! the prism where that 3D line crosses the triangle at a lab time
//! t = o.t + s d.t inside the span: one triangle test instead of the three
//! tetrahedron solves of the paper's cut, which tile the same prism.
//!
//! The triangle test is the watertight one of Woop, Benthin and Wald
//! (2013): the corners are sheared along the ray, which becomes the origin
//! of a plane, and the ray is inside when the three edge functions (signed
//! areas the origin spans with each edge) agree in sign. An edge function
//! depends only on its edge's two sheared corners, which neighbouring
//! triangles compute by the same operations from the same comoving corners;
//! near zero its sign is made exact (Shewchuk's adaptive orient2d), so
//! neighbours decide as one around every shared edge and corner, at any
//! coordinate scale.

use super::{Barycentric, Miss};
use glam::DVec3;

/// A ray in a straight stretch's comoving coordinates, sheared for the
/// watertight test: prepared once per ray and stretch.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ComovingRay {
    /// Comoving position at s = 0, its coordinates in the order of `axes`.
    origin: [f64; 3],
    /// Lab time at s = 0 and its rate along the ray.
    t: f64,
    dt: f64,
    /// The axis along which the comoving direction is largest, last, and the
    /// other two in an order that keeps the triangle's winding.
    axes: [usize; 3],
    /// The shear taking the comoving direction to the third axis, unit length.
    shear: DVec3,
}

/// The line `o + s d` (lab (x, y, z, t)) in the comoving coordinates
/// x' = x - v (t - t0) - x0 of the reference point at `x0` at lab time `t0`
/// moving with `velocity`: its position at s = 0 and its direction, the
/// parameter s unchanged. The one comoving transform of rays, for the
/// hierarchy's boxes and the triangle test alike.
#[inline]
pub(crate) fn comoving_line(
    o: glam::DVec4,
    d: glam::DVec4,
    (t0, x0): (f64, DVec3),
    velocity: DVec3,
) -> (DVec3, DVec3) {
    (
        o.truncate() - velocity * (o.w - t0) - x0,
        d.truncate() - velocity * d.w,
    )
}

impl ComovingRay {
    /// The ray `o + s d`, both (x, y, z, t) in lab coordinates, in the
    /// comoving coordinates of the reference point at `x0` at lab time `t0`
    /// moving with `velocity`; `None` when it is at rest there (a decoupled
    /// object moving with the light), when it meets no triangle.
    #[inline]
    pub(crate) fn new(
        o: glam::DVec4,
        d: glam::DVec4,
        (t0, x0): (f64, DVec3),
        velocity: DVec3,
    ) -> Option<ComovingRay> {
        let (origin, dir) = comoving_line(o, d, (t0, x0), velocity);
        let abs = dir.abs();
        let kz = if abs.x > abs.y {
            if abs.x > abs.z {
                0
            } else {
                2
            }
        } else if abs.y > abs.z {
            1
        } else {
            2
        };
        if dir[kz] == 0.0 || !dir[kz].is_finite() {
            return None;
        }
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Some(ComovingRay {
            origin: [origin[kx], origin[ky], origin[kz]],
            t: o.w,
            dt: d.w,
            axes: [kx, ky, kz],
            shear: DVec3::new(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]),
        })
    }

    /// The comoving origin and the axes, in the ray's axis order, and the
    /// shear's first two components (each at most 1 in magnitude).
    pub(crate) fn parts(&self) -> ([f64; 3], [usize; 3], [f64; 2]) {
        (self.origin, self.axes, [self.shear.x, self.shear.y])
    }

    /// A corner relative to the ray, sheared: the ray is the third axis.
    /// The corner's coordinates are read in the order of `axes` straight
    /// from memory (a DVec3's own index is a branch on the axis).
    #[inline(always)]
    fn sheared(&self, corner: &DVec3) -> DVec3 {
        let c: &[f64; 3] = corner.as_ref();
        let [kx, ky, kz] = self.axes;
        let [ox, oy, oz] = self.origin;
        let (rx, ry, rz) = (c[kx] - ox, c[ky] - oy, c[kz] - oz);
        DVec3::new(
            rx - self.shear.x * rz,
            ry - self.shear.y * rz,
            self.shear.z * rz,
        )
    }
}

/// Signed area of the origin with `a` and `b` (the 2D cross product
/// a x b), its sign exact: where rounding could have decided it, it is
/// computed again by Shewchuk's adaptive predicate.
#[inline]
fn edge(a: DVec3, b: DVec3) -> f64 {
    let (p, q) = (a.x * b.y, a.y * b.x);
    let e = p - q;
    // Shewchuk's ccwerrboundA, rounded up: beyond it the sign is right.
    if e.abs() > 3.3306690738754716e-16 * (p.abs() + q.abs()) {
        return e;
    }
    let c = |v: DVec3| robust::Coord { x: v.x, y: v.y };
    robust::orient2d(c(a), c(b), robust::Coord { x: 0.0, y: 0.0 })
}

/// The ray against the prism of the comoving triangle `corners` over lab
/// times `span`: the ray parameter s of the crossing within `range` and the
/// barycentric coordinates there (inclusive bounds throughout).
#[inline]
pub(crate) fn intersect_prism(
    corners: &[DVec3; 3],
    ray: &ComovingRay,
    span: (f64, f64),
    range: (f64, f64),
) -> Result<(f64, [f64; 3]), Miss> {
    let (a, b, c) = (
        ray.sheared(&corners[0]),
        ray.sheared(&corners[1]),
        ray.sheared(&corners[2]),
    );
    let (u, v, w) = (edge(c, b), edge(a, c), edge(b, a));
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        let det = u + v + w;
        let s = (u * a.z + v * b.z + w * c.z) / det;
        return Err(Miss::Outside {
            s,
            bary: Barycentric::Triangle([u / det, v / det, w / det]),
        });
    }
    let det = u + v + w;
    if det == 0.0 {
        return Err(Miss::Parallel);
    }
    let s = (u * a.z + v * b.z + w * c.z) / det;
    if !(s >= range.0 && s <= range.1) {
        return Err(Miss::OutOfRange { s });
    }
    let t = ray.t + s * ray.dt;
    if !(t >= span.0 && t <= span.1) {
        return Err(Miss::OutOfSpan { s, t });
    }
    Ok((s, [u / det, v / det, w / det]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use glam::DVec4;

    /// A static ray from `o` along unit `d`: lab time 0, infinite light speed.
    fn ray(o: DVec3, d: DVec3) -> ComovingRay {
        ComovingRay::new(
            o.extend(0.0),
            d.extend(0.0),
            (0.0, DVec3::ZERO),
            DVec3::ZERO,
        )
        .unwrap()
    }

    /// The textbook test (Moller-Trumbore): barycentric coordinates by
    /// division, each compared with zero on its own, so two triangles that
    /// share an edge may both reject a ray through it.
    fn textbook(c: &[DVec3; 3], o: DVec3, d: DVec3) -> bool {
        let (e1, e2) = (c[1] - c[0], c[2] - c[0]);
        let p = d.cross(e2);
        let det = e1.dot(p);
        let t = o - c[0];
        let u = t.dot(p) / det;
        let q = t.cross(e1);
        let v = d.dot(q) / det;
        u >= 0.0 && v >= 0.0 && u + v <= 1.0
    }

    fn random_unit(rng: &mut SplitMix64) -> DVec3 {
        loop {
            let v = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0 - 1.0;
            if (0.01..1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }

    /// Rays through points of an edge shared by two triangles, far from the
    /// origin (at 1e5, where rounding is coarse): the watertight test never
    /// lets one through; the textbook test, the negative control, does.
    #[test]
    fn a_ray_through_a_shared_edge_meets_one_of_its_triangles() {
        let mut rng = SplitMix64::new(3);
        let (mut leaks, mut textbook_leaks) = (0, 0);
        for _ in 0..20_000 {
            let base = DVec3::splat(1e5) + random_unit(&mut rng) * 10.0;
            let (a, b) = (base, base + random_unit(&mut rng) * 3.0);
            let normal = (b - a).cross(random_unit(&mut rng)).normalize();
            let side = (b - a).cross(normal).normalize();
            let (c1, c2) = (
                a + side * 2.0 + (b - a) * 0.3,
                a - side * 2.0 + (b - a) * 0.6,
            );
            let (t1, t2) = ([a, b, c1], [b, a, c2]);
            let aim = a.lerp(b, rng.next_f64());
            let d = (normal + random_unit(&mut rng) * 0.5).normalize();
            let o = aim - d * 50.0;
            let r = ray(o, d);
            let hit = |t: &[DVec3; 3]| intersect_prism(t, &r, (-1.0, 1.0), (0.0, 1e9)).is_ok();
            if !hit(&t1) && !hit(&t2) {
                leaks += 1;
            }
            if !textbook(&t1, o, d) && !textbook(&t2, o, d) {
                textbook_leaks += 1;
            }
        }
        assert_eq!(leaks, 0);
        assert!(textbook_leaks > 0, "the control found no leak to catch");
    }

    /// Near zero, the edge function's sign is the exact one, where the
    /// plain products' difference (the control) often has it wrong.
    #[test]
    fn the_edge_sign_is_exact_near_zero() {
        let mut rng = SplitMix64::new(4);
        let mut plain_wrong = 0;
        for _ in 0..100_000 {
            let a = DVec3::new(rng.next_f64(), rng.next_f64(), 0.0) * 1e3;
            // b nearly parallel to a: a x b is all rounding.
            let b =
                a * (1.0 + 1e-3 * rng.next_f64()) + DVec3::new(1e-13, -1e-13, 0.0) * rng.next_f64();
            let exact = robust::orient2d(
                robust::Coord { x: a.x, y: a.y },
                robust::Coord { x: b.x, y: b.y },
                robust::Coord { x: 0.0, y: 0.0 },
            );
            assert_eq!(edge(a, b).signum(), exact.signum(), "{a} {b}");
            if (a.x * b.y - a.y * b.x).signum() != exact.signum() {
                plain_wrong += 1;
            }
        }
        assert!(plain_wrong > 1000, "only {plain_wrong} plain signs wrong");
    }

    /// The time window: the triangle's crossing counts only within the
    /// prism's lab times.
    #[test]
    fn a_crossing_outside_the_lab_times_is_a_miss() {
        let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let o = DVec4::new(0.2, 0.2, 5.0, 10.0);
        let d = DVec4::new(0.0, 0.0, -1.0, -1.0);
        let r = ComovingRay::new(o, d, (0.0, DVec3::ZERO), DVec3::ZERO).unwrap();
        // Crossed at s = 5, lab time 5.
        assert!(intersect_prism(&tri, &r, (0.0, 6.0), (0.0, 1e9)).is_ok());
        assert!(matches!(
            intersect_prism(&tri, &r, (6.0, 9.0), (0.0, 1e9)),
            Err(Miss::OutOfSpan { t, .. }) if t == 5.0
        ));
    }
}
