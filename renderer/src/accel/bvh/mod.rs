//! A bounding volume hierarchy over 4D boxes (x, y, z, t). Built once per
//! database; it only decides which items a ray is tested against, never how
//! (that is the barycentric solve of `geometry`).
//!
//! Items are anything with 4D bounds: the database uses one hierarchy over
//! the time slices of its stretches (lab frame) and one per stretch over its
//! prisms (in the stretch's comoving coordinates, [`super::space_bvh`]).
//! Both are built by [`build()`], binary, each inner node keeping both
//! children's boxes and stored children first, the root last; the
//! per-stretch tree is then collapsed into nodes of eight children. Here:
//! the boxes and node types both share, and the lab-frame hierarchy
//! ([`Bvh`], searched in `traverse`).

mod build;
mod traverse;

pub(super) use build::build;

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
        Bvh::enter(self.min, self.max, o, inv, range)
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

/// A hierarchy as built: inner nodes children first, the root (and its box)
/// apart, and the item order its leaves index.
pub(super) struct Built<N> {
    pub(super) nodes: Vec<N>,
    pub(super) root: Child,
    pub(super) root_bounds: Bounds4,
    pub(super) order: Vec<u32>,
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

/// An inner node of the lab-frame hierarchy: both children's 4D boxes.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    min: [DVec4; 2],
    max: [DVec4; 2],
    children: [Child; 2],
}

impl PairNode for Node {
    fn pair(bounds: [Bounds4; 2], children: [Child; 2]) -> Node {
        Node {
            min: bounds.map(|b| b.min),
            max: bounds.map(|b| b.max),
            children,
        }
    }

    fn children_mut(&mut self) -> &mut [Child; 2] {
        &mut self.children
    }
}

/// The hierarchy over 4D boxes (the lab frame's time slices).
pub(crate) struct Bvh(Built<Node>);

impl Bvh {
    /// Builds the hierarchy over items given by their 4D bounds (x, y, z,
    /// t), in order: item i is the i-th bounds.
    pub(crate) fn build(bounds: impl Iterator<Item = Bounds4>) -> Bvh {
        Bvh(build(bounds))
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
}
