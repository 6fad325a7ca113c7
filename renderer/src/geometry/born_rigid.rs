//! The surface of a Born-rigid body under hyperbolic motion, within the
//! tolerance at every point and not only at the vertices.
//!
//! The point at rest-frame offset xi along the acceleration is, at lab time
//! t, at f(xi) = sqrt(A^2 + T^2) + const along it, A = 1/a + xi, and at its
//! rest offsets across it. A rest-frame triangle is flat, but its image at
//! one lab time is not: across it f is nonlinear in xi. The flat triangle
//! between the vertices' exact positions puts the rest point with
//! barycentric weights b at sum_v b_v f(xi_v) instead of f(sum_v b_v xi_v);
//! f is convex, so by the chord through the triangle's lowest and highest xi
//! the gap is at most (xi_max - xi_min)^2 / 8 max f'' over them, and
//! f'' = T^2 / (A^2 + T^2)^(3/2) <= 2 / (3 sqrt 3 A) at every lab time
//! (largest at T^2 = 2 A^2), so the smallest A over the triangle bounds it.
//!
//! So the rest mesh is cut by planes of constant xi (levels), the same for
//! every object on the worldline: level k at A = (k d)^2, d^2 fixed by the
//! tolerance. Between levels k and k + 1 the width is (2k + 1) d^2 and the
//! smallest A is (k d)^2, and (2k + 1)^2 / k^2 <= 9 for k >= 1, so
//! d^2 = 8 tolerance / (9 c), c = 2 / (3 sqrt 3), keeps every piece within
//! `tolerance`. An edge is split where it crosses a level, which depends on
//! its two ends alone, so triangles sharing an edge split it at the same
//! points and no crack opens; each triangle is then cut into the pieces
//! between consecutive levels. A level is along the surface exact: all its
//! points share one xi.

use crate::scene::{
    Fault, Hyperbolic, HyperbolicField as H, Mesh, SceneErrorKind as K, SceneField as F,
};
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::HashMap;

/// The largest f'' over all lab times, times A: 2 / (3 sqrt 3).
const CURVATURE: f64 = 0.384_900_179_459_750_5;

/// A level within this fraction of its slab's width from a vertex is taken
/// as passing through it (no sliver of a triangle is cut off); the pieces
/// may then be this much wider, which the spacing allows for.
const SNAP: f64 = 1e-6;

/// Most triangles the cut may add to one object's mesh.
pub(crate) const MAX_ADDED_TRIANGLES: usize = 1 << 20;

/// The levels of constant xi that cut a Born-rigid body under one motion.
#[derive(Clone, Copy, Debug)]
struct Levels {
    inv_a: f64,
    direction: DVec3,
    /// d: level k lies at A = (k d)^2.
    step: f64,
}

/// Where a vertex lies among the levels.
#[derive(Clone, Copy, Debug)]
struct Place {
    /// Its slab: between levels `slab` and `slab + 1`.
    slab: u64,
    /// The level it lies on (to the snap), if any.
    on: Option<u64>,
    /// Its xi, or its level's when on one: what orders the cut.
    key: f64,
    xi: f64,
}

/// What the snap may cost the bound: a piece up to 2 SNAP wider than its
/// slab, and its smallest A up to 3 SNAP d^2 lower (at k = 1), together
/// under (1 + 4 SNAP)^2.
const WIDEN: f64 = (1.0 + 4.0 * SNAP) * (1.0 + 4.0 * SNAP);

/// The largest surface tolerance whose first level, d^2, lies at or
/// below `big_a`: the point is then not in slab 0, where A reaches 0.
fn allowed(big_a: f64) -> f64 {
    9.0 * CURVATURE * WIDEN * big_a / 8.0
}

impl Levels {
    fn new(h: &Hyperbolic, tolerance: f64) -> Levels {
        let d2 = 8.0 * tolerance / (9.0 * CURVATURE * WIDEN);
        Levels {
            inv_a: 1.0 / h.acceleration,
            direction: h.direction,
            step: d2.sqrt(),
        }
    }

    /// The xi of level k.
    fn level(&self, k: u64) -> f64 {
        let r = k as f64 * self.step;
        r * r - self.inv_a
    }

    fn place(&self, p: DVec3) -> Place {
        let xi = p.dot(self.direction);
        let big_a = (self.inv_a + xi).max(0.0);
        let slab = (big_a.sqrt() / self.step).floor() as u64;
        let (lower, upper) = (self.level(slab), self.level(slab + 1));
        let width = upper - lower;
        let on = if xi - lower <= SNAP * width {
            Some(slab)
        } else if upper - xi <= SNAP * width {
            Some(slab + 1)
        } else {
            None
        };
        Place {
            slab,
            on,
            key: on.map_or(xi, |k| self.level(k)),
            xi,
        }
    }

    /// The levels an edge crosses strictly between its ends.
    fn crossed(&self, a: &Place, b: &Place) -> std::ops::RangeInclusive<u64> {
        let (lo, hi) = if a.key <= b.key { (a, b) } else { (b, a) };
        let first = lo.on.unwrap_or(lo.slab) + 1;
        let last = match hi.on {
            Some(k) => k.saturating_sub(1),
            None => hi.slab,
        };
        first..=last
    }
}

/// A mesh cut for a Born-rigid motion, and the triangle of the given mesh
/// each of its triangles lies in.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Pieces {
    pub(crate) mesh: Mesh,
    pub(crate) parents: Vec<u32>,
}

/// Orders points lexicographically, so that an edge is split the same way
/// whichever triangle names it first.
fn lexicographic(p: DVec3, q: DVec3) -> Ordering {
    p.x.total_cmp(&q.x)
        .then(p.y.total_cmp(&q.y))
        .then(p.z.total_cmp(&q.z))
}

/// The cut under construction.
struct Cutter<'m> {
    mesh: &'m Mesh,
    levels: Levels,
    places: Vec<Place>,
    vertices: Vec<DVec3>,
    split: HashMap<(u32, u32, u64), u32>,
}

impl Cutter<'_> {
    /// The points where the edge (i, j) crosses the levels, from i's end to
    /// j's, each as (vertex index, key).
    fn crossings(&mut self, i: u32, j: u32) -> Vec<(u32, f64)> {
        let (pi, pj) = (self.places[i as usize], self.places[j as usize]);
        let range = self.levels.crossed(&pi, &pj);
        let (vi, vj) = (
            self.mesh.vertices[i as usize],
            self.mesh.vertices[j as usize],
        );
        let (p, q, xp, xq) = if lexicographic(vi, vj) == Ordering::Greater {
            (vj, vi, pj.xi, pi.xi)
        } else {
            (vi, vj, pi.xi, pj.xi)
        };
        let mut out: Vec<(u32, f64)> = range
            .map(|k| {
                let level = self.levels.level(k);
                let at = *self
                    .split
                    .entry((i.min(j), i.max(j), k))
                    .or_insert_with(|| {
                        let s = (level - xp) / (xq - xp);
                        self.vertices.push(p + (q - p) * s);
                        (self.vertices.len() - 1) as u32
                    });
                (at, level)
            })
            .collect();
        if pi.key > pj.key {
            out.reverse();
        }
        out
    }

    /// Triangle `t` cut between consecutive levels: its corners sorted by
    /// key, P0 <= P1 <= P2, the chain P0 .. P1 .. P2 and the edge P0 .. P2
    /// are zipped in order of key, each step a triangle between the two
    /// chains' fronts and the next point, so every piece lies between two
    /// consecutive levels.
    fn cut(&mut self, t: usize, out: &mut Vec<[u32; 3]>) {
        let tri = self.mesh.triangles[t];
        let mut c = tri;
        c.sort_by(|&u, &v| {
            let (a, b) = (self.places[u as usize], self.places[v as usize]);
            a.key
                .total_cmp(&b.key)
                .then(a.xi.total_cmp(&b.xi))
                .then(u.cmp(&v))
        });
        let key = |v: u32, s: &Self| s.places[v as usize].key;
        let mut left = vec![(c[0], key(c[0], self))];
        left.extend(self.crossings(c[0], c[1]));
        left.push((c[1], key(c[1], self)));
        left.extend(self.crossings(c[1], c[2]));
        left.push((c[2], key(c[2], self)));
        let mut right = vec![(c[0], key(c[0], self))];
        right.extend(self.crossings(c[0], c[2]));
        right.push((c[2], key(c[2], self)));
        if left.len() == 3 && right.len() == 2 {
            out.push(tri);
            return;
        }
        let [a, b, d] = tri.map(|v| self.mesh.vertices[v as usize]);
        let normal = (b - a).cross(d - a);
        let (mut i, mut j) = (0, 0);
        while i + 1 < left.len() || j + 1 < right.len() {
            let step_left =
                j + 1 == right.len() || (i + 1 < left.len() && left[i + 1].1 <= right[j + 1].1);
            let next = if step_left {
                i += 1;
                left[i].0
            } else {
                j += 1;
                right[j].0
            };
            let (l, r) = if step_left {
                (left[i - 1].0, right[j].0)
            } else {
                (left[i].0, right[j - 1].0)
            };
            if l == r || next == l || next == r {
                continue;
            }
            let v = |k: u32| self.vertices[k as usize];
            let mut piece = [l, r, next];
            if (v(r) - v(l)).cross(v(next) - v(l)).dot(normal) < 0.0 {
                piece = [l, next, r];
            }
            out.push(piece);
        }
    }
}

/// Whether a vertex lies below the first level, where A reaches 0 (or
/// behind the horizon) and no spacing bounds the cut.
fn too_near(p: &Place) -> bool {
    p.slab == 0 && p.on != Some(1)
}

/// How many triangles the cut adds: one per level an edge crosses, summed
/// over the triangles (a triangle crossed c times is cut into c + 1).
fn added(levels: &Levels, places: &[Place], mesh: &Mesh) -> u64 {
    let edges = |t: &[u32; 3]| -> u64 {
        [(0, 1), (1, 2), (0, 2)]
            .iter()
            .map(|&(u, v)| {
                let r = levels.crossed(&places[t[u] as usize], &places[t[v] as usize]);
                (r.end() + 1).saturating_sub(*r.start())
            })
            .fold(0u64, u64::saturating_add)
    };
    mesh.triangles
        .iter()
        .map(edges)
        .fold(0u64, u64::saturating_add)
}

impl Hyperbolic {
    /// How many triangles `mesh` (rest frame) is extruded as when
    /// Born-rigid under this motion on its own: the cut of
    /// `Hyperbolic::born_rigid_pieces` within half the tolerance,
    /// counted without being made (for an estimate of the work; objects
    /// sharing the worldline may cut finer). A mesh that cannot be cut
    /// (a vertex at or behind the first level) counts as it is: inserting
    /// it is an error.
    pub fn born_rigid_triangles(&self, mesh: &Mesh) -> u64 {
        let levels = Levels::new(self, 0.5 * self.tolerance);
        let places: Vec<Place> = mesh.vertices.iter().map(|p| levels.place(*p)).collect();
        let given = mesh.triangles.len() as u64;
        if places.iter().any(too_near) {
            return given;
        }
        given.saturating_add(added(&levels, &places, mesh))
    }

    /// `mesh` (rest frame) cut so that, Born-rigid under this motion, every
    /// point of its flat pieces lies within `tolerance` of the exact body at
    /// every lab time (module doc); triangles that cross no level are kept
    /// as they are. The error names the tolerance when a vertex lies
    /// nearer the Rindler horizon than the first level, or when the cut
    /// would add more than [`MAX_ADDED_TRIANGLES`].
    pub(crate) fn born_rigid_pieces(&self, mesh: &Mesh, tolerance: f64) -> Result<Pieces, Fault> {
        let levels = Levels::new(self, tolerance);
        let places: Vec<Place> = mesh.vertices.iter().map(|p| levels.place(*p)).collect();
        if let Some(p) = places.iter().find(|p| too_near(p)) {
            return Err(Fault::new(
                F::Hyperbolic(H::Tolerance),
                K::NearHorizon {
                    tolerance: self.tolerance,
                    ahead: levels.inv_a + p.xi,
                    limit: 0.999 * self.tolerance / tolerance * allowed(levels.inv_a + p.xi),
                },
            ));
        }
        let added = added(&levels, &places, mesh);
        if added > MAX_ADDED_TRIANGLES as u64 {
            return Err(Fault::new(
                F::Hyperbolic(H::Tolerance),
                K::TooManyPieces {
                    tolerance: self.tolerance,
                    count: added,
                    max: MAX_ADDED_TRIANGLES,
                },
            ));
        }
        let mut cutter = Cutter {
            mesh,
            levels,
            places,
            vertices: mesh.vertices.clone(),
            split: HashMap::new(),
        };
        let (mut triangles, mut parents) = (Vec::new(), Vec::new());
        for t in 0..mesh.triangles.len() {
            let before = triangles.len();
            cutter.cut(t, &mut triangles);
            parents.resize(triangles.len(), t as u32);
            debug_assert!(triangles.len() - before >= 1);
        }
        let materials = if mesh.materials.is_empty() {
            Vec::new()
        } else {
            parents
                .iter()
                .map(|&t| mesh.materials[t as usize])
                .collect()
        };
        Ok(Pieces {
            mesh: Mesh {
                vertices: cutter.vertices,
                triangles,
                materials,
            },
            parents,
        })
    }
}

#[cfg(test)]
mod tests;
