//! Temporal extrusion (paper 3.1): the three tetrahedra of a prism tile it,
//! and neighbouring prisms cut their shared faces the same way.

use super::*;
use crate::rng::SplitMix64;
use crate::spacetime::{FourVector, Worldline};
use approx::abs_diff_eq;
use std::collections::{BTreeSet, HashMap};

/// A random point in the cube [-r, r]^3.
fn point(rng: &mut SplitMix64, r: f64) -> DVec3 {
    DVec3::new(rng.range(-r, r), rng.range(-r, r), rng.range(-r, r))
}

/// A random unit vector.
fn unit(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let p = point(rng, 1.0);
        let l = p.length();
        if l > 0.1 && l <= 1.0 {
            return p / l;
        }
    }
}

/// The prism `bottom[i] -> bottom[i] + extrusion` as three tetrahedra.
/// With corners ordered a < b < c by [`corner_order`] (0 = start, 1 = end):
/// (a0 b0 c0 c1), (a0 b0 b1 c1), (a0 a1 b1 c1).
fn split_prism(bottom: [Event; 3], extrusion: FourVector, order: [usize; 3]) -> [[Event; 4]; 3] {
    split_between(bottom, bottom.map(|e| e + extrusion), order)
}

/// The prism with bottom corners `lo` and top corners `hi` (corner i moving
/// straight from `lo[i]` to `hi[i]`) as three tetrahedra, cut as in
/// [`split_prism`].
fn split_between(lo: [Event; 3], hi: [Event; 3], order: [usize; 3]) -> [[Event; 4]; 3] {
    let corners = corners_between(lo, hi, order);
    [0, 1, 2].map(|k| piece(&corners, k))
}

/// Extrudes every triangle of `mesh` (lab-frame shape, relative to the
/// worldline's reference point) along `worldline`, appending prisms and
/// their corners: the paper's extrusion of uniform motion, cut as the
/// database cuts it (which keeps such a triangle at rest in the comoving
/// frame instead, and reads its corners back the same way,
/// `Database::prism_corners`).
fn extrude(
    mesh: &Mesh,
    worldline: &Worldline,
    object: u32,
    prisms: &mut Vec<Prism>,
    corners_out: &mut Vec<PrismCorners>,
) {
    for (t, _) in mesh.triangles.iter().enumerate() {
        let corners = mesh.corners(t);
        let normal = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .normalize();
        prisms.push(Prism {
            object,
            triangle: t as u32,
            normal,
            end_normal: normal,
            span: (worldline.start.t, worldline.end().t),
        });
        let bottom = corners.map(|p| Event::new(worldline.start.t, worldline.start.x + p));
        let top = bottom.map(|e| e + worldline.extrusion);
        corners_out.push(corners_between(bottom, top, corner_order(corners)));
    }
}

/// Euclidean 3-volume of a tetrahedron embedded in 4D (sqrt of the Gram
/// determinant of its edges, over 6).
fn tetrahedron_volume(v: &[Event; 4]) -> f64 {
    let e = [v[1] - v[0], v[2] - v[0], v[3] - v[0]].map(|e| e.to_xyzt());
    let g = glam::DMat3::from_cols_array_2d(&[
        [e[0].dot(e[0]), e[0].dot(e[1]), e[0].dot(e[2])],
        [e[1].dot(e[0]), e[1].dot(e[1]), e[1].dot(e[2])],
        [e[2].dot(e[0]), e[2].dot(e[1]), e[2].dot(e[2])],
    ]);
    g.determinant().max(0.0).sqrt() / 6.0
}

/// 3-volume of the prism spanned by triangle edges u, v and extrusion e:
/// base area times the height of e off the triangle's plane = sqrt(Gram(u, v, e)) / 2.
fn prism_volume(u: FourVector, v: FourVector, e: FourVector) -> f64 {
    let [a, b, c] = [u, v, e].map(|w| w.to_xyzt());
    let g = glam::DMat3::from_cols_array_2d(&[
        [a.dot(a), a.dot(b), a.dot(c)],
        [b.dot(a), b.dot(b), b.dot(c)],
        [c.dot(a), c.dot(b), c.dot(c)],
    ]);
    g.determinant().sqrt() / 2.0
}

/// Barycentric coordinates of `p` in tetrahedron `v` by least squares in
/// 4D (normal equations; fine for these well-shaped tetrahedra).
fn bary(v: &[Event; 4], p: Event) -> [f64; 4] {
    let e = [v[1] - v[0], v[2] - v[0], v[3] - v[0]].map(|e| e.to_xyzt());
    let r = (p - v[0]).to_xyzt();
    let g = glam::DMat3::from_cols_array_2d(&[
        [e[0].dot(e[0]), e[0].dot(e[1]), e[0].dot(e[2])],
        [e[1].dot(e[0]), e[1].dot(e[1]), e[1].dot(e[2])],
        [e[2].dot(e[0]), e[2].dot(e[1]), e[2].dot(e[2])],
    ]);
    let b = g.inverse() * DVec3::new(e[0].dot(r), e[1].dot(r), e[2].dot(r));
    [1.0 - b.x - b.y - b.z, b.x, b.y, b.z]
}

#[test]
fn three_tetrahedra_tile_the_prism() {
    let mut rng = SplitMix64::new(7);
    for _ in 0..500 {
        let corners = [
            point(&mut rng, 2.0),
            point(&mut rng, 2.0),
            point(&mut rng, 2.0),
        ];
        let t0 = rng.range(-5.0, 5.0);
        let bottom = corners.map(|c| Event::new(t0, c));
        let dt = rng.range(0.5, 20.0);
        let e = FourVector::new(dt, unit(&mut rng) * rng.range(0.0, 1.5) * dt);
        let tets = split_prism(bottom, e, corner_order(corners));
        let sum: f64 = tets.iter().map(tetrahedron_volume).sum();
        let expected = prism_volume(bottom[1] - bottom[0], bottom[2] - bottom[0], e);
        assert!(
            abs_diff_eq!(sum, expected, epsilon = 1e-9 * expected),
            "tets {sum} vs prism {expected}"
        );
        // Every interior point of the prism lies in exactly one tetrahedron.
        for _ in 0..20 {
            let (a, b) = (rng.range(0.02, 0.96), rng.range(0.02, 0.96));
            let (a, b) = if a + b > 0.98 {
                (0.98 - a, 0.98 - b)
            } else {
                (a, b)
            };
            let (a, b) = (a.max(0.01), b.max(0.01));
            let lam = rng.range(0.01, 0.99);
            let base = bottom[0] + (bottom[1] - bottom[0]) * a + (bottom[2] - bottom[0]) * b;
            let p = base + e * lam;
            let inside = tets
                .iter()
                .filter(|t| bary(t, p).iter().all(|x| *x >= -1e-9))
                .count();
            assert_eq!(inside, 1, "point {p:?} lies in {inside} tetrahedra");
        }
    }
}

/// Triangles of a set of tetrahedra that lie within `quad` (four events), as
/// sorted triples of exact coordinates.
fn faces_in(tets: &[[Event; 4]], quad: &[Event; 4]) -> BTreeSet<Vec<[u64; 4]>> {
    let key = |e: &Event| e.to_xyzt().to_array().map(f64::to_bits);
    let in_quad = |e: &Event| quad.iter().any(|q| q == e);
    let mut out = BTreeSet::new();
    for t in tets {
        for skip in 0..4 {
            let face: Vec<&Event> = (0..4).filter(|i| *i != skip).map(|i| &t[i]).collect();
            if face.iter().all(|e| in_quad(e)) {
                let mut k: Vec<[u64; 4]> = face.iter().map(|e| key(e)).collect();
                k.sort();
                out.insert(k);
            }
        }
    }
    out
}

#[test]
fn neighbouring_prisms_cut_shared_faces_alike() {
    let mut rng = SplitMix64::new(11);
    // A closed box with its corners shared, and the same box with every
    // triangle's corners duplicated: both must agree on every shared edge.
    let boxed = Mesh::cuboid(DVec3::new(-1.0, -0.5, -2.0), DVec3::new(1.5, 2.0, 0.25));
    let mut loose = Mesh::default();
    for t in 0..boxed.triangles.len() {
        let [a, b, c] = boxed.corners(t);
        let k = loose.vertices.len() as u32;
        loose.vertices.extend([c, a, b]);
        loose.triangles.push([k + 1, k + 2, k]);
    }
    for mesh in [boxed, loose] {
        for _ in 0..20 {
            let dt = rng.range(1.0, 50.0);
            let wl = Worldline {
                start: Event::new(rng.range(-10.0, 10.0), point(&mut rng, 3.0)),
                extrusion: FourVector::new(dt, unit(&mut rng) * rng.range(0.0, 0.99) * dt),
            };
            let (mut prisms, mut corners) = (Vec::new(), Vec::new());
            extrude(&mesh, &wl, 0, &mut prisms, &mut corners);
            assert_eq!(corners.len(), mesh.triangles.len());
            // Group prisms by the (position-keyed) mesh edges they contain.
            let mut by_edge: HashMap<[[u64; 3]; 2], Vec<usize>> = HashMap::new();
            for (t, _) in mesh.triangles.iter().enumerate() {
                let c = mesh.corners(t);
                for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                    let (mut p, mut q) = (
                        c[i].to_array().map(f64::to_bits),
                        c[j].to_array().map(f64::to_bits),
                    );
                    if p > q {
                        std::mem::swap(&mut p, &mut q);
                    }
                    by_edge.entry([p, q]).or_default().push(t);
                }
            }
            let mut shared = 0;
            for ([p, q], owners) in &by_edge {
                assert_eq!(owners.len(), 2, "a closed box has two triangles per edge");
                let at = |k: &[u64; 3]| wl.start.x + DVec3::from_array(k.map(f64::from_bits));
                let (p0, q0) = (Event::new(wl.start.t, at(p)), Event::new(wl.start.t, at(q)));
                let quad = [p0, q0, p0 + wl.extrusion, q0 + wl.extrusion];
                let faces: Vec<_> = owners
                    .iter()
                    .map(|t| {
                        faces_in(
                            &(0..3).map(|k| piece(&corners[*t], k)).collect::<Vec<_>>(),
                            &quad,
                        )
                    })
                    .collect();
                assert_eq!(
                    faces[0].len(),
                    2,
                    "each prism cuts the quad into two triangles"
                );
                assert_eq!(
                    faces[0], faces[1],
                    "prisms sharing an edge cut its face differently"
                );
                shared += 1;
            }
            assert_eq!(shared, 18);
        }
    }
}
