//! Building a wide hierarchy: the shared binary build, its nodes' boxes
//! rounded outward to f32, collapsed into nodes of eight children.

use super::{down, up, WideBvh, WideNode, NO_CHILD, WIDTH};
use crate::accel::bvh::{build_with_leaves, Bounds4, Child, PairNode, LEAF_SIZE};
use wide::f32x8;

/// A box over `A` axes in f32: lower faces then upper.
type Faces<const A: usize> = [[f32; A]; 2];

/// An inner node of the binary tree as built, before it is collapsed into
/// [`WideNode`]s: its two children and their boxes in f32 rounded outward,
/// so that each holds its f64 box.
#[derive(Clone, Copy, Debug)]
struct Node<const A: usize> {
    bounds: [Faces<A>; 2],
    children: [Child; 2],
}

impl<const A: usize> Node<A> {
    /// Both children with their boxes.
    fn halves(&self) -> [(Child, Faces<A>); 2] {
        [0, 1].map(|c| (self.children[c], self.bounds[c]))
    }
}

impl<const A: usize> PairNode for Node<A> {
    fn pair(boxes: [Bounds4; 2], children: [Child; 2]) -> Node<A> {
        let bounds = boxes.map(|b| {
            [
                std::array::from_fn(|axis| down(b.min[axis])),
                std::array::from_fn(|axis| up(b.max[axis])),
            ]
        });
        Node { bounds, children }
    }

    fn children_mut(&mut self) -> &mut [Child; 2] {
        &mut self.children
    }
}

impl<const A: usize> WideBvh<A> {
    /// Builds the hierarchy over `count` items given by their 4D bounds
    /// (of which its nodes keep the first `A` axes): item i's is
    /// `bounds(i)`. With `A` = 3 every box shares the first's lab times (a
    /// stretch's prisms), which the build holds once. Also gives the box
    /// of all the items (lower above upper when there are none).
    pub(crate) fn build(
        count: usize,
        bounds: impl Fn(usize) -> Bounds4 + Sync,
    ) -> (WideBvh<A>, Bounds4) {
        WideBvh::build_with_leaves(count, LEAF_SIZE, bounds)
    }

    /// [`WideBvh::build`] with leaves of at most `leaf_size` items.
    pub(crate) fn build_with_leaves(
        count: usize,
        leaf_size: usize,
        bounds: impl Fn(usize) -> Bounds4 + Sync,
    ) -> (WideBvh<A>, Bounds4) {
        let built = build_with_leaves::<Node<A>, A>(count, leaf_size, bounds);
        let (nodes, root) = if built.root.count == 0 && !built.nodes.is_empty() {
            let mut nodes = Vec::with_capacity(built.nodes.len() / 2 + 1);
            let root = Child {
                index: collapse(&built.nodes, built.root.index, &mut nodes),
                count: 0,
            };
            (nodes, root)
        } else {
            (Vec::new(), built.root)
        };
        let bvh = WideBvh {
            nodes,
            root,
            order: built.order,
        };
        (bvh, built.extent)
    }
}

/// A wide node's children with their boxes, in slot order, and how many.
type Slots<const A: usize> = ([(Child, Faces<A>); WIDTH], usize);

/// The children of the wide node over binary inner node `n`: the binary
/// node's two, the largest inner ones among them (by [`area`]) opened in
/// place until there are eight, so the same leaves hold the same items.
fn opened<const A: usize>(binary: &[Node<A>], n: u32) -> Slots<A> {
    let mut slots = [(NO_CHILD, [[0.0; A]; 2]); WIDTH];
    [slots[0], slots[1]] = binary[n as usize].halves();
    let mut len = 2;
    while len < WIDTH {
        let open = (0..len)
            .filter(|&i| slots[i].0.count == 0)
            .max_by(|&a, &b| area(&slots[a].1).total_cmp(&area(&slots[b].1)));
        let Some(i) = open else { break };
        let halves = binary[slots[i].0.index as usize].halves();
        slots.copy_within(i + 1..len, i + 2);
        [slots[i], slots[i + 1]] = halves;
        len += 1;
    }
    (slots, len)
}

/// The wide node of `slots`, its children `children`.
fn wide_node<const A: usize>((slots, len): &Slots<A>, children: [Child; WIDTH]) -> WideNode<A> {
    let mut faces = [[[f32::INFINITY; WIDTH]; A], [[f32::NEG_INFINITY; WIDTH]; A]];
    for (slot, (_, bounds)) in slots[..*len].iter().enumerate() {
        for side in 0..2 {
            for axis in 0..A {
                faces[side][axis][slot] = bounds[side][axis];
            }
        }
    }
    WideNode {
        faces: faces.map(|side| side.map(f32x8::from)),
        children,
    }
}

/// Collapses the binary subtree under inner node `n` into nodes of eight
/// children appended to `out` (a node before its children); returns its
/// index.
fn collapse<const A: usize>(binary: &[Node<A>], n: u32, out: &mut Vec<WideNode<A>>) -> u32 {
    let slots = opened(binary, n);
    let at = out.len();
    out.push(wide_node(&slots, [NO_CHILD; WIDTH]));
    for (slot, &(child, _)) in slots.0[..slots.1].iter().enumerate() {
        out[at].children[slot] = if child.count > 0 {
            child
        } else {
            Child {
                index: collapse(binary, child.index, out),
                count: 0,
            }
        };
    }
    at as u32
}

/// Half the boundary measure of a box: its surface area over x, y, z; over
/// x, y, z, t the 4D measure the binary build weighs splits by (xyz + t
/// (xy + yz + zx)).
fn area<const A: usize>(b: &Faces<A>) -> f32 {
    let e: [f32; A] = std::array::from_fn(|a| (b[1][a] - b[0][a]).max(0.0));
    let [x, y, z] = [e[0], e[1], e[2]];
    let space = x * y + y * z + z * x;
    match e.get(3) {
        Some(t) => x * y * z + t * space,
        None => space,
    }
}
