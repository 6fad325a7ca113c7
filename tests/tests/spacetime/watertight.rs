//! Watertightness: light-cone rays aimed exactly at the faces and edges
//! that neighbouring tetrahedra share (inside one prism and between the
//! prisms of neighbouring triangles) never slip through, and the BVH finds
//! what brute force finds, for a sheet of triangles at rest, moving as an
//! H_obj, Lorentz-contracted as a V_obj along an axis and diagonally, and
//! keyframed (changing velocity, so that corners at the middle keyframe are
//! shared by the prisms of both intervals), at 1x and at 100x coordinates:
//! 10^7 rays in all, at faces, edges and (keyframed) corners.
//!
//! The sheet is a flat grid moving slower than light, so each ray, which
//! crosses its world-volume once, must hit it at the aimed point.

use glam::DVec3;
use rayon::prelude::*;
use renderer::{Database, Event, FourVector, Keyframe, LightSpeed, Mesh, Motion, ObjectKind, Ray};
use renderer::{SplitMix64, Tetrahedron, Traversal};
use std::collections::HashMap;
use workspace_tests::{object, scene, unit};

/// Grid cells per side of the sheet.
const CELLS: u32 = 6;
/// Rays per configuration (10 configurations: 10^7 in all).
const RAYS: usize = 1_000_000;
/// Every this many rays is also traced by brute force.
const BRUTE_EVERY: usize = 10;

/// The sheet: `CELLS` x `CELLS` unit squares in z = 0, two triangles each,
/// scaled by `scale`.
fn sheet(scale: f64) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..CELLS {
        for j in 0..CELLS {
            let c = DVec3::new(f64::from(i), f64::from(j), 0.0) * scale;
            m.append(
                &Mesh::quad(c, DVec3::X * scale, DVec3::Y * scale),
                DVec3::ZERO,
            );
        }
    }
    m
}

/// Whether mesh triangle `t` touches the sheet's rim (its prisms' side
/// faces there are the world-volume's boundary, which rays may miss).
fn touches_rim(mesh: &Mesh, t: usize, scale: f64) -> bool {
    let rim = f64::from(CELLS) * scale;
    mesh.corners(t).iter().any(|c| {
        [c.x, c.y]
            .iter()
            .any(|&x| x.abs() < 1e-9 * scale || (x - rim).abs() < 1e-9 * scale)
    })
}

/// A face or edge shared by tetrahedra: its corners.
type Shared = Vec<Event>;

/// The faces shared by two tetrahedra and the edges and corners shared by
/// two or more, of prisms of triangles away from the rim, that do not lie
/// in the world-volume's first or last instant (its boundary): joining a
/// prism's bottom to its top, or at a keyframe time strictly inside `life`.
fn shared_elements(db: &Database, mesh: &Mesh, scale: f64, life: (f64, f64)) -> Vec<Shared> {
    let key = |e: &Event| [e.t, e.x.x, e.x.y, e.x.z].map(f64::to_bits);
    let mut count: HashMap<Vec<[u64; 4]>, (usize, Shared)> = HashMap::new();
    for tet in db.tetrahedra() {
        let prism = db.prism(tet.prism);
        if touches_rim(mesh, prism.triangle as usize, scale) {
            continue;
        }
        let inside = |p: &Shared| p.iter().all(|e| e.t > life.0 && e.t < life.1);
        for part in parts(&tet)
            .into_iter()
            .filter(|p| spans_time(&tet, p) || inside(p))
        {
            let mut k: Vec<[u64; 4]> = part.iter().map(key).collect();
            k.sort_unstable();
            count.entry(k).or_insert((0, part)).0 += 1;
        }
    }
    let mut shared: Vec<Shared> = count
        .into_values()
        .filter(|(n, part)| *n >= 2 && part.len() <= 3)
        .map(|(_, part)| part)
        .collect();
    shared.sort_by(|a, b| {
        let k = |s: &Shared| {
            s.iter()
                .map(|e| (e.t, e.x.x, e.x.y))
                .fold((0.0, 0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2))
        };
        k(a).partial_cmp(&k(b)).unwrap()
    });
    shared
}

/// Whether `part` of `tet` has corners at both the bottom and the top of
/// its prism. The pieces are (a0 b0 c0 c1), (a0 b0 b1 c1), (a0 a1 b1 c1).
fn spans_time(tet: &Tetrahedron, part: &Shared) -> bool {
    const BOTTOM: [[bool; 4]; 3] = [
        [true, true, true, false],
        [true, true, false, false],
        [true, false, false, false],
    ];
    let bottom = BOTTOM[tet.piece as usize];
    let at = |e: &Event| tet.vertices.iter().position(|v| v == e).unwrap();
    let b = part.iter().filter(|e| bottom[at(e)]).count();
    b > 0 && b < part.len()
}

/// A tetrahedron's four faces, six edges and four corners.
fn parts(tet: &Tetrahedron) -> Vec<Shared> {
    let v = tet.vertices;
    let mut out: Vec<Shared> = v.iter().map(|e| vec![*e]).collect();
    for skip in 0..4 {
        out.push((0..4).filter(|&i| i != skip).map(|i| v[i]).collect());
    }
    for a in 0..4 {
        for b in a + 1..4 {
            out.push(vec![v[a], v[b]]);
        }
    }
    out
}

/// A point of `part`, by random weights bounded away from zero.
fn point_on(part: &Shared, rng: &mut SplitMix64) -> Event {
    let w: Vec<f64> = part.iter().map(|_| rng.next_f64() + 1e-2).collect();
    let sum: f64 = w.iter().sum();
    let t = part.iter().zip(&w).map(|(e, w)| e.t * w).sum::<f64>() / sum;
    let x = part.iter().zip(&w).map(|(e, w)| e.x * *w).sum::<DVec3>() / sum;
    Event::new(t, x)
}

/// The light-cone ray from a camera event that sees `p`, from a direction
/// well away from the sheet's plane; and the distance to `p`.
fn ray_to(p: Event, rng: &mut SplitMix64, scale: f64) -> (Ray, f64) {
    let w = loop {
        let w = unit(rng);
        if w.z.abs() > 0.4 {
            break w;
        }
    };
    let dist = scale * rng.range(2.0, 20.0);
    let cam = p.x + w * dist;
    let ray = Ray::backwards(Event::new(p.t + dist, cam), -w, LightSpeed::Finite);
    (ray, dist)
}

/// Leaks and BVH-against-brute-force disagreements among `RAYS` rays aimed
/// at the shared faces and edges of the sheet on `motion`.
fn shoot(
    (kind, motion, lorentz): (ObjectKind, Motion, bool),
    scale: f64,
    seed: u64,
) -> (usize, usize, usize) {
    let mesh = sheet(scale);
    let life = match &motion {
        Motion::Extrusion { start, extrusion } => (start.t, start.t + extrusion.t),
        Motion::Keyframes(k) => (k[0].t, k[k.len() - 1].t),
        _ => unreachable!(),
    };
    let s = scene(vec![object("sheet", kind, mesh.clone(), motion)]);
    let db = Database::build(&s, lorentz).unwrap();
    let mut brute = Database::build(&s, lorentz).unwrap();
    brute.set_traversal(Traversal::BruteForce);
    let shared = shared_elements(&db, &mesh, scale, life);
    assert!(shared.len() > 100, "only {} shared elements", shared.len());
    let chunks = 64;
    let per = RAYS / chunks;
    (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut rng = SplitMix64::new(seed * 1000 + c as u64);
            let (mut leaks, mut disagree, mut shot) = (0, 0, 0);
            while shot < per {
                let part = &shared[rng.next_u64() as usize % shared.len()];
                let p = point_on(part, &mut rng);
                let (ray, dist) = ray_to(p, &mut rng, scale);
                let hit = db.closest_hit(&ray, (0.0, f64::INFINITY));
                if hit.is_none_or(|h| (h.s - dist).abs() > 1e-6 * dist) {
                    leaks += 1;
                }
                if shot % BRUTE_EVERY == 0 {
                    let b = brute.closest_hit(&ray, (0.0, f64::INFINITY));
                    if b.map(|h| (h.s.to_bits(), h.primitive))
                        != hit.map(|h| (h.s.to_bits(), h.primitive))
                    {
                        disagree += 1;
                    }
                }
                shot += 1;
            }
            (leaks, disagree, shot)
        })
        .reduce(|| (0, 0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2))
}

/// The sheet's motion at `scale`: uniform with velocity `v` over 40
/// scaled t.units, or (`None`) keyframed, at 0.5c along x and then at 0.8c
/// along y.
fn motion_at(v: Option<DVec3>, scale: f64) -> Motion {
    let life = 40.0 * scale;
    match v {
        Some(v) => Motion::Extrusion {
            start: Event::new(-life / 2.0, -v * life / 2.0),
            extrusion: FourVector::new(life, v * life),
        },
        None => {
            let half = life / 2.0;
            let at = |t: f64, x: DVec3| Keyframe {
                t,
                position: x,
                offsets: None,
            };
            Motion::Keyframes(vec![
                at(-half, DVec3::new(-0.5 * half, 0.0, 0.0)),
                at(0.0, DVec3::ZERO),
                at(half, DVec3::new(0.0, 0.8 * half, 0.0)),
            ])
        }
    }
}

#[test]
fn rays_at_shared_faces_edges_and_corners_never_leak_and_bvh_equals_brute_force() {
    let mut report = Vec::new();
    let mut total = 0;
    let diagonal = DVec3::ONE.normalize() * 0.9;
    let motions = [
        ("static", ObjectKind::HObj, Some(DVec3::ZERO), false),
        (
            "H_obj 0.9c along x",
            ObjectKind::HObj,
            Some(DVec3::X * 0.9),
            false,
        ),
        (
            "V_obj 0.9c along x",
            ObjectKind::VObj,
            Some(DVec3::X * 0.9),
            true,
        ),
        (
            "V_obj 0.9c diagonal",
            ObjectKind::VObj,
            Some(diagonal),
            true,
        ),
        ("keyframed H_obj", ObjectKind::HObj, None, false),
    ];
    for (k, scale) in [1.0, 100.0].into_iter().enumerate() {
        for (m, (label, kind, v, lorentz)) in motions.into_iter().enumerate() {
            let motion = motion_at(v, scale);
            let (leaks, disagree, shot) =
                shoot((kind, motion, lorentz), scale, (10 * k + m) as u64 + 1);
            total += shot;
            report.push(format!("{label} at {scale}x: {leaks} leaks, {disagree} BVH/brute disagreements of {shot} rays"));
            if leaks > 0 || disagree > 0 {
                report.push("  ^ FAILED".into());
            }
        }
    }
    let text = report.join("\n");
    assert!(total >= 9_900_000, "{total} rays");
    assert!(!text.contains("FAILED"), "{text}");
}
