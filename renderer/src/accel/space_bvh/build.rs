//! Building a stretch's hierarchy: the shared binary build, its nodes' boxes
//! rounded outward to f32, collapsed into nodes of eight children.

use super::{down, up, SpaceBvh, WideNode, NO_CHILD, WIDTH};
use crate::accel::bvh::{build, Bounds4, Child, PairNode};
use wide::f32x8;

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
