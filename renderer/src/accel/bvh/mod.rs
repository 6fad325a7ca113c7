//! A bounding volume hierarchy over 4D boxes (x, y, z, t). Built once per
//! database; it only decides which items a ray is tested against, never how
//! (that is the barycentric solve of `geometry`).
//!
//! Items are anything with 4D bounds: the database uses one hierarchy over
//! the time slices of its stretches (lab frame) and one per stretch over its
//! prisms (in the stretch's comoving coordinates). Both are built by
//! [`build_with_leaves`], binary, each inner node keeping both children's boxes and
//! stored children first, the root last, then collapsed into nodes of
//! eight children ([`super::wide`]). Here: the boxes, the f64 slab test and
//! the node types both share.

mod build;

pub(super) use build::{build_with_leaves, LEAF_SIZE};

use glam::DVec4;

/// An axis-aligned box of spacetime: lower and upper corners, (x, y, z, t).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bounds4 {
    pub(crate) min: DVec4,
    pub(crate) max: DVec4,
}

impl Bounds4 {
    /// The box from `min` to `max`.
    pub(crate) fn new(min: DVec4, max: DVec4) -> Bounds4 {
        Bounds4 { min, max }
    }

    /// Entry parameter of the ray `o + s d` (`inv` = 1/d) into the box
    /// within `range`, if any: the test the hierarchy's nodes make.
    #[inline(always)]
    pub(crate) fn entry(&self, o: DVec4, inv: DVec4, range: (f64, f64)) -> Option<f64> {
        enter(self.min, self.max, o, inv, range)
    }

    /// The box padded as a hierarchy pads a leaf's (see [`build::pad`]).
    pub(crate) fn padded(self) -> Bounds4 {
        let (min, max) = build::pad(self.min, self.max);
        Bounds4 { min, max }
    }

    fn centroid(self) -> DVec4 {
        (self.min + self.max) * 0.5
    }
}

/// How far a box is widened for the rounding of coordinates computed inside
/// it: 1e-9 of its extent plus 1e-12 of its coordinates' magnitude, the
/// largest over the three space axes on each of them, and its own on t.
/// Space is padded alike so that a flat box (a sheet in z = 0) is as wide
/// across as a rounding off its plane: a point computed there at z = -1e-15
/// would otherwise fall outside it.
#[inline]
pub(crate) fn rounding_margin(min: DVec4, max: DVec4) -> DVec4 {
    let per_axis = (max - min) * 1e-9 + (max.abs() + min.abs()) * 1e-12;
    let space = per_axis.x.max(per_axis.y).max(per_axis.z);
    DVec4::new(space, space, space, per_axis.w)
}

/// Entry parameter of the ray into the box `min..max` within `range`,
/// if any. `inv` holds 1/d per axis (infinite for d = 0: such an axis
/// constrains nothing unless the origin lies outside the slab); the
/// near face of each axis is the lower one when 1/d is positive
/// (+inf included) and the upper one otherwise.
#[inline(always)]
fn enter(min: DVec4, max: DVec4, o: DVec4, inv: DVec4, range: (f64, f64)) -> Option<f64> {
    let a = ((min - o) * inv).to_array();
    let b = ((max - o) * inv).to_array();
    let inv = inv.to_array();
    let (mut lo, mut hi) = range;
    for k in 0..4 {
        let (near, far) = if inv[k] < 0.0 {
            (b[k], a[k])
        } else {
            (a[k], b[k])
        };
        // A NaN (0 * inf: the origin on a slab face of a parallel
        // axis) fails both comparisons and is dropped, which keeps the
        // test conservative.
        if near > lo {
            lo = near;
        }
        if far < hi {
            hi = far;
        }
    }
    (lo <= hi).then_some(lo)
}

/// What a node's child is: an inner node, or a leaf's items.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Child {
    /// Inner: index of the node; leaf: first index into the item order.
    pub(super) index: u32,
    /// Number of items of a leaf; 0 for an inner node.
    pub(super) count: u32,
}

/// An inner node as a hierarchy stores it, made from its children's boxes.
pub(super) trait PairNode: Send {
    /// The node over two children with (padded) boxes `bounds`.
    fn pair(bounds: [Bounds4; 2], children: [Child; 2]) -> Self;
    /// Its children, to renumber when a subtree built on its own is appended.
    fn children_mut(&mut self) -> &mut [Child; 2];
}

/// A hierarchy as built: inner nodes children first, the root apart, the
/// item order its leaves index, and the box of all its items, unpadded
/// (lower above upper when there are none).
pub(super) struct Built<N> {
    pub(super) nodes: Vec<N>,
    pub(super) root: Child,
    pub(super) order: Vec<u32>,
    pub(super) extent: Bounds4,
}

/// A traversal's stack of (child, entry parameter): a small array, zeroed
/// (cheap to set up for each of the many searches of a ray, one per
/// stretch it meets), that holds all a ray needs in practice, spilling
/// into a vector beyond it.
pub(super) struct Stack<E> {
    fixed: [E; 8],
    len: usize,
    spill: Vec<E>,
}

impl<E: Copy + Default> Stack<E> {
    pub(super) fn new() -> Stack<E> {
        Stack {
            fixed: [E::default(); 8],
            len: 0,
            spill: Vec::new(),
        }
    }

    #[inline(always)]
    pub(super) fn push(&mut self, entry: E) {
        if self.len < self.fixed.len() {
            self.fixed[self.len] = entry;
            self.len += 1;
        } else {
            self.spill.push(entry);
        }
    }

    #[inline(always)]
    pub(super) fn pop(&mut self) -> Option<E> {
        if let Some(e) = self.spill.pop() {
            return Some(e);
        }
        self.len = self.len.checked_sub(1)?;
        Some(self.fixed[self.len])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stack gives back what was pushed, last first, across its spill
    /// from the array into the vector and back.
    #[test]
    fn the_stack_is_last_in_first_out_beyond_its_array() {
        let mut stack = Stack::new();
        for round in 0..2u32 {
            for i in 0..40 {
                stack.push(i + round);
            }
            for i in (0..40).rev() {
                assert_eq!(stack.pop(), Some(i + round));
            }
            assert_eq!(stack.pop(), None);
        }
    }

    /// A ray parallel to an axis (either signed zero) whose origin lies
    /// exactly on one of the box's faces on that axis enters it; one just
    /// outside does not. (Taking the near face as the lesser of the two
    /// crossings, as before, let the NaN of 0 * inf on the lower face pass
    /// the upper face's +inf as the entry: such boxes were culled.)
    #[test]
    fn a_parallel_ray_from_a_face_enters_the_box() {
        let (min, max) = (
            DVec4::new(0.0, 0.0, 0.0, 0.0),
            DVec4::new(1.0, 1.0, 1.0, 1.0),
        );
        for axis in 0..4 {
            for zero in [0.0, -0.0] {
                for (face, inside) in [
                    (0.0, true),
                    (1.0, true),
                    (-1e-9, false),
                    (1.0 + 1e-9, false),
                ] {
                    let mut o = DVec4::splat(0.5) - DVec4::new(3.0, 2.0, 2.5, 1.5);
                    let mut d = DVec4::new(3.0, 2.0, 2.5, 1.5);
                    o[axis] = face;
                    d[axis] = zero;
                    let entered = enter(min, max, o, DVec4::ONE / d, (0.0, 10.0)).is_some();
                    assert_eq!(
                        entered, inside,
                        "axis {axis}, d = {zero:?}, origin on {face}"
                    );
                }
            }
        }
    }
}
