//! Whole-image properties: static scenes look the same in every light-speed
//! model, images do not depend on the thread count or on the traversal, and
//! a moving point is seen at its retarded position.

use glam::DVec3;
use renderer::SplitMix64;
use renderer::{Attitude, LightSpeed, Ray};
use renderer::{
    Camera, Database, Event, Image, Mesh, Model, Motion, ObjectKind, RenderSettings, Traversal,
};
use vstf::fixture::Overrides;
use vstf::oracle::{retarded, PointWorldline};
use workspace_tests::{bits, object, scene, unit};

fn small(model: Option<Model>) -> Overrides {
    Overrides {
        model,
        width: Some(96),
        height: Some(72),
        ..Overrides::default()
    }
}

#[test]
fn a_static_scene_renders_the_same_in_all_three_models() {
    let f = workspace_tests::fixture("stage");
    let images: Vec<Image> = [Model::INFINITE, Model::CLASSICAL, Model::RELATIVISTIC]
        .iter()
        .map(|m| {
            let view = vstf::run::view(&f, &small(Some(*m))).unwrap();
            vstf::run::render(&f, &view, Traversal::Bvh).unwrap()
        })
        .collect();
    let rgb: Vec<_> = images.iter().map(vstf::rgb8).collect();
    assert_eq!(
        rgb[0], rgb[1],
        "infinite and classical differ on a static scene"
    );
    assert_eq!(
        rgb[1], rgb[2],
        "classical and relativistic differ on a static scene"
    );
    // And the scene is not blank.
    assert!(
        rgb[0]
            .pixels()
            .filter(|p| p.0 != rgb[0].get_pixel(0, 0).0)
            .count()
            > 1000
    );
}

#[test]
fn a_moving_scene_differs_between_models() {
    // The converse, so that the test above can fail: the flange at 0.00866c
    // is seen retarded, so its edge pixels differ between models.
    let f = workspace_tests::fixture("flange");
    let render = |m| {
        let view = vstf::run::view(&f, &small(Some(m))).unwrap();
        vstf::rgb8(&vstf::run::render(&f, &view, Traversal::Bvh).unwrap())
    };
    assert_ne!(render(Model::INFINITE), render(Model::CLASSICAL));
}

/// A frame rendered into an earlier frame's image (larger, every pixel
/// NaN) is the frame rendered alone, to the bit, in the same memory: flat,
/// in packets, and bent, pixel by pixel. The control: a spent image too
/// small for the frame is not reused, and the frame is the same again.
#[test]
fn a_frame_rendered_into_a_spent_image_is_the_frame_rendered_alone() {
    for name in ["flange", "black-hole"] {
        let f = workspace_tests::fixture(name);
        let view = vstf::run::view(&f, &small(None)).unwrap();
        let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        let alone = vstf::run::render_with(&db, &f, &view).unwrap();
        let spent = |w: u32, h: u32| Image {
            width: w,
            height: h,
            pixels: vec![DVec3::NAN; (w * h) as usize],
        };
        let (large, small) = (spent(100, 80), spent(10, 10));
        let (at_large, at_small) = (large.pixels.as_ptr(), small.pixels.as_ptr());
        let reused = vstf::run::render_reusing(&db, &f, &view, large).unwrap();
        assert_eq!(bits(&reused), bits(&alone), "{name}");
        assert_eq!((reused.width, reused.height), (alone.width, alone.height));
        assert_eq!(
            reused.pixels.as_ptr(),
            at_large,
            "{name}: not rendered in place"
        );
        let fresh = vstf::run::render_reusing(&db, &f, &view, small).unwrap();
        assert_eq!(bits(&fresh), bits(&alone), "{name}");
        assert_ne!(
            fresh.pixels.as_ptr(),
            at_small,
            "{name}: a too small image reused"
        );
    }
}

#[test]
fn images_do_not_depend_on_thread_count() {
    // Flat, bent by a mass (chord by chord, pixel by pixel), and bent
    // into the sky (each escaping ray followed out to its asymptote).
    for name in ["flange", "black-hole", "black-hole-stars"] {
        let f = workspace_tests::fixture(name);
        let mut view = vstf::run::view(&f, &small(None)).unwrap();
        view.settings.spp = 5;
        view.settings.shutter = 30.0;
        let db = vstf::run::database(&f, true, Traversal::Bvh).unwrap();
        let with = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| vstf::run::render_with(&db, &f, &view).unwrap())
        };
        assert_eq!(bits(&with(1)), bits(&with(2)), "{name}");
        assert_eq!(bits(&with(2)), bits(&with(3)), "{name}");
    }
}

#[test]
fn bvh_and_brute_force_give_identical_images() {
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        for m in [Model::INFINITE, Model::CLASSICAL, Model::RELATIVISTIC] {
            let view = vstf::run::view(
                &f,
                &Overrides {
                    model: Some(m),
                    width: Some(48),
                    height: Some(36),
                    ..Default::default()
                },
            )
            .unwrap();
            let a = vstf::run::render(&f, &view, Traversal::Bvh).unwrap();
            let b = vstf::run::render(&f, &view, Traversal::BruteForce).unwrap();
            assert_eq!(
                bits(&a),
                bits(&b),
                "{name} ({m}): BVH and brute force differ"
            );
        }
    }
}

/// The rest-frame offset `r` of a V_obj point, as seen in the lab at one
/// lab time: the component along the velocity shrinks by 1/gamma.
fn contracted(r: DVec3, v: DVec3) -> DVec3 {
    let n = v.normalize_or_zero();
    let gamma = 1.0 / (1.0 - v.length_squared()).sqrt();
    r - n * r.dot(n) * (1.0 - 1.0 / gamma)
}

#[test]
fn a_moving_point_is_seen_at_its_retarded_position() {
    let mut rng = SplitMix64::new(23);
    for _ in 0..200 {
        let v = unit(&mut rng) * rng.range(0.0, 0.95);
        let start = Event::new(
            -50.0,
            DVec3::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            ),
        );
        let quad = Mesh::quad(
            DVec3::new(-1.0, -1.0, 0.3),
            DVec3::new(2.0, 0.2, 0.0),
            DVec3::new(0.1, 2.0, 0.4),
        );
        let motion = Motion::Velocity {
            start,
            velocity: v,
            proper_lifetime: 100.0,
        };
        let db = Database::build(
            &scene(vec![object("q", ObjectKind::VObj, quad.clone(), motion)]),
            true,
        )
        .unwrap();
        // A point of the quad, by its rest-frame offset.
        let (a, b) = (rng.range(0.1, 0.9), rng.range(0.1, 0.9));
        let r = quad.vertices[0]
            + (quad.vertices[1] - quad.vertices[0]) * a
            + (quad.vertices[3] - quad.vertices[0]) * b;
        let point = PointWorldline {
            t0: start.t,
            x0: start.x + contracted(r, v),
            v,
        };
        let camera = DVec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), 12.0);
        let tc = 0.0;
        let seen = retarded(&point, tc, camera).unwrap();
        let ray = Ray::backwards(Event::new(tc, camera), seen.direction, LightSpeed::Finite);
        let hit = db
            .closest_hit(&ray, (0.0, f64::INFINITY))
            .expect("the ray towards the retarded position misses");
        assert!(
            abs_diff_eq!(hit.event.t, seen.t, epsilon = 1e-9 * seen.t.abs().max(1.0)),
            "t {} vs {}",
            hit.event.t,
            seen.t
        );
        assert!(
            (hit.event.x - seen.x).length() < 1e-9 * seen.x.length().max(1.0),
            "x {} vs {}",
            hit.event.x,
            seen.x
        );
    }
}

#[test]
fn a_small_moving_marker_is_drawn_where_its_retarded_position_projects() {
    let v = DVec3::new(0.8, 0.0, 0.3);
    let start = Event::new(-40.0, DVec3::new(-20.0, 0.5, -10.0));
    let marker = Mesh::cuboid(DVec3::splat(-0.04), DVec3::splat(0.04));
    let motion = Motion::Velocity {
        start,
        velocity: v,
        proper_lifetime: 60.0,
    };
    let s = scene(vec![object("marker", ObjectKind::VObj, marker, motion)]);
    let db = Database::build(&s, true).unwrap();
    let cam_x = DVec3::new(0.0, 2.0, 12.0);
    let tc = 5.0;
    let centre = retarded(
        &PointWorldline {
            t0: start.t,
            x0: start.x,
            v,
        },
        tc,
        cam_x,
    )
    .unwrap();
    let camera = Camera::new(
        Event::new(tc, cam_x),
        Attitude::LookAt {
            look_at: centre.x,
            up: DVec3::Y,
        },
        6.0,
        121,
        121,
    )
    .unwrap();
    let img = renderer::render(
        &db,
        &s,
        &camera,
        tc,
        Model::RELATIVISTIC,
        &RenderSettings::default(),
    );
    let (mut n, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for (i, p) in img.pixels.iter().enumerate() {
        if p.length() > 0.0 {
            n += 1.0;
            sx += (i % 121) as f64 + 0.5;
            sy += (i / 121) as f64 + 0.5;
        }
    }
    assert!(n >= 9.0, "the marker covers {n} pixels");
    let (px, py) = camera.pixel_of(centre.direction).unwrap();
    let (cx, cy) = (sx / n, sy / n);
    // The marker is ~8 px across; its silhouette's centroid sits within a pixel of its centre's image.
    assert!(
        abs_diff_eq!(cx, px, epsilon = 1.0) && abs_diff_eq!(cy, py, epsilon = 1.0),
        "centroid ({cx}, {cy}) vs retarded ({px}, {py})"
    );
}

#[test]
fn bvh_and_brute_force_agree_on_many_moving_boxes() {
    // Fast, long-lived objects: many time segments per object in the top level.
    for (scene, lorentz) in [
        (vstf::bench::boxes(120, 3), false),
        (vstf::bench::tessellated_boxes(20, 3, 4), false),
        (vstf::bench::boxes(40, 5), true),
    ] {
        let mut db = Database::build(&scene, lorentz).unwrap();
        let cam = Camera::new(
            Event::new(0.0, DVec3::new(0.0, 0.0, 160.0)),
            Attitude::LookAt {
                look_at: DVec3::ZERO,
                up: DVec3::Y,
            },
            45.0,
            80,
            60,
        )
        .unwrap();
        for model in [Model::INFINITE, Model::CLASSICAL, Model::RELATIVISTIC] {
            let model = Model { lorentz, ..model };
            db.set_traversal(Traversal::Bvh);
            let a = renderer::render(&db, &scene, &cam, 0.0, model, &RenderSettings::default());
            db.set_traversal(Traversal::BruteForce);
            let b = renderer::render(&db, &scene, &cam, 0.0, model, &RenderSettings::default());
            assert_eq!(bits(&a), bits(&b), "{model}: BVH and brute force differ");
            let lit = a.pixels.iter().filter(|p| p.length() > 0.0).count();
            assert!(
                lit > 5,
                "the boxes are out of view: {lit} lit pixels ({model})"
            );
        }
    }
}

/// `render` searches the primary rays of 2 x 2 pixels together (in packets
/// where the database says so); each pixel is the colour `pixel` gives it
/// alone, to the bit: on every fixture (odd
/// sizes, so that blocks are cut at the right and bottom edges), with
/// several jittered samples over a shutter, and with the colour effects
/// where the fixture has them.
#[test]
fn a_render_gives_each_pixel_the_colour_it_has_alone() {
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        let camera_t = on_its_worldline(&f);
        let mut view = vstf::run::view(
            &f,
            &Overrides {
                width: Some(23),
                height: Some(17),
                camera_t,
                ..Default::default()
            },
        )
        .unwrap();
        view.settings.spp = 3;
        view.settings.shutter = 2.0;
        let mut db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        // Packets whatever the scene's size (see `Packing::Auto`).
        db.set_packing(renderer::Packing::Packets);
        let image = vstf::run::render_with(&db, &f, &view).unwrap();
        let mut camera = view.camera;
        camera.kinematics = renderer::Kinematics::of(view.model);
        let frame = renderer::Frame {
            camera: &camera,
            camera_t: view.camera_t,
            model: view.model,
            settings: &view.settings,
        };
        let shader = renderer::shader(&db, &f.scene, &frame);
        let alone: Vec<[u64; 3]> = (0..17)
            .flat_map(|y| (0..23).map(move |x| (x, y)))
            .map(|(x, y)| {
                renderer::pixel(&shader, &frame, x, y)
                    .to_array()
                    .map(f64::to_bits)
            })
            .collect();
        assert_eq!(bits(&image), alone, "{name}: packed pixels differ");
        // Negative control: the pixels are not all one colour, so a block
        // given its first pixel's colour would be caught.
        let first = alone[0];
        assert!(alone.iter().any(|p| *p != first), "{name} is one colour");
    }
}

/// For an accelerating camera (rocket), a time a while after its
/// worldline's start, so that a shutter's proper time lies on it.
fn on_its_worldline(f: &vstf::fixture::Fixture) -> Option<f64> {
    f.spec
        .camera
        .worldline
        .as_ref()
        .map(|_| f.spec.camera.t + 10.0)
}

/// The pixels (x0..x0 + w, y0..y0 + h) of `img`, as bits.
fn crop(img: &Image, (x0, y0, w, h): (u32, u32, u32, u32)) -> Vec<[u64; 3]> {
    let all = bits(img);
    (y0..y0 + h)
        .flat_map(|y| (x0..x0 + w).map(move |x| (x, y)))
        .map(|(x, y)| all[(y * img.width + x) as usize])
        .collect()
}

#[test]
fn a_window_of_a_frame_is_that_part_of_the_whole_frame() {
    // Odd corners (packets straddle the whole image's 2 x 2 blocks), a
    // single pixel, and a window running past the image's edge (cut).
    let windows = [(3, 5, 11, 7), (10, 9, 1, 1), (18, 12, 9, 9)];
    let mut shifted_differs = false;
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        let overrides = Overrides {
            width: Some(23),
            height: Some(17),
            camera_t: on_its_worldline(&f),
            ..Default::default()
        };
        let mut view = vstf::run::view(&f, &overrides).unwrap();
        (view.settings.spp, view.settings.shutter) = (3, 2.0);
        let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        let whole = vstf::run::render_with(&db, &f, &view).unwrap();
        for (x, y, width, height) in windows {
            let window = renderer::Window {
                x,
                y,
                width,
                height,
            };
            let part = vstf::run::render_with(
                &db,
                &f,
                &vstf::fixture::View {
                    window: Some(window),
                    ..view
                },
            )
            .unwrap();
            let (w, h) = (width.min(23 - x), height.min(17 - y));
            assert_eq!((part.width, part.height), (w, h), "{name}");
            assert_eq!(
                bits(&part),
                crop(&whole, (x, y, w, h)),
                "{name}: {window:?}"
            );
            // Negative control: the same comparison one column over fails
            // somewhere, so a window rendered off by one would be caught.
            shifted_differs |= bits(&part) != crop(&whole, (x - 1, y, w, h));
        }
    }
    assert!(shifted_differs, "no window differs from its neighbour's");
}
