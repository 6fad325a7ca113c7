//! A bounding volume hierarchy over 4D boxes (x, y, z, t). Built once per
//! database; it only decides which items a ray is tested against, never how
//! (that is the barycentric solve of `geometry`).
//!
//! Items are anything with 4D bounds: the database uses one hierarchy over
//! the time slices of its stretches (lab frame) and one per stretch over its
//! prisms (in the stretch's comoving coordinates).
//!
//! Splits are chosen by the surface area heuristic over binned centroids
//! on x, y, z and t, with the 4D boundary measure of a box as its area: the
//! time slices of moving objects are told apart by t, while for static
//! objects (which all live for the whole scene) a split along t gains
//! nothing and is not chosen.

use crate::geometry::{nearer, Hit};
use glam::DVec4;

const LEAF_SIZE: usize = 4;
/// Deeper subtrees become leaves, so that the traversal stack (64) never overflows.
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

#[derive(Clone, Copy, Debug)]
struct Node {
    min: DVec4,
    max: DVec4,
    /// Leaf: first index into `order`; inner: index of the second child
    /// (the first child follows the node).
    index: u32,
    /// Number of items of a leaf; 0 for an inner node.
    count: u32,
}

/// The hierarchy: nodes in depth-first order and the item order they index.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

/// Half the boundary 3-volume of a 4D box (x, y, z, t; c = 1): by Cauchy's
/// formula, proportional to the chance that a random line meets it, the
/// surface area heuristic's measure in 4D. A short-lived box is less likely
/// to be met than a long-lived one of the same size.
fn area(min: DVec4, max: DVec4) -> f64 {
    let d = (max - min).max(DVec4::ZERO);
    d.x * d.y * d.z + d.w * (d.x * d.y + d.y * d.z + d.z * d.x)
}

/// Chooses a split of `items` by the surface area heuristic over binned
/// centroids on x, y, z and t, reorders `items` so that the left part comes
/// first, and returns its length; `None` when no split beats a leaf.
fn sah_split(bounds: &[Bounds4], items: &mut [u32], cmin: DVec4, extent: DVec4) -> Option<usize> {
    const BINS: usize = 16;
    let centroid = |i: u32| bounds[i as usize].centroid();
    let (mut pmin, mut pmax) = (DVec4::splat(f64::INFINITY), DVec4::splat(f64::NEG_INFINITY));
    for &i in items.iter() {
        let b = bounds[i as usize];
        pmin = pmin.min(b.min);
        pmax = pmax.max(b.max);
    }
    let leaf_cost = items.len() as f64;
    let parent = area(pmin, pmax).max(1e-300);
    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins on the left)
    for axis in 0..4 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let bin_of = |i: u32| {
            (((centroid(i)[axis] - cmin[axis]) / extent[axis] * BINS as f64) as usize).min(BINS - 1)
        };
        let mut count = [0usize; BINS];
        let mut bmin = [DVec4::splat(f64::INFINITY); BINS];
        let mut bmax = [DVec4::splat(f64::NEG_INFINITY); BINS];
        for &i in items.iter() {
            let b = bin_of(i);
            let item = bounds[i as usize];
            count[b] += 1;
            bmin[b] = bmin[b].min(item.min);
            bmax[b] = bmax[b].max(item.max);
        }
        // Sweep from the right to know each right part's box.
        let mut right_area = [0.0; BINS];
        let (mut rmin, mut rmax, mut rcount) = (
            DVec4::splat(f64::INFINITY),
            DVec4::splat(f64::NEG_INFINITY),
            [0usize; BINS],
        );
        let mut n = 0;
        for b in (1..BINS).rev() {
            rmin = rmin.min(bmin[b]);
            rmax = rmax.max(bmax[b]);
            n += count[b];
            right_area[b] = area(rmin, rmax);
            rcount[b] = n;
        }
        let (mut lmin, mut lmax, mut lcount) = (
            DVec4::splat(f64::INFINITY),
            DVec4::splat(f64::NEG_INFINITY),
            0,
        );
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
    if cost >= leaf_cost {
        return None;
    }
    let bin_of = |i: u32| {
        (((centroid(i)[axis] - cmin[axis]) / extent[axis] * BINS as f64) as usize).min(BINS - 1)
    };
    // Stable partition: deterministic, and keeps the input order within each side.
    let (mut left, mut right): (Vec<u32>, Vec<u32>) =
        items.iter().partition(|&&i| bin_of(i) < split);
    let mid = left.len();
    left.append(&mut right);
    items.copy_from_slice(&left);
    Some(mid)
}

/// Pads a box so that hits accepted with barycentric slack are never culled.
fn pad(min: DVec4, max: DVec4) -> (DVec4, DVec4) {
    let e = rounding_margin(min, max) + DVec4::splat(1e-300);
    (min - e, max + e)
}

impl Bvh {
    /// Builds the hierarchy over items given by their 4D bounds (x, y, z, t).
    pub(crate) fn build(bounds: &[Bounds4]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::new(),
            order: (0..bounds.len() as u32).collect(),
        };
        if !bounds.is_empty() {
            let mut order = std::mem::take(&mut bvh.order);
            bvh.build_node(bounds, &mut order, 0, 0);
            bvh.order = order;
        }
        bvh
    }

    fn build_node(
        &mut self,
        bounds: &[Bounds4],
        items: &mut [u32],
        first: usize,
        depth: usize,
    ) -> usize {
        let (mut min, mut max) = (DVec4::splat(f64::INFINITY), DVec4::splat(f64::NEG_INFINITY));
        let (mut cmin, mut cmax) = (min, max);
        for &i in items.iter() {
            let b = bounds[i as usize];
            min = min.min(b.min);
            max = max.max(b.max);
            let c = b.centroid();
            cmin = cmin.min(c);
            cmax = cmax.max(c);
        }
        let (min, max) = pad(min, max);
        let node = self.nodes.len();
        self.nodes.push(Node {
            min,
            max,
            index: first as u32,
            count: items.len() as u32,
        });
        let extent = cmax - cmin;
        let split = if items.len() <= LEAF_SIZE || depth >= MAX_DEPTH {
            None
        } else {
            sah_split(bounds, items, cmin, extent)
        };
        let Some(mid) = split else {
            return node;
        };
        let (left, right) = items.split_at_mut(mid);
        self.nodes[node].count = 0;
        self.build_node(bounds, left, first, depth + 1);
        let second = self.build_node(bounds, right, first + mid, depth + 1);
        self.nodes[node].index = second as u32;
        node
    }

    /// Entry parameter of the ray into a node's box within `range`, if any.
    /// `inv` holds 1/d per axis (infinite for d = 0: such an axis constrains
    /// nothing unless the origin lies outside the slab).
    #[inline]
    fn enter(node: &Node, o: DVec4, inv: DVec4, range: (f64, f64)) -> Option<f64> {
        let a = (node.min - o) * inv;
        let b = (node.max - o) * inv;
        // NaN (0 * inf: the origin on a slab face of a parallel axis) is
        // dropped by f64::min/max, which keeps the test conservative.
        let near = a.min(b);
        let far = a.max(b);
        let lo = range.0.max(near.x).max(near.y).max(near.z).max(near.w);
        let hi = range.1.min(far.x).min(far.y).min(far.z).min(far.w);
        (lo <= hi).then_some(lo)
    }

    /// The closest hit along the ray `o + s d` (both (x, y, z, t), in the
    /// coordinates the bounds were built in) within `range`: `test(item,
    /// range)` is called for every item whose box the ray enters, with the
    /// range shrunk to the best hit so far. Ties go to the lower primitive.
    pub(crate) fn closest(
        &self,
        o: DVec4,
        d: DVec4,
        range: (f64, f64),
        mut test: impl FnMut(u32, (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv = DVec4::ONE / d;
        let mut best: Option<Hit> = None;
        let hi = |best: &Option<Hit>| best.map_or(range.1, |b| b.s);
        let mut stack = [(0u32, 0.0f64); 64];
        let e = Self::enter(&self.nodes[0], o, inv, range)?;
        stack[0] = (0, e);
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (n, entry) = stack[top];
            if entry > hi(&best) {
                continue;
            }
            let node = &self.nodes[n as usize];
            if node.count > 0 {
                let start = node.index as usize;
                for &i in &self.order[start..start + node.count as usize] {
                    if let Some(h) = test(i, (range.0, hi(&best))) {
                        best = Some(nearer(best, h));
                    }
                }
                continue;
            }
            let (a, b) = (n + 1, node.index);
            let r = (range.0, hi(&best));
            let ea = Self::enter(&self.nodes[a as usize], o, inv, r);
            let eb = Self::enter(&self.nodes[b as usize], o, inv, r);
            // Push the farther child first so the nearer is searched first.
            let mut push = |n: u32, e: Option<f64>| {
                if let Some(e) = e {
                    stack[top] = (n, e);
                    top += 1;
                }
            };
            match (ea, eb) {
                (Some(x), Some(y)) if x <= y => {
                    push(b, eb);
                    push(a, ea);
                }
                _ => {
                    push(a, ea);
                    push(b, eb);
                }
            }
        }
        best
    }
}
