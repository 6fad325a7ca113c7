//! Every hit lies on the ray's light cone, inside its tetrahedron; and the
//! barycentric solve agrees with an independent closed form in the object's
//! comoving coordinates on 100,000 random rays.

use glam::DVec3;
use renderer::SplitMix64;
use renderer::{Database, Event, Motion, ObjectKind, PrimitiveId, Traversal};
use renderer::{LightSpeed, Ray};
use workspace_tests::{object, point, random_mesh, random_motion, scene, unit};

/// Closed-form hit of `ray` with a triangle (corners relative to the
/// reference point) of an object on `motion`: in comoving coordinates
/// y = x - v (t - t0) - x0 the object is static and the ray is a straight 3D
/// line, met by the Moller-Trumbore formula. Returns (s, margin) where the
/// line crosses the triangle's plane ahead of the ray's origin; the margin is
/// the smallest distance to the triangle's edges (in barycentric units) or to
/// the ends of the lifetime (as a fraction of it), negative outside.
fn plane_crossing(
    ray: &Ray,
    tri: [DVec3; 3],
    start: Event,
    extrusion: renderer::FourVector,
) -> Option<(f64, f64)> {
    let v = extrusion.velocity();
    let o = ray.origin.x - start.x - v * (ray.origin.t - start.t);
    let d = ray.direction.x - v * ray.direction.t;
    let (e1, e2) = (tri[1] - tri[0], tri[2] - tri[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return None;
    }
    let tv = o - tri[0];
    let u = tv.dot(p) / det;
    let q = tv.cross(e1);
    let w = d.dot(q) / det;
    let s = e2.dot(q) / det;
    let t = ray.origin.t + s * ray.direction.t;
    let life = ((t - start.t) / extrusion.t).min((start.t + extrusion.t - t) / extrusion.t);
    let margin = u.min(w).min(1.0 - u - w).min(life);
    (s >= 0.0).then_some((s, margin))
}

/// The closed-form hit: a plane crossing inside the triangle and lifetime.
fn comoving_hit(
    ray: &Ray,
    tri: [DVec3; 3],
    start: Event,
    extrusion: renderer::FourVector,
) -> Option<f64> {
    plane_crossing(ray, tri, start, extrusion)
        .filter(|(_, m)| *m >= 0.0)
        .map(|(s, _)| s)
}

fn random_ray(rng: &mut SplitMix64, light: LightSpeed) -> Ray {
    Ray::backwards(
        Event::new(rng.range(-30.0, 40.0), point(rng, 8.0)),
        unit(rng),
        light,
    )
}

/// A ray from a camera event on the future light cone of a random event of
/// the object, aimed at it: such rays hit often.
fn aimed_ray(
    rng: &mut SplitMix64,
    mesh: &renderer::Mesh,
    start: Event,
    ext: renderer::FourVector,
) -> Ray {
    let t = rng.next_u64() as usize % mesh.triangles.len();
    let [a, b, c] = mesh.corners(t);
    let (u, w) = (rng.next_f64(), rng.next_f64());
    let (u, w) = if u + w > 1.0 {
        (1.0 - u, 1.0 - w)
    } else {
        (u, w)
    };
    let lam = rng.next_f64();
    let e = start + ext * lam;
    let p = e.x + a + (b - a) * u + (c - a) * w;
    let cam = p + unit(rng) * rng.range(1.0, 15.0);
    let dist = (cam - p).length();
    Ray::backwards(
        Event::new(e.t + dist, cam),
        (p - cam) / dist,
        LightSpeed::Finite,
    )
}

/// A random H_obj of `triangles` triangles moving uniformly (at rest when
/// `at_rest`), its mesh, start event and extrusion, and its database.
fn random_object(
    rng: &mut SplitMix64,
    triangles: usize,
    at_rest: bool,
) -> (renderer::Mesh, Event, renderer::FourVector, Database) {
    let mesh = random_mesh(rng, triangles, 2.0);
    let motion = random_motion(rng, at_rest);
    let (start, ext) = match motion {
        Motion::Extrusion { start, extrusion } => (start, extrusion),
        _ => unreachable!(),
    };
    let db = Database::build(
        &scene(vec![object("o", ObjectKind::HObj, mesh.clone(), motion)]),
        false,
    )
    .unwrap();
    (mesh, start, ext, db)
}

#[test]
fn normalized_light_cone_direction_has_t_minus_sqrt2_over_2() {
    let mut rng = SplitMix64::new(3);
    for _ in 0..100 {
        let r = random_ray(&mut rng, LightSpeed::Finite);
        let n = r.normalized_direction();
        assert_abs_diff_eq!(n.t, -std::f64::consts::FRAC_1_SQRT_2, epsilon = 1e-15);
        assert_abs_diff_eq!(n.interval(), 0.0, epsilon = 1e-15);
    }
}

#[test]
fn hits_lie_on_the_light_cone_inside_their_prism() {
    let mut rng = SplitMix64::new(5);
    let mut hits = 0;
    for k in 0..200 {
        let (mesh, start, ext, db) = random_object(&mut rng, 6, k % 5 == 0);
        for _ in 0..200 {
            let ray = aimed_ray(&mut rng, &mesh, start, ext);
            let Some(hit) = db.closest_hit(&ray, (0.0, f64::INFINITY)) else {
                continue;
            };
            hits += 1;
            let bary = hit.bary.coordinates();
            assert!(bary.iter().all(|b| (0.0..=1.0).contains(b)), "{bary:?}");
            assert_abs_diff_eq!(bary.iter().sum::<f64>(), 1.0, epsilon = 1e-9);
            // Rebuild the event from the barycentric coordinates alone: over
            // the triangle where it is at the hit's time, within the
            // prism's lab times.
            let PrimitiveId::Prism(p) = hit.primitive else {
                panic!(
                    "uniform motion is tested prism by prism: {:?}",
                    hit.primitive
                )
            };
            let span = db.prism(p).span;
            assert!(
                span.0 <= hit.event.t && hit.event.t <= span.1,
                "outside its prism's times"
            );
            let v = db.triangle_at(p, hit.event.t);
            let from_bary = (0..3).fold(glam::DVec4::ZERO, |acc, i| acc + v[i].to_xyzt() * bary[i]);
            let scale = 1.0
                + v.iter()
                    .map(|e| e.to_xyzt().abs().max_element())
                    .fold(0.0, f64::max);
            assert!(
                abs_diff_eq!(from_bary, hit.event.to_xyzt(), epsilon = 1e-9 * scale),
                "event off its triangle"
            );
            let d = Event::from_xyzt(from_bary) - ray.origin;
            assert!(
                abs_diff_eq!(d.interval(), 0.0, epsilon = 1e-9 * (d.t * d.t).max(1.0)),
                "not null: {}",
                d.interval()
            );
            assert!(d.t <= 1e-12, "the hit is in the camera's future");
        }
    }
    assert!(
        hits > 20_000,
        "only {hits} hits: the test rays miss too often to test anything"
    );
}

#[test]
fn tetrahedron_solve_agrees_with_comoving_closed_form() {
    let mut rng = SplitMix64::new(17);
    let (mut rays, mut hits, mut boundary) = (0, 0, 0);
    for k in 0..250 {
        let (mesh, start, ext, mut db) = random_object(&mut rng, 4, k % 4 == 0);
        db.set_traversal(Traversal::BruteForce);
        for i in 0..400 {
            let ray = if i % 2 == 0 {
                aimed_ray(&mut rng, &mesh, start, ext)
            } else {
                random_ray(&mut rng, LightSpeed::Finite)
            };
            rays += 1;
            let closed = (0..mesh.triangles.len())
                .filter_map(|t| comoving_hit(&ray, mesh.corners(t), start, ext))
                .min_by(f64::total_cmp);
            let solved = db.closest_hit(&ray, (0.0, f64::INFINITY));
            match (closed, solved) {
                (Some(s), Some(h)) => {
                    hits += 1;
                    let e = ray.at(s);
                    let scale = 1.0 + e.t.abs() + e.x.abs().max_element();
                    assert!(
                        abs_diff_eq!(e.to_xyzt(), h.event.to_xyzt(), epsilon = 1e-9 * scale),
                        "events differ: {e:?} vs {:?}",
                        h.event
                    );
                }
                (None, None) => {}
                (c, s) => {
                    // Only a ray grazing an edge or the end of the lifetime may disagree.
                    let near_edge = (0..mesh.triangles.len())
                        .filter_map(|t| plane_crossing(&ray, mesh.corners(t), start, ext))
                        .any(|(_, m)| m.abs() < 1e-9);
                    assert!(
                        near_edge,
                        "hit/miss disagree away from any edge: closed {c:?}, solved {s:?}"
                    );
                    boundary += 1;
                }
            }
        }
    }
    assert!(rays >= 100_000);
    assert!(hits > 25_000, "only {hits} hits");
    assert!(boundary < rays / 1000, "{boundary} boundary disagreements");
}

/// A ray runs forward from its origin, whatever range it is given: moved
/// past the event it met, to where that event lies behind it (s = -1), a
/// range starting far below zero finds neither it nor anything else behind,
/// and finds what the range from zero finds, through the hierarchy and by
/// brute force alike.
#[test]
fn a_range_starting_below_zero_is_searched_from_zero() {
    let mut rng = SplitMix64::new(29);
    let (mut behind, mut ahead) = (0, 0);
    for k in 0..100 {
        let (mesh, start, ext, mut db) = random_object(&mut rng, 6, k % 5 == 0);
        for _ in 0..50 {
            let ray = aimed_ray(&mut rng, &mesh, start, ext);
            let Some(hit) = db.closest_hit(&ray, (0.0, f64::INFINITY)) else {
                continue;
            };
            behind += 1;
            let moved = Ray {
                origin: ray.at(hit.s + 1.0),
                ..ray
            };
            for traversal in [Traversal::Bvh, Traversal::BruteForce] {
                db.set_traversal(traversal);
                let from_below = db.closest_hit(&moved, (-1e9, f64::INFINITY));
                let from_zero = db.closest_hit(&moved, (0.0, f64::INFINITY));
                assert_eq!(from_below, from_zero, "{traversal:?}");
                if let Some(h) = from_below {
                    assert!(h.s >= 0.0, "{traversal:?}: a hit behind, at s = {}", h.s);
                    ahead += 1;
                }
            }
            db.set_traversal(Traversal::Bvh);
        }
    }
    assert!(behind > 1000, "{behind} rays moved past their hit");
    assert!(ahead < behind, "{ahead} of {behind} met something ahead");
}
