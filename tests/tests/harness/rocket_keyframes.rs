//! A camera on keyframes (`camera.worldline.keyframes`, docs/physics.md,
//! "The accelerated observer"), on the `rocket` scene: a frame at a
//! keyframe is the inertial camera's at that event and velocity bit for
//! bit; two keyframes of uniform motion reproduce the inertial moving
//! camera between them; views' `tau` and `animate --frames tau:` read the
//! camera's proper time; bad keyframes are refused at their field.

use glam::DVec3;
use renderer::{Image, Traversal};
use serde_json::{json, Value};
use vstf::fixture::Overrides;
use vstf::Fixture;

/// The rocket scene with its camera on `keyframes`, one view at lab time
/// `t`, no checks.
fn edit_keyframes(v: &mut Value, keyframes: Value, t: f64) {
    v["camera"]["worldline"] = json!({ "keyframes": keyframes });
    v["camera"]["t"] = json!(t);
    v["views"] = json!([{ "name": "k", "t": t }]);
    v["checks"] = json!([]);
}

fn on_keyframes(keyframes: Value, t: f64) -> Fixture {
    workspace_tests::fixture_with("rocket", |v| edit_keyframes(v, keyframes, t))
}

/// The rocket scene with an inertial camera at `event` moving at `v`.
fn inertial((t, x): (f64, DVec3), v: DVec3) -> Fixture {
    workspace_tests::fixture_with("rocket", |j| {
        j["camera"].as_object_mut().unwrap().remove("worldline");
        j["camera"]["t"] = json!(t);
        j["camera"]["position"] = json!([x.x, x.y, x.z]);
        j["camera"]["velocity"] = json!([v.x, v.y, v.z]);
        j["views"] = json!([{ "name": "k", "t": t }]);
        j["checks"] = json!([]);
    })
}

fn render_at(f: &Fixture, t: f64) -> Image {
    let view = vstf::run::view(
        f,
        &Overrides {
            camera_t: Some(t),
            width: Some(96),
            height: Some(72),
            spp: Some(4),
            ..Overrides::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    vstf::run::render(f, &view, Traversal::Bvh).unwrap_or_else(|e| panic!("{e}"))
}

fn camera_at(f: &Fixture, t: f64) -> renderer::Camera {
    let o = Overrides {
        camera_t: Some(t),
        ..Overrides::default()
    };
    vstf::run::view(f, &o)
        .unwrap_or_else(|e| panic!("{e}"))
        .camera
}

fn three_keyframes() -> Value {
    json!([
        { "t": 0.0, "position": [0, 0, 0], "velocity": [0, 0, -0.2] },
        { "t": 10.0, "position": [0, 0, -4], "velocity": [0.1, 0, -0.6] },
        { "t": 20.0, "position": [1, 0, -11], "velocity": [0, 0, -0.3] }
    ])
}

#[test]
fn a_frame_at_a_keyframe_is_the_inertial_cameras_there_bit_for_bit() {
    let f = on_keyframes(three_keyframes(), 0.0);
    let at = (10.0, DVec3::new(0.0, 0.0, -4.0));
    let v = DVec3::new(0.1, 0.0, -0.6);
    let c = camera_at(&f, 10.0);
    assert_eq!((c.event.t, c.event.x, c.velocity), (at.0, at.1, v));
    let keyed = render_at(&f, 10.0);
    assert!(keyed.pixels == render_at(&inertial(at, v), 10.0).pixels);
    // Negative control: the curve's velocity at a neighbouring time turns
    // the view.
    let later = camera_at(&f, 10.5).velocity;
    assert_ne!(later, v);
    assert!(keyed.pixels != render_at(&inertial(at, later), 10.0).pixels);
}

#[test]
fn two_keyframes_of_uniform_motion_are_the_inertial_moving_camera_between_them() {
    let (x0, v) = (DVec3::new(0.5, 0.0, 1.0), DVec3::new(0.3, 0.0, -0.5));
    let keys = json!([
        { "t": 0.0, "position": [x0.x, x0.y, x0.z], "velocity": [v.x, v.y, v.z] },
        { "t": 20.0, "position": [x0.x + 20.0 * v.x, x0.y, x0.z + 20.0 * v.z], "velocity": [v.x, v.y, v.z] }
    ]);
    let f = on_keyframes(keys, 0.0);
    let t = 7.3;
    let c = camera_at(&f, t);
    // The event and velocity are the straight worldline's to rounding.
    assert!(
        (c.event.x - (x0 + v * t)).length() < 1e-13,
        "{:?}",
        c.event.x
    );
    assert!((c.velocity - v).length() < 1e-14, "{:?}", c.velocity);
    let keyed = render_at(&f, t);
    let straight = render_at(&inertial((0.0, x0), v), t);
    let worst = |a: &Image, b: &Image| {
        a.pixels
            .iter()
            .zip(&b.pixels)
            .map(|(p, q)| (*p - *q).abs().max_element())
            .fold(0.0, f64::max)
    };
    let e = worst(&keyed, &straight);
    assert!(e < 1e-9, "largest channel difference {e}");
    // Negative control: a camera slower by 0.05c along x differs.
    let slower = render_at(&inertial((0.0, x0), v - DVec3::new(0.05, 0.0, 0.0)), t);
    assert!(worst(&keyed, &slower) > 0.1);
}

/// The rocket fixture with keyframes and `edit` applied, parsed: its error.
fn error_with(edit: impl FnOnce(&mut Value)) -> String {
    workspace_tests::fixture_error_with("rocket", |v| {
        edit_keyframes(v, three_keyframes(), 0.0);
        edit(v);
    })
}

#[test]
fn bad_keyframes_are_refused_at_their_field() {
    for (edit, field, says) in [
        (
            (|v: &mut Value| v["camera"]["worldline"]["keyframes"][2]["t"] = json!(10.0))
                as fn(&mut Value),
            "camera.worldline.keyframes[2].t",
            "increase",
        ),
        (
            |v| v["camera"]["worldline"]["keyframes"][0]["velocity"] = json!([0, 0, -1]),
            "camera.worldline.keyframes[0].velocity",
            "slower than light",
        ),
        (
            |v| v["camera"]["worldline"]["keyframes"][1]["position"] = json!([0, 0, -14]),
            "camera.worldline.keyframes[1]",
            "light speed",
        ),
        (
            |v| {
                let first = v["camera"]["worldline"]["keyframes"][0].clone();
                v["camera"]["worldline"]["keyframes"] = json!([first]);
            },
            "camera.worldline.keyframes",
            "at least two",
        ),
        (
            |v| {
                v["camera"]["worldline"]["hyperbolic"] =
                    json!({"acceleration": [0, 0, -0.1], "duration": 60.0})
            },
            "camera.worldline",
            "exactly one",
        ),
        (
            |v| v["views"] = json!([{ "name": "k", "tau": 30.0 }]),
            "views[0].tau",
            "span proper times",
        ),
        (
            |v| {
                let outline =
                    json!({"outline": {"view": "k", "object": "south", "read": "centre_azimuth"}});
                v["checks"] = json!([{"name": "x", "measure": outline}]);
            },
            "checks[0].measure.outline",
            "keyframes",
        ),
    ] {
        let e = error_with(edit);
        assert!(e.contains(field) && e.contains(says), "{field}: {e}");
    }
    // The control: the unedited keyframes parse, and are asked for only
    // at lab times within them.
    let f = on_keyframes(three_keyframes(), 0.0);
    let o = Overrides {
        camera_t: Some(25.0),
        ..Overrides::default()
    };
    let e = vstf::run::view(&f, &o).unwrap_err().to_string();
    assert!(
        e.contains("camera.worldline.keyframes") && e.contains("outside"),
        "{e}"
    );
    assert_eq!(camera_at(&f, 0.0).velocity, DVec3::new(0.0, 0.0, -0.2));
}

#[test]
fn a_views_proper_time_on_keyframes_is_read_on_the_cameras_clock() {
    // Uniform motion at 0.6c from lab time 2: proper time tau is reached at
    // lab time 2 + tau / 0.8.
    let keys = json!([
        { "t": 2.0, "position": [0, 0, 0], "velocity": [0, 0, -0.6] },
        { "t": 22.0, "position": [0, 0, -12], "velocity": [0, 0, -0.6] }
    ]);
    let f = workspace_tests::fixture_with("rocket", |v| {
        edit_keyframes(v, keys, 2.0);
        v["views"] = json!([{ "name": "k", "tau": 4.0 }]);
    });
    let t = f.spec.views[0].camera_t(f.spec.camera.t);
    assert!((t - 7.0).abs() < 1e-12, "{t}");
    // The control: the lab time is not the proper time.
    assert!((t - 2.0 - 4.0).abs() > 0.9);
}

#[test]
fn animate_steps_the_proper_time_of_a_camera_on_keyframes() {
    let keys = json!([
        { "t": 2.0, "position": [0, 0, 0], "velocity": [0, 0, -0.6] },
        { "t": 22.0, "position": [0, 0, -12], "velocity": [0, 0, -0.6] }
    ]);
    let f = workspace_tests::fixture_with("rocket", |v| edit_keyframes(v, keys, 2.0));
    let tau = vstf::animate::parse_frames("tau:0..8").unwrap();
    let times = vstf::animate::lab_times(&f, tau, 4.0).unwrap();
    assert_eq!(times.len(), 3);
    for (t, want) in times.iter().zip([2.0, 7.0, 12.0]) {
        assert!((t - want).abs() < 1e-12, "{t} vs {want}");
    }
    // Lab time is stepped as given; a proper time past the keyframes'
    // 16 is refused.
    let lab = vstf::animate::parse_frames("2..10").unwrap();
    assert_eq!(
        vstf::animate::lab_times(&f, lab, 4.0).unwrap(),
        [2.0, 6.0, 10.0]
    );
    let past = vstf::animate::parse_frames("tau:0..20").unwrap();
    assert!(vstf::animate::lab_times(&f, past, 4.0).is_err());
}
