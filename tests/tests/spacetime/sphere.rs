//! Analytic spheres: hits lie on the light cone and on the sphere's
//! (contracted) worldtube, agree with the tessellated sphere, and the BVH
//! path finds the same hits as brute force.

use glam::DVec3;
use renderer::SplitMix64;
use renderer::{Database, Event, Mesh, Motion, ObjectKind, SceneObject, Shape, Traversal};
use renderer::{LightSpeed, Ray};
use workspace_tests::{object, scene, unit};

fn sphere_object(kind: ObjectKind, v: DVec3, analytic: bool) -> SceneObject {
    let motion = Motion::Velocity {
        start: Event::new(-50.0, DVec3::new(0.0, 0.0, -8.0) - v * 50.0),
        velocity: v,
        proper_lifetime: 80.0,
    };
    let mut o = object(
        "ball",
        kind,
        if analytic {
            Mesh::default()
        } else {
            Mesh::uv_sphere(1.5, 96)
        },
        motion,
    );
    if analytic {
        o.shape = Shape::Sphere { radius: 1.5 };
    }
    o
}

/// The offset of `e` from the sphere's centre at the same lab time, with
/// its component along v stretched by gamma (the contraction undone):
/// on the surface exactly when its length is the rest radius.
fn rest_offset(e: Event, v: DVec3, contracted: bool) -> DVec3 {
    let centre = DVec3::new(0.0, 0.0, -8.0) + v * e.t;
    let d = e.x - centre;
    if !contracted || v == DVec3::ZERO {
        return d;
    }
    let n = v.normalize();
    let g = 1.0 / (1.0 - v.length_squared()).sqrt();
    d + n * (d.dot(n) * (g - 1.0))
}

/// Where the centre of the sphere (moving with v through (0, 0, -8) at t = 0)
/// is seen from `cam`: its retarded position.
fn seen_centre(v: DVec3, cam: Event) -> DVec3 {
    let p = vstf::oracle::PointWorldline {
        t0: 0.0,
        x0: DVec3::new(0.0, 0.0, -8.0),
        v,
    };
    vstf::oracle::retarded(&p, cam.t, cam.x).unwrap().x
}

#[test]
fn analytic_hits_lie_on_the_light_cone_and_the_contracted_sphere() {
    let mut rng = SplitMix64::new(41);
    for (kind, lorentz) in [(ObjectKind::VObj, true), (ObjectKind::HObj, false)] {
        let v = DVec3::new(0.8, 0.1, 0.0);
        let db = Database::build(&scene(vec![sphere_object(kind, v, true)]), lorentz).unwrap();
        let mut hits = 0;
        for _ in 0..2000 {
            let cam = Event::new(
                rng.range(-5.0, 5.0),
                DVec3::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), 6.0),
            );
            // Aim near where the sphere's centre is seen (its retarded position).
            let target = seen_centre(v, cam) + unit(&mut rng) * 1.2;
            let ray = Ray::backwards(cam, (target - cam.x).normalize(), LightSpeed::Finite);
            let Some(h) = db.closest_hit(&ray, (0.0, f64::INFINITY)) else {
                continue;
            };
            hits += 1;
            let d = h.event - cam;
            assert!(
                abs_diff_eq!(d.interval(), 0.0, epsilon = 1e-9 * d.t * d.t),
                "off the light cone"
            );
            let r = rest_offset(h.event, v, lorentz).length();
            assert!(
                abs_diff_eq!(r, 1.5, epsilon = 1e-9),
                "hit at rest radius {r}"
            );
            let n = db.surface(&h).normal;
            assert!(
                n.dot(h.event.x - (DVec3::new(0.0, 0.0, -8.0) + v * h.event.t)) > 0.0,
                "normal points inwards"
            );
        }
        assert!(hits > 800, "only {hits} hits");
    }
}

#[test]
fn analytic_and_tessellated_spheres_agree() {
    let v = DVec3::new(0.6, 0.0, 0.0);
    let exact =
        Database::build(&scene(vec![sphere_object(ObjectKind::VObj, v, true)]), true).unwrap();
    let mesh = Database::build(
        &scene(vec![sphere_object(ObjectKind::VObj, v, false)]),
        true,
    )
    .unwrap();
    let mut rng = SplitMix64::new(43);
    let mut compared = 0;
    for _ in 0..500 {
        let cam = Event::new(0.0, DVec3::new(0.0, 0.0, 6.0));
        let target = seen_centre(v, cam) + unit(&mut rng) * 0.5;
        let ray = Ray::backwards(cam, (target - cam.x).normalize(), LightSpeed::Finite);
        if let (Some(a), Some(b)) = (
            exact.closest_hit(&ray, (0.0, f64::INFINITY)),
            mesh.closest_hit(&ray, (0.0, f64::INFINITY)),
        ) {
            compared += 1;
            // 96 segments: the facets lie within 1.5 (1 - cos(pi / 48)) of the sphere.
            assert!(
                abs_diff_eq!(a.s, b.s, epsilon = 0.01),
                "analytic {} vs tessellated {}",
                a.s,
                b.s
            );
        }
    }
    assert!(compared > 100);
}

#[test]
fn bvh_and_brute_force_agree_with_spheres_present() {
    let v = DVec3::new(0.7, 0.0, 0.2);
    let mut objects = vec![
        sphere_object(ObjectKind::VObj, v, true),
        sphere_object(ObjectKind::VObj, -v, false),
    ];
    objects.push(object(
        "floor",
        ObjectKind::HObj,
        Mesh::cuboid(DVec3::new(-20.0, -3.0, -30.0), DVec3::new(20.0, -2.5, 5.0)),
        Motion::at_rest(DVec3::ZERO, -1e3, 1e3),
    ));
    let mut db = Database::build(&scene(objects), true).unwrap();
    let mut rng = SplitMix64::new(47);
    for _ in 0..3000 {
        let ray = Ray::backwards(
            Event::new(rng.range(-10.0, 10.0), DVec3::new(0.0, 1.0, 8.0)),
            (unit(&mut rng) - DVec3::Z * 1.5).normalize(),
            LightSpeed::Finite,
        );
        db.set_traversal(Traversal::Bvh);
        let a = db.closest_hit(&ray, (0.0, f64::INFINITY));
        db.set_traversal(Traversal::BruteForce);
        let b = db.closest_hit(&ray, (0.0, f64::INFINITY));
        assert_eq!(a, b);
    }
}

#[test]
fn a_bad_sphere_radius_is_refused() {
    let mut o = sphere_object(ObjectKind::VObj, DVec3::X * 0.5, true);
    o.shape = Shape::Sphere { radius: -1.0 };
    let e = Database::build(&scene(vec![o]), true)
        .err()
        .expect("a negative radius was accepted");
    assert!(e.to_string().contains("sphere radius -1"), "{e}");
}
