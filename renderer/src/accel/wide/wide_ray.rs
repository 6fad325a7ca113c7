//! The eight-lane f32 slab test of a ray against a node's boxes, made
//! conservative.

use super::{down, up, WideNode, WIDTH};
use crate::simd::Simd8;

/// Relative margin of the f32 slab parameters: each is (face - origin) *
/// (1/d) with three roundings to nearest of at most 2^-24 each (the
/// subtraction, 1/d to f32, the product), and the margin itself is applied
/// to 1/d with one more; 2^-20 covers them with room to spare.
const MARGIN: f32 = 1.0 / (1u32 << 20) as f32;
/// Absolute margin, for parameters in f32's subnormal range (where the
/// roundings are absolute, at most 2^-150 each).
const TINY: f32 = f32::MIN_POSITIVE;

/// A ray prepared for the eight-lane f32 slab test.
///
/// The test is conservative, so that a box the ray enters is never culled:
/// - each face is met from an origin rounded to f32 toward the side that
///   moves the crossing outward (for a near face, so that it is crossed no
///   later; for a far face, no sooner): per axis, one origin for the near
///   faces and one for the far;
/// - the crossings are found with 1/d made smaller in magnitude by
///   [`MARGIN`] for the near faces and larger for the far ones, which
///   covers the rounding of the subtraction, of 1/d and of the product:
///   a crossing at a positive parameter (the only kind that can decide,
///   the searched range starting at zero or later) is so found no later
///   at a near face and no sooner at a far one; the entry and exit are
///   then moved out by [`TINY`], for parameters in f32's subnormal range;
/// - a NaN (0 * inf: an axis the ray is parallel to, its origin exactly on
///   a face) is dropped, as in f64.
///
/// Parameters beyond f32's range become infinite, and a direction component
/// below 2^-128 makes 1/d infinite: the ray is then treated as parallel to
/// that axis, which can cull a box only when, on that axis, the box's face
/// lies within 2^-128 times the longest searched ray parameter of the
/// origin.
pub(super) struct WideRay<const A: usize, S: Simd8> {
    /// The vector level the test runs at.
    simd: S,
    /// Per axis: the origin for the near faces and for the far faces, and
    /// 1/d for each, moved by [`MARGIN`] toward zero (near) and away from
    /// it (far).
    near_o: [S::F; A],
    far_o: [S::F; A],
    near_inv: [S::F; A],
    far_inv: [S::F; A],
    /// Per axis, the side of a node's boxes whose face the ray crosses
    /// entering: 0 for the lower faces (a positive direction), 1 for the
    /// upper; it leaves through the other.
    near_side: [usize; A],
}

impl<const A: usize, S: Simd8> WideRay<A, S> {
    /// The ray `o + s d` given `o` and `inv` = 1/d, tested at the level of
    /// `simd`.
    #[inline(always)]
    pub(super) fn new(simd: S, o: [f64; A], inv: [f64; A]) -> WideRay<A, S> {
        let zero = simd.splat(0.0);
        let mut ray = WideRay {
            simd,
            near_o: [zero; A],
            far_o: [zero; A],
            near_inv: [zero; A],
            far_inv: [zero; A],
            near_side: [0; A],
        };
        for a in 0..A {
            let (lower, upper) = (simd.splat(down(o[a])), simd.splat(up(o[a])));
            let inv32 = inv[a] as f32;
            ray.near_inv[a] = simd.splat(inv32 * (1.0 - MARGIN));
            ray.far_inv[a] = simd.splat(inv32 * (1.0 + MARGIN));
            // 1/(-0) = -inf: a direction of -0 is negative here.
            if inv[a].is_sign_negative() {
                (ray.near_o[a], ray.far_o[a]) = (lower, upper);
                ray.near_side[a] = 1;
            } else {
                (ray.near_o[a], ray.far_o[a]) = (upper, lower);
            }
        }
        ray
    }

    /// Where the ray enters each of a node's eight boxes within `range`
    /// (in f32, rounded outward), and which it enters (bit i for child i).
    #[inline(always)]
    pub(super) fn enter(&self, node: &WideNode<A>, range: (f32, f32)) -> ([f32; WIDTH], u32) {
        let (entry, entered) = self.enter_lanes(node, range);
        (self.simd.to_array(entry), self.simd.bits(entered))
    }

    /// [`WideRay::enter`] with the entries kept in lanes, and a lane of all
    /// ones for each box entered.
    #[inline(always)]
    pub(super) fn enter_lanes(&self, node: &WideNode<A>, range: (f32, f32)) -> (S::F, S::F) {
        self.enter_from(&self.offsets(node), range)
    }

    /// A node's faces less this ray's origins, per axis: the near faces'
    /// and the far faces'. Rays that start at the same point with the
    /// same direction signs have the same origins ([`WideRay::new`]), so
    /// a packet of them finds these once a node for all its rays.
    #[inline(always)]
    pub(super) fn offsets(&self, node: &WideNode<A>) -> [(S::F, S::F); A] {
        let s = self.simd;
        std::array::from_fn(|a| {
            // (A side of 0 or 1 and an axis below A: indices that need no
            // bounds check.)
            let side = self.near_side[a] & 1;
            let near_face = s.load(node.faces[side][a]);
            let far_face = s.load(node.faces[side ^ 1][a]);
            (
                s.sub(near_face, self.near_o[a]),
                s.sub(far_face, self.far_o[a]),
            )
        })
    }

    /// [`WideRay::enter_lanes`] from the node's [`WideRay::offsets`] (this
    /// ray's, or those of a ray with the same origins).
    #[inline(always)]
    pub(super) fn enter_from(
        &self,
        offsets: &[(S::F, S::F); A],
        range: (f32, f32),
    ) -> (S::F, S::F) {
        let s = self.simd;
        let mut entry = s.splat(range.0);
        let mut exit = s.splat(range.1);
        for (a, &(near_offset, far_offset)) in offsets.iter().enumerate() {
            let near = s.mul(near_offset, self.near_inv[a]);
            let far = s.mul(far_offset, self.far_inv[a]);
            // A NaN (an axis the ray is parallel to) is dropped.
            entry = s.max_or_second(near, entry);
            exit = s.min_or_second(far, exit);
        }
        let tiny = s.splat(TINY);
        let (entry, exit) = (s.sub(entry, tiny), s.add(exit, tiny));
        (entry, s.le(entry, exit))
    }

    /// The vector level the test runs at.
    #[inline(always)]
    pub(super) fn simd(&self) -> S {
        self.simd
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{aimed_ray, f64_entry, random_box, Box64};
    use super::super::NO_CHILD;
    use super::*;
    use crate::rng::SplitMix64;
    use crate::simd::{wider, Baseline};
    use wide::f32x8;

    /// The same slab test in f32 without care: origin and 1/d rounded to
    /// nearest, no margin (the negative control).
    fn naive_enters<const A: usize>(
        b: &Box64<A>,
        o: [f64; A],
        d: [f64; A],
        range: (f64, f64),
    ) -> bool {
        let (mut lo, mut hi) = (range.0 as f32, range.1 as f32);
        for a in 0..A {
            let inv = (1.0 / d[a]) as f32;
            let (t0, t1) = (
                (b[0][a] as f32 - o[a] as f32) * inv,
                (b[1][a] as f32 - o[a] as f32) * inv,
            );
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        }
        lo <= hi
    }

    /// Over `A` axes, rays aimed at the corners, edges and faces of boxes
    /// at scales from 0.05 to 1e5, parallel to an axis or not: the
    /// eight-lane f32 test enters every box the f64 test enters, no later,
    /// at the vector level of `simd`; the naive f32 test (the negative
    /// control) culls some.
    fn never_culls<const A: usize>(simd: impl Simd8, seed: u64) {
        let mut rng = SplitMix64::new(seed);
        let (mut entered, mut naive_culled) = (0, 0);
        for n in 0..200_000 {
            let scale = [0.05, 1.0, 300.0, 1e5][n % 4];
            let boxes: [Box64<A>; WIDTH] = std::array::from_fn(|_| random_box(&mut rng, scale));
            let lane = n % WIDTH;
            let (o, d) = aimed_ray(&mut rng, &boxes[lane], scale);
            let inv = d.map(|d| 1.0 / d);
            let range = match n % 3 {
                0 => (0.0, f64::INFINITY),
                1 => (0.25 * scale, 1e3 * scale),
                _ => (0.0, (boxes[lane][0][0] - o[0]).abs() + scale),
            };
            let node = WideNode {
                faces: [0, 1].map(|side| {
                    std::array::from_fn(|a| f32x8::from(boxes.map(|b| b[side][a] as f32)))
                }),
                children: [NO_CHILD; WIDTH],
            };
            let (entries, mask) =
                WideRay::new(simd, o, inv).enter(&node, (down(range.0), up(range.1)));
            for (k, b) in boxes.iter().enumerate() {
                let Some(exact) = f64_entry(b, o, inv, range) else {
                    continue;
                };
                entered += 1;
                assert!(
                    mask & (1 << k) != 0 && f64::from(entries[k]) <= exact,
                    "culled: box {b:?}, ray {o:?} + s {d:?}, range {range:?}"
                );
                if k == lane && !naive_enters(b, o, d, range) {
                    naive_culled += 1;
                }
            }
        }
        assert!(entered > 100_000, "{entered}");
        assert!(naive_culled > 100, "the control culled only {naive_culled}");
    }

    /// Boxes of comoving space (x, y, z), as a stretch's hierarchy holds.
    #[test]
    fn the_f32_slab_test_never_culls_a_space_box_the_ray_enters() {
        never_culls::<3>(Baseline, 21);
        if let Some(wider) = wider() {
            never_culls::<3>(wider, 21);
        }
    }

    /// Boxes of spacetime (x, y, z, t), as the top level holds.
    #[test]
    fn the_f32_slab_test_never_culls_a_spacetime_box_the_ray_enters() {
        never_culls::<4>(Baseline, 23);
        if let Some(wider) = wider() {
            never_culls::<4>(wider, 23);
        }
    }
}
