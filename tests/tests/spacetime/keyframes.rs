//! Keyframed motion: every hit on a keyframed object lies
//! on its triangle as interpolated at the hit's lab time, a closed mesh stays
//! closed in spacetime while it turns, and the hierarchy finds exactly what
//! brute force finds.

use glam::{DQuat, DVec3};
use renderer::SplitMix64;
use renderer::{
    Database, Event, Keyframe, LightSpeed, Mesh, Motion, ObjectKind, PrimitiveId, Ray, Traversal,
};
use workspace_tests::{object, scene, unit};

/// Radians turned per keyframe interval.
const TURN: f64 = 0.12;

/// A cube turning about a tilted axis while its centre swings on a curve.
fn tumbling() -> (Mesh, Vec<Keyframe>) {
    let mesh = Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0));
    let axis = DVec3::new(0.3, 1.0, 0.2).normalize();
    let frames = (0..40)
        .map(|k| {
            let t = -20.0 + k as f64;
            let turn = DQuat::from_axis_angle(axis, TURN * k as f64);
            Keyframe {
                t,
                position: DVec3::new(3.0 * (0.1 * t).sin(), 0.4 * (0.05 * t).cos(), -0.1 * t),
                offsets: Some(mesh.vertices.iter().map(|p| turn * *p).collect()),
            }
        })
        .collect();
    (mesh, frames)
}

fn database(kind: ObjectKind) -> (Database, Mesh, Vec<Keyframe>) {
    let (mesh, frames) = tumbling();
    let s = scene(vec![object(
        "cube",
        kind,
        mesh.clone(),
        Motion::Keyframes(frames.clone()),
    )]);
    (Database::build(&s, true).unwrap(), mesh, frames)
}

/// The reference point at lab time t, and the interval's keyframes.
fn bracket(frames: &[Keyframe], t: f64) -> (usize, f64) {
    let k = frames
        .iter()
        .rposition(|f| f.t <= t)
        .unwrap()
        .min(frames.len() - 2);
    (k, (t - frames[k].t) / (frames[k + 1].t - frames[k].t))
}

#[test]
fn hits_lie_on_the_interpolated_triangle_and_the_cube_stays_closed() {
    let (db, mesh, frames) = database(ObjectKind::HObj);
    let mut rng = SplitMix64::new(5);
    let mut hits = 0;
    for _ in 0..3000 {
        // A light-cone ray from a random camera event, aimed at where the
        // centre was some time before: it passes through the cube's
        // interior, so it must cross its boundary.
        let tc = rng.range(-5.0, 25.0);
        let cam = unit(&mut rng) * rng.range(6.0, 12.0);
        let (mut lo, mut hi) = (-19.9, tc);
        let centre = |t: f64| {
            let (k, f) = bracket(&frames, t);
            frames[k].position.lerp(frames[k + 1].position, f)
        };
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if tc - m > (centre(m) - cam).length() {
                lo = m;
            } else {
                hi = m;
            }
        }
        if !(-19.0..=18.0).contains(&lo) {
            continue;
        }
        let ray = Ray::backwards(
            Event::new(tc, cam),
            (centre(lo) - cam).normalize(),
            LightSpeed::Finite,
        );
        let hit = db
            .closest_hit(&ray, (0.0, f64::INFINITY))
            .expect("a ray through the cube's centre event missed it: a hole in spacetime");
        hits += 1;
        let triangle = db.surface(&hit).triangle as usize;
        let (k, f) = bracket(&frames, hit.event.t);
        let at = |i: u32| {
            let (a, b) = (&frames[k], &frames[k + 1]);
            let p = |fr: &Keyframe| fr.position + fr.offsets.as_ref().unwrap()[i as usize];
            p(a).lerp(p(b), f)
        };
        let [a, b, c] = mesh.triangles[triangle].map(at);
        let n = (b - a).cross(c - a).normalize();
        // Within an interval the three tetrahedra bend the turning face
        // along their cut. A point of the cut at time fraction f with
        // corner weights split into bottom and top parts differs from the
        // interpolated triangle's point by sum_v (beta_v - f lambda_v) dv,
        // dv the corners' displacements: at most 2 f (1 - f) <= 1/2 times
        // the largest change of an edge vector over the interval.
        let tri = mesh.triangles[triangle];
        let corner = |fr: &Keyframe, i: u32| fr.offsets.as_ref().unwrap()[i as usize] + fr.position;
        let change = |i: u32, j: u32| {
            ((corner(&frames[k + 1], i) - corner(&frames[k + 1], j))
                - (corner(&frames[k], i) - corner(&frames[k], j)))
            .length()
        };
        let bend = 0.5
            * change(tri[0], tri[1])
                .max(change(tri[1], tri[2]))
                .max(change(tri[0], tri[2]));
        let off = (hit.event.x - a).dot(n).abs();
        assert!(
            off <= bend + 1e-9,
            "the hit is {off} off its triangle's plane (bound {bend})"
        );
        assert!(
            off <= bend,
            "the hit is {off} off its triangle's plane (bound {bend})"
        );
        let along = db.surface(&hit).normal.dot(n).abs();
        assert!(along > 0.99, "normal off by {}", along.acos());
    }
    assert!(hits > 1000, "only {hits} rays tested");
}

#[test]
fn the_hierarchy_finds_what_brute_force_finds() {
    for kind in [ObjectKind::HObj, ObjectKind::VObj] {
        let (mut db, _, _) = database(kind);
        let mut rng = SplitMix64::new(9);
        let rays: Vec<Ray> = (0..4000)
            .map(|_| {
                let o = Event::new(
                    rng.range(-25.0, 30.0),
                    unit(&mut rng) * rng.range(4.0, 10.0),
                );
                let aim = DVec3::new(
                    rng.range(-4.0, 4.0),
                    rng.range(-2.0, 2.0),
                    rng.range(-4.0, 4.0),
                );
                Ray::backwards(o, (aim - o.x).normalize(), LightSpeed::Finite)
            })
            .collect();
        let found = |db: &Database| -> Vec<Option<(PrimitiveId, u64)>> {
            rays.iter()
                .map(|r| {
                    db.closest_hit(r, (0.0, f64::INFINITY))
                        .map(|h| (h.primitive, h.s.to_bits()))
                })
                .collect()
        };
        let bvh = found(&db);
        db.set_traversal(Traversal::BruteForce);
        assert_eq!(bvh, found(&db), "{kind:?}");
        assert!(bvh.iter().filter(|h| h.is_some()).count() > 300);
    }
}
