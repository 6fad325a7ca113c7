//! The shared builder of both hierarchies: binary, over items given by
//! their 4D bounds.
//!
//! Splits are chosen by the surface area heuristic over binned centroids
//! on x, y, z and t, with the 4D boundary measure of a box as its area: the
//! time slices of moving objects are told apart by t, while for static
//! objects (which all live for the whole scene) a split along t gains
//! nothing and is not chosen. A large node's split is chosen from a
//! sample of its items (see [`sah_split`]).

use super::{rounding_margin, Bounds4, Built, Child, PairNode};
use glam::DVec4;
use rayon::prelude::*;

/// The most items a leaf holds unless a build asks for more
/// ([`build_with_leaves`]): four prisms, one pass of the f32 filter.
pub(in crate::accel) const LEAF_SIZE: usize = 4;
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

/// Nodes of at least this many items choose their split from a sample of
/// their items (see [`sah_split`]). With the sample's size, chosen by
/// callgrind on the benchmark's 1M tori (docs/performance.md): from 16k
/// items with samples of 2048 the build took 11% more instructions, from
/// 256 with samples of 64 the tracing 1.5% more.
const SAMPLED_FROM: usize = 1024;

/// About how many items a sampled node bins: every (n / `SAMPLE`)-th of
/// its n items.
const SAMPLE: usize = 512;

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

/// The centroid bins of a node's items along the axes their centroids
/// spread over (the k-th such axis's at k): each bin's item count and
/// box, and which bins hold any item (bit b for bin b).
struct Bins<const A: usize> {
    count: [[usize; BINS]; A],
    min: [[DVec4; BINS]; A],
    max: [[DVec4; BINS]; A],
    occupied: [u32; A],
}

impl<const A: usize> Bins<A> {
    /// The bins along `axes` of every `stride`-th item from the first,
    /// `place` giving a centroid's place in bins on every axis.
    #[inline(always)]
    fn of(
        items: &[Item<A>],
        stride: usize,
        shared: &Shared,
        axes: &[usize],
        place: impl Fn(DVec4) -> [f64; 4],
    ) -> Bins<A> {
        let mut bins = Bins {
            count: [[0; BINS]; A],
            min: [[DVec4::INFINITY; BINS]; A],
            max: [[DVec4::NEG_INFINITY; BINS]; A],
            occupied: [0; A],
        };
        for item in items.iter().step_by(stride) {
            let bounds = item.bounds(shared);
            let c = place(bounds.centroid());
            for (k, &axis) in axes.iter().enumerate() {
                let b = bin_at(c[axis]);
                bins.count[k][b] += 1;
                bins.min[k][b] = bins.min[k][b].min(bounds.min);
                bins.max[k][b] = bins.max[k][b].max(bounds.max);
                bins.occupied[k] |= 1 << b;
            }
        }
        bins
    }

    /// The cheapest split along the k-th binned axis, and the bins left of
    /// it, if it beats `best` (its cost, below which a split must come):
    /// the surface area heuristic's cost 1 + (area_l n_l + area_r n_r) /
    /// `parent` of splitting after each occupied bin but the last. An
    /// empty bin changes neither part: its split is the one before it,
    /// whose area and cost are the same to the bit, and is passed over,
    /// so that only the occupied bins are visited.
    #[inline(always)]
    fn cheapest(&self, k: usize, parent: f64, best: Option<f64>) -> Option<(f64, usize)> {
        let (count, bmin, bmax, occupied) =
            (&self.count[k], &self.min[k], &self.max[k], self.occupied[k]);
        // Sweep from the right to know each right part's box: at an
        // occupied bin, the area and count of it and the bins above.
        let mut right_area = [0.0; BINS];
        let mut rcount = [0usize; BINS];
        let (mut rmin, mut rmax) = (DVec4::INFINITY, DVec4::NEG_INFINITY);
        let mut n = 0;
        let mut bits = occupied;
        while bits != 0 {
            let b = (u32::BITS - 1 - bits.leading_zeros()) as usize;
            bits &= !(1 << b);
            rmin = rmin.min(bmin[b]);
            rmax = rmax.max(bmax[b]);
            n += count[b];
            right_area[b] = area(rmin, rmax);
            rcount[b] = n;
        }
        let (mut lmin, mut lmax) = (DVec4::INFINITY, DVec4::NEG_INFINITY);
        let mut lcount = 0;
        let mut found: Option<(f64, usize)> = None;
        let mut bits = occupied;
        while bits != 0 {
            let b = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            lmin = lmin.min(bmin[b]);
            lmax = lmax.max(bmax[b]);
            lcount += count[b];
            // The right part starts at the next occupied bin.
            if bits == 0 {
                break;
            }
            let next = bits.trailing_zeros() as usize;
            let cost = 1.0
                + (area(lmin, lmax) * lcount as f64 + right_area[next] * rcount[next] as f64)
                    / parent;
            if found.map(|f| f.0).or(best).is_none_or(|c| cost < c) {
                found = Some((cost, b + 1));
            }
        }
        found
    }
}

/// Chooses a split of `items` (of extent `ext`) by the surface area
/// heuristic over binned centroids on x, y, z and t, one pass binning every
/// axis; moves the left part first and returns its length and both parts'
/// extents; `None` when no split beats a leaf. A node of at least
/// [`SAMPLED_FROM`] items bins a sample of them, every (n / [`SAMPLE`])-th,
/// and splits at the plane between centroid bins that the sample's costs
/// favour (the heuristic estimated from a subset: binning was most of a
/// large node's split, and the benchmark's trees built so trace as fast,
/// docs/performance.md); such a node is split wherever its
/// centroids spread, never made a leaf, and where its sample's centroids
/// share one bin on every axis, it bins them all. Deterministic: the same
/// items in the same order give the same split and order.
fn sah_split<const A: usize>(
    items: &mut [Item<A>],
    shared: &Shared,
    ext: &Extent,
) -> Option<(usize, Extent, Extent)> {
    let (cmin, extent) = (ext.cmin, ext.cmax - ext.cmin);
    let scale = DVec4::select(extent.cmpgt(DVec4::ZERO), BINS as f64 / extent, DVec4::ZERO);
    // A centroid's place in the bins of every axis (an array: glam's own
    // index is a branch on the axis).
    let place = |c: DVec4| ((c - cmin) * scale).to_array();
    // The axes the centroids spread along (of the first `A`: the others
    // are the same for every item), binned side by side.
    let (mut axes, mut spread) = ([0usize; A], 0);
    for a in (0..A).filter(|&a| extent[a] > 0.0) {
        (axes[spread], spread) = (a, spread + 1);
    }
    let axes = &axes[..spread];
    let parent = area(ext.min, ext.max).max(1e-300);
    // (cost, axis, bins on the left) of binning every `stride`-th item.
    let cheapest = |stride: usize| {
        let bins = Bins::of(items, stride, shared, axes, place);
        let mut best: Option<(f64, usize, usize)> = None;
        for (k, &axis) in axes.iter().enumerate() {
            if let Some((cost, split)) = bins.cheapest(k, parent, best.map(|b| b.0)) {
                best = Some((cost, axis, split));
            }
        }
        best
    };
    let (_, axis, split) = if items.len() >= SAMPLED_FROM {
        cheapest(items.len() / SAMPLE).or_else(|| cheapest(1))?
    } else {
        cheapest(1).filter(|(cost, ..)| *cost < items.len() as f64)?
    };
    Some(partition(items, shared, |c| bin_at(place(c)[axis]) < split))
}

/// Moves the items whose centroids are `left` first; returns how many
/// there are and both parts' extents.
#[inline(always)]
fn partition<const A: usize>(
    items: &mut [Item<A>],
    shared: &Shared,
    left_of: impl Fn(DVec4) -> bool,
) -> (usize, Extent, Extent) {
    let mut mid = 0;
    let (mut left, mut right) = (Extent::EMPTY, Extent::EMPTY);
    for i in 0..items.len() {
        let b = items[i].bounds(shared);
        if left_of(b.centroid()) {
            left.add(&b);
            items.swap(i, mid);
            mid += 1;
        } else {
            right.add(&b);
        }
    }
    (mid, left, right)
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
    (items, shared, leaf_size): (&mut [Item<A>], &Shared, usize),
    ext: Extent,
    (first, depth): (usize, usize),
) -> (Child, Bounds4) {
    let (pmin, pmax) = pad(ext.min, ext.max);
    let padded = Bounds4::new(pmin, pmax);
    let split = if items.len() <= leaf_size || depth >= MAX_DEPTH {
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
            || build_into(nodes, (left, shared, leaf_size), lext, at_left),
            || {
                let mut own = Vec::new();
                let r = build_into(&mut own, (right, shared, leaf_size), rext, at_right);
                (r, own)
            },
        );
        (l, append(nodes, own, r))
    } else {
        let l = build_into(nodes, (left, shared, leaf_size), lext, at_left);
        (
            l,
            build_into(nodes, (right, shared, leaf_size), rext, at_right),
        )
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

/// [`build_with_leaves`] with leaves of at most [`LEAF_SIZE`] items.
#[cfg(test)]
pub(in crate::accel) fn build<N: PairNode, const A: usize>(
    count: usize,
    bounds: impl Fn(usize) -> Bounds4 + Sync,
) -> Built<N> {
    build_with_leaves::<N, A>(count, LEAF_SIZE, bounds)
}

/// Builds a hierarchy over `count` items given by their 4D bounds: item i's
/// is `bounds(i)`, with leaves of at most `leaf_size` items (a node of
/// more is split where the surface area heuristic finds a split that
/// pays). Every box must match the first on the axes past the first `A`
/// (as a stretch's prisms all share its lab times), which the build keeps
/// once.
pub(in crate::accel) fn build_with_leaves<N: PairNode, const A: usize>(
    count: usize,
    leaf_size: usize,
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
        build_into(&mut nodes, (&mut items, &shared, leaf_size), ext, (0, 0)).0
    };
    Built {
        nodes,
        root,
        order: items.iter().map(|i| i.index).collect(),
        extent: Bounds4::new(ext.min, ext.max),
    }
}

#[cfg(test)]
mod tests;
