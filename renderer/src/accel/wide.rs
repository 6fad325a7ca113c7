//! A four-wide hierarchy collapsed from the binary one ([`Bvh`]): each node
//! holds its four children's boxes side by side (one array per axis and
//! bound), so one node visit tests four boxes in a loop the compiler turns
//! into vector instructions, and a ray visits about half as many nodes.
//! `AXES` is 4 for boxes in (x, y, z, t) and 3 where t needs no test (a
//! stretch's prisms all span its times, to which the ray's range is already
//! clipped). Which leaves exist, and so which hit is found, is exactly the
//! binary hierarchy's.

use super::bvh::{Bvh, BvhNode};
use crate::geometry::{nearer, Hit};
use glam::DVec4;

/// Children per node.
const WIDTH: usize = 4;
/// A child reference with this bit set is a leaf (index into `leaves`).
const LEAF: u32 = 1 << 31;
/// An empty child slot (its box is never entered).
const EMPTY: u32 = u32::MAX;

#[derive(Clone, Debug)]
struct WideNode<const AXES: usize> {
    /// Lower and upper bounds of the four children, per axis. An empty
    /// slot has +inf for both, which no ray enters.
    min: [[f64; WIDTH]; AXES],
    max: [[f64; WIDTH]; AXES],
    /// Inner node index, `LEAF | leaf index`, or `EMPTY`.
    child: [u32; WIDTH],
}

/// The four-wide hierarchy: nodes (the root first), leaves (first item
/// and count in `order`) and the item order.
#[derive(Clone, Debug, Default)]
pub(crate) struct WideBvh<const AXES: usize> {
    nodes: Vec<WideNode<AXES>>,
    leaves: Vec<(u32, u32)>,
    order: Vec<u32>,
    /// The root when it is a leaf (a hierarchy of at most one leaf).
    root_leaf: Option<u32>,
}

impl<const AXES: usize> WideBvh<AXES> {
    /// Collapses `bvh`: each wide node takes a binary node's children and
    /// opens the largest inner ones among them until it has four.
    pub(crate) fn collapse(bvh: &Bvh) -> WideBvh<AXES> {
        let mut wide = WideBvh {
            nodes: Vec::new(),
            leaves: Vec::new(),
            order: bvh.order().to_vec(),
            root_leaf: None,
        };
        let nodes = bvh.nodes();
        if nodes.is_empty() {
            return wide;
        }
        if nodes[0].is_leaf() {
            wide.root_leaf = Some(wide.leaf(&nodes[0]));
            return wide;
        }
        wide.node(nodes, 0);
        wide
    }

    fn leaf(&mut self, n: &BvhNode) -> u32 {
        self.leaves.push((n.first(), n.count()));
        (self.leaves.len() - 1) as u32
    }

    /// Builds the wide node for the binary inner node `n`; returns its index.
    fn node(&mut self, nodes: &[BvhNode], n: usize) -> u32 {
        let mut kids: Vec<usize> = nodes[n].children(n).to_vec();
        while kids.len() < WIDTH {
            let open = kids
                .iter()
                .enumerate()
                .filter(|(_, &k)| !nodes[k].is_leaf())
                .max_by(|a, b| nodes[*a.1].area().total_cmp(&nodes[*b.1].area()))
                .map(|(i, _)| i);
            let Some(i) = open else { break };
            let k = kids.remove(i);
            kids.splice(i..i, nodes[k].children(k));
        }
        let at = self.nodes.len();
        self.nodes.push(WideNode {
            min: [[f64::INFINITY; WIDTH]; AXES],
            max: [[f64::INFINITY; WIDTH]; AXES],
            child: [EMPTY; WIDTH],
        });
        for (slot, &k) in kids.iter().enumerate() {
            let (lo, hi) = nodes[k].bounds();
            let child = if nodes[k].is_leaf() {
                LEAF | self.leaf(&nodes[k])
            } else {
                self.node(nodes, k)
            };
            let node = &mut self.nodes[at];
            for axis in 0..AXES {
                node.min[axis][slot] = lo[axis];
                node.max[axis][slot] = hi[axis];
            }
            node.child[slot] = child;
        }
        at as u32
    }

    /// Entry parameters of the ray into the four children's boxes within
    /// `range` (+inf where it does not enter). `inv` holds 1/d per axis; as
    /// in [`Bvh`], NaN from 0 * inf is dropped by `f64::min`/`max`, which
    /// keeps the test conservative.
    #[inline]
    fn enter(node: &WideNode<AXES>, o: DVec4, inv: DVec4, range: (f64, f64)) -> [f64; WIDTH] {
        let mut lo = [range.0; WIDTH];
        let mut hi = [range.1; WIDTH];
        for axis in 0..AXES {
            for k in 0..WIDTH {
                let a = (node.min[axis][k] - o[axis]) * inv[axis];
                let b = (node.max[axis][k] - o[axis]) * inv[axis];
                lo[k] = lo[k].max(a.min(b));
                hi[k] = hi[k].min(a.max(b));
            }
        }
        let mut entry = [f64::INFINITY; WIDTH];
        for k in 0..WIDTH {
            if lo[k] <= hi[k] {
                entry[k] = lo[k];
            }
        }
        entry
    }

    /// The closest hit along `o + s d` within `range`, as [`Bvh::closest`]:
    /// `test(item, range)` for every item whose leaf box the ray enters,
    /// the range shrunk to the best hit so far; ties to the lower primitive.
    pub(crate) fn closest(
        &self,
        o: DVec4,
        d: DVec4,
        range: (f64, f64),
        mut test: impl FnMut(u32, (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut leaf = |leaf: u32, best: &mut Option<Hit>| {
            let (first, count) = self.leaves[leaf as usize];
            for &i in &self.order[first as usize..(first + count) as usize] {
                let hi = best.map_or(range.1, |b| b.s);
                if let Some(h) = test(i, (range.0, hi)) {
                    *best = Some(nearer(*best, h));
                }
            }
        };
        if let Some(root) = self.root_leaf {
            leaf(root, &mut best);
            return best;
        }
        if self.nodes.is_empty() {
            return None;
        }
        let inv = DVec4::ONE / d;
        let mut stack = Stack::new();
        stack.push((0, range.0));
        while let Some((n, entry)) = stack.pop() {
            let hi = best.map_or(range.1, |b| b.s);
            if entry > hi {
                continue;
            }
            if n & LEAF != 0 {
                leaf(n & !LEAF, &mut best);
                continue;
            }
            let node = &self.nodes[n as usize];
            let e = Self::enter(node, o, inv, (range.0, hi));
            // Push the entered children farthest first, so that the
            // nearest is searched first.
            let mut entered = [(0.0f64, 0u32); WIDTH];
            let mut m = 0;
            for (&entry, &child) in e.iter().zip(&node.child) {
                if entry.is_finite() && child != EMPTY {
                    // Insertion into `entered`, farthest first.
                    let mut j = m;
                    while j > 0 && entered[j - 1].0 < entry {
                        entered[j] = entered[j - 1];
                        j -= 1;
                    }
                    entered[j] = (entry, child);
                    m += 1;
                }
            }
            for &(e, child) in &entered[..m] {
                stack.push((child, e));
            }
        }
        best
    }
}

/// The traversal's stack of (child reference, entry parameter): a small
/// array, which is all a ray needs in practice and cheap to set up for each
/// of the many per-stretch searches of one ray, spilling into a vector
/// beyond it (each node visited adds at most three entries net, so a deep
/// tree can need more).
struct Stack {
    fixed: [(u32, f64); 32],
    len: usize,
    spill: Vec<(u32, f64)>,
}

impl Stack {
    fn new() -> Stack {
        Stack {
            fixed: [(0, 0.0); 32],
            len: 0,
            spill: Vec::new(),
        }
    }

    #[inline]
    fn push(&mut self, entry: (u32, f64)) {
        if self.len < self.fixed.len() {
            self.fixed[self.len] = entry;
            self.len += 1;
        } else {
            self.spill.push(entry);
        }
    }

    #[inline]
    fn pop(&mut self) -> Option<(u32, f64)> {
        if let Some(e) = self.spill.pop() {
            return Some(e);
        }
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        Some(self.fixed[self.len])
    }
}
