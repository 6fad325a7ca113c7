//! Checks with a camera on keyframes (docs/physics.md, "The accelerated
//! observer"), on the `rocket-keyframes` fixture: the oracle's own
//! evaluation of the keyframes (power-form cubic, Simpson's proper time)
//! agrees with the fixture's (Hermite basis, Gauss-Legendre); the
//! fixture's `marker_angle` and `doppler` rows pass, and fail for a camera
//! rendered 10 % faster; check kinds whose expectations assume another
//! camera are refused at their field.

use serde_json::{json, Value};
use vstf::fixture::Overrides;
use vstf::oracle::keyframed::{CameraKey, KeyframedCamera};
use vstf::Fixture;

/// The oracle's worldline of the fixture's camera, read from its plain data.
fn oracle(f: &Fixture) -> KeyframedCamera {
    let keys = f
        .spec
        .camera
        .worldline
        .as_ref()
        .unwrap()
        .keyframes
        .as_ref()
        .unwrap();
    KeyframedCamera {
        keys: keys
            .iter()
            .map(|k| CameraKey {
                t: k.t,
                position: k.position,
                velocity: k.velocity,
            })
            .collect(),
    }
}

#[test]
fn the_oracles_keyframed_camera_agrees_with_the_fixtures() {
    let f = workspace_tests::fixture("rocket-keyframes");
    let o = oracle(&f);
    let clock = vstf::fixture::camera_clock(&f.spec.camera)
        .unwrap()
        .unwrap();
    for t in [0.0, 0.7, 4.21, 7.999, 8.0, 8.001, 13.3, 20.0] {
        let c = vstf::run::view(
            &f,
            &Overrides {
                camera_t: Some(t),
                ..Overrides::default()
            },
        )
        .unwrap()
        .camera;
        let (x, v) = o.at(t).unwrap();
        assert!(
            (c.event.x - x).length() < 1e-13,
            "{t}: {} vs {x}",
            c.event.x
        );
        assert!(
            (c.velocity - v).length() < 1e-14,
            "{t}: {} vs {v}",
            c.velocity
        );
        let (a, b) = (clock.proper_time(t), o.proper_time(t));
        assert!((a - b).abs() < 1e-11, "{t}: {a} vs {b}");
    }
    // Coasting at 0.6c, the clock runs at 0.8 of lab time.
    let coast = o.proper_time(20.0) - o.proper_time(8.0);
    assert!((coast - 0.8 * 12.0).abs() < 1e-12, "{coast}");
    // The control: an oracle whose middle keyframe is 0.05c slower
    // disagrees within the accelerating interval.
    let mut slower = o.clone();
    slower.keys[1].velocity *= 0.6 / 0.65;
    let (_, v) = slower.at(6.0).unwrap();
    let c = vstf::run::view(
        &f,
        &Overrides {
            camera_t: Some(6.0),
            ..Overrides::default()
        },
    )
    .unwrap()
    .camera;
    assert!((c.velocity - v).length() > 1e-3);
}

#[test]
fn the_rows_pass_and_fail_for_a_camera_rendered_faster() {
    let f = workspace_tests::fixture("rocket-keyframes");
    let rows = workspace_tests::declared_rows(&f, &f);
    assert_eq!(rows.len(), 12);
    assert!(
        rows.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&rows)
    );
    // Rendered with every keyframe's velocity 10 % higher (the same
    // positions), every row fails.
    let faster = workspace_tests::fixture_with("rocket-keyframes", |v| {
        for k in v["camera"]["worldline"]["keyframes"]
            .as_array_mut()
            .unwrap()
        {
            let z = k["velocity"][2].as_f64().unwrap();
            k["velocity"] = json!([0.0, 0.0, 1.1 * z]);
        }
    });
    let rows = workspace_tests::declared_rows(&faster, &f);
    assert!(
        rows.iter().all(|r| !r.pass),
        "{}",
        vstf::report::table(&rows)
    );
}

#[test]
fn check_kinds_not_derived_for_a_camera_on_keyframes_are_refused_at_their_field() {
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("rocket-keyframes.json");
    let base: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let with = |check: Value| {
        let mut v = base.clone();
        v["checks"] = json!([{ "name": "x", "measure": check }]);
        Fixture::parse(&v.to_string(), &file)
    };
    let outline =
        json!({"outline": {"view": "start", "object": "south", "read": "centre_azimuth"}});
    let e = with(outline).unwrap_err().to_string();
    assert!(
        e.contains("checks[0].measure.outline") && e.contains("camera on keyframes"),
        "{e}"
    );
    // The control: a marker_angle check is taken.
    let angle = json!({"marker_angle": {"view": "coasting", "object": "north-west"}});
    assert!(with(angle).is_ok());
    // At rest at a view, the angle from the velocity is not defined: the
    // rows there fail saying so rather than measure from a made-up
    // direction.
    let still = workspace_tests::fixture_with("rocket-keyframes", |v| {
        v["camera"]["worldline"]["keyframes"][0]["velocity"] = json!([0.0, 0.0, 0.0]);
    });
    let e = vstf::check::evaluate(&still, &still, &vstf::Effort::QUICK);
    let said = match e {
        Err(e) => e.to_string(),
        Ok(o) => o
            .quantities
            .iter()
            .filter_map(|q| q.error.clone())
            .collect::<Vec<_>>()
            .join("; "),
    };
    assert!(said.contains("at rest at this view"), "{said}");
}
