//! The binary build's tests: trees independent of the thread count and of
//! how the shared span is kept, every item in one leaf, and the split
//! sweep against one that visits every bin.

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

/// [`sah_split`] as it was first written, the reference of the sweep over
/// occupied bins: every bin of every axis visited in both sweeps, the bins'
/// boxes taken from infinite bounds.
fn every_bin_split<const A: usize>(
    items: &mut [Item<A>],
    shared: &Shared,
    ext: &Extent,
) -> Option<(usize, Extent, Extent)> {
    sweeping_every_bin(items, shared, ext, |cost, best| cost < best)
}

/// [`every_bin_split`] with a tie won by the later split: the control.
fn later_tie_split<const A: usize>(
    items: &mut [Item<A>],
    shared: &Shared,
    ext: &Extent,
) -> Option<(usize, Extent, Extent)> {
    sweeping_every_bin(items, shared, ext, |cost, best| cost <= best)
}

/// The sweep over every bin, a split replacing the best so far where
/// `beats(its cost, the best's)`.
fn sweeping_every_bin<const A: usize>(
    items: &mut [Item<A>],
    shared: &Shared,
    ext: &Extent,
    beats: impl Fn(f64, f64) -> bool,
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
            if best.is_none_or(|(c, _, _)| beats(cost, c)) {
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

/// Random items in `clusters` clumps (so that many bins stay empty and
/// some hold many centroids), some flat on an axis, some sharing corners.
fn clumped_items(n: usize, clusters: usize, seed: u64) -> Vec<Item<3>> {
    let mut rng = SplitMix64::new(seed);
    let centres: Vec<DVec4> = (0..clusters.max(1))
        .map(|_| DVec4::new(rng.next_f64(), rng.next_f64(), rng.next_f64(), 0.0) * 50.0)
        .collect();
    (0..n)
        .map(|i| {
            let c = centres[i % centres.len()];
            let jitter = match i % 5 {
                0 => DVec4::ZERO,
                _ => DVec4::new(rng.next_f64(), rng.next_f64(), rng.next_f64(), 0.0),
            };
            let mut size = DVec4::splat(0.3 * rng.next_f64());
            if i % 7 == 0 {
                size.y = 0.0;
            }
            let min = (c + jitter).truncate().extend(0.0);
            Item::new(
                Bounds4::new(min, min + size.truncate().extend(1.0)),
                i as u32,
            )
        })
        .collect()
}

/// The sweep over occupied bins chooses the split the sweep over every bin
/// chooses, to the bit: the same items left, in the same order, and the
/// same extents, over nodes of every size from a leaf's up to the largest
/// that bins every item, clumped so that most bins are empty. The control: a sweep that lets a later
/// split win a tie chooses another split somewhere.
#[test]
fn the_occupied_bins_choose_the_split_every_bin_chooses() {
    let shared = Bounds4::new(
        DVec4::new(0.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 0.0, 1.0),
    );
    let (mut splits, mut ties_differ) = (0, false);
    let sizes = [5, 6, 8, 11, 16, 17, 40, 64, 200, 600, SAMPLED_FROM - 1];
    for (case, n) in sizes.into_iter().enumerate() {
        for clusters in [1, 2, 3, 7, 1000] {
            let seed = (case * 10 + clusters) as u64;
            let items = clumped_items(n, clusters, seed);
            let ext = Extent::of(&items, &shared);
            let (mut a, mut b) = (items.clone(), items.clone());
            let (sa, sb) = (
                sah_split(&mut a, &shared, &ext),
                every_bin_split(&mut b, &shared, &ext),
            );
            assert_eq!(
                split_key(&sa, &a),
                split_key(&sb, &b),
                "{n} items in {clusters} clumps"
            );
            splits += usize::from(sa.is_some());
            let mut c = items.clone();
            let later = later_tie_split(&mut c, &shared, &ext);
            ties_differ |= split_key(&later, &c) != split_key(&sb, &b);
        }
    }
    assert!(splits > 40, "only {splits} nodes split");
    assert!(ties_differ, "no case tells a tie's winner");
}

/// A split as the tests compare them: the left part's length, both parts'
/// extents to the bit, and the items' order.
type SplitKey = (Option<(usize, [[u64; 4]; 4], [[u64; 4]; 4])>, Vec<u32>);

fn split_key(split: &Option<(usize, Extent, Extent)>, items: &[Item<3>]) -> SplitKey {
    let bits = |v: DVec4| v.to_array().map(f64::to_bits);
    let ext = |e: &Extent| [e.min, e.max, e.cmin, e.cmax].map(bits);
    let order = items.iter().map(|i| i.index).collect();
    (
        split.as_ref().map(|(mid, l, r)| (*mid, ext(l), ext(r))),
        order,
    )
}

/// A time span shared by every item of these tests.
fn span() -> Shared {
    Bounds4::new(DVec4::ZERO, DVec4::new(0.0, 0.0, 0.0, 1.0))
}

/// The items of `items` a node of their number samples.
fn sample_of(items: &[Item<3>]) -> Vec<Item<3>> {
    items
        .iter()
        .step_by(items.len() / SAMPLE)
        .copied()
        .collect()
}

/// A large node splits where the sweep over every bin splits its sample
/// (binned against the whole node's centroid extent): the sample's items
/// fall on the sides it puts them, and every item beside them on the side
/// of its centroid. Here the sampled items spread evenly along x while
/// the others sit in three clumps, so binning every item would choose
/// another plane (the control, which shows which items were binned).
#[test]
fn a_large_node_splits_where_its_sample_chooses() {
    let n = SAMPLED_FROM + 3000;
    let stride = n / SAMPLE;
    let mut rng = SplitMix64::new(78);
    let items: Vec<Item<3>> = (0..n)
        .map(|i| {
            let x = match (i % stride, i % 3) {
                (0, _) => 100.0 * rng.next_f64(),
                (_, 0) => 10.0 + rng.next_f64(),
                (_, 1) => 12.0 + rng.next_f64(),
                _ => 95.0 + rng.next_f64(),
            };
            let min = DVec4::new(x, rng.next_f64(), rng.next_f64(), 0.0);
            Item::new(
                Bounds4::new(min, min + DVec4::new(0.5, 0.5, 0.5, 1.0)),
                i as u32,
            )
        })
        .collect();
    let (shared, ext) = (span(), Extent::of(&items, &span()));
    let mut sample = sample_of(&items);
    let chosen = every_bin_split(&mut sample, &shared, &ext).expect("the sample splits");
    let left: std::collections::BTreeSet<u32> =
        sample[..chosen.0].iter().map(|i| i.index).collect();
    let mut split = items.clone();
    let (mid, ..) = sah_split(&mut split, &shared, &ext).expect("a large node splits");
    let sampled_left: std::collections::BTreeSet<u32> = (split[..mid].iter())
        .filter(|i| i.index as usize % stride == 0)
        .map(|i| i.index)
        .collect();
    assert_eq!(sampled_left, left);
    let mut all = items.clone();
    let every = every_bin_split(&mut all, &shared, &ext).expect("the node splits");
    assert_ne!(every.0, mid, "binning every item splits here too");
}

/// A large node whose sampled items share one centroid (so that their bins
/// tell no split) bins every item instead, and splits as the sweep over
/// every bin splits it. The control: its sample alone gives no split.
#[test]
fn a_sample_in_one_bin_bins_every_item() {
    let n = SAMPLED_FROM + 100;
    let mut items = clumped_items(n, 1000, 79);
    let stride = n / SAMPLE;
    let lone = Item::new(Bounds4::new(DVec4::splat(5.0), DVec4::splat(5.5)), 0);
    for (i, item) in items.iter_mut().enumerate().step_by(stride) {
        *item = Item {
            index: i as u32,
            ..lone
        };
    }
    let (shared, ext) = (span(), Extent::of(&items, &span()));
    let mut reference = items.clone();
    let expected = every_bin_split(&mut reference, &shared, &ext);
    assert!(expected
        .as_ref()
        .is_some_and(|(mid, ..)| (1..n).contains(mid)));
    let mut split = items.clone();
    let found = sah_split(&mut split, &shared, &ext);
    assert_eq!(split_key(&found, &split), split_key(&expected, &reference));
    assert!(every_bin_split(&mut sample_of(&items), &shared, &ext).is_none());
}
