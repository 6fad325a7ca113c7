//! One stretch's hierarchy over its prisms, in the stretch's comoving x, y,
//! z only. Every prism of a stretch lives over the stretch's lab times, and
//! the top level has already cut the ray to those of one time slice, so
//! time tells the prisms nothing apart.
//!
//! The tree is built binary (the shared SAH builder) and collapsed into
//! nodes of eight children, whose boxes sit side by side per face in f32
//! rounded outward: one node visit tests the eight boxes at once in 8-lane
//! SIMD (through the `wide` crate: two SSE2 registers on every x86-64, one
//! AVX register when built for it). A ray of the benchmark's 1M tori
//! visits 6.7 nodes, against 9.9 with four children. The slab test runs in
//! f32 and is made conservative (a box the ray enters is never culled, see
//! [`WideRay`]), so which prisms are tested, and so which hit is found, is
//! decided by the leaf tests alone.

use super::bvh::{build, Bounds4, Child, PairNode, Stack};
use super::packet::{Lanes, PACKET};
use crate::geometry::{nearer, Hit};
use glam::DVec3;
use wide::{f32x8, CmpLe};

/// An inner node of the binary tree as built, before it is collapsed into
/// [`WideNode`]s: its two children and their boxes in f32 rounded outward,
/// so that each holds its f64 box.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// Lower x, y, z then upper x, y, z, each for both children.
    bounds: [[f32; 2]; 6],
    children: [Child; 2],
}

impl Node {
    /// Both children with their boxes (lower then upper x, y, z).
    fn halves(&self) -> [(Child, [f32; 6]); 2] {
        [0, 1].map(|c| (self.children[c], self.bounds.map(|face| face[c])))
    }
}

/// The f32 at or below `v`.
#[inline(always)]
pub(super) fn down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v {
        -next_up(-f)
    } else {
        f
    }
}

/// The f32 at or above `v`.
#[inline(always)]
pub(super) fn up(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) < v {
        next_up(f)
    } else {
        f
    }
}

/// The least f32 above `f`, a finite value or -infinity (f32::next_up,
/// stable only since Rust 1.86).
#[inline(always)]
fn next_up(f: f32) -> f32 {
    let bits = f.to_bits();
    if f == 0.0 {
        f32::from_bits(1)
    } else if f > 0.0 {
        f32::from_bits(bits + 1)
    } else {
        f32::from_bits(bits - 1)
    }
}

impl PairNode for Node {
    fn pair(boxes: [Bounds4; 2], children: [Child; 2]) -> Node {
        let mut bounds = [[0.0; 2]; 6];
        for (c, b) in boxes.iter().enumerate() {
            for axis in 0..3 {
                bounds[axis][c] = down(b.min[axis]);
                bounds[axis + 3][c] = up(b.max[axis]);
            }
        }
        Node { bounds, children }
    }

    fn children_mut(&mut self) -> &mut [Child; 2] {
        &mut self.children
    }
}

/// Children of a node of the collapsed tree.
const WIDTH: usize = 8;

/// A node of the collapsed tree: its eight children's boxes, per face (lower
/// x, y, z then upper x, y, z) one lane a child, in f32 rounded outward.
/// An empty slot has lower bounds +inf and upper -inf, which no ray enters.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct WideNode {
    faces: [f32x8; 6],
    children: [Child; WIDTH],
}

const NO_CHILD: Child = Child { index: 0, count: 0 };

/// The hierarchy: nodes of eight children (the root first; a tree of one
/// leaf has none) and the item order the leaves index.
#[derive(Clone, Debug)]
pub(crate) struct SpaceBvh {
    nodes: Vec<WideNode>,
    root: Child,
    order: Vec<u32>,
}

impl SpaceBvh {
    /// Builds the hierarchy over boxes that all span the same lab times,
    /// in order: item i is the i-th bounds.
    pub(crate) fn build(bounds: impl Iterator<Item = Bounds4>) -> SpaceBvh {
        let built = build::<Node>(bounds);
        let mut nodes = Vec::with_capacity(built.nodes.len() / 2 + 1);
        let root = if built.root.count == 0 && !built.nodes.is_empty() {
            Child {
                index: collapse(&built.nodes, built.root.index, &mut nodes),
                count: 0,
            }
        } else {
            built.root
        };
        SpaceBvh {
            nodes,
            root,
            order: built.order,
        }
    }

    /// The item order of the leaves: position j of a leaf holds item
    /// `order()[j]`.
    pub(crate) fn order(&self) -> &[u32] {
        &self.order
    }

    /// The closest hit along the ray `o + s d` (comoving x, y, z) within
    /// `range`: `leaf(first, items, range)` is called for every leaf whose
    /// box the ray enters, with the position in [`SpaceBvh::order`] of its
    /// first item, its items (side by side there) and the range shrunk to
    /// the best hit so far, and returns the best hit among its items. The
    /// nearest entered child is searched first, the others wait on a
    /// stack. Ties go to the lower primitive, whatever the order. The
    /// range starts at zero or later (see [`WideRay`]).
    pub(crate) fn closest(
        &self,
        o: DVec3,
        d: DVec3,
        range: (f64, f64),
        leaf: impl FnMut(u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if self.root.count == 0 && self.nodes.is_empty() {
            return None; // no items
        }
        // No test of the root's own box: the top level has tested the time
        // slice's, and the root node tests its children's.
        debug_assert!(range.0 >= 0.0, "searched from {}", range.0);
        let ray = WideRay::new(o, DVec3::ONE / d);
        self.closest_below((self.root, down(range.0)), &ray, range, leaf)
    }

    /// [`SpaceBvh::closest`] of `ray` in the subtree `start.0`, entered at
    /// `start.1` (in f32, rounded down).
    #[inline(always)]
    fn closest_below(
        &self,
        start: (Child, f32),
        ray: &WideRay,
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

    /// [`SpaceBvh::closest`] for a packet of rays `rays[i]` = (o, d), those
    /// of `lanes` searching within `ranges[i]`, each starting at zero or
    /// later: `leaf(i, first, items, range)` is called for ray i at every
    /// leaf whose box it enters (or, once it has entered its parent, that
    /// another ray of the packet enters no later than its best hit so far).
    /// Each ray finds the hit it finds alone.
    pub(crate) fn closest_packet(
        &self,
        rays: &[(DVec3, DVec3); PACKET],
        lanes: Lanes,
        ranges: &[(f64, f64); PACKET],
        mut leaf: impl FnMut(usize, u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> [Option<Hit>; PACKET] {
        let mut best: [Option<Hit>; PACKET] = [None; PACKET];
        if self.root.count == 0 && self.nodes.is_empty() {
            return best; // no items
        }
        if let Some(i) = lanes.single() {
            let (o, d) = rays[i];
            best[i] = self.closest(o, d, ranges[i], |f, it, r| leaf(i, f, it, r));
            return best;
        }
        // (A lane not searched holds some ray, never used.)
        let ray = |i: usize| WideRay::new(rays[i].0, DVec3::ONE / rays[i].1);
        // Built in place (`map` would copy them).
        let wide: [WideRay; PACKET] = [ray(0), ray(1), ray(2), ray(3)];
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
            // Per child, the least entry of the rays that enter it, and
            // which rays do: byte i of `by_ray` for ray i, bit c for child c.
            let mut least = f32x8::splat(f32::INFINITY);
            let mut by_ray = 0u32;
            for (i, ray) in wide.iter().enumerate() {
                if lanes.holds(i) {
                    let (entry, inside) = ray.enter_lanes(node, (lo32[i], hi32[i]));
                    least = least.fast_min(inside.blend(entry, f32x8::splat(f32::INFINITY)));
                    by_ray |= (inside.move_mask() as u32) << (8 * i);
                }
            }
            current = nearest_first_of_packet(node, least.to_array(), by_ray, &mut stack);
        }
        best
    }
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
fn nearest_first_of_packet(
    node: &WideNode,
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
fn nearest_first(
    node: &WideNode,
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

/// Collapses the binary subtree under inner node `n` into nodes of eight
/// children appended to `out` (a node before its children); returns its
/// index. A node takes the binary node's two children and opens the
/// largest inner ones among them (by surface area) until it has eight, so
/// the same leaves hold the same items.
fn collapse(binary: &[Node], n: u32, out: &mut Vec<WideNode>) -> u32 {
    let mut slots: Vec<(Child, [f32; 6])> = binary[n as usize].halves().into();
    while slots.len() < WIDTH {
        let open = (0..slots.len())
            .filter(|&i| slots[i].0.count == 0)
            .max_by(|&a, &b| area(&slots[a].1).total_cmp(&area(&slots[b].1)));
        let Some(i) = open else { break };
        let (child, _) = slots.remove(i);
        let halves = binary[child.index as usize].halves();
        slots.splice(i..i, halves);
    }
    let at = out.len();
    out.push(WideNode {
        faces: [f32x8::ZERO; 6],
        children: [NO_CHILD; WIDTH],
    });
    let mut faces = [[f32::INFINITY; WIDTH]; 6];
    faces[3..]
        .iter_mut()
        .for_each(|f| *f = [f32::NEG_INFINITY; WIDTH]);
    for (slot, (child, bounds)) in slots.into_iter().enumerate() {
        for (face, &b) in faces.iter_mut().zip(&bounds) {
            face[slot] = b;
        }
        out[at].children[slot] = if child.count > 0 {
            child
        } else {
            Child {
                index: collapse(binary, child.index, out),
                count: 0,
            }
        };
    }
    out[at].faces = faces.map(f32x8::from);
    at as u32
}

/// Half the surface area of a box given as lower then upper x, y, z.
fn area(b: &[f32; 6]) -> f32 {
    let [x, y, z] = [0, 1, 2].map(|a| (b[a + 3] - b[a]).max(0.0));
    x * y + y * z + z * x
}

/// Relative margin of the f32 slab parameters: each is (face - origin) *
/// (1/d) with three roundings to nearest of at most 2^-24 each (the
/// subtraction, 1/d to f32, the product), and the margin itself is applied
/// to 1/d with one more; 2^-20 covers them with room to spare.
const MARGIN: f32 = 1.0 / (1u32 << 20) as f32;
/// Absolute margin, for parameters in f32's subnormal range (where the
/// roundings are absolute, at most 2^-150 each).
const TINY: f32 = f32::MIN_POSITIVE;

/// A ray prepared for the eight-lane f32 slab test.
///
/// The test is conservative, so that a box the ray enters is never culled:
/// - each face is met from an origin rounded to f32 toward the side that
///   moves the crossing outward (for a near face, so that it is crossed no
///   later; for a far face, no sooner): per axis, one origin for the near
///   faces and one for the far;
/// - the crossings are found with 1/d made smaller in magnitude by
///   [`MARGIN`] for the near faces and larger for the far ones, which
///   covers the rounding of the subtraction, of 1/d and of the product:
///   a crossing at a positive parameter (the only kind that can decide,
///   the searched range starting at zero or later) is so found no later
///   at a near face and no sooner at a far one; the entry and exit are
///   then moved out by [`TINY`], for parameters in f32's subnormal range;
/// - a NaN (0 * inf: an axis the ray is parallel to, its origin exactly on
///   a face) is dropped, as in f64.
///
/// Parameters beyond f32's range become infinite, and a direction component
/// below 2^-128 makes 1/d infinite: the ray is then treated as parallel to
/// that axis, which can cull a box only when, on that axis, the box's face
/// lies within 2^-128 times the longest searched ray parameter of the
/// origin.
struct WideRay {
    /// Per axis: the origin for the near faces and for the far faces, and
    /// 1/d for each, moved by [`MARGIN`] toward zero (near) and away from
    /// it (far).
    near_o: [f32x8; 3],
    far_o: [f32x8; 3],
    near_inv: [f32x8; 3],
    far_inv: [f32x8; 3],
    /// Per axis, the index into a node's faces of the near face and of the
    /// far one (lower then upper when the direction is positive).
    near: [usize; 3],
    far: [usize; 3],
}

impl WideRay {
    #[inline(always)]
    fn new(o: DVec3, inv: DVec3) -> WideRay {
        let mut ray = WideRay {
            near_o: [f32x8::ZERO; 3],
            far_o: [f32x8::ZERO; 3],
            near_inv: [f32x8::ZERO; 3],
            far_inv: [f32x8::ZERO; 3],
            near: [0, 1, 2],
            far: [3, 4, 5],
        };
        for a in 0..3 {
            let (lower, upper) = (f32x8::splat(down(o[a])), f32x8::splat(up(o[a])));
            let inv32 = inv[a] as f32;
            ray.near_inv[a] = f32x8::splat(inv32 * (1.0 - MARGIN));
            ray.far_inv[a] = f32x8::splat(inv32 * (1.0 + MARGIN));
            // 1/(-0) = -inf: a direction of -0 is negative here.
            if inv[a].is_sign_negative() {
                (ray.near_o[a], ray.far_o[a]) = (lower, upper);
                (ray.near[a], ray.far[a]) = (a + 3, a);
            } else {
                (ray.near_o[a], ray.far_o[a]) = (upper, lower);
            }
        }
        ray
    }

    /// Where the ray enters each of a node's eight boxes within `range`
    /// (in f32, rounded outward), and which it enters (bit i for child i).
    #[inline(always)]
    fn enter(&self, node: &WideNode, range: (f32, f32)) -> ([f32; WIDTH], u32) {
        let (entry, entered) = self.enter_lanes(node, range);
        (entry.to_array(), entered.move_mask() as u32)
    }

    /// [`WideRay::enter`] with the entries kept in lanes, and a lane of all
    /// ones for each box entered.
    #[inline(always)]
    fn enter_lanes(&self, node: &WideNode, range: (f32, f32)) -> (f32x8, f32x8) {
        let mut entry = f32x8::splat(range.0);
        let mut exit = f32x8::splat(range.1);
        for a in 0..3 {
            let near = (node.faces[self.near[a]] - self.near_o[a]) * self.near_inv[a];
            let far = (node.faces[self.far[a]] - self.far_o[a]) * self.far_inv[a];
            entry = max_dropping_nan(entry, near);
            exit = min_dropping_nan(exit, far);
        }
        let tiny = f32x8::splat(TINY);
        let (entry, exit) = (entry - tiny, exit + tiny);
        (entry, entry.cmp_le(exit))
    }
}

/// Lanewise max(acc, t), a NaN lane of `t` dropped (`acc` is never NaN).
#[inline(always)]
fn max_dropping_nan(acc: f32x8, t: f32x8) -> f32x8 {
    // SSE's maxps returns its second operand when either is NaN.
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    let m = t.fast_max(acc);
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    let m = acc.max(t);
    m
}

/// Lanewise min(acc, t), a NaN lane of `t` dropped (`acc` is never NaN).
#[inline(always)]
fn min_dropping_nan(acc: f32x8, t: f32x8) -> f32x8 {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    let m = t.fast_min(acc);
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    let m = acc.min(t);
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use glam::DVec4;

    /// Entry parameter of the ray `o + s d` (`inv` = 1/d) into the box (f64)
    /// within `range`: the reference the f32 test is held to, the top
    /// level's own f64 slab test (the box at one lab time, met by a ray of
    /// constant time, so that t constrains nothing).
    fn f64_entry(bounds: &[f64; 6], o: DVec3, inv: DVec3, range: (f64, f64)) -> Option<f64> {
        let (min, max) = (
            DVec4::new(bounds[0], bounds[1], bounds[2], 0.0),
            DVec4::new(bounds[3], bounds[4], bounds[5], 0.0),
        );
        Bounds4::new(min, max).entry(o.extend(0.0), inv.extend(f64::INFINITY), range)
    }

    /// A box (lower then upper x, y, z) with f32 faces, at a random place
    /// and size of the scale `scale`.
    fn random_box(rng: &mut SplitMix64, scale: f64) -> [f64; 6] {
        let c = [0; 3].map(|_| (rng.next_f64() - 0.5) * scale);
        let h = [0; 3].map(|_| rng.next_f64() * 0.1 * scale);
        let (lo, hi) = (
            [0, 1, 2].map(|a| f64::from(down(c[a] - h[a]))),
            [0, 1, 2].map(|a| f64::from(up(c[a] + h[a]))),
        );
        [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
    }

    /// A ray aimed exactly at a corner, an edge or a face of `b` from up
    /// to 1000 times its scale away; one in four runs parallel to an axis
    /// with its origin on a face plane (signed zero directions included).
    fn aimed_ray(rng: &mut SplitMix64, b: &[f64; 6], scale: f64) -> (DVec3, DVec3) {
        let mut target = DVec3::ZERO;
        let kind = (rng.next_u64() % 3) as usize; // 0 corner, 1 edge, 2 face
        for a in 0..3 {
            let on_face = a + kind < 3;
            let side = (rng.next_u64() % 2) as usize * 3;
            let t = rng.next_f64();
            target[a] = if on_face {
                b[a + side]
            } else {
                b[a] + t * (b[a + 3] - b[a])
            };
        }
        let mut d = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0 - 1.0;
        if rng.next_u64() % 4 == 0 {
            let a = (rng.next_u64() % 3) as usize;
            d[a] = if rng.next_u64() % 2 == 0 { 0.0 } else { -0.0 };
            target[a] = b[a + 3 * (rng.next_u64() % 2) as usize];
        }
        let d = d.normalize();
        let far = scale * (1.0 + 1000.0 * rng.next_f64());
        let mut o = target - d * far;
        for a in 0..3 {
            if d[a] == 0.0 {
                o[a] = target[a];
            }
        }
        (o, d)
    }

    /// The same slab test in f32 without care: origin and 1/d rounded to
    /// nearest, no margin (the negative control).
    fn naive_enters(b: &[f64; 6], o: DVec3, d: DVec3, range: (f64, f64)) -> bool {
        let (mut lo, mut hi) = (range.0 as f32, range.1 as f32);
        for a in 0..3 {
            let inv = (1.0 / d[a]) as f32;
            let (t0, t1) = (
                (b[a] as f32 - o[a] as f32) * inv,
                (b[a + 3] as f32 - o[a] as f32) * inv,
            );
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        }
        lo <= hi
    }

    /// Rays aimed at the corners, edges and faces of boxes at scales from
    /// 0.05 to 1e5, parallel to an axis or not: the eight-lane f32 test
    /// enters every box the f64 test enters, no later; the naive f32 test
    /// (the negative control) culls some.
    #[test]
    fn the_f32_slab_test_never_culls_a_box_the_ray_enters() {
        let mut rng = SplitMix64::new(21);
        let (mut entered, mut naive_culled) = (0, 0);
        for n in 0..200_000 {
            let scale = [0.05, 1.0, 300.0, 1e5][n % 4];
            let boxes: [[f64; 6]; WIDTH] = [0; WIDTH].map(|_| random_box(&mut rng, scale));
            let lane = n % WIDTH;
            let (o, d) = aimed_ray(&mut rng, &boxes[lane], scale);
            let inv = DVec3::ONE / d;
            let range = match n % 3 {
                0 => (0.0, f64::INFINITY),
                1 => (0.25 * scale, 1e3 * scale),
                _ => (0.0, (boxes[lane][0] - o.x).abs() + scale),
            };
            let node = WideNode {
                faces: [0, 1, 2, 3, 4, 5].map(|f| f32x8::from(boxes.map(|b| b[f] as f32))),
                children: [NO_CHILD; WIDTH],
            };
            let (entries, mask) = WideRay::new(o, inv).enter(&node, (down(range.0), up(range.1)));
            for (k, b) in boxes.iter().enumerate() {
                let Some(exact) = f64_entry(b, o, inv, range) else {
                    continue;
                };
                entered += 1;
                assert!(
                    mask & (1 << k) != 0 && f64::from(entries[k]) <= exact,
                    "culled: box {b:?}, ray {o} + s {d}, range {range:?}"
                );
                if k == lane && !naive_enters(b, o, d, range) {
                    naive_culled += 1;
                }
            }
        }
        assert!(entered > 100_000, "{entered}");
        assert!(naive_culled > 100, "the control culled only {naive_culled}");
    }

    /// Every item whose box a ray enters is tested, through the collapsed
    /// tree, for rays aimed at the items' corners, edges and faces.
    #[test]
    fn every_item_whose_box_the_ray_enters_is_tested() {
        let mut rng = SplitMix64::new(22);
        for scale in [0.05, 1.0, 1e5] {
            let items: Vec<[f64; 6]> = (0..2000).map(|_| random_box(&mut rng, scale)).collect();
            let bvh = SpaceBvh::build(items.iter().map(|b| {
                Bounds4::new(
                    DVec4::new(b[0], b[1], b[2], 0.0),
                    DVec4::new(b[3], b[4], b[5], 1.0),
                )
            }));
            assert!(bvh.nodes.len() > 100);
            for _ in 0..300 {
                let aim = (rng.next_u64() % items.len() as u64) as usize;
                let (o, d) = aimed_ray(&mut rng, &items[aim], scale);
                let range = (0.0, f64::INFINITY);
                let mut tested = vec![false; items.len()];
                bvh.closest(o, d, range, |_, items, _| {
                    items.iter().for_each(|&item| tested[item as usize] = true);
                    None
                });
                let inv = DVec3::ONE / d;
                for (i, b) in items.iter().enumerate() {
                    if f64_entry(b, o, inv, range).is_some() {
                        assert!(tested[i], "item {i} {b:?} skipped by {o} + s {d}");
                    }
                }
            }
        }
    }

    /// Rounded outward, every f32 bound holds its f64 value, and is the
    /// nearest f32 that does.
    #[test]
    fn boxes_round_outward() {
        for v in [
            0.0,
            1e-40,
            -1e-40,
            0.1,
            -0.1,
            1e5 + 1e-9,
            -3.3e38,
            7.0,
            f64::MAX,
        ] {
            let (d, u) = (down(v), up(v));
            assert!(f64::from(d) <= v && v <= f64::from(u), "{v}: {d} {u}");
            if v.abs() < 3e38 {
                assert!(f64::from(next_up(d)) > v || f64::from(d) == v, "{v}: {d}");
                assert!(f64::from(-next_up(-u)) < v || f64::from(u) == v, "{v}: {u}");
            }
        }
        assert_eq!(next_up(-0.0), f32::from_bits(1));
        assert_eq!(next_up(f32::NEG_INFINITY), f32::MIN);
    }
}
