//! A shutter on a camera on keyframes (docs/physics.md, "The accelerated
//! observer"): it spans the camera's own proper time, each sample taken at
//! the camera's event and velocity then. A shutter of 0 is the still
//! frame bit for bit; keyframes sampled densely from the `rocket` camera's
//! hyperbola give its shuttered frame; a shutter leaving the keyframes is
//! refused at `image.shutter`; a frame retimed by an animation is on the
//! curve at its own time.

use glam::DVec3;
use renderer::{Hyperbolic, Image, Traversal};
use serde_json::{json, Value};
use vstf::fixture::{Overrides, View};
use vstf::Fixture;

/// The `rocket` camera's hyperbola (proper acceleration 0.1 along -z from
/// rest at the origin at t = 0), in the renderer's closed form.
fn hyperbola() -> Hyperbolic {
    Hyperbolic {
        start: renderer::Event::new(0.0, DVec3::ZERO),
        direction: DVec3::NEG_Z,
        acceleration: 0.1,
        initial_velocity: 0.0,
        duration: 60.0,
        tolerance: 1e-4,
    }
}

/// Keyframes every `h` of lab time on the hyperbola over [0, `end`].
fn sampled(h: f64, end: f64) -> Value {
    let w = hyperbola();
    let n = (end / h).round() as usize;
    let keys: Vec<Value> = (0..=n)
        .map(|i| {
            let (e, v) = w.event_at(h * i as f64);
            json!({ "t": e.t, "position": [e.x.x, e.x.y, e.x.z], "velocity": [v.x, v.y, v.z] })
        })
        .collect();
    Value::Array(keys)
}

/// The rocket scene with its camera on `keyframes` and `shutter`.
fn on_keyframes(keyframes: Value, shutter: f64) -> Fixture {
    workspace_tests::fixture_with("rocket", |v| {
        v["camera"]["worldline"] = json!({ "keyframes": keyframes });
        v["image"]["shutter"] = json!(shutter);
        v["camera"]["t"] = json!(10.0);
        v["views"] = json!([{ "name": "k", "t": 10.0 }]);
        v["checks"] = json!([]);
    })
}

fn view_at(f: &Fixture, t: f64, spp: u32) -> View {
    let o = Overrides {
        camera_t: Some(t),
        spp: Some(spp),
        ..Overrides::default()
    };
    vstf::run::view(f, &o).unwrap_or_else(|e| panic!("{e}"))
}

fn render(f: &Fixture, view: &View) -> Image {
    let db = vstf::run::database(f, true, Traversal::Bvh).unwrap();
    vstf::run::render_with(&db, f, view).unwrap_or_else(|e| panic!("{e}"))
}

/// The lab times of pixel (48, 36)'s samples in `view`.
fn sample_times(f: &Fixture, view: &View) -> Vec<f64> {
    let db = vstf::run::database(f, true, Traversal::Bvh).unwrap();
    let frame = renderer::Frame {
        camera: &view.camera,
        camera_t: view.camera_t,
        model: view.model,
        settings: &view.settings,
    };
    let shader = renderer::shader(&db, &f.scene, &frame);
    let mut rec = renderer::Recorder::default();
    renderer::pixel_traced(&shader, &frame, 48, 36, &mut rec);
    rec.steps
        .iter()
        .filter_map(|s| match s {
            renderer::Step::Sample { camera_t, .. } => Some(*camera_t),
            _ => None,
        })
        .collect()
}

fn worst(a: &Image, b: &Image) -> f64 {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| (*p - *q).abs().max_element())
        .fold(0.0, f64::max)
}

fn three_keyframes() -> Value {
    json!([
        { "t": 0.0, "position": [0, 0, 0], "velocity": [0, 0, -0.2] },
        { "t": 10.0, "position": [0, 0, -4], "velocity": [0.1, 0, -0.6] },
        { "t": 20.0, "position": [1, 0, -11], "velocity": [0, 0, -0.3] }
    ])
}

#[test]
fn a_shutter_of_zero_on_keyframes_is_the_still_frame_bit_for_bit() {
    let f = on_keyframes(three_keyframes(), 0.0);
    let t = 7.3;
    let view = view_at(&f, t, 16);
    let (event, velocity) = (view.camera.event, view.camera.velocity);
    // The inertial camera at the same event and velocity.
    let g = workspace_tests::fixture_with("rocket", |v| {
        v["camera"].as_object_mut().unwrap().remove("worldline");
        v["camera"]["t"] = json!(event.t);
        v["camera"]["position"] = json!([event.x.x, event.x.y, event.x.z]);
        v["camera"]["velocity"] = json!([velocity.x, velocity.y, velocity.z]);
        v["views"] = json!([{ "name": "k", "t": t }]);
        v["checks"] = json!([]);
    });
    let still = render(&g, &view_at(&g, t, 16));
    let keyed = render(&f, &view);
    assert!(keyed.pixels == still.pixels);
    // The control: a shutter of 2 on the same keyframes blurs the frame.
    let blurred = on_keyframes(three_keyframes(), 2.0);
    let e = worst(&render(&blurred, &view_at(&blurred, t, 16)), &still);
    assert!(e > 0.05, "largest channel difference {e}");
}

/// Keyframes every 1/8 of lab time on the hyperbola: the cubic Hermite
/// curve is off the hyperbola by at most h^4 M4 / 384 in position and
/// sqrt(3) h^3 M4 / 216 in velocity, M4 = 3 a^3 = 3e-3 bounding
/// |d^4 z / dt^4| = a^3 |f''''(a t)|, f(u) = sqrt(1 + u^2): 2e-9 l.units
/// and 5e-8. Over the shutter's lab times (within 0.7 of the centre, at
/// gamma < 1.5) the proper times then agree to gamma * 5e-8 * 0.7 < 6e-8,
/// and each sample's lab time to gamma times that, < 1e-7 (asserted:
/// 1e-6). A sample whose ray meets another marker moves by 5e-8 rad, 3e-6
/// px: at 96 x 72 px and 16 samples the chance that any of the some 2,000
/// samples near the markers' edges crosses one is under 1 %, and an unlit
/// marker's colour does not depend on the camera's velocity, so the
/// shuttered frames are equal.
#[test]
fn a_shutter_on_keyframes_sampling_the_hyperbola_is_the_hyperbolic_cameras() {
    let w = hyperbola();
    let (tau, shutter) = (8.0, 1.0);
    let t = w.lab_time(tau);
    let keyed = on_keyframes(sampled(0.125, 20.0), shutter);
    let mut hyper = workspace_tests::fixture("rocket");
    hyper.spec.image.shutter = shutter;
    let (kv, hv) = (view_at(&keyed, t, 16), view_at(&hyper, t, 16));
    let (ks, hs) = (sample_times(&keyed, &kv), sample_times(&hyper, &hv));
    assert_eq!(ks.len(), 16);
    let gap = ks
        .iter()
        .zip(&hs)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(gap < 1e-6, "sample lab times differ by up to {gap}");
    // Each sample's proper time on the hyperbola is within the shutter,
    // and they spread over it.
    let offsets: Vec<f64> = ks.iter().map(|&s| w.proper_time(s) - tau).collect();
    assert!(
        offsets.iter().all(|o| o.abs() <= shutter / 2.0 + 1e-6),
        "{offsets:?}"
    );
    assert!(
        offsets.iter().any(|o| o.abs() > 0.3 * shutter),
        "{offsets:?}"
    );
    // The control: a shutter of lab time would put the samples at other
    // lab times (gamma = cosh 0.8 = 1.34 apart).
    let lab_gap = ks
        .iter()
        .zip(&offsets)
        .map(|(s, o)| (s - (t + o)).abs())
        .fold(0.0, f64::max);
    assert!(lab_gap > 0.05, "{lab_gap}");
    let e = worst(&render(&keyed, &kv), &render(&hyper, &hv));
    assert!(e < 1e-9, "largest channel difference {e}");
    // The control: the hyperbolic camera's frame half a unit of proper
    // time later differs.
    let later = view_at(&hyper, w.lab_time(tau + 0.5), 16);
    assert!(worst(&render(&keyed, &kv), &render(&hyper, &later)) > 0.05);
}

#[test]
fn a_shutter_leaving_the_keyframes_is_refused_at_image_shutter() {
    let f = on_keyframes(three_keyframes(), 2.0);
    let o = |t| Overrides {
        camera_t: Some(t),
        ..Overrides::default()
    };
    for t in [0.0, 0.5, 19.9] {
        let e = vstf::run::view(&f, &o(t)).unwrap_err().to_string();
        assert!(
            e.contains("image.shutter") && e.contains("outside"),
            "{t}: {e}"
        );
    }
    // The control: a frame whose shutter stays within them is allowed.
    assert!(vstf::run::view(&f, &o(5.0)).is_ok());
    // A shutter over more keyframes than a camera carries is refused too.
    let e = workspace_tests::fixture_error_with("rocket", |v| {
        v["camera"]["worldline"] = json!({ "keyframes": sampled(0.0625, 20.0) });
        v["image"]["shutter"] = json!(2.0);
        v["camera"]["t"] = json!(10.0);
        v["views"] = json!([{ "name": "k", "t": 10.0 }]);
        v["checks"] = json!([]);
    });
    assert!(e.contains("image.shutter") && e.contains("at most"), "{e}");
}

#[test]
fn a_frame_retimed_by_an_animation_is_on_the_keyframes_at_its_time() {
    let f = on_keyframes(three_keyframes(), 0.0);
    let first = view_at(&f, 2.0, 4);
    let retimed = View {
        camera_t: 14.0,
        ..first
    };
    let direct = view_at(&f, 14.0, 4);
    let (a, b) = (render(&f, &retimed), render(&f, &direct));
    assert!(a.pixels == b.pixels);
    // The control: the first frame's camera carried on inertially to lab
    // time 14 sees another picture.
    let mut inertial = first;
    inertial.camera.worldline = None;
    inertial.camera_t = 14.0;
    let g = workspace_tests::fixture_with("rocket", |v| {
        v["camera"].as_object_mut().unwrap().remove("worldline");
        v["views"] = json!([{ "name": "k", "t": 0.0 }]);
        v["checks"] = json!([]);
    });
    let db = vstf::run::database(&g, true, Traversal::Bvh).unwrap();
    let c = vstf::run::render_with(&db, &g, &inertial).unwrap();
    assert!(worst(&c, &b) > 0.05);
}
