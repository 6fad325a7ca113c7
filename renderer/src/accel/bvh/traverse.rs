//! Searching the lab-frame hierarchy: one ray, or a packet of rays, nearer
//! child first.

use super::{Built, Bvh, Child, Stack};
use crate::accel::packet::{Lanes, PACKET};
use crate::geometry::{nearer, Hit};
use glam::DVec4;

impl Bvh {
    /// Entry parameter of the ray into the box `min..max` within `range`,
    /// if any. `inv` holds 1/d per axis (infinite for d = 0: such an axis
    /// constrains nothing unless the origin lies outside the slab); the
    /// near face of each axis is the lower one when 1/d is positive
    /// (+inf included) and the upper one otherwise.
    #[inline(always)]
    pub(super) fn enter(
        min: DVec4,
        max: DVec4,
        o: DVec4,
        inv: DVec4,
        range: (f64, f64),
    ) -> Option<f64> {
        let a = ((min - o) * inv).to_array();
        let b = ((max - o) * inv).to_array();
        let inv = inv.to_array();
        let (mut lo, mut hi) = range;
        for k in 0..4 {
            let (near, far) = if inv[k] < 0.0 {
                (b[k], a[k])
            } else {
                (a[k], b[k])
            };
            // A NaN (0 * inf: the origin on a slab face of a parallel
            // axis) fails both comparisons and is dropped, which keeps the
            // test conservative.
            if near > lo {
                lo = near;
            }
            if far < hi {
                hi = far;
            }
        }
        (lo <= hi).then_some(lo)
    }

    /// The closest hit along the ray `o + s d` (both (x, y, z, t), in the
    /// coordinates the bounds were built in; `inv` = 1/d) within `range`:
    /// `test(item, range)` is called for every item whose box the ray
    /// enters, with the range shrunk to the best hit so far. The nearer
    /// child is searched first, the farther waiting on a stack. Ties go to
    /// the lower primitive, whatever the order.
    pub(crate) fn closest(
        &self,
        o: DVec4,
        inv: DVec4,
        range: (f64, f64),
        mut test: impl FnMut(u32, (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if self.0.root.count == 0 && self.0.nodes.is_empty() {
            return None; // no items
        }
        let Built {
            nodes, root, order, ..
        } = &self.0;
        let bounds = &self.0.root_bounds;
        let entry = Self::enter(bounds.min, bounds.max, o, inv, range)?;
        let mut best: Option<Hit> = None;
        let hi = |best: &Option<Hit>| best.map_or(range.1, |b| b.s);
        if root.count > 0 {
            // A root leaf (a scene of few objects): no stack to set up.
            let start = root.index as usize;
            for &i in &order[start..start + root.count as usize] {
                if let Some(h) = test(i, (range.0, hi(&best))) {
                    best = Some(nearer(best, h));
                }
            }
            return best;
        }
        let mut stack = Stack::new();
        let mut current = Some((*root, entry));
        while let Some((child, entry)) = current.take().or_else(|| stack.pop()) {
            if entry > hi(&best) {
                continue;
            }
            if child.count > 0 {
                let start = child.index as usize;
                for &i in &order[start..start + child.count as usize] {
                    if let Some(h) = test(i, (range.0, hi(&best))) {
                        best = Some(nearer(best, h));
                    }
                }
                continue;
            }
            let node = &nodes[child.index as usize];
            let [a, b] = node.children;
            let r = (range.0, hi(&best));
            let entered = [
                Self::enter(node.min[0], node.max[0], o, inv, r),
                Self::enter(node.min[1], node.max[1], o, inv, r),
            ];
            current = match entered {
                [Some(x), Some(y)] => {
                    let (near, far) = if x <= y {
                        ((a, x), (b, y))
                    } else {
                        ((b, y), (a, x))
                    };
                    stack.push(far);
                    Some(near)
                }
                [Some(x), None] => Some((a, x)),
                [None, Some(y)] => Some((b, y)),
                [None, None] => None,
            };
        }
        best
    }

    /// [`Bvh::closest`] for a packet of rays (`o[i]`, `inv[i]` = 1/d),
    /// those of `lanes` searching within `range`: `test(item, lanes, hi)`
    /// is called for every item whose box any of `lanes` enters, with those
    /// that do; `hi[i]` is the upper end of ray i's range, which `test`
    /// lowers to the ray's best hit so far.
    pub(crate) fn closest_packet(
        &self,
        (o, inv): (&[DVec4; PACKET], &[DVec4; PACKET]),
        lanes: Lanes,
        range: (f64, f64),
        mut test: impl FnMut(u32, Lanes, &mut [f64; PACKET]),
    ) {
        if self.0.root.count == 0 && self.0.nodes.is_empty() {
            return; // no items
        }
        let Built {
            nodes, root, order, ..
        } = &self.0;
        let mut hi = [range.1; PACKET];
        let mut entries = [range.0; PACKET];
        let bounds = &self.0.root_bounds;
        let lanes = lanes.filter(|i| {
            let entry = Self::enter(bounds.min, bounds.max, o[i], inv[i], range);
            entries[i] = entry.unwrap_or(range.0);
            entry.is_some()
        });
        let mut stack = Stack::new();
        let mut current = Some(TopWaiting {
            child: *root,
            lanes,
            entries,
        });
        while let Some(w) = current.take().or_else(|| stack.pop()) {
            let lanes = w.lanes.filter(|i| w.entries[i] <= hi[i]);
            if lanes.is_empty() {
                continue;
            }
            if w.child.count > 0 {
                let start = w.child.index as usize;
                for &item in &order[start..start + w.child.count as usize] {
                    test(item, lanes, &mut hi);
                }
                continue;
            }
            let node = &nodes[w.child.index as usize];
            let child = |c: usize| {
                let mut entries = [0.0; PACKET];
                let entered = lanes.filter(|i| {
                    let r = (range.0, hi[i]);
                    let entry = Self::enter(node.min[c], node.max[c], o[i], inv[i], r);
                    entries[i] = entry.unwrap_or(0.0);
                    entry.is_some()
                });
                let key = entered
                    .iter()
                    .map(|i| entries[i])
                    .fold(f64::INFINITY, f64::min);
                let child = node.children[c];
                (
                    TopWaiting {
                        child,
                        lanes: entered,
                        entries,
                    },
                    key,
                )
            };
            // (Not `map`, which is not inlined here.)
            let (a, b) = (child(0), child(1));
            current = match (a.0.lanes.is_empty(), b.0.lanes.is_empty()) {
                (false, false) => {
                    let (near, far) = if a.1 <= b.1 { (a.0, b.0) } else { (b.0, a.0) };
                    stack.push(far);
                    Some(near)
                }
                (false, true) => Some(a.0),
                (true, false) => Some(b.0),
                (true, true) => None,
            };
        }
    }
}

/// A child waiting on a packet's stack: the rays that entered it and where
/// each did.
#[derive(Clone, Copy, Debug, Default)]
struct TopWaiting {
    child: Child,
    lanes: Lanes,
    entries: [f64; PACKET],
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ray parallel to an axis (either signed zero) whose origin lies
    /// exactly on one of the box's faces on that axis enters it; one just
    /// outside does not. (Taking the near face as the lesser of the two
    /// crossings, as before, let the NaN of 0 * inf on the lower face pass
    /// the upper face's +inf as the entry: such boxes were culled.)
    #[test]
    fn a_parallel_ray_from_a_face_enters_the_box() {
        let (min, max) = (
            DVec4::new(0.0, 0.0, 0.0, 0.0),
            DVec4::new(1.0, 1.0, 1.0, 1.0),
        );
        for axis in 0..4 {
            for zero in [0.0, -0.0] {
                for (face, inside) in [
                    (0.0, true),
                    (1.0, true),
                    (-1e-9, false),
                    (1.0 + 1e-9, false),
                ] {
                    let mut o = DVec4::splat(0.5) - DVec4::new(3.0, 2.0, 2.5, 1.5);
                    let mut d = DVec4::new(3.0, 2.0, 2.5, 1.5);
                    o[axis] = face;
                    d[axis] = zero;
                    let entered = Bvh::enter(min, max, o, DVec4::ONE / d, (0.0, 10.0)).is_some();
                    assert_eq!(
                        entered, inside,
                        "axis {axis}, d = {zero:?}, origin on {face}"
                    );
                }
            }
        }
    }
}
