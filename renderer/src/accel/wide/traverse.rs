//! Searching a wide hierarchy, nearest child first: one ray; a packet of
//! rays that parts into single rays where only one still searches (a
//! stretch's prisms); or a packet whose leaves are searched by the rays
//! that reach them together (the top level's time slices, each a
//! stretch's hierarchy that the packet searches on).

use super::wide_ray::WideRay;
use super::{down, up, WideBvh, WideNode, NO_CHILD, WIDTH};
use crate::accel::bvh::{Child, Stack};
use crate::accel::packet::{Lanes, PACKET};
use crate::geometry::{nearer, Hit};
use wide::f32x8;

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
    /// range starts at zero or later (see [`WideRay`]).
    pub(crate) fn closest(
        &self,
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
        let ray = WideRay::new(o, inv);
        self.closest_below((self.root, down(range.0)), &ray, range, leaf)
    }

    /// [`WideBvh::closest`] of `ray` in the subtree `start.0`, entered at
    /// `start.1` (in f32, rounded down).
    #[inline(always)]
    fn closest_below(
        &self,
        start: (Child, f32),
        ray: &WideRay<A>,
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
                let start = child.index as usize;
                let items = &self.order[start..start + child.count as usize];
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

    /// [`WideBvh::closest`] for a packet of rays `rays[i]` = (o, 1/d), those
    /// of `lanes` searching within `ranges[i]`, each starting at zero or
    /// later: `leaf(i, first, items, range)` is called for ray i at every
    /// leaf whose box it enters (or, once it has entered its parent, that
    /// another ray of the packet enters no later than its best hit so far).
    /// Each ray finds the hit it finds alone.
    pub(crate) fn closest_packet(
        &self,
        rays: &[AxisRay<A>; PACKET],
        lanes: Lanes,
        ranges: &[(f64, f64); PACKET],
        mut leaf: impl FnMut(usize, u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> [Option<Hit>; PACKET] {
        let mut best: [Option<Hit>; PACKET] = [None; PACKET];
        if self.root.count == 0 && self.nodes.is_empty() {
            return best; // no items
        }
        if let Some(i) = lanes.single() {
            best[i] = self.closest(rays[i], ranges[i], |f, it, r| leaf(i, f, it, r));
            return best;
        }
        let wide = wide_rays(rays);
        // (Loops rather than `map`, which is not inlined here.)
        let (mut lo32, mut hi32) = ([0.0; PACKET], [0.0; PACKET]);
        for i in 0..PACKET {
            // hi32[i] is ray i's best hit's parameter, rounded up.
            (lo32[i], hi32[i]) = (down(ranges[i].0), up(ranges[i].1));
        }
        let mut stack = Stack::new();
        let least = lo32.iter().copied().fold(f32::INFINITY, f32::min);
        let mut current = Some(Waiting {
            child: self.root,
            lanes,
            entry: least,
        });
        while let Some(w) = current.take().or_else(|| stack.pop()) {
            // `entry` is the least of its rays' entries.
            let lanes = w.lanes.filter(|i| w.entry <= hi32[i]);
            if lanes.is_empty() {
                continue;
            }
            if let Some(i) = lanes.single() {
                // The packet has come apart here: one ray goes on alone.
                let range = (ranges[i].0, best[i].map_or(ranges[i].1, |b| b.s));
                let found = self.closest_below((w.child, w.entry), &wide[i], range, |f, it, r| {
                    leaf(i, f, it, r)
                });
                if let Some(h) = found {
                    let b = nearer(best[i], h);
                    best[i] = Some(b);
                    hi32[i] = up(b.s);
                }
                continue;
            }
            if w.child.count > 0 {
                let start = w.child.index as usize;
                let items = &self.order[start..start + w.child.count as usize];
                for i in lanes.iter() {
                    let hi = best[i].map_or(ranges[i].1, |b| b.s);
                    if let Some(h) = leaf(i, w.child.index, items, (ranges[i].0, hi)) {
                        let b = nearer(best[i], h);
                        best[i] = Some(b);
                        hi32[i] = up(b.s);
                    }
                }
                continue;
            }
            let node = &self.nodes[w.child.index as usize];
            current = packet_enters(node, &wide, lanes, (&lo32, &hi32), &mut stack);
        }
        best
    }

    /// For a packet of rays `rays[i]` = (o, 1/d), those of `lanes`
    /// searching within `range`: `leaf(items, lanes, hi)` is called at
    /// every leaf any of them enters, with those that do (or, once they
    /// have entered its parent, that another ray enters no later than
    /// their best hit so far); `hi[i]` is the upper end of ray i's range,
    /// which `leaf` lowers to the ray's best hit so far. The rays never
    /// part: a leaf's items are searched by the packet that reaches it.
    pub(crate) fn search_packet(
        &self,
        rays: &[AxisRay<A>; PACKET],
        lanes: Lanes,
        range: (f64, f64),
        mut leaf: impl FnMut(&[u32], Lanes, &mut [f64; PACKET]),
    ) {
        if self.root.count == 0 && self.nodes.is_empty() {
            return; // no items
        }
        debug_assert!(range.0 >= 0.0, "searched from {}", range.0);
        let mut hi = [range.1; PACKET];
        if self.root.count > 0 {
            return leaf(self.leaf_items(self.root), lanes, &mut hi);
        }
        let wide = wide_rays(rays);
        // hi32[i] is hi[i] rounded up.
        let (lo32, mut hi32) = ([down(range.0); PACKET], [up(range.1); PACKET]);
        let mut stack = Stack::new();
        let mut current = Some(Waiting {
            child: self.root,
            lanes,
            entry: lo32[0],
        });
        while let Some(w) = current.take().or_else(|| stack.pop()) {
            // `entry` is the least of its rays' entries.
            let lanes = w.lanes.filter(|i| w.entry <= hi32[i]);
            if lanes.is_empty() {
                continue;
            }
            if w.child.count > 0 {
                leaf(self.leaf_items(w.child), lanes, &mut hi);
                lanes.iter().for_each(|i| hi32[i] = up(hi[i]));
                continue;
            }
            let node = &self.nodes[w.child.index as usize];
            current = packet_enters(node, &wide, lanes, (&lo32, &hi32), &mut stack);
        }
    }
}

impl<const A: usize> WideBvh<A> {
    /// The items of leaf `child`, side by side in the item order.
    #[inline(always)]
    fn leaf_items(&self, child: Child) -> &[u32] {
        let start = child.index as usize;
        &self.order[start..start + child.count as usize]
    }
}

/// The packet's rays prepared for the slab test. (A lane not searched
/// holds some ray, never used.)
#[inline(always)]
fn wide_rays<const A: usize>(rays: &[AxisRay<A>; PACKET]) -> [WideRay<A>; PACKET] {
    let ray = |i: usize| WideRay::new(rays[i].0, rays[i].1);
    // Built in place (`map` would copy them).
    [ray(0), ray(1), ray(2), ray(3)]
}

/// A packet's visit of `node`: its rays of `lanes` tested against the
/// eight boxes, each within its range `(lo32[i], hi32[i])`; returns the
/// nearest child any entered, the others pushed (see
/// [`nearest_first_of_packet`]).
#[inline(always)]
fn packet_enters<const A: usize>(
    node: &WideNode<A>,
    wide: &[WideRay<A>; PACKET],
    lanes: Lanes,
    (lo32, hi32): (&[f32; PACKET], &[f32; PACKET]),
    stack: &mut Stack<Waiting>,
) -> Option<Waiting> {
    // Per child, the least entry of the rays that enter it, and which rays
    // do: byte i of `by_ray` for ray i, bit c for child c.
    let mut least = f32x8::splat(f32::INFINITY);
    let mut by_ray = 0u32;
    for (i, ray) in wide.iter().enumerate() {
        if lanes.holds(i) {
            let (entry, inside) = ray.enter_lanes(node, (lo32[i], hi32[i]));
            least = least.fast_min(inside.blend(entry, f32x8::splat(f32::INFINITY)));
            by_ray |= (inside.move_mask() as u32) << (8 * i);
        }
    }
    nearest_first_of_packet(node, least.to_array(), by_ray, stack)
}

/// A child waiting on a packet's stack: the rays that entered it and the
/// least of their entries (in f32, rounded outward).
#[derive(Clone, Copy, Debug, Default)]
struct Waiting {
    child: Child,
    lanes: Lanes,
    entry: f32,
}

/// The rays (bit i for ray i) that entered child `c`, given byte i of
/// `by_ray` for ray i (bit c of it for child c).
#[inline(always)]
fn rays_entering(by_ray: u32, c: u32) -> Lanes {
    const _: () = assert!(PACKET == 4, "one byte a ray in a u32");
    // Bits c, c + 8, c + 16, c + 24 gathered into bits 24 to 27.
    Lanes(((by_ray >> c) & 0x0101_0101).wrapping_mul(0x0102_0408) >> 24)
}

/// [`nearest_first`] for a packet: of the children any ray entered (see
/// [`rays_entering`]), the nearest (by the least entry of its rays), with
/// the others pushed farthest first, each with the rays that entered it.
/// (The two are kept apart: one generic over the entry cost the single
/// ray's search 4.4% more instructions, by callgrind on the flange.)
#[inline(always)]
fn nearest_first_of_packet<const A: usize>(
    node: &WideNode<A>,
    least: [f32; WIDTH],
    by_ray: u32,
    stack: &mut Stack<Waiting>,
) -> Option<Waiting> {
    let entered = (by_ray | by_ray >> 8 | by_ray >> 16 | by_ray >> 24) & 0xff;
    let at = |c: u32| Waiting {
        child: node.children[c as usize],
        lanes: rays_entering(by_ray, c),
        entry: least[c as usize],
    };
    let rest = entered & entered.wrapping_sub(1);
    if entered == 0 {
        return None;
    }
    if rest == 0 {
        return Some(at(entered.trailing_zeros()));
    }
    if rest & (rest - 1) == 0 {
        let (a, b) = (at(entered.trailing_zeros()), at(rest.trailing_zeros()));
        let (near, far) = if b.entry <= a.entry { (b, a) } else { (a, b) };
        stack.push(far);
        return Some(near);
    }
    let mut found = [Waiting::default(); WIDTH];
    let mut n = 0;
    let mut bits = entered;
    while bits != 0 {
        let w = at(bits.trailing_zeros());
        bits &= bits - 1;
        let mut j = n;
        while j > 0 && found[j - 1].entry < w.entry {
            found[j] = found[j - 1];
            j -= 1;
        }
        found[j] = w;
        n += 1;
    }
    found[..n - 1].iter().for_each(|&f| stack.push(f));
    Some(found[n - 1])
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
    use crate::accel::bvh::Bounds4;
    use crate::rng::SplitMix64;
    use glam::DVec4;

    /// 2000 random boxes over `A` axes at the scale `scale`, and the
    /// hierarchy over them (a box of three axes over the times 0..1).
    fn random_tree<const A: usize>(
        rng: &mut SplitMix64,
        scale: f64,
    ) -> (Vec<Box64<A>>, WideBvh<A>) {
        let items: Vec<Box64<A>> = (0..2000).map(|_| random_box(rng, scale)).collect();
        let bvh = WideBvh::build(items.iter().map(|b| {
            let (mut min, mut max) = (DVec4::ZERO, DVec4::ONE);
            for a in 0..A {
                (min[a], max[a]) = (b[0][a], b[1][a]);
            }
            Bounds4::new(min, max)
        }));
        assert!(bvh.nodes.len() > 100);
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
    /// together.
    fn every_item_whose_box_the_ray_enters_is_tested<const A: usize>(seed: u64) {
        let mut rng = SplitMix64::new(seed);
        let range = (0.0, f64::INFINITY);
        for scale in [0.05, 1.0, 1e5] {
            let (items, bvh) = random_tree::<A>(&mut rng, scale);
            for round in 0..100 {
                let rays = aimed_packet(&mut rng, &items, scale);
                let lanes = Lanes::first(1 + round % PACKET);
                let untested = || std::array::from_fn(|_| vec![false; items.len()]);
                let mut tested: [Vec<bool>; PACKET] = untested();
                for i in lanes.iter() {
                    bvh.closest(rays[i], range, |_, leaf, _| {
                        leaf.iter().for_each(|&k| tested[i][k as usize] = true);
                        None
                    });
                }
                assert_every_entered_item_tested(&items, &rays, lanes, &tested);
                let mut tested = untested();
                bvh.closest_packet(&rays, lanes, &[range; PACKET], |i, _, leaf, _| {
                    leaf.iter().for_each(|&k| tested[i][k as usize] = true);
                    None
                });
                assert_every_entered_item_tested(&items, &rays, lanes, &tested);
                let mut tested = untested();
                bvh.search_packet(&rays, lanes, range, |leaf, reached, _| {
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
        every_item_whose_box_the_ray_enters_is_tested::<3>(22);
    }

    /// Spacetime (x, y, z, t): the top level's time slices.
    #[test]
    fn every_spacetime_box_the_ray_enters_is_tested() {
        every_item_whose_box_the_ray_enters_is_tested::<4>(24);
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
            &rays,
            Lanes::first(PACKET),
            (0.0, f64::INFINITY),
            |_, _, hi| {
                leaves += 1;
                *hi = [0.0; PACKET];
            },
        );
        bvh.search_packet(
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
