//! Searching a wide hierarchy with a packet of rays: one that parts into
//! single rays where only one still searches (a stretch's prisms), or one
//! whose leaves are searched by the rays that reach them together (the top
//! level's time slices, each a stretch's hierarchy the packet searches on).

use super::traverse::AxisRay;
use super::wide_ray::WideRay;
use super::{down, up, WideBvh, WideNode, WIDTH};
use crate::accel::bvh::{Child, Stack};
use crate::accel::packet::{Lanes, PACKET};
use crate::geometry::{nearer, Hit};
use crate::simd::Simd8;

impl<const A: usize> WideBvh<A> {
    /// [`WideBvh::closest`] for a packet of rays `rays[i]` = (o, 1/d), those
    /// of `lanes` searching within `ranges[i]`, each starting at zero or
    /// later: `leaf(i, first, items, range)` is called for ray i at every
    /// leaf whose box it enters (or, once it has entered its parent, that
    /// another ray of the packet enters no later than its best hit so far).
    /// Each ray finds the hit it finds alone. The node tests run at the
    /// vector level of `simd`.
    #[inline(always)]
    pub(crate) fn closest_packet<S: Simd8>(
        &self,
        simd: S,
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
            best[i] = self.closest(simd, rays[i], ranges[i], |f, it, r| leaf(i, f, it, r));
            return best;
        }
        let wide = wide_rays(simd, rays);
        let one = one_origin(rays);
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
            let lanes = w.lanes.reaching(w.entry, &hi32);
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
                let items = self.leaf_items(w.child);
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
            current = packet_enters(node, (&wide, one), lanes, (&lo32, &hi32), &mut stack);
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
    /// The node tests run at the vector level of `simd`.
    #[inline(always)]
    pub(crate) fn search_packet<S: Simd8>(
        &self,
        simd: S,
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
        let wide = wide_rays(simd, rays);
        let one = one_origin(rays);
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
            let lanes = w.lanes.reaching(w.entry, &hi32);
            if lanes.is_empty() {
                continue;
            }
            if w.child.count > 0 {
                leaf(self.leaf_items(w.child), lanes, &mut hi);
                lanes.iter().for_each(|i| hi32[i] = up(hi[i]));
                continue;
            }
            let node = &self.nodes[w.child.index as usize];
            current = packet_enters(node, (&wide, one), lanes, (&lo32, &hi32), &mut stack);
        }
    }
}

/// The packet's rays prepared for the slab test. (A lane not searched
/// holds some ray, never used.)
#[inline(always)]
fn wide_rays<const A: usize, S: Simd8>(
    simd: S,
    rays: &[AxisRay<A>; PACKET],
) -> [WideRay<A, S>; PACKET] {
    let ray = |i: usize| WideRay::new(simd, rays[i].0, rays[i].1);
    // Built in place (`map` would copy them).
    [ray(0), ray(1), ray(2), ray(3)]
}

/// Whether the packet's rays all start at the same point with the same
/// direction signs (a camera's primary rays, from one event): their slab
/// tests then share the node's faces less their origins
/// ([`WideRay::offsets`]), the same values to the bit.
#[inline(always)]
fn one_origin<const A: usize>(rays: &[AxisRay<A>; PACKET]) -> bool {
    let (o, inv) = rays[0];
    rays[1..].iter().all(|(oi, invi)| {
        (0..A).all(|a| {
            oi[a].to_bits() == o[a].to_bits()
                && invi[a].is_sign_negative() == inv[a].is_sign_negative()
        })
    })
}

/// A packet's visit of `node`: its rays of `lanes` tested against the
/// eight boxes, each within its range `(lo32[i], hi32[i])`, from the
/// faces less their origins found once where the rays share them
/// (`one`, [`one_origin`]); returns the nearest child any entered, the
/// others pushed (see [`nearest_first_of_packet`]).
#[inline(always)]
fn packet_enters<const A: usize, S: Simd8>(
    node: &WideNode<A>,
    (wide, one): (&[WideRay<A, S>; PACKET], bool),
    lanes: Lanes,
    (lo32, hi32): (&[f32; PACKET], &[f32; PACKET]),
    stack: &mut Stack<Waiting>,
) -> Option<Waiting> {
    // Per child, the least entry of the rays that enter it, and which rays
    // do: byte i of `by_ray` for ray i, bit c for child c.
    let s = wide[0].simd();
    let infinity = s.splat(f32::INFINITY);
    let mut least = infinity;
    let mut by_ray = 0u32;
    let shared = one.then(|| wide[0].offsets(node));
    for (i, ray) in wide.iter().enumerate() {
        if lanes.holds(i) {
            let offsets = match &shared {
                Some(offsets) => *offsets,
                None => ray.offsets(node),
            };
            let (entry, inside) = ray.enter_from(&offsets, (lo32[i], hi32[i]));
            least = s.min_or_second(least, s.select(inside, entry, infinity));
            by_ray |= s.bits(inside) << (8 * i);
        }
    }
    nearest_first_of_packet(node, s.to_array(least), by_ray, stack)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Rays share their origins when they start at the same point with
    /// the same direction signs, whatever their directions' sizes; a ray
    /// one ulp away, turned on one axis, or starting at -0 where the others
    /// start at +0 does not.
    #[test]
    fn one_origin_needs_the_same_point_and_direction_signs() {
        let ray: AxisRay<3> = ([1.0, -2.0, 0.0], [0.5, -4.0, 2.0]);
        let mut rays = [ray; PACKET];
        rays[2].1 = [0.7, -1.0, 9.0];
        assert!(one_origin(&rays));
        let mut moved = rays;
        moved[3].0[1] = f64::from_bits((-2.0f64).to_bits() + 1);
        assert!(!one_origin(&moved));
        let mut turned = rays;
        turned[1].1[2] = -2.0;
        assert!(!one_origin(&turned));
        let mut signed = rays;
        signed[1].0[2] = -0.0;
        assert!(!one_origin(&signed));
    }
}
