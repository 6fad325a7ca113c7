//! One stretch's hierarchy over its prisms, in the stretch's comoving x, y,
//! z only. Every prism of a stretch lives over the stretch's lab times, and
//! the top level has already cut the ray to those of one time slice, so
//! time tells the prisms nothing apart.
//!
//! The tree is built binary (the shared SAH builder) and collapsed into
//! nodes of eight children, whose boxes sit side by side per face in f32
//! rounded outward: one node visit tests the eight boxes at once in 8-lane
//! SIMD (through the `wide` crate: two SSE2 registers on every x86-64, one
//! AVX register when built for it). A ray of the benchmark's 1M tori
//! visits 6.7 nodes, against 9.9 with four children. The slab test runs in
//! f32 and is made conservative (a box the ray enters is never culled, see
//! [`wide_ray::WideRay`]), so which prisms are tested, and so which hit is
//! found, is decided by the leaf tests alone.
//!
//! Here: the collapsed tree's layout and the rounding of bounds to f32;
//! the tree is built in `build`, searched in `traverse`, with the slab test
//! of `wide_ray`.

mod build;
mod traverse;
mod wide_ray;

use super::bvh::Child;
use wide::f32x8;

/// The f32 at or below `v`.
#[inline(always)]
pub(super) fn down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v {
        -next_up(-f)
    } else {
        f
    }
}

/// The f32 at or above `v`.
#[inline(always)]
pub(super) fn up(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) < v {
        next_up(f)
    } else {
        f
    }
}

/// The least f32 above `f`, a finite value or -infinity (f32::next_up,
/// stable only since Rust 1.86).
#[inline(always)]
fn next_up(f: f32) -> f32 {
    let bits = f.to_bits();
    if f == 0.0 {
        f32::from_bits(1)
    } else if f > 0.0 {
        f32::from_bits(bits + 1)
    } else {
        f32::from_bits(bits - 1)
    }
}

/// Children of a node of the collapsed tree.
const WIDTH: usize = 8;

/// A node of the collapsed tree: its eight children's boxes, per face (lower
/// x, y, z then upper x, y, z) one lane a child, in f32 rounded outward.
/// An empty slot has lower bounds +inf and upper -inf, which no ray enters.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct WideNode {
    faces: [f32x8; 6],
    children: [Child; WIDTH],
}

const NO_CHILD: Child = Child { index: 0, count: 0 };

/// The hierarchy: nodes of eight children (the root first; a tree of one
/// leaf has none) and the item order the leaves index.
#[derive(Clone, Debug)]
pub(crate) struct SpaceBvh {
    nodes: Vec<WideNode>,
    root: Child,
    order: Vec<u32>,
}

impl SpaceBvh {
    /// The item order of the leaves: position j of a leaf holds item
    /// `order()[j]`.
    pub(crate) fn order(&self) -> &[u32] {
        &self.order
    }
}

/// Helpers shared by the hierarchy's tests.
#[cfg(test)]
mod test_support {
    use super::{down, up};
    use crate::accel::bvh::Bounds4;
    use crate::rng::SplitMix64;
    use glam::{DVec3, DVec4};

    /// Entry parameter of the ray `o + s d` (`inv` = 1/d) into the box (f64)
    /// within `range`: the reference the f32 test is held to, the top
    /// level's own f64 slab test (the box at one lab time, met by a ray of
    /// constant time, so that t constrains nothing).
    pub(super) fn f64_entry(
        bounds: &[f64; 6],
        o: DVec3,
        inv: DVec3,
        range: (f64, f64),
    ) -> Option<f64> {
        let (min, max) = (
            DVec4::new(bounds[0], bounds[1], bounds[2], 0.0),
            DVec4::new(bounds[3], bounds[4], bounds[5], 0.0),
        );
        Bounds4::new(min, max).entry(o.extend(0.0), inv.extend(f64::INFINITY), range)
    }

    /// A box (lower then upper x, y, z) with f32 faces, at a random place
    /// and size of the scale `scale`.
    pub(super) fn random_box(rng: &mut SplitMix64, scale: f64) -> [f64; 6] {
        let c = [0; 3].map(|_| (rng.next_f64() - 0.5) * scale);
        let h = [0; 3].map(|_| rng.next_f64() * 0.1 * scale);
        let (lo, hi) = (
            [0, 1, 2].map(|a| f64::from(down(c[a] - h[a]))),
            [0, 1, 2].map(|a| f64::from(up(c[a] + h[a]))),
        );
        [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
    }

    /// A ray aimed exactly at a corner, an edge or a face of `b` from up
    /// to 1000 times its scale away; one in four runs parallel to an axis
    /// with its origin on a face plane (signed zero directions included).
    pub(super) fn aimed_ray(rng: &mut SplitMix64, b: &[f64; 6], scale: f64) -> (DVec3, DVec3) {
        let mut target = DVec3::ZERO;
        let kind = (rng.next_u64() % 3) as usize; // 0 corner, 1 edge, 2 face
        for a in 0..3 {
            let on_face = a + kind < 3;
            let side = (rng.next_u64() % 2) as usize * 3;
            let t = rng.next_f64();
            target[a] = if on_face {
                b[a + side]
            } else {
                b[a] + t * (b[a + 3] - b[a])
            };
        }
        let mut d = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0 - 1.0;
        if rng.next_u64() % 4 == 0 {
            let a = (rng.next_u64() % 3) as usize;
            d[a] = if rng.next_u64() % 2 == 0 { 0.0 } else { -0.0 };
            target[a] = b[a + 3 * (rng.next_u64() % 2) as usize];
        }
        let d = d.normalize();
        let far = scale * (1.0 + 1000.0 * rng.next_f64());
        let mut o = target - d * far;
        for a in 0..3 {
            if d[a] == 0.0 {
                o[a] = target[a];
            }
        }
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
}
