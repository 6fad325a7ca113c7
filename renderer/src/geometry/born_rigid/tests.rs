use super::*;
use crate::geometry::Pose;
use crate::spacetime::Event;
use std::collections::HashMap;

/// From rest at x = -9, proper acceleration 0.2 along x, for 25 t.units
/// (the `born-rigid-plate` fixture's motion).
fn motion(tolerance: f64) -> Hyperbolic {
    Hyperbolic {
        start: Event::new(0.0, DVec3::new(-9.0, 0.0, 0.0)),
        direction: DVec3::X,
        acceleration: 0.2,
        initial_velocity: 0.0,
        duration: 25.0,
        tolerance,
    }
}

/// A plate whose sides are tilted to the acceleration: 4 wide along it.
fn plate() -> Mesh {
    Mesh::quad(
        DVec3::new(-2.0, -1.5, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(2.0, 3.0, 0.0),
    )
}

/// The exact lab position at `t` of the rest point `p` of a Born-rigid body
/// under `h`, from first principles: the point at rest offset xi along n
/// rides the hyperbola S^2 - T^2 = (1/a + xi)^2 about the common centre
/// (S = s + gamma0 / a, T = t - t0 + gamma0 v0 / a); across n it keeps its
/// rest offset.
fn exact(h: &Hyperbolic, p: DVec3, t: f64) -> DVec3 {
    let (a, v0) = (h.acceleration, h.initial_velocity);
    let gamma0 = 1.0 / (1.0 - v0 * v0).sqrt();
    let xi = p.dot(h.direction);
    let big_a = 1.0 / a + xi;
    let big_t = t - h.start.t + gamma0 * v0 / a;
    let s = (big_a * big_a + big_t * big_t).sqrt() - gamma0 / a;
    h.start.x + (p - h.direction * xi) + h.direction * s
}

/// The largest distance between a rendered surface point and the exact
/// body: points spread over every triangle of `mesh` (rest frame), at lab
/// times spread over every interval of `poses`, each interpolated as the
/// prisms do (straight between poses, flat across the triangle).
fn worst(h: &Hyperbolic, mesh: &Mesh, poses: &[Pose]) -> f64 {
    let n = 12;
    let mut worst: f64 = 0.0;
    for w in poses.windows(2) {
        for f in [0.0, 0.25, 0.5, 0.75] {
            let t = w[0].t + f * (w[1].t - w[0].t);
            for tri in &mesh.triangles {
                let at = |pose: &Pose, b: [f64; 3]| -> DVec3 {
                    (0..3).map(|k| pose.vertices[tri[k] as usize] * b[k]).sum()
                };
                for i in 0..=n {
                    for j in 0..=(n - i) {
                        let b = [i as f64 / n as f64, j as f64 / n as f64, 0.0];
                        let b = [b[0], b[1], 1.0 - b[0] - b[1]];
                        let rest: DVec3 =
                            (0..3).map(|k| mesh.vertices[tri[k] as usize] * b[k]).sum();
                        let drawn = at(&w[0], b).lerp(at(&w[1], b), f);
                        worst = worst.max((drawn - exact(h, rest, t)).length());
                    }
                }
            }
        }
    }
    worst
}

/// Every sampled point of the cut plate, at every sampled lab time, lies
/// within the tolerance of the exact Born-rigid body, using a good part of
/// it; the plate's two flat triangles (the old body) exceed it many times.
#[test]
fn every_point_of_a_cut_face_is_within_the_tolerance() {
    let h = motion(1e-3);
    let count = h.intervals(&plate(), true).unwrap();
    let pieces = h.born_rigid_pieces(&plate(), 0.5 * h.tolerance).unwrap();
    assert!(pieces.mesh.triangles.len() > 20);
    let poses = h.poses_in(&pieces.mesh, true, count).unwrap();
    let cut = worst(&h, &pieces.mesh, &poses);
    assert!(cut <= h.tolerance, "cut: {cut}");
    assert!(
        cut > 0.2 * h.tolerance,
        "cut: {cut}, the bound far from tight"
    );
    let flat = h.poses_in(&plate(), true, count).unwrap();
    let uncut = worst(&h, &plate(), &flat);
    assert!(uncut > 10.0 * h.tolerance, "uncut: {uncut}");
}

/// The pieces tile the given triangles: each lies in its parent's plane,
/// faces the same way, and they cover its area exactly; materials follow.
#[test]
fn pieces_tile_their_triangles() {
    let h = motion(1e-3);
    let mut mesh = Mesh::cuboid(DVec3::new(-1.0, -0.5, -0.3), DVec3::new(2.0, 0.5, 0.3));
    mesh.materials = (0..12).map(|t| t % 3).collect();
    let p = h.born_rigid_pieces(&mesh, 5e-4).unwrap();
    let area = |m: &Mesh, t: usize| {
        let [a, b, c] = m.corners(t);
        (b - a).cross(c - a)
    };
    let mut covered = vec![DVec3::ZERO; 12];
    for (t, &parent) in p.parents.iter().enumerate() {
        let (piece, whole) = (area(&p.mesh, t), area(&mesh, parent as usize));
        assert!(piece.dot(whole) > 0.0, "piece {t} turned");
        assert!(piece.cross(whole).length() < 1e-12 * whole.length_squared());
        assert_eq!(p.mesh.materials[t], mesh.materials[parent as usize]);
        covered[parent as usize] += piece;
    }
    for (t, c) in covered.iter().enumerate() {
        assert!((*c - area(&mesh, t)).length() < 1e-12, "triangle {t}");
    }
    // The faces across the acceleration (x = -1, x = 2) cross no level
    // and are kept as they were.
    for t in [0, 1, 2, 3] {
        let kept = p.parents.iter().position(|&q| q == t).unwrap();
        assert_eq!(p.mesh.corners(kept), mesh.corners(t as usize));
        assert_eq!(p.parents.iter().filter(|&&q| q == t).count(), 1);
    }
    assert!(p.mesh.validate().is_ok());
}

/// A closed mesh stays closed: every edge of the cut cuboid is shared by
/// exactly two pieces, once each way (no edge split on one side only).
#[test]
fn a_closed_mesh_stays_closed() {
    let h = motion(1e-4);
    let mesh = Mesh::cuboid(DVec3::new(-1.0, -0.5, -0.3), DVec3::new(2.0, 0.5, 0.3));
    let p = h.born_rigid_pieces(&mesh, 5e-5).unwrap();
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for t in &p.mesh.triangles {
        for k in 0..3 {
            let (u, v) = (t[k], t[(k + 1) % 3]);
            *edges.entry((u.min(v), u.max(v))).or_default() += if u < v { 1 } else { -1 };
        }
    }
    assert!(edges.values().all(|&n| n == 0), "an open edge");
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &p.mesh.triangles {
        for k in 0..3 {
            let (u, v) = (t[k], t[(k + 1) % 3]);
            *uses.entry((u.min(v), u.max(v))).or_default() += 1;
        }
    }
    assert!(uses.values().all(|&n| n == 2));
}

/// Two objects sharing an edge (given in opposite orders, at other vertex
/// indices) split it at the same points, to the bit.
#[test]
fn a_shared_edge_splits_alike_in_both_objects() {
    let h = motion(1e-3);
    let (a, b) = (DVec3::new(-2.0, 0.0, 0.0), DVec3::new(1.5, 1.0, 0.0));
    let one = Mesh {
        vertices: vec![a, b, DVec3::new(0.0, 2.0, 0.0)],
        triangles: vec![[0, 1, 2]],
        materials: Vec::new(),
    };
    let other = Mesh {
        vertices: vec![DVec3::new(0.5, -2.0, 0.3), b, a],
        triangles: vec![[0, 1, 2]],
        materials: Vec::new(),
    };
    let on_edge = |m: &Mesh| -> Vec<[u64; 3]> {
        let mut v: Vec<[u64; 3]> = m
            .vertices
            .iter()
            .filter(|p| {
                let s = (**p - a).dot(b - a) / (b - a).length_squared();
                (a + (b - a) * s - **p).length() < 1e-12
            })
            .map(|p| p.to_array().map(f64::to_bits))
            .collect();
        v.sort_unstable();
        v
    };
    let (x, y) = (
        h.born_rigid_pieces(&one, 5e-4).unwrap(),
        h.born_rigid_pieces(&other, 5e-4).unwrap(),
    );
    let split = on_edge(&x.mesh);
    assert!(split.len() > 10);
    assert_eq!(split, on_edge(&y.mesh));
}

#[test]
fn a_tolerance_too_fine_for_the_cut_is_an_error() {
    let h = motion(1e-12);
    let e = h.born_rigid_pieces(&plate(), 5e-13).unwrap_err();
    assert_eq!(e.field, F::Hyperbolic(H::Tolerance));
    assert!(matches!(e.kind, K::TooManyPieces { .. }), "{:?}", e.kind);
    assert!(e.kind.to_string().contains("loosen it"));
}

#[test]
fn a_vertex_at_the_horizon_is_an_error_naming_the_tolerance() {
    let h = motion(1e-3);
    // 1/a = 5: a vertex 1e-4 in front of the horizon lies below the first
    // level, A = d^2, about 1.15 times the surface tolerance.
    let near = Mesh::quad(
        DVec3::new(-5.0 + 1e-4, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    );
    let e = h.born_rigid_pieces(&near, 5e-4).unwrap_err();
    assert_eq!(e.field, F::Hyperbolic(H::Tolerance));
    let K::NearHorizon { limit, .. } = e.kind else {
        panic!("{:?}", e.kind)
    };
    let finer = motion(limit);
    assert!(finer.born_rigid_pieces(&near, 0.5 * limit).is_ok());
}
