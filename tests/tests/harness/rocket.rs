//! The accelerated observer (docs/physics.md, "The accelerated observer"),
//! on the `rocket` fixture: a camera from rest under proper acceleration
//! 0.1 along -z, looking back. A frame is the frame of the inertial camera
//! at the same event with the same velocity, bit for bit; static markers
//! are seen where relativistic aberration at the camera's rapidity puts
//! them; a marker beyond the Rindler horizon is never seen, and markers
//! inside it are first (last) seen at the closed-form time. (Its
//! fixture's errors in `rocket_errors`.)

use glam::DVec3;
use renderer::{Image, Motion, Shape, Traversal};
use vstf::fixture::Overrides;
use vstf::measure::{edge, Pinhole, Scan, SkyCircle};
use vstf::oracle::rocket::{aberrated_angle_galilean, first_seen, seen_circle, RocketWorldline};
use vstf::Fixture;

/// The oracle's worldline of the fixture's camera, read from its plain data.
fn worldline(f: &Fixture) -> RocketWorldline {
    let c = &f.spec.camera;
    let h = c
        .worldline
        .as_ref()
        .and_then(|w| w.hyperbolic)
        .expect("the rocket camera has a hyperbolic worldline");
    RocketWorldline {
        t0: c.t,
        x0: c.position,
        direction: h.acceleration.normalize(),
        acceleration: h.acceleration.length(),
        initial_velocity: h.initial_velocity,
    }
}

/// The fixture rendered at the camera's lab time `t`, `size` and `spp`.
fn render_at(f: &Fixture, t: f64, size: (u32, u32), spp: u32) -> Image {
    let view = vstf::run::view(
        f,
        &Overrides {
            camera_t: Some(t),
            width: Some(size.0),
            height: Some(size.1),
            spp: Some(spp),
            ..Overrides::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    vstf::run::render(f, &view, Traversal::Bvh).unwrap_or_else(|e| panic!("{e}"))
}

/// The same fixture with an inertial camera at `event` moving at `v`.
fn inertial(f: &Fixture, (t, x): (f64, DVec3), v: DVec3) -> Fixture {
    let mut g = f.clone();
    g.spec.camera.worldline = None;
    (g.spec.camera.t, g.spec.camera.position) = (t, x);
    g.spec.camera.velocity = Some(v);
    g
}

#[test]
fn a_frame_is_the_inertial_cameras_at_the_same_event_and_velocity_bit_for_bit() {
    let f = workspace_tests::fixture("rocket");
    for tau in [0.0, 4.0, 9.5] {
        let t = worldline(&f).lab_time(tau);
        let view = vstf::run::view(
            &f,
            &Overrides {
                camera_t: Some(t),
                ..Overrides::default()
            },
        )
        .unwrap();
        let (event, v) = (view.camera.event, view.camera.velocity);
        let accelerating = render_at(&f, t, (96, 72), 4);
        let same = render_at(&inertial(&f, (event.t, event.x), v), t, (96, 72), 4);
        assert!(accelerating.pixels == same.pixels, "tau = {tau}");
        // Negative control: the velocity of a later proper time turns the view.
        if tau > 0.0 {
            let later = worldline(&f).velocity(tau + 0.5);
            let other = render_at(&inertial(&f, (event.t, event.x), later), t, (96, 72), 4);
            assert!(accelerating.pixels != other.pixels, "tau = {tau}");
        }
    }
}

/// A static marker's centre and radius.
fn marker(f: &Fixture, name: &str) -> (DVec3, f64) {
    let o = f.object(name).unwrap();
    let Shape::Sphere { radius } = o.shape else {
        panic!("{name} is an analytic sphere")
    };
    let (start, _) = o.motion.uniform().unwrap();
    (start.x, radius)
}

/// The marker's outline seen at the camera's lab time `t`, as directions
/// in the camera's own frame (the measurement's pinhole at rest with the
/// camera's attitude: a boost along the acceleration keeps the axes), and
/// the angle of a pixel at the centre.
fn outline(f: &Fixture, name: &str, t: f64) -> (Vec<DVec3>, f64) {
    const SIZE: (u32, u32) = (480, 360);
    let mut only = f.only(&[name]).unwrap();
    only.scene.background = DVec3::ZERO;
    let img = vstf::rgb8(&render_at(&only, t, SIZE, 16));
    let c = &f.spec.camera;
    let yaw_pitch = (c.yaw_deg.unwrap_or(0.0), c.pitch_deg.unwrap_or(0.0));
    let pinhole = Pinhole::yaw_pitch(DVec3::ZERO, yaw_pitch, c.vfov_deg, SIZE).unwrap();
    let lit = |c: DVec3| c.max_element() > 0.5;
    let mut dirs = Vec::new();
    for horizontal in [true, false] {
        let (n, len) = if horizontal {
            (SIZE.1, SIZE.0)
        } else {
            (SIZE.0, SIZE.1)
        };
        for at in 0..n {
            let scan = Scan { horizontal, at };
            for (from, step) in [(0, 1), (i64::from(len) - 1, -1)] {
                if let Some(u) = edge(&img, scan, from, step, |c| !lit(c)) {
                    let (px, py) = scan.point(u);
                    dirs.push(pinhole.rest_direction(px, py));
                }
            }
        }
    }
    let centre = pinhole.rest_direction(240.0, 180.0);
    let pixel = centre.angle_between(pinhole.rest_direction(241.0, 180.0));
    (dirs, pixel)
}

#[test]
fn static_markers_are_seen_where_relativistic_aberration_at_the_rapidity_puts_them() {
    let f = workspace_tests::fixture("rocket");
    let w = worldline(&f);
    for tau in [0.0, 4.0, 8.0] {
        let t = w.lab_time(tau);
        let (x, beta) = (w.position(tau), w.rapidity(tau).tanh());
        for name in ["south", "north-west"] {
            let (centre, radius) = marker(&f, name);
            let to = centre - x;
            let theta = w.direction.angle_between(to);
            let alpha = (radius / to.length()).asin();
            let (expected, expected_radius) = seen_circle(theta, alpha, beta).unwrap();
            let (dirs, pixel) = outline(&f, name, t);
            let fit = SkyCircle::fit(&dirs).expect("an outline");
            let measured = w.direction.angle_between(fit.centre);
            // Each edge point is placed within a tenth of a pixel (the
            // area method on 16 samples per pixel: a coverage's standard
            // deviation is at most 1/8); the centre of a circle fitted to
            // n of them within sqrt(2 / n) of that, taken four times over.
            let n = dirs.len() as f64;
            let tolerance = 4.0 * (pixel / 8.0).max(fit.rms) * (2.0 / n).sqrt();
            println!(
                "tau {tau} {name}: centre {:.5} deg (expected {:.5}, tolerance {:.5}), radius {:.5} ({:.5}), {} points",
                measured.to_degrees(),
                expected.to_degrees(),
                tolerance.to_degrees(),
                fit.radius.to_degrees(),
                expected_radius.to_degrees(),
                dirs.len()
            );
            assert!((measured - expected).abs() < tolerance, "tau {tau} {name}");
            assert!((fit.radius - expected_radius).abs() < 2.0 * tolerance);
            if tau > 0.0 {
                // Negative controls: Galilean aberration, and the rapidity
                // of a proper time 0.5 earlier, miss by many tolerances.
                let galilean = aberrated_angle_galilean(theta, beta);
                assert!((measured - galilean).abs() > 10.0 * tolerance, "{name}");
                let earlier = w.rapidity(tau - 0.5).tanh();
                let (off, _) = seen_circle(theta, alpha, earlier).unwrap();
                assert!((measured - off).abs() > 10.0 * tolerance, "{name}");
            }
        }
    }
}

/// Whether any pixel at camera lab time `t` shows the marker `name` (the
/// only object rendered, on black).
fn shows(f: &Fixture, name: &str, t: f64) -> bool {
    let mut only = f.only(&[name]).unwrap();
    only.scene.background = DVec3::ZERO;
    let img = render_at(&only, t, (96, 72), 4);
    img.pixels.iter().any(|c| c.max_element() > 0.0)
}

/// The marker's static place behind the camera's start and aside of its line.
fn behind_aside(f: &Fixture, name: &str) -> (f64, f64, f64) {
    let w = worldline(f);
    let (centre, radius) = marker(f, name);
    let r = centre - w.x0;
    let behind = -r.dot(w.direction);
    (behind, (r + w.direction * behind).length(), radius)
}

/// The proper times at which light leaving the marker's nearest and
/// farthest points at lab time 0 reaches the camera (first_seen grows with
/// the distance behind and aside).
fn bracket(f: &Fixture, name: &str) -> (f64, f64) {
    let w = worldline(f);
    let (behind, aside, r) = behind_aside(f, name);
    let a = w.acceleration;
    let early = first_seen(a, behind - r, (aside - r).max(0.0)).unwrap();
    let late = first_seen(a, behind + r, aside + r).unwrap();
    (w.proper_time(early), w.proper_time(late))
}

#[test]
fn markers_inside_the_horizon_are_first_and_last_seen_at_the_closed_form_times() {
    let f = workspace_tests::fixture("rocket");
    let w = worldline(&f);
    for (name, switched_on) in [("near", true), ("gone", false)] {
        let o = f.object(name).unwrap();
        let Motion::Extrusion { start, extrusion } = o.motion else {
            panic!("{name} has a lifetime")
        };
        assert_eq!(
            if switched_on {
                start.t
            } else {
                start.t + extrusion.t
            },
            0.0
        );
        let (early, late) = bracket(&f, name);
        println!("{name}: light from t = 0 arrives at proper times {early:.4}..{late:.4}");
        for (tau, after) in [(early - 0.2, false), (late + 0.2, true), (late + 3.0, true)] {
            let seen = shows(&f, name, w.lab_time(tau));
            assert_eq!(seen, after == switched_on, "{name} at tau {tau}");
        }
    }
}

#[test]
fn a_marker_beyond_the_rindler_horizon_is_never_seen() {
    let f = workspace_tests::fixture("rocket");
    let w = worldline(&f);
    let (behind, _, r) = behind_aside(&f, "far");
    assert!(behind - r > 1.0 / w.acceleration, "beyond the horizon");
    let end = w.proper_time(f.spec.camera.t + 60.0);
    let taus: Vec<f64> = (0..=12).map(|k| end * f64::from(k) / 12.0).collect();
    for &tau in &taus {
        assert!(!shows(&f, "far", w.lab_time(tau)), "far seen at tau {tau}");
    }
    // Negative control: the same marker just inside the horizon is seen
    // before the end.
    let inside = workspace_tests::fixture_with("rocket", |v| {
        let far = v["objects"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .find(|o| o["name"] == "far")
            .unwrap();
        far["worldline"]["start"][3] = serde_json::json!(8.5);
    });
    let (early, _) = bracket(&inside, "far");
    assert!(early < end);
    assert!(taus
        .iter()
        .any(|&tau| shows(&inside, "far", w.lab_time(tau))));
}

#[test]
fn a_shutter_integrates_over_the_cameras_proper_time() {
    let f = workspace_tests::fixture("rocket");
    let w = worldline(&f);
    let (tau, shutter) = (8.0, 1.0);
    let t = w.lab_time(tau);
    let mut g = f.clone();
    g.spec.image.shutter = shutter;
    let view = vstf::run::view(
        &g,
        &Overrides {
            camera_t: Some(t),
            spp: Some(64),
            ..Overrides::default()
        },
    )
    .unwrap();
    let db = vstf::run::database(&g, true, Traversal::Bvh).unwrap();
    let frame = renderer::Frame {
        camera: &view.camera,
        camera_t: view.camera_t,
        model: view.model,
        settings: &view.settings,
    };
    let shader = renderer::shader(&db, &g.scene, &frame);
    let mut rec = renderer::Recorder::default();
    renderer::pixel_traced(&shader, &frame, 48, 36, &mut rec);
    let times: Vec<f64> = rec
        .steps
        .iter()
        .filter_map(|s| match s {
            renderer::Step::Sample { camera_t, .. } => Some(*camera_t),
            _ => None,
        })
        .collect();
    assert_eq!(times.len(), 64);
    // Every sample's proper time lies within the shutter about tau ...
    let offsets: Vec<f64> = times.iter().map(|&s| w.proper_time(s) - tau).collect();
    assert!(
        offsets.iter().all(|o| o.abs() <= shutter / 2.0 + 1e-9),
        "{offsets:?}"
    );
    assert!(
        offsets.iter().any(|o| o.abs() > 0.4 * shutter),
        "{offsets:?}"
    );
    // ... so that in lab time they spread gamma times wider, and not
    // evenly about t: a shutter of lab time would stay within 0.5.
    let gamma = w.rapidity(tau).cosh();
    let lab: Vec<f64> = times.iter().map(|&s| s - t).collect();
    assert!(gamma > 1.3 && lab.iter().any(|d| d.abs() > 0.55), "{lab:?}");
}

/// The `marker_angle` rows pass; rendered with a camera accelerating 10 %
/// harder (the velocity of another proper time at each view) or under
/// the classical model (Galilean aberration), they fail where the camera
/// moves, and pass at its start, at rest (the control).
#[test]
fn the_marker_angle_rows_pass_and_fail_for_a_wrong_rapidity_or_galilean_aberration() {
    let f = workspace_tests::fixture("rocket");
    let rows = workspace_tests::declared_rows(&f, &f);
    assert_eq!(rows.len(), 6);
    assert!(
        rows.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&rows)
    );
    let harder = workspace_tests::fixture_with("rocket", |v| {
        let h = &mut v["camera"]["worldline"]["hyperbolic"];
        (h["acceleration"], h["duration"]) = (serde_json::json!([0, 0, -0.11]), 80.into());
    });
    let mut classical = f.clone();
    classical.spec.model = vstf::fixture::ModelName::Classical;
    for wrong in [harder, classical] {
        let rows = workspace_tests::declared_rows(&wrong, &f);
        for r in &rows {
            let at_rest = r.quantity.starts_with("start:");
            assert_eq!(r.pass, at_rest, "{}", vstf::report::table(&rows));
        }
    }
}

/// The `rocket-doppler` fixture's Doppler rows (static blackbody markers
/// seen by the accelerating camera, D from the colour) pass; rendered with
/// a camera accelerating 10 % harder (another rapidity at each view) or
/// with a camera that stays at rest (its velocity ignored: D = 1), they
/// fail where the camera moves and pass at its start (the control).
#[test]
fn the_doppler_rows_of_static_markers_pass_and_fail_for_a_wrong_or_ignored_velocity() {
    let f = workspace_tests::fixture("rocket-doppler");
    let rows = workspace_tests::declared_rows(&f, &f);
    assert_eq!(rows.len(), 6);
    assert!(
        rows.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&rows)
    );
    let harder = workspace_tests::fixture_with("rocket-doppler", |v| {
        let h = &mut v["camera"]["worldline"]["hyperbolic"];
        (h["acceleration"], h["duration"]) = (serde_json::json!([0, 0, -0.11]), 80.into());
    });
    let at_rest = workspace_tests::fixture_with("rocket-doppler", |v| {
        let h = &mut v["camera"]["worldline"]["hyperbolic"];
        (h["acceleration"], h["duration"]) = (serde_json::json!([0, 0, -1e-9]), 80.into());
    });
    for wrong in [harder, at_rest] {
        let rows = workspace_tests::declared_rows(&wrong, &f);
        for r in &rows {
            let at_start = r.quantity.starts_with("start:");
            assert_eq!(r.pass, at_start, "{}", vstf::report::table(&rows));
        }
    }
}

/// With an accelerating camera a Doppler check reads a static object at
/// the centre of its image: a moving object or a `point` is refused at
/// its field.
#[test]
fn a_doppler_check_of_a_moving_marker_or_a_point_is_refused_with_an_accelerating_camera() {
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("rocket-doppler.json");
    let text = std::fs::read_to_string(&file).unwrap();
    for (edit, field, says) in [
        (
            (|v: &mut serde_json::Value| {
                let o = v["objects"][0].as_object_mut().unwrap();
                o.remove("position");
                o.insert(
                    "worldline".into(),
                    serde_json::json!({"start": [0, 0, -1, 8], "velocity": [0.1, 0, 0], "proper_lifetime": 1000}),
                );
            }) as fn(&mut serde_json::Value),
            "checks[0].measure.doppler.object",
            "at rest in the lab",
        ),
        (
            |v| v["checks"][1]["measure"]["doppler"]["point"] = serde_json::json!([0, 0, 0.6]),
            "checks[1].measure.doppler.point",
            "remove point",
        ),
    ] {
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        edit(&mut v);
        let e = match Fixture::parse(&v.to_string(), &file) {
            Ok(_) => panic!("a bad fixture was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(field) && e.contains(says), "{e}");
    }
}
