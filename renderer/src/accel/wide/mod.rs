//! Hierarchies of nodes of eight children whose boxes sit side by side
//! per face in f32 rounded outward: one node visit tests the eight boxes
//! at once in 8-lane SIMD, at the widest vector level the machine offers
//! (`crate::simd`: one AVX register where there is AVX2, two SSE2 registers at
//! x86-64's baseline). Two live here, alike but for their axes:
//! - [`SpaceBvh`], one stretch's hierarchy over its prisms, in the
//!   stretch's comoving x, y, z only. Every prism of a stretch lives over
//!   the stretch's lab times, and the top level has already cut the ray to
//!   those of one time slice, so time tells the prisms nothing apart. A ray
//!   of the benchmark's 1M tori visits 6.7 nodes, against 9.9 with four
//!   children.
//! - [`SliceBvh`], the top level over all stretches' time slices, in the
//!   lab's x, y, z and t: a slice is a stretch over part of its lab times,
//!   bounded by its sweep over them.
//!
//! Both are built binary (the shared SAH builder over 4D boxes) and
//! collapsed into nodes of eight children. The slab test runs in f32 and
//! is made conservative (a box the ray enters is never culled, see
//! [`wide_ray::WideRay`]), so which items are tested, and so which hit is
//! found, is decided by the leaf tests alone.
//!
//! Here: the collapsed tree's layout and the rounding of bounds to f32;
//! the tree is built in `build`, searched in `traverse` (one ray) and
//! `packets`, with the slab test of `wide_ray` in the lanes of `simd`.

mod build;
mod packets;
mod traverse;
mod wide_ray;

pub(crate) use traverse::AxisRay;

use super::bvh::Child;
use wide::f32x8;

/// The f32 at or below `v`. (Both candidates are found and one taken, so
/// that no branch waits on the rounding's direction, which varies from
/// one value to the next.)
#[inline(always)]
pub(super) fn down(v: f64) -> f32 {
    let f = v as f32;
    let below = -next_up(-f);
    if f64::from(f) > v {
        below
    } else {
        f
    }
}

/// The f32 at or above `v` (as [`down`], without a branch).
#[inline(always)]
pub(super) fn up(v: f64) -> f32 {
    let f = v as f32;
    let above = next_up(f);
    if f64::from(f) < v {
        above
    } else {
        f
    }
}

/// The least f32 above `f`, a finite value or -infinity (f32::next_up,
/// stable only since Rust 1.86): one step of the bits away from zero for
/// a positive `f`, toward it for a negative one, and the least subnormal
/// for a zero of either sign.
#[inline(always)]
fn next_up(f: f32) -> f32 {
    let bits = f.to_bits();
    // All ones for a negative f: a step of -1, +1 otherwise.
    let negative = ((bits as i32) >> 31) as u32;
    let stepped = bits.wrapping_add((negative << 1) | 1);
    f32::from_bits(if f == 0.0 { 1 } else { stepped })
}

/// Children of a node of the collapsed tree.
const WIDTH: usize = 8;

/// A node of the collapsed tree over `A` axes: its eight children's boxes,
/// per face (lower faces, one per axis, then upper) one lane a child, in
/// f32 rounded outward. An empty slot has lower bounds +inf and upper
/// -inf, which no ray enters.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct WideNode<const A: usize> {
    faces: [[f32x8; A]; 2],
    children: [Child; WIDTH],
}

const NO_CHILD: Child = Child { index: 0, count: 0 };

/// A hierarchy over boxes of `A` axes: nodes of eight children (the root
/// first; a tree of one leaf has none) and the item order the leaves index.
#[derive(Clone, Debug)]
pub(crate) struct WideBvh<const A: usize> {
    nodes: Vec<WideNode<A>>,
    root: Child,
    order: Vec<u32>,
}

/// A stretch's hierarchy over its prisms, in comoving x, y, z.
pub(crate) type SpaceBvh = WideBvh<3>;

/// The top level's hierarchy over the stretches' time slices, in lab x, y,
/// z, t.
pub(crate) type SliceBvh = WideBvh<4>;

impl<const A: usize> WideBvh<A> {
    /// The item order of the leaves: position j of a leaf holds item
    /// `order()[j]`.
    pub(crate) fn order(&self) -> &[u32] {
        &self.order
    }
}

/// Helpers shared by the hierarchies' tests.
#[cfg(test)]
mod test_support {
    use super::{down, up};
    use crate::accel::bvh::Bounds4;
    use crate::rng::SplitMix64;
    use glam::DVec4;

    /// A box over `A` axes in f64: lower corner, upper corner.
    pub(super) type Box64<const A: usize> = [[f64; A]; 2];

    /// Entry parameter of the ray `o + s d` (`inv` = 1/d) into the box (f64)
    /// within `range`: the reference the f32 test is held to, the f64 slab
    /// test of [`Bounds4`] (a box of three axes taken at one lab time, met
    /// by a ray of constant time, so that t constrains nothing).
    pub(super) fn f64_entry<const A: usize>(
        b: &Box64<A>,
        o: [f64; A],
        inv: [f64; A],
        range: (f64, f64),
    ) -> Option<f64> {
        let (mut min, mut max) = (DVec4::ZERO, DVec4::ZERO);
        let (mut o4, mut inv4) = (DVec4::ZERO, DVec4::INFINITY);
        for a in 0..A {
            (min[a], max[a], o4[a], inv4[a]) = (b[0][a], b[1][a], o[a], inv[a]);
        }
        Bounds4::new(min, max).entry(o4, inv4, range)
    }

    /// A box with f32 faces, at a random place and size of the scale
    /// `scale`.
    pub(super) fn random_box<const A: usize>(rng: &mut SplitMix64, scale: f64) -> Box64<A> {
        let c: [f64; A] = std::array::from_fn(|_| (rng.next_f64() - 0.5) * scale);
        let h: [f64; A] = std::array::from_fn(|_| rng.next_f64() * 0.1 * scale);
        [
            std::array::from_fn(|a| f64::from(down(c[a] - h[a]))),
            std::array::from_fn(|a| f64::from(up(c[a] + h[a]))),
        ]
    }

    /// A ray `(o, d)` aimed exactly at a corner, an edge or a face of `b`
    /// from up to 1000 times its scale away; one in four runs parallel to
    /// an axis with its origin on a face plane (signed zero directions
    /// included).
    pub(super) fn aimed_ray<const A: usize>(
        rng: &mut SplitMix64,
        b: &Box64<A>,
        scale: f64,
    ) -> ([f64; A], [f64; A]) {
        let mut target = [0.0; A];
        // 0 a corner, 1 on all faces but one, ... (an edge or a face).
        let kind = (rng.next_u64() % A as u64) as usize;
        for (a, x) in target.iter_mut().enumerate() {
            let on_face = a + kind < A;
            let side = (rng.next_u64() % 2) as usize;
            let t = rng.next_f64();
            *x = if on_face {
                b[side][a]
            } else {
                b[0][a] + t * (b[1][a] - b[0][a])
            };
        }
        let mut d: [f64; A] = std::array::from_fn(|_| rng.next_f64() * 2.0 - 1.0);
        if rng.next_u64() % 4 == 0 {
            let a = (rng.next_u64() % A as u64) as usize;
            d[a] = if rng.next_u64() % 2 == 0 { 0.0 } else { -0.0 };
            target[a] = b[(rng.next_u64() % 2) as usize][a];
        }
        let length = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        let d = d.map(|x| x / length);
        let far = scale * (1.0 + 1000.0 * rng.next_f64());
        let o = std::array::from_fn(|a| {
            if d[a] == 0.0 {
                target[a]
            } else {
                target[a] - d[a] * far
            }
        });
        (o, d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rounded outward, every f32 bound holds its f64 value, and is the
    /// nearest f32 that does.
    #[test]
    fn boxes_round_outward() {
        for v in [
            0.0,
            1e-40,
            -1e-40,
            0.1,
            -0.1,
            1e5 + 1e-9,
            -3.3e38,
            7.0,
            f64::MAX,
        ] {
            let (d, u) = (down(v), up(v));
            assert!(f64::from(d) <= v && v <= f64::from(u), "{v}: {d} {u}");
            if v.abs() < 3e38 {
                assert!(f64::from(next_up(d)) > v || f64::from(d) == v, "{v}: {d}");
                assert!(f64::from(-next_up(-u)) < v || f64::from(u) == v, "{v}: {u}");
            }
        }
        assert_eq!(next_up(-0.0), f32::from_bits(1));
        assert_eq!(next_up(f32::NEG_INFINITY), f32::MIN);
    }

    /// The step without branches is the step by cases (zero, positive,
    /// negative), to the bit, on zeros, subnormals, extremes, infinities
    /// and random bits (NaN aside); the control: the same step without its case for zeros
    /// differs at -0.
    #[test]
    fn next_up_steps_as_by_cases() {
        let by_cases = |f: f32| {
            let bits = f.to_bits();
            if f == 0.0 {
                f32::from_bits(1)
            } else if f > 0.0 {
                f32::from_bits(bits + 1)
            } else {
                f32::from_bits(bits - 1)
            }
        };
        let mut rng = crate::rng::SplitMix64::new(5);
        let special = [
            0.0,
            -0.0,
            1e-45,
            -1e-45,
            f32::MAX,
            f32::MIN,
            f32::NEG_INFINITY,
            1.0,
        ];
        let random = (0..100_000).map(|_| f32::from_bits(rng.next_u64() as u32));
        for f in special.into_iter().chain(random).filter(|f| !f.is_nan()) {
            assert_eq!(next_up(f).to_bits(), by_cases(f).to_bits(), "{f:e}");
        }
        let unguarded = |f: f32| {
            let negative = ((f.to_bits() as i32) >> 31) as u32;
            f32::from_bits(f.to_bits().wrapping_add((negative << 1) | 1))
        };
        assert_ne!(unguarded(-0.0).to_bits(), by_cases(-0.0).to_bits());
    }
}
