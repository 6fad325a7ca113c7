//! What the page lists and renders, as `vstf check` names and renders it:
//! a fixture's own view, and a speed that stays below light's.

use super::*;

/// `TINY` without its views: a fixture `vstf check` compares with its
/// golden image as its own view `view`.
fn bare() -> String {
    let (head, _) = TINY.split_once(",\n  \"views\"").unwrap();
    format!("{head}\n}}")
}

/// A GET with the token; the status and the body's bytes.
fn get_bytes(s: &Running, target: &str) -> (u16, Vec<u8>) {
    let mut stream = TcpStream::connect(s.addr).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(60)))
        .unwrap();
    let raw = format!(
        "GET {target} HTTP/1.1\r\nHost: {}\r\nX-Vstf-Token: {}\r\n\r\n",
        s.host(),
        s.site.token()
    );
    stream.write_all(raw.as_bytes()).unwrap();
    let mut answer = Vec::new();
    let _ = stream.read_to_end(&mut answer);
    let status = parse_answer(&answer).0;
    let at = answer.windows(4).position(|w| w == b"\r\n\r\n").unwrap();
    (status, answer[at + 4..].to_vec())
}

/// The views the page lists for `fixture`.
fn listed(s: &Running, fixture: &str) -> Vec<serde_json::Value> {
    let (status, list) = s.get("/api/fixtures");
    assert_eq!(status, 200, "{list}");
    let list: serde_json::Value = serde_json::from_str(&list).unwrap();
    let f = list
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["name"] == fixture)
        .unwrap_or_else(|| panic!("{fixture} not listed: {list}"));
    f["views"].as_array().unwrap().clone()
}

/// A fixture that declares neither views nor checks is listed with the
/// one view `vstf check` gives it, `view`, at its camera time and model;
/// the page renders that view exactly as the check rendered it. A fixture
/// with declared views lists those and not `view` (the control).
#[test]
fn a_fixture_without_views_lists_its_own_view() {
    let s = start("own-view", Limits::default());
    std::fs::write(s.dir.0.join("fixtures/bare.json"), bare()).unwrap();
    let views = listed(&s, "bare");
    assert_eq!(views.len(), 1, "{views:?}");
    assert_eq!(
        (&views[0]["name"], &views[0]["t"], &views[0]["model"]),
        (
            &serde_json::json!("view"),
            &serde_json::json!(10.0),
            &serde_json::json!("relativistic")
        )
    );
    let names: Vec<serde_json::Value> = listed(&s, "tiny")
        .into_iter()
        .map(|v| v["name"].clone())
        .collect();
    assert_eq!(names, [serde_json::json!("t = 10")]);
    let (status, said) = s.post("/api/check", r#"{"fixture": "bare"}"#);
    assert_eq!(status, 200, "{said}");
    let checked = s.dir.0.join("target/vstf/bare/view/actual.png");
    assert!(
        checked.is_file(),
        "the check wrote no pending image: {said}"
    );
    let (status, png) = get_bytes(&s, "/api/render?fixture=bare&view=view");
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&png));
    let served = image::load_from_memory(&png).unwrap().to_rgb8();
    let checked = image::open(&checked).unwrap().to_rgb8();
    assert!(
        served == checked,
        "the page's view differs from the check's"
    );
    assert_eq!(listed(&s, "bare")[0]["pending"], true);
}

/// The speed slider's factor takes the one moving object (0.8c) up to
/// just below c and no further: 1.24 renders (0.992c), 1.25 (c) and 2 are
/// refused with why; the list gives the object's speed, from which the
/// page bounds its slider.
#[test]
fn the_speed_stays_below_light() {
    let s = start("speed", Limits::default());
    let (status, list) = s.get("/api/fixtures");
    assert_eq!(status, 200);
    let list: serde_json::Value = serde_json::from_str(&list).unwrap();
    let speed = list[0]["mover_speed"].as_f64().unwrap();
    assert!((speed - 0.8).abs() < 1e-12, "{list}");
    let at = |k: &str| {
        s.get(&format!(
            "/api/render?fixture=tiny&view=t%20%3D%2010&speed={k}"
        ))
    };
    assert_eq!(at("1.24").0, 200);
    for k in ["1.25", "2", "-1.3"] {
        let (status, said) = at(k);
        assert_eq!(status, 400, "×{k}: {said}");
        assert!(said.contains("slower than light"), "{said}");
    }
}

/// The fixture list entry of `name`.
fn entry(s: &Running, name: &str) -> serde_json::Value {
    let (status, list) = s.get("/api/fixtures");
    assert_eq!(status, 200);
    let list: serde_json::Value = serde_json::from_str(&list).unwrap();
    list.as_array()
        .unwrap()
        .iter()
        .find(|f| f["name"] == name)
        .unwrap()
        .clone()
}

/// The lab time a render of `query` was made at, as the server says it.
fn rendered_at(s: &Running, query: &str) -> f64 {
    let t = s.get_header(&format!("/api/render?{query}"), "X-Vstf-Camera-T");
    t.and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{query}: no camera time"))
}

/// An accelerating camera's fixture gives the page its clock (the proper
/// time at the worldline's end, and each view's proper time); the page
/// asks for a proper time (`tau=`) and the server reads the lab time on
/// the camera's hyperbola, t = sinh(a tau) / a from rest at t = 0; a
/// camera without a worldline gives none (the control). A lab time off
/// the worldline is refused, naming the field.
#[test]
fn an_accelerating_camera_gives_the_slider_its_proper_time() {
    let s = start("clock", Limits::default());
    let rocket = include_str!("../../../../fixtures/rocket.json");
    std::fs::write(s.dir.0.join("fixtures/rocket.json"), rocket).unwrap();
    let f = entry(&s, "rocket");
    let tau_end = f["clock"]["tau_end"].as_f64().unwrap();
    assert!((tau_end - 6f64.asinh() / 0.1).abs() < 1e-9, "{f}");
    let cruise = f["views"]
        .as_array()
        .unwrap()
        .iter()
        .find(|v| v["name"] == "cruise")
        .unwrap();
    assert!(
        (cruise["tau"].as_f64().unwrap() - 4.0).abs() < 1e-12,
        "{cruise}"
    );
    assert!(entry(&s, "tiny")["clock"].is_null());
    let t = rendered_at(&s, "fixture=rocket&view=cruise&tau=8");
    assert!((t - 0.8f64.sinh() / 0.1).abs() < 1e-12, "{t}");
    // The control: the proper time is not taken as a lab time.
    assert!((t - 8.0).abs() > 0.8);
    assert_eq!(
        s.get("/api/render?fixture=rocket&view=cruise&tau=8"),
        s.get(&format!("/api/render?fixture=rocket&view=cruise&t={t}"))
    );
    assert_eq!(s.get("/api/render?fixture=rocket&view=cruise&t=30").0, 200);
    let (status, said) = s.get("/api/render?fixture=rocket&view=cruise&t=100");
    assert_eq!(status, 400, "{said}");
    assert!(
        said.contains("camera.worldline.hyperbolic.duration"),
        "{said}"
    );
}

/// A camera on keyframes: uniform motion at 0.6c from lab time 2, whose
/// clock runs at 0.8 of lab time, so proper time tau is at lab time 2 +
/// tau / 0.8 and the keyframes end at tau = 16. The page's `tau=` is read
/// there, as `animate --frames tau:` reads it; a proper time past the end,
/// one for a camera without a worldline, and both t and tau are refused.
#[test]
fn a_camera_on_keyframes_gives_the_slider_its_proper_time() {
    let s = start("clock-keyframes", Limits::default());
    let mut v: serde_json::Value =
        serde_json::from_str(include_str!("../../../../fixtures/rocket.json")).unwrap();
    v["camera"]["worldline"] = serde_json::json!({"keyframes": [
        { "t": 2.0, "position": [0, 0, 0], "velocity": [0, 0, -0.6] },
        { "t": 22.0, "position": [0, 0, -12], "velocity": [0, 0, -0.6] }
    ]});
    v["camera"]["t"] = serde_json::json!(2.0);
    v["views"] = serde_json::json!([{ "name": "k", "tau": 4.0 }]);
    v["checks"] = serde_json::json!([]);
    let file = s.dir.0.join("fixtures/coast.json");
    std::fs::write(&file, v.to_string()).unwrap();
    let f = entry(&s, "coast");
    assert!(
        (f["clock"]["tau_end"].as_f64().unwrap() - 16.0).abs() < 1e-12,
        "{f}"
    );
    let k = &f["views"][0];
    assert!((k["t"].as_f64().unwrap() - 7.0).abs() < 1e-12, "{k}");
    assert!((k["tau"].as_f64().unwrap() - 4.0).abs() < 1e-12, "{k}");
    let t = rendered_at(&s, "fixture=coast&view=k&tau=8");
    assert!((t - 12.0).abs() < 1e-12, "{t}");
    let loaded = crate::Fixture::load(&file).unwrap();
    let cli = crate::animate::lab_times(
        &loaded,
        crate::animate::parse_frames("tau:8..8").unwrap(),
        1.0,
    )
    .unwrap();
    assert_eq!(cli, [t]);
    assert_eq!(
        s.get("/api/render?fixture=coast&view=k&tau=8"),
        s.get("/api/render?fixture=coast&view=k&t=12")
    );
    // The control: the frame at lab time 8 is another picture.
    assert_ne!(
        s.get("/api/render?fixture=coast&view=k&tau=8"),
        s.get("/api/render?fixture=coast&view=k&t=8")
    );
    for (query, says) in [
        ("fixture=coast&view=k&tau=17", "span proper times"),
        ("fixture=tiny&view=t%20%3D%2010&tau=1", "camera.worldline"),
        ("fixture=coast&view=k&tau=1&t=3", "not both"),
    ] {
        let (status, said) = s.get(&format!("/api/render?{query}"));
        assert!(
            status == 400 && said.contains(says),
            "{query}: {status} {said}"
        );
    }
}
