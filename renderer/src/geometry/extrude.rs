//! Temporal extrusion (paper 3.1): a triangle swept along its object's
//! worldline is a prism, a 3-manifold of spacetime, cut into three
//! tetrahedra by a fixed table (paper Figure 4).

use super::Pose;
use crate::scene::Mesh;
use crate::spacetime::Event;
use glam::DVec3;
use std::cmp::Ordering;

/// A 3-simplex of spacetime: one of the three pieces of an extruded triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tetrahedron {
    /// Its corners, lab frame.
    pub vertices: [Event; 4],
    /// Index of the prism (extruded triangle) this piece belongs to.
    pub prism: u32,
    /// Which of the prism's three pieces, 0..3.
    pub piece: u8,
}

/// An extruded triangle: the shading data shared by its three tetrahedra.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prism {
    /// Index into the database's objects.
    pub object: u32,
    /// Index of the triangle in the object's mesh.
    pub triangle: u32,
    /// Lab-frame unit normal of the triangle (after any Lorentz contraction)
    /// at the start of the prism.
    pub normal: DVec3,
    /// The same at the end: equal to `normal` for a pure translation, not
    /// for a keyframe interval that turns or deforms the triangle.
    pub end_normal: DVec3,
    /// Lab times of the prism's bottom and top.
    pub span: (f64, f64),
}

impl Prism {
    /// The unit normal at lab time `t`: the start and end normals
    /// interpolated (exact for a translation, to first order in the turn
    /// for a keyframe interval).
    pub fn normal_at(&self, t: f64) -> DVec3 {
        if self.normal == self.end_normal {
            return self.normal;
        }
        let f = ((t - self.span.0) / (self.span.1 - self.span.0)).clamp(0.0, 1.0);
        self.normal
            .lerp(self.end_normal, f)
            .try_normalize()
            .unwrap_or(self.normal)
    }
}

/// Orders a triangle's corners by position (lexicographic x, y, z). Every
/// prism cuts the quad face over a mesh edge along the diagonal from the
/// edge's lower corner at the start to its higher corner at the end, so two
/// prisms sharing an edge cut their common face identically: a closed mesh
/// stays closed in spacetime.
pub fn corner_order(corners: [DVec3; 3]) -> [usize; 3] {
    let key = |p: DVec3| [p.x, p.y, p.z];
    let cmp = |a: &usize, b: &usize| {
        let (ka, kb) = (key(corners[*a]), key(corners[*b]));
        ka.iter()
            .zip(kb.iter())
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| *o != Ordering::Equal)
            .unwrap_or(Ordering::Equal)
    };
    let mut order = [0, 1, 2];
    order.sort_by(cmp);
    order
}

/// A prism's six corners in its cut's order: the bottom corners a0, b0, c0
/// (a < b < c by [`corner_order`]), then the top corners a1, b1, c1. The
/// database keeps these, once per prism, and its tetrahedra are read off
/// them ([`piece`]).
pub type PrismCorners = [Event; 6];

/// Which of a prism's [`PrismCorners`] each of its three pieces has:
/// (a0 b0 c0 c1), (a0 b0 b1 c1), (a0 a1 b1 c1).
const PIECES: [[usize; 4]; 3] = [[0, 1, 2, 5], [0, 1, 4, 5], [0, 3, 4, 5]];

/// The [`PrismCorners`] of the prism from `lo` to `hi`, ordered by `order`.
pub fn corners_between(lo: [Event; 3], hi: [Event; 3], order: [usize; 3]) -> PrismCorners {
    let [a, b, c] = order;
    [lo[a], lo[b], lo[c], hi[a], hi[b], hi[c]]
}

/// Piece `k` (0..3) of the prism with `corners`, as a tetrahedron's corners.
pub fn piece(corners: &PrismCorners, k: usize) -> [Event; 4] {
    PIECES[k].map(|i| corners[i])
}

/// Extrudes every triangle of `mesh` over one keyframe interval: each
/// vertex moves in a straight line from its lab position in `from` to that
/// in `to` (curved temporal extrusion, paper 6, as a chain of straight
/// ones). The cut follows the rest mesh's [`corner_order`], the same in
/// every interval, so neighbouring prisms share faces. The caller has
/// checked that no triangle is degenerate at either keyframe. A prism
/// names the triangle `parents` gives for its own (a piece of a cut
/// Born-rigid surface names the given mesh's triangle it lies in; empty:
/// its own).
pub fn extrude_between(
    mesh: &Mesh,
    parents: &[u32],
    from: &Pose,
    to: &Pose,
    object: u32,
    prisms: &mut Vec<Prism>,
    corners_out: &mut Vec<PrismCorners>,
) {
    let normal_of = |c: [Event; 3]| (c[1].x - c[0].x).cross(c[2].x - c[0].x).normalize();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let lo = tri.map(|i| Event::new(from.t, from.vertices[i as usize]));
        let hi = tri.map(|i| Event::new(to.t, to.vertices[i as usize]));
        prisms.push(Prism {
            object,
            triangle: parents.get(t).copied().unwrap_or(t as u32),
            normal: normal_of(lo),
            end_normal: normal_of(hi),
            span: (from.t, to.t),
        });
        corners_out.push(corners_between(lo, hi, corner_order(mesh.corners(t))));
    }
}

#[cfg(test)]
mod tests;
