//! One stretch's hierarchy over its prisms, in the stretch's comoving x, y,
//! z only. Every prism of a stretch lives over the stretch's lab times, and
//! the top level has already cut the ray to those of one time slice, so
//! time tells the prisms nothing apart. Each node keeps both children's
//! boxes side by side: a step of the traversal reads one node and tests
//! both, with the near and far face of each axis chosen once per ray by
//! the sign of its direction.

use super::bvh::{build, closest_in, Bounds4, Child, PairNode};
use crate::geometry::Hit;
use glam::DVec3;

/// An inner node: its two children and their boxes, one cache line. The
/// boxes are in f32 rounded outward, so each holds its f64 box (no hit is
/// lost), and are tested in f64, into which every f32 converts exactly.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Node {
    /// Lower x, y, z then upper x, y, z, each for both children.
    bounds: [[f32; 2]; 6],
    children: [Child; 2],
}

/// The f32 at or below `v`.
fn down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v {
        -next_up(-f)
    } else {
        f
    }
}

/// The f32 at or above `v`.
fn up(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) < v {
        next_up(f)
    } else {
        f
    }
}

/// The least f32 above `f`, a finite value or -infinity (f32::next_up,
/// stable only since Rust 1.86).
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

impl PairNode for Node {
    fn pair(boxes: [Bounds4; 2], children: [Child; 2]) -> Node {
        let mut bounds = [[0.0; 2]; 6];
        for (c, b) in boxes.iter().enumerate() {
            for axis in 0..3 {
                bounds[axis][c] = down(b.min[axis]);
                bounds[axis + 3][c] = up(b.max[axis]);
            }
        }
        Node { bounds, children }
    }

    fn children_mut(&mut self) -> &mut [Child; 2] {
        &mut self.children
    }

    fn children(&self) -> [Child; 2] {
        self.children
    }
}

/// The hierarchy: inner nodes children first, the root's own box (a tree
/// of one leaf has no inner node), and the item order the leaves index.
#[derive(Clone, Debug)]
pub(crate) struct SpaceBvh {
    nodes: Vec<Node>,
    root: Child,
    root_bounds: [f64; 6],
    order: Vec<u32>,
}

impl SpaceBvh {
    /// Builds the hierarchy over boxes that all span the same lab times,
    /// in order: item i is the i-th bounds.
    pub(crate) fn build(bounds: impl Iterator<Item = Bounds4>) -> SpaceBvh {
        let built = build::<Node>(bounds);
        let (lo, hi) = (built.root_bounds.min, built.root_bounds.max);
        SpaceBvh {
            nodes: built.nodes,
            root: built.root,
            root_bounds: [lo.x, lo.y, lo.z, hi.x, hi.y, hi.z],
            order: built.order,
        }
    }

    /// The closest hit along the ray `o + s d` (comoving x, y, z) within
    /// `range`: `test(item, range)` is called for every item whose box the
    /// ray enters, with the range shrunk to the best hit so far.
    pub(crate) fn closest(
        &self,
        o: DVec3,
        d: DVec3,
        range: (f64, f64),
        test: impl FnMut(u32, (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if self.root.count == 0 && self.nodes.is_empty() {
            return None; // no items
        }
        let ray = SlabRay::new(o, d);
        let entry = ray.enter_root(&self.root_bounds, range)?;
        let enter = |node: &Node, r| ray.enter(&node.bounds, r);
        closest_in(
            (&self.nodes, &self.order),
            (self.root, entry),
            range,
            enter,
            test,
        )
    }
}

impl SlabRay {
    /// Entry parameter of the ray into the root's box (f64) within `range`.
    fn enter_root(&self, bounds: &[f64; 6], range: (f64, f64)) -> Option<f64> {
        let (mut lo, mut hi) = range;
        for a in 0..3 {
            lo = lo.max((bounds[self.near[a]] - self.o[a]) * self.inv[a]);
            hi = hi.min((bounds[self.far[a]] - self.o[a]) * self.inv[a]);
        }
        (lo <= hi).then_some(lo)
    }
}

/// A ray prepared for slab tests: origin, inverse direction, and which of
/// a box's bounds is met first on each axis.
struct SlabRay {
    o: [f64; 3],
    inv: [f64; 3],
    /// Per axis, the index into a node's bounds of the near face and of the
    /// far one (lower then upper when the direction is positive).
    near: [usize; 3],
    far: [usize; 3],
}

impl SlabRay {
    fn new(o: DVec3, d: DVec3) -> SlabRay {
        let inv = (DVec3::ONE / d).to_array();
        let negative = |a: usize| inv[a] < 0.0;
        SlabRay {
            o: o.to_array(),
            inv,
            near: [0, 1, 2].map(|a| if negative(a) { a + 3 } else { a }),
            far: [0, 1, 2].map(|a| if negative(a) { a } else { a + 3 }),
        }
    }

    /// Entry parameters of the ray into both boxes of `bounds` within
    /// `range`. A NaN (0 * inf: the origin on a slab face of an axis the
    /// ray is parallel to) is dropped by f64::max/min, which keeps the test
    /// conservative.
    #[inline(always)]
    fn enter(&self, bounds: &[[f32; 2]; 6], range: (f64, f64)) -> [Option<f64>; 2] {
        let (mut lo, mut hi) = ([range.0; 2], [range.1; 2]);
        for a in 0..3 {
            let (near, far) = (&bounds[self.near[a]], &bounds[self.far[a]]);
            for c in 0..2 {
                lo[c] = lo[c].max((f64::from(near[c]) - self.o[a]) * self.inv[a]);
                hi[c] = hi[c].min((f64::from(far[c]) - self.o[a]) * self.inv[a]);
            }
        }
        [
            (lo[0] <= hi[0]).then_some(lo[0]),
            (lo[1] <= hi[1]).then_some(lo[1]),
        ]
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
