//! The shared builder of both hierarchies: binary, over items given by
//! their 4D bounds.
//!
//! Splits are chosen by the surface area heuristic over binned centroids
//! on x, y, z and t, with the 4D boundary measure of a box as its area: the
//! time slices of moving objects are told apart by t, while for static
//! objects (which all live for the whole scene) a split along t gains
//! nothing and is not chosen.

use super::{rounding_margin, Bounds4, Built, Child, PairNode};
use glam::DVec4;
use rayon::prelude::*;

const LEAF_SIZE: usize = 4;
/// Deeper subtrees become leaves (a bound on the recursion of the build).
const MAX_DEPTH: usize = 48;

/// Half the boundary 3-volume of a 4D box (x, y, z, t; c = 1): by Cauchy's
/// formula, proportional to the chance that a random line meets it, the
/// surface area heuristic's measure in 4D. A short-lived box is less likely
/// to be met than a long-lived one of the same size.
fn area(min: DVec4, max: DVec4) -> f64 {
    let d = (max - min).max(DVec4::ZERO);
    d.x * d.y * d.z + d.w * (d.x * d.y + d.y * d.z + d.z * d.x)
}

/// An item while the hierarchy is built: its box over the first `A` axes
/// beside its index, so that every pass over a node's items reads them in
/// order. The box's other axes are the same for every item of the build
/// (t, for the prisms of one stretch, which all live over its lab times)
/// and kept once, in the build's [`Shared`] box.
#[derive(Clone, Copy, Debug)]
struct Item<const A: usize> {
    min: [f64; A],
    max: [f64; A],
    index: u32,
}

/// The box every item of a build shares on the axes past the first `A`
/// (the first item's, on those axes).
type Shared = Bounds4;

impl<const A: usize> Item<A> {
    fn new(b: Bounds4, index: u32) -> Item<A> {
        let first = |v: DVec4| std::array::from_fn(|axis| v[axis]);
        Item {
            min: first(b.min),
            max: first(b.max),
            index,
        }
    }

    /// Its 4D box, the axes past the first `A` the `shared` box's: to the
    /// bit the box it was made from.
    #[inline(always)]
    fn bounds(&self, shared: &Shared) -> Bounds4 {
        let (mut min, mut max) = (shared.min.to_array(), shared.max.to_array());
        min[..A].copy_from_slice(&self.min);
        max[..A].copy_from_slice(&self.max);
        Bounds4::new(DVec4::from_array(min), DVec4::from_array(max))
    }
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

    fn of<const A: usize>(items: &[Item<A>], shared: &Shared) -> Extent {
        let mut e = Extent::EMPTY;
        items.iter().for_each(|i| e.add(&i.bounds(shared)));
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
fn sah_split<const A: usize>(
    items: &mut [Item<A>],
    shared: &Shared,
    ext: &Extent,
) -> Option<(usize, Extent, Extent)> {
    let (min, max, cmin, extent) = (ext.min, ext.max, ext.cmin, ext.cmax - ext.cmin);
    let scale = DVec4::select(extent.cmpgt(DVec4::ZERO), BINS as f64 / extent, DVec4::ZERO);
    // A centroid's place in the bins of every axis (an array: glam's own
    // index is a branch on the axis).
    let place = |c: DVec4| ((c - cmin) * scale).to_array();
    // The axes the centroids spread along (of the first `A`: the others
    // are the same for every item), binned side by side (the k-th such
    // axis's bins at k).
    let (mut axes, mut spread) = ([0usize; A], 0);
    for a in (0..A).filter(|&a| extent[a] > 0.0) {
        (axes[spread], spread) = (a, spread + 1);
    }
    let axes = &axes[..spread];
    let mut count = [[0usize; BINS]; A];
    let mut bmin = [[DVec4::splat(f64::INFINITY); BINS]; A];
    let mut bmax = [[DVec4::splat(f64::NEG_INFINITY); BINS]; A];
    let (count, bmin, bmax) = (
        &mut count[..spread],
        &mut bmin[..spread],
        &mut bmax[..spread],
    );
    for item in items.iter() {
        let bounds = item.bounds(shared);
        let c = place(bounds.centroid());
        for (k, &axis) in axes.iter().enumerate() {
            let b = bin_at(c[axis]);
            count[k][b] += 1;
            bmin[k][b] = bmin[k][b].min(bounds.min);
            bmax[k][b] = bmax[k][b].max(bounds.max);
        }
    }
    let parent = area(min, max).max(1e-300);
    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins on the left)
    for (k, &axis) in axes.iter().enumerate() {
        let (count, bmin, bmax) = (&count[k], &bmin[k], &bmax[k]);
        // Sweep from the right to know each right part's box. An empty
        // bin changes neither part: its split is the one before it, whose
        // area and cost are the same to the bit, and is passed over.
        let mut right_area = [0.0; BINS];
        let mut rcount = [0usize; BINS];
        let (mut rmin, mut rmax) = (DVec4::splat(f64::INFINITY), DVec4::splat(f64::NEG_INFINITY));
        let (mut n, mut right) = (0, area(rmin, rmax));
        for b in (1..BINS).rev() {
            if count[b] > 0 {
                rmin = rmin.min(bmin[b]);
                rmax = rmax.max(bmax[b]);
                n += count[b];
                right = area(rmin, rmax);
            }
            right_area[b] = right;
            rcount[b] = n;
        }
        let (mut lmin, mut lmax) = (DVec4::splat(f64::INFINITY), DVec4::splat(f64::NEG_INFINITY));
        let mut lcount = 0;
        for split in 1..BINS {
            if count[split - 1] == 0 {
                continue;
            }
            lmin = lmin.min(bmin[split - 1]);
            lmax = lmax.max(bmax[split - 1]);
            lcount += count[split - 1];
            if rcount[split] == 0 {
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
        let b = items[i].bounds(shared);
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
pub(super) fn pad(min: DVec4, max: DVec4) -> (DVec4, DVec4) {
    let e = rounding_margin(min, max) + DVec4::splat(1e-300);
    (min - e, max + e)
}

/// Builds the subtree over `items` (at `first` in the item order), its
/// inner nodes appended to `nodes` children first; returns it as a child,
/// with its padded box. Large subtrees build their two halves on both
/// threads, the second into nodes of its own appended after the first's:
/// the same nodes in the same order as a build on one thread.
fn build_into<N: PairNode, const A: usize>(
    nodes: &mut Vec<N>,
    (items, shared): (&mut [Item<A>], &Shared),
    ext: Extent,
    (first, depth): (usize, usize),
) -> (Child, Bounds4) {
    let (pmin, pmax) = pad(ext.min, ext.max);
    let padded = Bounds4::new(pmin, pmax);
    let split = if items.len() <= LEAF_SIZE || depth >= MAX_DEPTH {
        None
    } else {
        sah_split(items, shared, &ext)
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
            || build_into(nodes, (left, shared), lext, at_left),
            || {
                let mut own = Vec::new();
                let r = build_into(&mut own, (right, shared), rext, at_right);
                (r, own)
            },
        );
        (l, append(nodes, own, r))
    } else {
        let l = build_into(nodes, (left, shared), lext, at_left);
        (l, build_into(nodes, (right, shared), rext, at_right))
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

/// Builds a hierarchy over `count` items given by their 4D bounds: item i's
/// is `bounds(i)`. Every box must match the first on the axes past the
/// first `A` (as a stretch's prisms all share its lab times), which the
/// build keeps once.
pub(in crate::accel) fn build<N: PairNode, const A: usize>(
    count: usize,
    bounds: impl Fn(usize) -> Bounds4 + Sync,
) -> Built<N> {
    const { assert!(A <= 4) };
    let shared: Shared = match count {
        0 => Bounds4::new(DVec4::ZERO, DVec4::ZERO),
        _ => bounds(0),
    };
    let same_past = |a: DVec4, b: DVec4| {
        let (a, b) = (a.to_array(), b.to_array());
        (A..4).all(|axis| a[axis].to_bits() == b[axis].to_bits())
    };
    let item = |i: usize| {
        let b = bounds(i);
        assert!(
            same_past(b.min, shared.min) && same_past(b.max, shared.max),
            "item {i}'s box differs from the first's past axis {A}"
        );
        Item::new(b, i as u32)
    };
    let mut items: Vec<Item<A>> = if count >= PARALLEL_ITEMS {
        (0..count).into_par_iter().map(item).collect()
    } else {
        (0..count).map(item).collect()
    };
    let mut nodes = Vec::new();
    let ext = Extent::of(&items, &shared);
    let root = if items.is_empty() {
        Child { index: 0, count: 0 }
    } else {
        build_into(&mut nodes, (&mut items, &shared), ext, (0, 0)).0
    };
    Built {
        nodes,
        root,
        order: items.iter().map(|i| i.index).collect(),
        extent: Bounds4::new(ext.min, ext.max),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// An inner node as the build makes it, in f64: both children's boxes.
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

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    fn built_on(threads: usize, boxes: &[Bounds4]) -> Built<Node> {
        pool(threads).install(|| build::<Node, 4>(boxes.len(), |i| boxes[i]))
    }

    /// A build large enough to split on both threads gives the tree a build
    /// on one thread gives, node for node; the control, one box moved,
    /// gives another.
    #[test]
    fn the_tree_does_not_depend_on_the_thread_count() {
        let boxes = random_boxes(4 * PARALLEL_ITEMS, 9);
        let (one, two) = (built_on(1, &boxes), built_on(2, &boxes));
        assert!(one.nodes.len() > 1000);
        assert_eq!(one.nodes, two.nodes);
        assert_eq!((one.root, one.order.clone()), (two.root, two.order));
        let mut moved = boxes.clone();
        moved[7].min.x += 50.0;
        moved[7].max.x += 50.0;
        assert_ne!(built_on(2, &moved).nodes, one.nodes);
    }

    /// Boxes that share one time span (a stretch's prisms) build the same
    /// tree, node for node and to the bit, when the build keeps their
    /// space axes alone and the span once; the control, one box's span
    /// changed, builds another tree over all four axes.
    #[test]
    fn keeping_the_shared_span_once_builds_the_same_tree() {
        let spanned: Vec<Bounds4> = random_boxes(2 * PARALLEL_ITEMS, 11)
            .into_iter()
            .map(|b| Bounds4::new(b.min.truncate().extend(-2.5), b.max.truncate().extend(7.0)))
            .collect();
        let space = pool(2).install(|| build::<Node, 3>(spanned.len(), |i| spanned[i]));
        let spacetime = pool(2).install(|| build::<Node, 4>(spanned.len(), |i| spanned[i]));
        assert!(space.nodes.len() > 1000);
        assert_eq!(space.nodes, spacetime.nodes);
        assert_eq!((space.root, space.order), (spacetime.root, spacetime.order));
        let mut longer = spanned.clone();
        longer[3].max.w = 70.0;
        let other = pool(2).install(|| build::<Node, 4>(longer.len(), |i| longer[i]));
        assert_ne!(other.nodes, spacetime.nodes);
    }

    /// A box whose span is not the others' cannot be built over space
    /// alone: the build refuses it rather than give it the first's span.
    #[test]
    #[should_panic(expected = "differs from the first's past axis 3")]
    fn a_box_of_another_span_is_refused_over_space() {
        let mut boxes: Vec<Bounds4> = random_boxes(100, 12)
            .into_iter()
            .map(|b| Bounds4::new(b.min.truncate().extend(0.0), b.max.truncate().extend(1.0)))
            .collect();
        boxes[40].min.w = -1.0;
        build::<Node, 3>(boxes.len(), |i| boxes[i]);
    }

    /// Every item sits in exactly one leaf, inside every box on its path.
    #[test]
    fn every_item_is_in_one_leaf_inside_its_boxes() {
        let boxes = random_boxes(3 * PARALLEL_ITEMS, 10);
        let bvh = built_on(2, &boxes);
        let mut seen = vec![0u32; boxes.len()];
        let inside =
            |b: &Bounds4, min: DVec4, max: DVec4| b.min.cmpge(min).all() && b.max.cmple(max).all();
        let everywhere = Bounds4::new(DVec4::NEG_INFINITY, DVec4::INFINITY);
        let mut stack = vec![(bvh.root, everywhere)];
        while let Some((child, bounds)) = stack.pop() {
            if child.count > 0 {
                let start = child.index as usize;
                for &i in &bvh.order[start..start + child.count as usize] {
                    assert!(inside(&boxes[i as usize], bounds.min, bounds.max));
                    seen[i as usize] += 1;
                }
                continue;
            }
            let node = &bvh.nodes[child.index as usize];
            for c in 0..2 {
                let b = Bounds4::new(node.min[c], node.max[c]);
                assert!(inside(&b, bounds.min, bounds.max));
                stack.push((node.children[c], b));
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }
}
