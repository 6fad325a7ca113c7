//! Rays searched a packet at a time (`Database::closest_hits`) find the
//! hits they find one at a time (`Database::closest_hit`), to the bit: on
//! the primary rays of every fixture in all three models, on many moving
//! boxes, and on packets whose rays share nothing.

use renderer::{
    Database, Event, Hit, LightSpeed, Model, Motion, Packing, Ray, Shape, SplitMix64, Traversal,
};
use vstf::fixture::Overrides;
use workspace_tests::{point, unit};

/// Each ray's hit alone and in packets (in order, `rays.len()` need not
/// be a whole number of packets); the number of rays that hit.
fn assert_packets_find_single_hits(db: &mut Database, rays: &[Ray], what: &str) -> usize {
    let mut packed: Vec<Option<Hit>> = vec![None; rays.len()];
    // Whatever the database's size (`Packing::Auto` would search these
    // small scenes one ray at a time).
    db.set_packing(Packing::Packets);
    db.closest_hits(rays, (0.0, f64::INFINITY), &mut packed);
    for (k, (ray, hit)) in rays.iter().zip(&packed).enumerate() {
        let alone = db.closest_hit(ray, (0.0, f64::INFINITY));
        // Debug prints each f64 exactly (shortest round trip, signed zeros).
        assert_eq!(
            format!("{hit:?}"),
            format!("{alone:?}"),
            "{what}: ray {k} finds another hit in a packet"
        );
    }
    packed.iter().filter(|h| h.is_some()).count()
}

/// The primary rays of `view`, one at each pixel's centre, 2 x 2 pixels
/// after each other (as a renderer would pack them).
fn primary_rays(view: &vstf::fixture::View) -> Vec<Ray> {
    let (w, h) = (view.camera.width, view.camera.height);
    let mut rays = Vec::new();
    for y0 in (0..h).step_by(2) {
        for x0 in (0..w).step_by(2) {
            for y in y0..(y0 + 2).min(h) {
                for x in x0..(x0 + 2).min(w) {
                    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    rays.push(
                        view.camera
                            .ray(px, py, view.camera_t, view.model.light_speed),
                    );
                }
            }
        }
    }
    rays
}

#[test]
fn packets_of_primary_rays_find_the_hits_single_rays_find_on_every_fixture() {
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        for m in [Model::INFINITE, Model::CLASSICAL, Model::RELATIVISTIC] {
            let small = Overrides {
                model: Some(m),
                width: Some(47),
                height: Some(35),
                ..Default::default()
            };
            let view = vstf::run::view(&f, &small).unwrap();
            let mut db = vstf::run::database(&f, m.lorentz, Traversal::Bvh).unwrap();
            let rays = primary_rays(&view);
            assert_packets_find_single_hits(&mut db, &rays, &format!("{name} ({m})"));
        }
    }
}

/// 300 boxes moving at up to 0.6 over lab times -300..100, their time
/// slices in the top level; `coherent` packs neighbouring rays of one
/// camera event, otherwise every ray has its own event and direction.
fn boxes_and_rays(coherent: bool) -> (Database, Vec<Ray>) {
    let scene = vstf::bench::boxes(300, 7);
    let db = Database::build(&scene, false).unwrap();
    let mut rng = SplitMix64::new(11);
    // A ray from a random event aimed near where box k was when its light
    // left it, roughly.
    let aimed = |k: usize, rng: &mut SplitMix64| {
        let at = Event::new(rng.range(-100.0, 50.0), point(rng, 80.0));
        let Motion::Extrusion { start, extrusion } = scene.objects[k % 300].motion else {
            unreachable!("the boxes move uniformly")
        };
        let place = |t: f64| start.x + extrusion.x * ((t - start.t) / extrusion.t);
        let seen = (0..3).fold(at.t, |t, _| at.t - (place(t) - at.x).length());
        (at, place(seen) + point(rng, 1.0) - at.x)
    };
    let mut rays = Vec::new();
    for k in 0..5000 {
        let (at, aim) = aimed(k, &mut rng);
        for j in 0..4 {
            let (origin, d) = if coherent {
                (at, aim.normalize() + unit(&mut rng) * 0.01)
            } else {
                aimed(7 * k + j, &mut rng)
            };
            rays.push(Ray::backwards(origin, d.normalize(), LightSpeed::Finite));
        }
    }
    (db, rays)
}

#[test]
fn packets_find_the_hits_single_rays_find_among_many_moving_boxes() {
    for coherent in [true, false] {
        let (mut db, rays) = boxes_and_rays(coherent);
        let hits = assert_packets_find_single_hits(&mut db, &rays, "moving boxes");
        // Enough rays hit for the comparison to mean something.
        assert!(hits > rays.len() / 4, "{hits} of {} rays hit", rays.len());
        // Every count of rays, not only whole packets.
        for n in 1..=9 {
            assert_packets_find_single_hits(&mut db, &rays[..n], "a short run of rays");
        }
    }
}

/// The comparison above can fail: neighbouring rays of a packet find
/// different hits, so a packet giving every ray its first ray's hit (or
/// its rays' hits in another order) would be caught.
#[test]
fn the_rays_of_a_packet_find_different_hits() {
    let (mut db, rays) = boxes_and_rays(true);
    db.set_packing(Packing::Packets);
    let mut packed: Vec<Option<Hit>> = vec![None; rays.len()];
    db.closest_hits(&rays, (0.0, f64::INFINITY), &mut packed);
    let differing = packed
        .chunks(4)
        .filter(|p| p.iter().any(|h| format!("{h:?}") != format!("{:?}", p[0])))
        .count();
    assert!(differing > 100, "{differing} packets of differing hits");
    let mut shifted = packed.clone();
    shifted.rotate_left(1);
    let moved = packed
        .iter()
        .zip(&shifted)
        .filter(|(a, b)| format!("{a:?}") != format!("{b:?}"))
        .count();
    assert!(
        moved > 1000,
        "only {moved} hits change when shifted by one ray"
    );
}

#[test]
fn brute_force_packets_are_single_rays() {
    let (mut db, rays) = boxes_and_rays(false);
    db.set_traversal(Traversal::BruteForce);
    assert_packets_find_single_hits(&mut db, &rays[..400], "brute force");
}

/// One moving object is one stretch, searched without the top level's
/// time slices (its own hierarchy culls every ray they would): its hits,
/// one ray at a time and in packets, are brute force's, on rays aimed at
/// it across its sweep and on rays from anywhere.
#[test]
fn one_moving_object_in_many_time_slices_finds_brute_forces_hits() {
    let scene = vstf::bench::tessellated_boxes(1, 6, 12);
    let db = Database::build(&scene, false).unwrap();
    assert!(
        db.time_slice_count() >= 16,
        "{} slices: the box hardly moves",
        db.time_slice_count()
    );
    let rays = rays_at_the_box(&scene, 4000);
    assert_brute_forces_hits(&scene, db, &rays, "one moving box");
}

/// A uniformly moving mesh of 2^18 prisms or more has leaves of up to
/// eight prisms (two passes of the f32 filter): its hits, one ray at a
/// time and in packets, are brute force's.
#[test]
fn a_large_moving_mesh_with_leaves_of_eight_finds_brute_forces_hits() {
    let scene = vstf::bench::tessellated_boxes(1, 150, 12);
    let Shape::Mesh(mesh) = &scene.objects[0].shape else {
        unreachable!("a tessellated box is a mesh")
    };
    assert!(mesh.triangles.len() >= 1 << 18, "{}", mesh.triangles.len());
    let db = Database::build(&scene, false).unwrap();
    let rays = rays_at_the_box(&scene, 240);
    assert_brute_forces_hits(&scene, db, &rays, "a large moving box");
}

/// `n` rays from around the one moving box of `scene`, three in four
/// aimed at where it was when their light left it (roughly), the others
/// anywhere.
fn rays_at_the_box(scene: &renderer::Scene, n: usize) -> Vec<Ray> {
    let Motion::Extrusion { start, extrusion } = scene.objects[0].motion else {
        unreachable!("the box moves uniformly")
    };
    let place = |t: f64| start.x + extrusion.x * ((t - start.t) / extrusion.t);
    let mut rng = SplitMix64::new(13);
    let mut rays = Vec::new();
    for k in 0..n {
        let at = Event::new(rng.range(-300.0, 100.0), point(&mut rng, 80.0));
        let seen = (0..8).fold(at.t, |t, _| at.t - (place(t) - at.x).length());
        let aim = match k % 4 {
            3 => unit(&mut rng),
            _ => place(seen) + point(&mut rng, 0.5) - at.x,
        };
        rays.push(Ray::backwards(at, aim.normalize(), LightSpeed::Finite));
    }
    rays
}

/// Each of `rays` finds in `db` the hit brute force finds in `scene`, one
/// ray at a time and in packets; enough of the scene is hit for the
/// comparison to mean something.
fn assert_brute_forces_hits(scene: &renderer::Scene, mut db: Database, rays: &[Ray], what: &str) {
    let mut brute = Database::build(scene, false).unwrap();
    brute.set_traversal(Traversal::BruteForce);
    let mut hits = std::collections::BTreeSet::new();
    for (k, ray) in rays.iter().enumerate() {
        let exact = brute.closest_hit(ray, (0.0, f64::INFINITY));
        let found = db.closest_hit(ray, (0.0, f64::INFINITY));
        assert_eq!(
            format!("{found:?}"),
            format!("{exact:?}"),
            "{what}: ray {k}"
        );
        hits.extend(exact.map(|h| h.primitive));
    }
    assert!(hits.len() > 100, "{what}: {} prisms hit", hits.len());
    assert_packets_find_single_hits(&mut db, rays, what);
}

/// `Packing::Auto` packs rays over a large mesh in few time slices, and not
/// over many small moving objects; a lone moving mesh, whose slices no
/// search passes through, is packed as a mesh at rest is; `Single` and
/// `Packets` are obeyed.
#[test]
fn packets_are_chosen_where_a_search_meets_many_prisms_a_slice() {
    let (mut boxes, _) = boxes_and_rays(false);
    assert!(!boxes.packs(), "300 moving boxes in packets");
    boxes.set_packing(Packing::Packets);
    assert!(boxes.packs());
    let sheets = |n: usize, speed: f64, count: usize| {
        let mut rng = SplitMix64::new(3);
        let moving = Motion::Extrusion {
            start: Event::new(-100.0, glam::DVec3::ZERO),
            extrusion: renderer::FourVector::new(200.0, glam::DVec3::X * 200.0 * speed),
        };
        let objects = (0..count)
            .map(|_| {
                let mesh = workspace_tests::random_mesh(&mut rng, n, 2.0);
                workspace_tests::object("mesh", renderer::ObjectKind::HObj, mesh, moving.clone())
            })
            .collect();
        Database::build(&workspace_tests::scene(objects), false).unwrap()
    };
    let sheet = |n: usize| sheets(n, 0.0, 1);
    // At 0.9c over 200 time units, each mesh is cut into many time slices
    // (under the rule for many stretches, too few prisms a slice to pack).
    let fast = sheets(Database::PACKED_FROM, 0.9, 1);
    assert!(fast.time_slice_count() > 1, "{}", fast.time_slice_count());
    assert!(fast.packs(), "a lone moving mesh");
    assert!(!sheets(Database::PACKED_FROM - 1, 0.9, 1).packs());
    let two = sheets(Database::PACKED_FROM, 0.9, 2);
    assert!(!two.packs(), "two moving meshes, their slices searched");
    let mut large = sheet(Database::PACKED_FROM);
    assert!(
        large.packs(),
        "a mesh of {} triangles alone",
        Database::PACKED_FROM
    );
    large.set_packing(Packing::Single);
    assert!(!large.packs());
    assert!(!sheet(Database::PACKED_FROM - 1).packs());
}

/// A ray whose direction or origin is not a number, or whose range ends
/// at NaN, meets nothing, alone or in a packet, and its packet's other
/// rays still find their own hits. (Such a ray once sent the hierarchy's
/// search into every box, growing without bound: the process was killed.)
#[test]
fn a_ray_that_is_not_a_number_meets_nothing_and_spoils_no_packet() {
    let (mut db, rays) = boxes_and_rays(true);
    let nan = f64::NAN;
    let broken = [
        Ray::backwards(rays[0].origin, glam::DVec3::splat(nan), LightSpeed::Finite),
        Ray::backwards(
            Event::new(nan, rays[0].origin.x),
            rays[0].direction.x,
            LightSpeed::Finite,
        ),
    ];
    for ray in &broken {
        assert!(db.closest_hit(ray, (0.0, 1e3)).is_none());
    }
    assert!(db.closest_hit(&rays[0], (0.0, nan)).is_none());
    // The control: the same packets without the broken rays hit.
    let whole = assert_packets_find_single_hits(&mut db, &rays[..400], "whole rays");
    assert!(whole > 100, "{whole} of 400 rays hit");
    let mut mixed = rays[..400].to_vec();
    for k in (0..400).step_by(7) {
        mixed[k] = broken[k % 2];
    }
    let hits = assert_packets_find_single_hits(&mut db, &mixed, "a packet with a broken ray");
    let lost = (0..400)
        .step_by(7)
        .filter(|&k| db.closest_hit(&rays[k], (0.0, f64::INFINITY)).is_some())
        .count();
    assert_eq!(hits, whole - lost);
}
