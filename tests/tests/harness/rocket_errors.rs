//! The `rocket` fixture's accelerated camera and proper times, wrong:
//! each refused at load, naming the JSON field and what it must be.

/// The rocket fixture's text with `edit` applied, parsed: its error.
fn error_with(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    workspace_tests::fixture_error_with("rocket", edit)
}

#[test]
fn a_bad_camera_worldline_or_proper_time_is_refused_at_its_field() {
    for (edit, field, says) in [
        (
            (|v: &mut serde_json::Value| {
                v["camera"]["worldline"]["hyperbolic"]["acceleration"] =
                    serde_json::json!([0, 0, 0])
            }) as fn(&mut serde_json::Value),
            "camera.worldline.hyperbolic.acceleration",
            "non-zero",
        ),
        (
            |v| v["camera"]["worldline"]["hyperbolic"]["initial_velocity"] = serde_json::json!(1.0),
            "camera.worldline.hyperbolic.initial_velocity",
            "slower than light",
        ),
        (
            |v| v["camera"]["worldline"]["hyperbolic"]["duration"] = serde_json::json!(-1.0),
            "camera.worldline.hyperbolic.duration",
            "positive",
        ),
        (
            |v| v["camera"]["velocity"] = serde_json::json!([0.1, 0, 0]),
            "camera.worldline",
            "not both",
        ),
        (
            |v| v["views"][1]["tau"] = serde_json::json!(30.0),
            "views[1].tau",
            "spans proper times [0, 24.9",
        ),
        (
            |v| v["views"][1]["t"] = serde_json::json!(3.0),
            "views[1].tau",
            "not both",
        ),
        (
            |v| {
                v["views"][1].as_object_mut().unwrap().remove("tau");
                v["views"][1]["t"] = serde_json::json!(100.0)
            },
            "views[1].t",
            "outside its worldline",
        ),
        (
            |v| v["image"]["shutter"] = serde_json::json!(1.0),
            "camera.worldline.hyperbolic.duration",
            "lab time -",
        ),
        (
            |v| v["checks"][0]["measure"]["marker_angle"]["object"] = "nope".into(),
            "checks[0].measure.marker_angle.object",
            "no object named",
        ),
    ] {
        let e = error_with(edit);
        assert!(e.contains(field) && e.contains(says), "{field}: {e}");
    }
    // A proper time without a worldline names the view's tau.
    let e = error_with(|v| {
        v["camera"].as_object_mut().unwrap().remove("worldline");
    });
    assert!(
        e.contains("views[0].tau") && e.contains("camera.worldline"),
        "{e}"
    );
    // marker_angle is for an accelerating camera.
    let e = error_with(|v| {
        v["camera"].as_object_mut().unwrap().remove("worldline");
        v["views"] = serde_json::json!([{"name": "start"}]);
        let check = serde_json::json!({"marker_angle": {"view": "start", "object": "south"}});
        v["checks"] = serde_json::json!([{"name": "x", "measure": check}]);
    });
    assert!(
        e.contains("checks[0].measure.marker_angle.view") && e.contains("accelerating camera"),
        "{e}"
    );
}
