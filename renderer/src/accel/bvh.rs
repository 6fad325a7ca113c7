//! A bounding volume hierarchy over 4D boxes (x, y, z, t). Built once per
//! database; it only decides which items a ray is tested against, never how
//! (that is the barycentric solve of `geometry`).
//!
//! Items are anything with 4D bounds: the database uses one hierarchy over
//! the time slices of its stretches (lab frame) and one per stretch over its
//! prisms (in the stretch's comoving coordinates, [`super::space_bvh`]).
//! Both are built here, binary, each inner node keeping both children's
//! boxes and stored children first, the root last; the per-stretch tree is
//! then collapsed into nodes of eight children.
//!
//! Splits are chosen by the surface area heuristic over binned centroids
//! on x, y, z and t, with the 4D boundary measure of a box as its area: the
//! time slices of moving objects are told apart by t, while for static
//! objects (which all live for the whole scene) a split along t gains
//! nothing and is not chosen.

use super::packet::{Lanes, PACKET};
use crate::geometry::{nearer, Hit};
use glam::DVec4;

const LEAF_SIZE: usize = 4;
/// Deeper subtrees become leaves (a bound on the recursion of the build).
const MAX_DEPTH: usize = 48;

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

    /// The box padded as a hierarchy pads a leaf's (see [`pad`]).
    pub(crate) fn padded(self) -> Bounds4 {
        let (min, max) = pad(self.min, self.max);
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

/// Half the boundary 3-volume of a 4D box (x, y, z, t; c = 1): by Cauchy's
/// formula, proportional to the chance that a random line meets it, the
/// surface area heuristic's measure in 4D. A short-lived box is less likely
/// to be met than a long-lived one of the same size.
fn area(min: DVec4, max: DVec4) -> f64 {
    let d = (max - min).max(DVec4::ZERO);
    d.x * d.y * d.z + d.w * (d.x * d.y + d.y * d.z + d.z * d.x)
}

/// An item while the hierarchy is built: its bounds beside its index, so
/// that every pass over a node's items reads them in order.
#[derive(Clone, Copy, Debug)]
struct Item {
    bounds: Bounds4,
    index: u32,
}

/// The box of a set of items and the box of their centroids.
#[derive(Clone, Copy, Debug)]
struct Extent {
    min: DVec4,
    max: DVec4,
    cmin: DVec4,
    cmax: DVec4,
}

impl Extent {
    const EMPTY: Extent = Extent {
        min: DVec4::INFINITY,
        max: DVec4::NEG_INFINITY,
        cmin: DVec4::INFINITY,
        cmax: DVec4::NEG_INFINITY,
    };

    #[inline]
    fn add(&mut self, b: &Bounds4) {
        self.min = self.min.min(b.min);
        self.max = self.max.max(b.max);
        let c = b.centroid();
        self.cmin = self.cmin.min(c);
        self.cmax = self.cmax.max(c);
    }

    fn of(items: &[Item]) -> Extent {
        let mut e = Extent::EMPTY;
        items.iter().for_each(|i| e.add(&i.bounds));
        e
    }
}

/// Subtrees of at least this many items are built on both threads.
const PARALLEL_ITEMS: usize = 16_384;

/// Centroid bins per axis of the surface area heuristic.
const BINS: usize = 16;

/// The bin of a place `x` along an axis (in bins from the lowest
/// centroid): `(x as usize).min(BINS - 1)` for every x, NaN and the
/// infinities included, through i64, whose saturating conversion takes
/// fewer instructions than usize's.
#[inline(always)]
fn bin_at(x: f64) -> usize {
    (x as i64).clamp(0, BINS as i64 - 1) as usize
}

/// Chooses a split of `items` (of extent `ext`) by the surface area
/// heuristic over binned centroids on x, y, z and t, one pass binning every
/// axis; moves the left part first and returns its length and both parts'
/// extents; `None` when no split beats a leaf. Deterministic: the same
/// items in the same order give the same split and order.
fn sah_split(items: &mut [Item], ext: &Extent) -> Option<(usize, Extent, Extent)> {
    let (min, max, cmin, extent) = (ext.min, ext.max, ext.cmin, ext.cmax - ext.cmin);
    let scale = DVec4::select(extent.cmpgt(DVec4::ZERO), BINS as f64 / extent, DVec4::ZERO);
    // A centroid's place in the bins of every axis (an array: glam's own
    // index is a branch on the axis).
    let place = |c: DVec4| ((c - cmin) * scale).to_array();
    let axes: Vec<usize> = (0..4).filter(|&a| extent[a] > 0.0).collect();
    let mut count = [[0usize; BINS]; 4];
    let mut bmin = [[DVec4::splat(f64::INFINITY); BINS]; 4];
    let mut bmax = [[DVec4::splat(f64::NEG_INFINITY); BINS]; 4];
    for item in items.iter() {
        let c = place(item.bounds.centroid());
        for &axis in &axes {
            let b = bin_at(c[axis]);
            count[axis][b] += 1;
            bmin[axis][b] = bmin[axis][b].min(item.bounds.min);
            bmax[axis][b] = bmax[axis][b].max(item.bounds.max);
        }
    }
    let parent = area(min, max).max(1e-300);
    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins on the left)
    for &axis in &axes {
        let (count, bmin, bmax) = (&count[axis], &bmin[axis], &bmax[axis]);
        // Sweep from the right to know each right part's box.
        let mut right_area = [0.0; BINS];
        let mut rcount = [0usize; BINS];
        let (mut rmin, mut rmax) = (DVec4::splat(f64::INFINITY), DVec4::splat(f64::NEG_INFINITY));
        let mut n = 0;
        for b in (1..BINS).rev() {
            rmin = rmin.min(bmin[b]);
            rmax = rmax.max(bmax[b]);
            n += count[b];
            right_area[b] = area(rmin, rmax);
            rcount[b] = n;
        }
        let (mut lmin, mut lmax) = (DVec4::splat(f64::INFINITY), DVec4::splat(f64::NEG_INFINITY));
        let mut lcount = 0;
        for split in 1..BINS {
            lmin = lmin.min(bmin[split - 1]);
            lmax = lmax.max(bmax[split - 1]);
            lcount += count[split - 1];
            if lcount == 0 || rcount[split] == 0 {
                continue;
            }
            let cost = 1.0
                + (area(lmin, lmax) * lcount as f64 + right_area[split] * rcount[split] as f64)
                    / parent;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, split));
            }
        }
    }
    let (cost, axis, split) = best?;
    if cost >= items.len() as f64 {
        return None;
    }
    let mut mid = 0;
    let (mut left, mut right) = (Extent::EMPTY, Extent::EMPTY);
    for i in 0..items.len() {
        let b = items[i].bounds;
        if bin_at(place(b.centroid())[axis]) < split {
            left.add(&b);
            items.swap(i, mid);
            mid += 1;
        } else {
            right.add(&b);
        }
    }
    Some((mid, left, right))
}

/// Pads a box so that hits accepted with barycentric slack are never culled.
fn pad(min: DVec4, max: DVec4) -> (DVec4, DVec4) {
    let e = rounding_margin(min, max) + DVec4::splat(1e-300);
    (min - e, max + e)
}

/// Builds the subtree over `items` (at `first` in the item order), its
/// inner nodes appended to `nodes` children first; returns it as a child,
/// with its padded box. Large subtrees build their two halves on both
/// threads, the second into nodes of its own appended after the first's:
/// the same nodes in the same order as a build on one thread.
fn build_into<N: PairNode>(
    nodes: &mut Vec<N>,
    items: &mut [Item],
    ext: Extent,
    (first, depth): (usize, usize),
) -> (Child, Bounds4) {
    let (pmin, pmax) = pad(ext.min, ext.max);
    let padded = Bounds4::new(pmin, pmax);
    let split = if items.len() <= LEAF_SIZE || depth >= MAX_DEPTH {
        None
    } else {
        sah_split(items, &ext)
    };
    let Some((mid, lext, rext)) = split else {
        let leaf = Child {
            index: first as u32,
            count: items.len() as u32,
        };
        return (leaf, padded);
    };
    let parallel = items.len() >= PARALLEL_ITEMS;
    let (left, right) = items.split_at_mut(mid);
    let (at_left, at_right) = ((first, depth + 1), (first + mid, depth + 1));
    let (l, r) = if parallel {
        let (l, (r, own)) = rayon::join(
            || build_into(nodes, left, lext, at_left),
            || {
                let mut own = Vec::new();
                let r = build_into(&mut own, right, rext, at_right);
                (r, own)
            },
        );
        (l, append(nodes, own, r))
    } else {
        let l = build_into(nodes, left, lext, at_left);
        (l, build_into(nodes, right, rext, at_right))
    };
    nodes.push(N::pair([l.1, r.1], [l.0, r.0]));
    let inner = Child {
        index: (nodes.len() - 1) as u32,
        count: 0,
    };
    (inner, padded)
}

/// Appends a subtree built into nodes of its own, renumbering its inner
/// nodes by where they land; returns its root renumbered alike.
fn append<N: PairNode>(
    nodes: &mut Vec<N>,
    subtree: Vec<N>,
    root: (Child, Bounds4),
) -> (Child, Bounds4) {
    let base = nodes.len() as u32;
    let moved = |c: &mut Child| {
        if c.count == 0 {
            c.index += base;
        }
    };
    nodes.reserve_exact(subtree.len());
    for mut n in subtree {
        n.children_mut().iter_mut().for_each(moved);
        nodes.push(n);
    }
    let (mut child, bounds) = root;
    moved(&mut child);
    (child, bounds)
}

/// Builds a hierarchy over items given by their 4D bounds, in order: item i
/// is the i-th bounds.
pub(super) fn build<N: PairNode>(bounds: impl Iterator<Item = Bounds4>) -> Built<N> {
    let mut items: Vec<Item> = bounds
        .enumerate()
        .map(|(i, bounds)| Item {
            bounds,
            index: i as u32,
        })
        .collect();
    let mut nodes = Vec::new();
    let (root, root_bounds) = if items.is_empty() {
        let none = DVec4::splat(f64::INFINITY);
        (Child { index: 0, count: 0 }, Bounds4::new(none, -none))
    } else {
        let ext = Extent::of(&items);
        build_into(&mut nodes, &mut items, ext, (0, 0))
    };
    Built {
        nodes,
        root,
        root_bounds,
        order: items.iter().map(|i| i.index).collect(),
    }
}

impl Bvh {
    /// Builds the hierarchy over items given by their 4D bounds (x, y, z,
    /// t), in order: item i is the i-th bounds.
    pub(crate) fn build(bounds: impl Iterator<Item = Bounds4>) -> Bvh {
        Bvh(build(bounds))
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

    /// The closest hit along the ray `o + s d` (both (x, y, z, t), in the
    /// coordinates the bounds were built in; `inv` = 1/d) within `range`:
    /// `test(item, range)` is called for every item whose box the ray
    /// enters, with the range shrunk to the best hit so far. The nearer
    /// child is searched first, the farther waiting on a stack. Ties go to
    /// the lower primitive, whatever the order.
    pub(crate) fn closest(
        &self,
        o: DVec4,
        inv: DVec4,
        range: (f64, f64),
        mut test: impl FnMut(u32, (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if self.0.root.count == 0 && self.0.nodes.is_empty() {
            return None; // no items
        }
        let Built {
            nodes, root, order, ..
        } = &self.0;
        let bounds = &self.0.root_bounds;
        let entry = Self::enter(bounds.min, bounds.max, o, inv, range)?;
        let mut best: Option<Hit> = None;
        let hi = |best: &Option<Hit>| best.map_or(range.1, |b| b.s);
        if root.count > 0 {
            // A root leaf (a scene of few objects): no stack to set up.
            let start = root.index as usize;
            for &i in &order[start..start + root.count as usize] {
                if let Some(h) = test(i, (range.0, hi(&best))) {
                    best = Some(nearer(best, h));
                }
            }
            return best;
        }
        let mut stack = Stack::new();
        let mut current = Some((*root, entry));
        while let Some((child, entry)) = current.take().or_else(|| stack.pop()) {
            if entry > hi(&best) {
                continue;
            }
            if child.count > 0 {
                let start = child.index as usize;
                for &i in &order[start..start + child.count as usize] {
                    if let Some(h) = test(i, (range.0, hi(&best))) {
                        best = Some(nearer(best, h));
                    }
                }
                continue;
            }
            let node = &nodes[child.index as usize];
            let [a, b] = node.children;
            let r = (range.0, hi(&best));
            let entered = [
                Self::enter(node.min[0], node.max[0], o, inv, r),
                Self::enter(node.min[1], node.max[1], o, inv, r),
            ];
            current = match entered {
                [Some(x), Some(y)] => {
                    let (near, far) = if x <= y {
                        ((a, x), (b, y))
                    } else {
                        ((b, y), (a, x))
                    };
                    stack.push(far);
                    Some(near)
                }
                [Some(x), None] => Some((a, x)),
                [None, Some(y)] => Some((b, y)),
                [None, None] => None,
            };
        }
        best
    }

    /// [`Bvh::closest`] for a packet of rays (`o[i]`, `inv[i]` = 1/d),
    /// those of `lanes` searching within `range`: `test(item, lanes, hi)`
    /// is called for every item whose box any of `lanes` enters, with those
    /// that do; `hi[i]` is the upper end of ray i's range, which `test`
    /// lowers to the ray's best hit so far.
    pub(crate) fn closest_packet(
        &self,
        (o, inv): (&[DVec4; PACKET], &[DVec4; PACKET]),
        lanes: Lanes,
        range: (f64, f64),
        mut test: impl FnMut(u32, Lanes, &mut [f64; PACKET]),
    ) {
        if self.0.root.count == 0 && self.0.nodes.is_empty() {
            return; // no items
        }
        let Built {
            nodes, root, order, ..
        } = &self.0;
        let mut hi = [range.1; PACKET];
        let mut entries = [range.0; PACKET];
        let bounds = &self.0.root_bounds;
        let lanes = lanes.filter(|i| {
            let entry = Self::enter(bounds.min, bounds.max, o[i], inv[i], range);
            entries[i] = entry.unwrap_or(range.0);
            entry.is_some()
        });
        let mut stack = Stack::new();
        let mut current = Some(TopWaiting {
            child: *root,
            lanes,
            entries,
        });
        while let Some(w) = current.take().or_else(|| stack.pop()) {
            let lanes = w.lanes.filter(|i| w.entries[i] <= hi[i]);
            if lanes.is_empty() {
                continue;
            }
            if w.child.count > 0 {
                let start = w.child.index as usize;
                for &item in &order[start..start + w.child.count as usize] {
                    test(item, lanes, &mut hi);
                }
                continue;
            }
            let node = &nodes[w.child.index as usize];
            let child = |c: usize| {
                let mut entries = [0.0; PACKET];
                let entered = lanes.filter(|i| {
                    let r = (range.0, hi[i]);
                    let entry = Self::enter(node.min[c], node.max[c], o[i], inv[i], r);
                    entries[i] = entry.unwrap_or(0.0);
                    entry.is_some()
                });
                let key = entered
                    .iter()
                    .map(|i| entries[i])
                    .fold(f64::INFINITY, f64::min);
                let child = node.children[c];
                (
                    TopWaiting {
                        child,
                        lanes: entered,
                        entries,
                    },
                    key,
                )
            };
            // (Not `map`, which is not inlined here.)
            let (a, b) = (child(0), child(1));
            current = match (a.0.lanes.is_empty(), b.0.lanes.is_empty()) {
                (false, false) => {
                    let (near, far) = if a.1 <= b.1 { (a.0, b.0) } else { (b.0, a.0) };
                    stack.push(far);
                    Some(near)
                }
                (false, true) => Some(a.0),
                (true, false) => Some(b.0),
                (true, true) => None,
            };
        }
    }
}

/// A child waiting on a packet's stack: the rays that entered it and where
/// each did.
#[derive(Clone, Copy, Debug, Default)]
struct TopWaiting {
    child: Child,
    lanes: Lanes,
    entries: [f64; PACKET],
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// The bin through i64 is the bin through usize, at every kind of
    /// value: in range, at the edges, negative, huge, infinite, NaN.
    #[test]
    fn bins_are_those_of_the_usize_conversion() {
        let mut rng = SplitMix64::new(9);
        let special = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            0.0,
            -1e-300,
            5e-324,
            -0.5,
            15.0,
            15.999999999999998,
            16.0,
            9.3e18,
            -9.3e18,
            1e300,
        ];
        let random = (0..10_000).map(|_| (rng.next_f64() - 0.1) * 20.0);
        for x in special.into_iter().chain(random) {
            assert_eq!(bin_at(x), (x as usize).min(BINS - 1), "{x}");
        }
    }

    fn random_boxes(n: usize, seed: u64) -> Vec<Bounds4> {
        let mut rng = SplitMix64::new(seed);
        (0..n)
            .map(|_| {
                let c = DVec4::new(
                    rng.next_f64(),
                    rng.next_f64(),
                    rng.next_f64(),
                    rng.next_f64(),
                );
                let size = DVec4::splat(0.01 * rng.next_f64());
                Bounds4::new(c * 100.0, c * 100.0 + size)
            })
            .collect()
    }

    fn built_on(threads: usize, boxes: &[Bounds4]) -> Bvh {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| Bvh::build(boxes.iter().copied()))
    }

    /// A build large enough to split on both threads gives the tree a build
    /// on one thread gives, node for node; the control, one box moved,
    /// gives another.
    #[test]
    fn the_tree_does_not_depend_on_the_thread_count() {
        let boxes = random_boxes(4 * PARALLEL_ITEMS, 9);
        let (one, two) = (built_on(1, &boxes), built_on(2, &boxes));
        assert!(one.0.nodes.len() > 1000);
        assert_eq!(one.0.nodes, two.0.nodes);
        assert_eq!((one.0.root, one.0.order.clone()), (two.0.root, two.0.order));
        let mut moved = boxes.clone();
        moved[7].min.x += 50.0;
        moved[7].max.x += 50.0;
        assert_ne!(built_on(2, &moved).0.nodes, one.0.nodes);
    }

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
                    let entered = Bvh::enter(min, max, o, DVec4::ONE / d, (0.0, 10.0)).is_some();
                    assert_eq!(
                        entered, inside,
                        "axis {axis}, d = {zero:?}, origin on {face}"
                    );
                }
            }
        }
    }

    /// Every item sits in exactly one leaf, inside every box on its path.
    #[test]
    fn every_item_is_in_one_leaf_inside_its_boxes() {
        let boxes = random_boxes(3 * PARALLEL_ITEMS, 10);
        let bvh = built_on(2, &boxes);
        let mut seen = vec![0u32; boxes.len()];
        let inside =
            |b: &Bounds4, min: DVec4, max: DVec4| b.min.cmpge(min).all() && b.max.cmple(max).all();
        let mut stack = vec![(bvh.0.root, bvh.0.root_bounds)];
        while let Some((child, bounds)) = stack.pop() {
            if child.count > 0 {
                let start = child.index as usize;
                for &i in &bvh.0.order[start..start + child.count as usize] {
                    assert!(inside(&boxes[i as usize], bounds.min, bounds.max));
                    seen[i as usize] += 1;
                }
                continue;
            }
            let node = &bvh.0.nodes[child.index as usize];
            for c in 0..2 {
                let b = Bounds4::new(node.min[c], node.max[c]);
                assert!(inside(&b, bounds.min, bounds.max));
                stack.push((node.children[c], b));
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }
}
