//! The database's shared test scenes, and a translated prism's surface,
//! read where its exact test found its triangle, against the one its
//! index gives.

use super::*;
use crate::rng::SplitMix64;
use crate::scene::{Light, Material, Mesh, Motion, ObjectKind, Scene, SceneObject, Shape};
use crate::spacetime::{LightSpeed, Ray, Spacetime};

/// A scene of the given objects under a light far above.
pub(super) fn scene(objects: Vec<SceneObject>) -> Scene {
    Scene {
        objects,
        light: Light {
            position: DVec3::new(0.0, 100.0, 0.0),
            color: DVec3::ONE,
            ambient: 0.3,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    }
}

/// An object named `name` of the given kind, mesh and motion, matte
/// orange (0.8, 0.5, 0.2), neither an analytic sphere nor blinking.
pub(super) fn object(name: &str, kind: ObjectKind, mesh: Mesh, motion: Motion) -> SceneObject {
    SceneObject {
        name: name.into(),
        kind,
        shape: Shape::Mesh(mesh),
        motion,
        material: Material::matte(DVec3::new(0.8, 0.5, 0.2)),
        face_materials: Vec::new(),
    }
}

/// `n` random triangles moving at 0.6c along a diagonal from lab time -50
/// (V_obj: contracted in the lab), about the origin at lab time -30: a
/// hierarchy that stores them in another order than the mesh's.
fn moving_triangles(n: usize) -> Database {
    let mut rng = SplitMix64::new(7);
    let mut point = || DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 8.0 - 4.0;
    let mut mesh = Mesh::default();
    while mesh.triangles.len() < n {
        let (a, b, c) = (point(), point(), point());
        if (b - a).cross(c - a).length() > 1.0 {
            let k = mesh.vertices.len() as u32;
            mesh.vertices.extend([a, b, c]);
            mesh.triangles.push([k, k + 1, k + 2]);
        }
    }
    let motion = Motion::Velocity {
        start: Event::new(-50.0, DVec3::new(-8.5, -8.5, 0.0)),
        velocity: DVec3::new(0.6, 0.6, 0.0) / 2f64.sqrt(),
        proper_lifetime: 200.0,
    };
    let scene = scene(vec![object("triangles", ObjectKind::VObj, mesh, motion)]);
    Database::build(&scene, true).expect("a valid scene")
}

/// The surface of a prism hit found by its index: [`Database::prism`]'s.
fn by_index(db: &Database, hit: &Hit) -> Surface {
    let prism = db.prism(hit.primitive.prism().expect("a prism's hit"));
    Surface {
        object: prism.object,
        normal: prism.normal_at(hit.event.t),
        triangle: prism.triangle,
    }
}

/// Rays from a camera at (0, 0, 30) at lab time 0, on its past light
/// cone, towards the moving triangles; their hits.
fn hits(db: &Database) -> Vec<Hit> {
    let mut rng = SplitMix64::new(11);
    (0..400)
        .filter_map(|_| {
            let aim = DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, -2.0);
            let ray = Ray::backwards(
                Event::new(0.0, DVec3::new(0.0, 0.0, 30.0)),
                aim.normalize(),
                LightSpeed::Finite,
            );
            db.closest_hit(&ray, (0.0, f64::INFINITY))
        })
        .collect()
}

#[test]
fn a_translated_prisms_surface_is_the_one_its_index_gives() {
    let db = moving_triangles(300);
    let hits = hits(&db);
    assert!(hits.len() > 100, "{} rays hit", hits.len());
    for hit in &hits {
        assert_ne!(hit.stored, Hit::NOT_STORED, "{hit:?}");
        assert_eq!(db.surface(hit), by_index(&db, hit), "{hit:?}");
    }
}

/// The control: the surface is read where the hit says its triangle is
/// kept, so a hit naming another triangle's place gets another normal.
#[test]
fn a_hit_naming_another_triangles_place_gets_another_normal() {
    let db = moving_triangles(300);
    let hits = hits(&db);
    assert!(hits.len() > 100, "{} rays hit", hits.len());
    let moved = hits
        .iter()
        .filter(|h| {
            let elsewhere = Hit {
                stored: (h.stored + 1) % db.comoving.len() as u32,
                ..**h
            };
            db.surface(&elsewhere).normal != by_index(&db, h).normal
        })
        .count();
    assert_eq!(moved, hits.len());
}
