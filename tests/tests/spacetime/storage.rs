//! What the database stores comes back as the scene gave it: a
//! translation's triangles, kept as corner indices into its run's
//! vertices and in the order of its hierarchy, are its mesh's triangles,
//! corner for corner and bit for bit, whatever run they belong to.

use glam::DVec3;
use renderer::{Boost, Database, Event, FourVector, Mesh, Motion, ObjectKind, SplitMix64};
use workspace_tests::{object, point, scene};

/// A mesh of `n` triangles over a pool of `pool` vertices, each vertex
/// shared by several triangles (as in a closed mesh).
fn shared_mesh(rng: &mut SplitMix64, pool: usize, n: usize) -> Mesh {
    let mut m = Mesh {
        vertices: (0..pool).map(|_| point(rng, 2.0)).collect(),
        ..Mesh::default()
    };
    while m.triangles.len() < n {
        let k = [0, 1, 2].map(|_| (rng.next_u64() % pool as u64) as u32);
        let [a, b, c] = k.map(|i| m.vertices[i as usize]);
        if (b - a).cross(c - a).length() > 0.1 {
            m.triangles.push(k);
        }
    }
    m
}

/// Each object's start event and the corners its prisms hold at rest (contracted along the velocity for a V_obj under the Lorentz
/// transform), in prism order.
struct Expected {
    start: Event,
    corners: Vec<[DVec3; 3]>,
}

#[test]
fn every_translated_prism_holds_its_meshs_triangle() {
    let mut rng = SplitMix64::new(29);
    let kinds = [ObjectKind::HObj, ObjectKind::HObj, ObjectKind::VObj];
    let velocities = [
        DVec3::ZERO,
        DVec3::new(0.3, 0.0, 0.1),
        DVec3::new(0.0, 0.8, 0.0),
    ];
    let mut objects = Vec::new();
    let mut expected = Vec::new();
    for (i, (kind, v)) in kinds.into_iter().zip(velocities).enumerate() {
        let mesh = shared_mesh(&mut rng, 40 + 7 * i, 300 + 50 * i);
        let start = Event::new(-20.0, point(&mut rng, 5.0));
        let extrusion = FourVector::new(30.0, v * 30.0);
        let boost = Boost::new(extrusion.velocity()).expect("below c");
        let rest = match kind {
            ObjectKind::VObj => mesh.map_vertices(|p| boost.contract(p)),
            ObjectKind::HObj => mesh.clone(),
        };
        expected.push(Expected {
            start,
            corners: (0..rest.triangles.len()).map(|t| rest.corners(t)).collect(),
        });
        let motion = Motion::Extrusion { start, extrusion };
        objects.push(object(&format!("object {i}"), kind, mesh, motion));
    }
    let db = Database::build(&scene(objects), true).expect("a valid scene");
    let mut p = 0;
    let mut differ_from_the_next_objects = 0;
    for (o, e) in expected.iter().enumerate() {
        for (t, corners) in e.corners.iter().enumerate() {
            let prism = db.prism(p);
            assert_eq!((prism.object, prism.triangle), (o as u32, t as u32));
            let got = db.triangle_at(p, e.start.t).map(|c| c.x);
            assert_eq!(
                got,
                corners.map(|c| e.start.x + c),
                "object {o}, triangle {t}"
            );
            // Negative control: the same position in the next object's
            // mesh is another triangle, so a run read through another
            // run's vertices would fail above.
            if let Some(next) = expected.get(o + 1).and_then(|n| n.corners.get(t)) {
                differ_from_the_next_objects += usize::from(next.map(|c| e.start.x + c) != got);
            }
            p += 1;
        }
    }
    assert_eq!(p as usize, db.prism_count());
    assert!(
        differ_from_the_next_objects > 500,
        "{differ_from_the_next_objects}"
    );
}
