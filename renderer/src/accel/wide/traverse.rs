//! Searching a wide hierarchy with one ray, nearest child first (packets
//! in `packets`, which part into this search where one ray is left).

use super::wide_ray::WideRay;
use super::{down, up, WideBvh, WideNode, NO_CHILD, WIDTH};
use crate::accel::bvh::{Child, Stack};
use crate::geometry::{nearer, Hit};
use crate::simd::Simd8;

/// A ray as the searches take it: its origin o and 1/d, one entry an axis.
pub(crate) type AxisRay<const A: usize> = ([f64; A], [f64; A]);

impl<const A: usize> WideBvh<A> {
    /// The closest hit along the ray `o + s d` (`ray` = (o, 1/d), in the
    /// coordinates the hierarchy was built in) within `range`:
    /// `leaf(first, items, range)` is called for every leaf whose
    /// box the ray enters, with the position in [`WideBvh::order`] of its
    /// first item, its items (side by side there) and the range shrunk to
    /// the best hit so far, and returns the best hit among its items. The
    /// nearest entered child is searched first, the others wait on a
    /// stack. Ties go to the lower primitive, whatever the order. The
    /// range starts at zero or later (see [`WideRay`]). The node tests run
    /// at the vector level of `simd`.
    #[inline(always)]
    pub(crate) fn closest<S: Simd8>(
        &self,
        simd: S,
        (o, inv): AxisRay<A>,
        range: (f64, f64),
        mut leaf: impl FnMut(u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if self.root.count == 0 && self.nodes.is_empty() {
            return None; // no items
        }
        debug_assert!(range.0 >= 0.0, "searched from {}", range.0);
        if self.root.count > 0 {
            // A root leaf (a scene of a few stretches, or a stretch of a
            // few prisms): nothing to test the ray against before it.
            return leaf(self.root.index, self.leaf_items(self.root), range);
        }
        // No test of the root's own box: the root node tests its
        // children's (and a stretch's, the top level has tested the time
        // slice's).
        let ray = WideRay::new(simd, o, inv);
        self.closest_below((self.root, down(range.0)), &ray, range, leaf)
    }

    /// [`WideBvh::closest`] of `ray` in the subtree `start.0`, entered at
    /// `start.1` (in f32, rounded down).
    #[inline(always)]
    pub(super) fn closest_below<S: Simd8>(
        &self,
        start: (Child, f32),
        ray: &WideRay<A, S>,
        range: (f64, f64),
        mut leaf: impl FnMut(u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let hi = |best: &Option<Hit>| best.map_or(range.1, |b| b.s);
        // The range in f32, rounded outward.
        let (lo32, mut hi32) = (down(range.0), up(range.1));
        let mut stack = Stack::new();
        let mut current = Some(start);
        while let Some((child, entry)) = current.take().or_else(|| stack.pop()) {
            // hi32 holds the best hit's parameter, rounded up.
            if entry > hi32 {
                continue;
            }
            if child.count > 0 {
                let items = self.leaf_items(child);
                if let Some(h) = leaf(child.index, items, (range.0, hi(&best))) {
                    best = Some(nearer(best, h));
                    hi32 = up(hi(&best));
                }
                continue;
            }
            let node = &self.nodes[child.index as usize];
            let (entries, entered) = ray.enter(node, (lo32, hi32));
            current = nearest_first(node, entries, entered, &mut stack);
        }
        best
    }

    /// The items of leaf `child`, side by side in the item order.
    #[inline(always)]
    pub(super) fn leaf_items(&self, child: Child) -> &[u32] {
        let start = child.index as usize;
        &self.order[start..start + child.count as usize]
    }
}

/// Of a node's entered children (bit i of `entered` for child i), the
/// nearest, with the others pushed farthest first.
#[inline(always)]
fn nearest_first<const A: usize>(
    node: &WideNode<A>,
    entries: [f32; WIDTH],
    entered: u32,
    stack: &mut Stack<(Child, f32)>,
) -> Option<(Child, f32)> {
    let at = |i: u32| (node.children[i as usize], entries[i as usize]);
    // (Bit tricks rather than a count: x86-64's baseline has no popcnt.)
    let rest = entered & entered.wrapping_sub(1);
    if entered == 0 {
        return None;
    }
    if rest == 0 {
        return Some(at(entered.trailing_zeros()));
    }
    if rest & (rest - 1) == 0 {
        // Two: the nearer (on a tie the later child, as below) first.
        let (a, b) = (at(entered.trailing_zeros()), at(rest.trailing_zeros()));
        let (near, far) = if b.1 <= a.1 { (b, a) } else { (a, b) };
        stack.push(far);
        return Some(near);
    }
    let mut found = [(NO_CHILD, 0.0f32); WIDTH];
    let mut n = 0;
    let mut bits = entered;
    while bits != 0 {
        let (child, e) = at(bits.trailing_zeros());
        bits &= bits - 1;
        let mut j = n;
        while j > 0 && found[j - 1].1 < e {
            found[j] = found[j - 1];
            j -= 1;
        }
        found[j] = (child, e);
        n += 1;
    }
    found[..n - 1].iter().for_each(|&f| stack.push(f));
    Some(found[n - 1])
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{aimed_ray, f64_entry, random_box, Box64};
    use super::*;
    use crate::accel::bvh::{Bounds4, LEAF_SIZE};
    use crate::accel::packet::{Lanes, PACKET};
    use crate::rng::SplitMix64;
    use crate::simd::{wider, Baseline};
    use glam::DVec4;

    /// 2000 random boxes over `A` axes at the scale `scale`, and the
    /// hierarchy over them (a box of three axes over the times 0..1).
    fn random_tree<const A: usize>(
        rng: &mut SplitMix64,
        scale: f64,
    ) -> (Vec<Box64<A>>, WideBvh<A>) {
        random_tree_of_leaves(rng, scale, LEAF_SIZE)
    }

    /// [`random_tree`] with leaves of at most `leaf_size` boxes.
    fn random_tree_of_leaves<const A: usize>(
        rng: &mut SplitMix64,
        scale: f64,
        leaf_size: usize,
    ) -> (Vec<Box64<A>>, WideBvh<A>) {
        let items: Vec<Box64<A>> = (0..2000).map(|_| random_box(rng, scale)).collect();
        let (bvh, _) = WideBvh::build_with_leaves(items.len(), leaf_size, |i| {
            let (mut min, mut max) = (DVec4::ZERO, DVec4::ONE);
            for a in 0..A {
                (min[a], max[a]) = (items[i][0][a], items[i][1][a]);
            }
            Bounds4::new(min, max)
        });
        assert!(
            bvh.nodes.len() > 400 / leaf_size,
            "{} nodes",
            bvh.nodes.len()
        );
        (items, bvh)
    }

    /// A packet of rays, each aimed at a random item's corner, edge or
    /// face (as (o, 1/d)).
    fn aimed_packet<const A: usize>(
        rng: &mut SplitMix64,
        items: &[Box64<A>],
        scale: f64,
    ) -> [AxisRay<A>; PACKET] {
        std::array::from_fn(|_| {
            let aim = (rng.next_u64() % items.len() as u64) as usize;
            let (o, d) = aimed_ray(rng, &items[aim], scale);
            (o, d.map(|d| 1.0 / d))
        })
    }

    /// Every item whose box a ray enters was tested for it (`tested[i][k]`
    /// for ray i and item k); the rays of `lanes` are checked.
    fn assert_every_entered_item_tested<const A: usize>(
        items: &[Box64<A>],
        rays: &[AxisRay<A>; PACKET],
        lanes: Lanes,
        tested: &[Vec<bool>; PACKET],
    ) {
        for i in lanes.iter() {
            let (o, inv) = rays[i];
            for (k, b) in items.iter().enumerate() {
                if f64_entry(b, o, inv, (0.0, f64::INFINITY)).is_some() {
                    assert!(
                        tested[i][k],
                        "item {k} {b:?} skipped by ray {i}: {o:?}, 1/d {inv:?}"
                    );
                }
            }
        }
    }

    /// Every item whose box a ray enters is tested, through the collapsed
    /// tree, for rays aimed at the items' corners, edges and faces: alone,
    /// in a packet that parts, and in a packet that searches leaves
    /// together; at the vector level of `simd`.
    fn every_item_whose_box_the_ray_enters_is_tested<const A: usize>(simd: impl Simd8, seed: u64) {
        every_entered_item_tested_in_leaves_of::<A>(simd, seed, LEAF_SIZE);
    }

    /// [`every_item_whose_box_the_ray_enters_is_tested`] in a tree whose
    /// leaves hold at most `leaf_size` items.
    fn every_entered_item_tested_in_leaves_of<const A: usize>(
        simd: impl Simd8,
        seed: u64,
        leaf_size: usize,
    ) {
        let mut rng = SplitMix64::new(seed);
        let range = (0.0, f64::INFINITY);
        for scale in [0.05, 1.0, 1e5] {
            let (items, bvh) = random_tree_of_leaves::<A>(&mut rng, scale, leaf_size);
            for round in 0..100 {
                let rays = aimed_packet(&mut rng, &items, scale);
                let lanes = Lanes::first(1 + round % PACKET);
                let untested = || std::array::from_fn(|_| vec![false; items.len()]);
                let mut tested: [Vec<bool>; PACKET] = untested();
                for i in lanes.iter() {
                    bvh.closest(simd, rays[i], range, |_, leaf, _| {
                        leaf.iter().for_each(|&k| tested[i][k as usize] = true);
                        None
                    });
                }
                assert_every_entered_item_tested(&items, &rays, lanes, &tested);
                let mut tested = untested();
                bvh.closest_packet(simd, &rays, lanes, &[range; PACKET], |i, _, leaf, _| {
                    leaf.iter().for_each(|&k| tested[i][k as usize] = true);
                    None
                });
                assert_every_entered_item_tested(&items, &rays, lanes, &tested);
                let mut tested = untested();
                bvh.search_packet(simd, &rays, lanes, range, |leaf, reached, _| {
                    assert_eq!(reached.0 & !lanes.0, 0, "a ray outside the packet");
                    for i in reached.iter() {
                        leaf.iter().for_each(|&k| tested[i][k as usize] = true);
                    }
                });
                assert_every_entered_item_tested(&items, &rays, lanes, &tested);
            }
        }
    }

    /// Comoving space (x, y, z): a stretch's prisms.
    #[test]
    fn every_space_box_the_ray_enters_is_tested() {
        every_item_whose_box_the_ray_enters_is_tested::<3>(Baseline, 22);
        if let Some(wider) = wider() {
            every_item_whose_box_the_ray_enters_is_tested::<3>(wider, 22);
        }
    }

    /// How many items the largest leaf of `bvh` holds.
    fn largest_leaf<const A: usize>(bvh: &WideBvh<A>) -> u32 {
        let children = bvh.nodes.iter().flat_map(|n| n.children);
        children.map(|c| c.count).max().unwrap_or(bvh.root.count)
    }

    /// Leaves of up to eight boxes (a large stretch's): the tree holds
    /// leaves of more than four, none of more than eight (the control: with
    /// the default, none of more than four), and every box a ray enters is
    /// tested, alone and in packets.
    #[test]
    fn leaves_of_eight_test_every_box_the_ray_enters() {
        let mut rng = SplitMix64::new(26);
        let (_, eights) = random_tree_of_leaves::<3>(&mut rng, 1.0, 8);
        let (_, fours) = random_tree::<3>(&mut rng, 1.0);
        assert!(
            (5..=8).contains(&largest_leaf(&eights)),
            "{}",
            largest_leaf(&eights)
        );
        assert!(largest_leaf(&fours) <= 4, "{}", largest_leaf(&fours));
        every_entered_item_tested_in_leaves_of::<3>(Baseline, 26, 8);
        if let Some(wider) = wider() {
            every_entered_item_tested_in_leaves_of::<3>(wider, 26, 8);
        }
    }

    /// Spacetime (x, y, z, t): the top level's time slices.
    #[test]
    fn every_spacetime_box_the_ray_enters_is_tested() {
        every_item_whose_box_the_ray_enters_is_tested::<4>(Baseline, 24);
        if let Some(wider) = wider() {
            every_item_whose_box_the_ray_enters_is_tested::<4>(wider, 24);
        }
    }

    /// The control: a search told its best hit so far lies short of every
    /// box (`hi` lowered to zero by the first leaf) tests no further leaf,
    /// so the tests above could see an item skipped.
    #[test]
    fn a_packet_whose_best_hit_is_at_zero_searches_no_further() {
        let mut rng = SplitMix64::new(25);
        let (items, bvh) = random_tree::<4>(&mut rng, 1.0);
        let rays = aimed_packet(&mut rng, &items, 1.0);
        let (mut leaves, mut reached) = (0, 0);
        bvh.search_packet(
            Baseline,
            &rays,
            Lanes::first(PACKET),
            (0.0, f64::INFINITY),
            |_, _, hi| {
                leaves += 1;
                *hi = [0.0; PACKET];
            },
        );
        bvh.search_packet(
            Baseline,
            &rays,
            Lanes::first(PACKET),
            (0.0, f64::INFINITY),
            |_, _, _| {
                reached += 1;
            },
        );
        assert!(reached > 1, "{reached}");
        assert!(leaves < reached, "{leaves} of {reached}");
    }
}
