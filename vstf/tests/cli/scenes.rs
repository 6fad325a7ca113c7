//! Three scenes as a new user writes them (a rod at 0.9c, an analytic
//! sphere at 0.95c passing off the axis, an L-shaped plate read from an OBJ
//! file a script wrote), their views at camera times given by what they
//! should show (`auto:OBJECT`, `seen_at_azimuth`) and their declared
//! checks, checked in a folder of their own outside any project.

use crate::support::{vstf, RunExt, Scratch};
use std::path::Path;

const ROD: &str = include_str!("scenes/rod.json");
const BALL: &str = include_str!("scenes/ball.json");
const PLATE: &str = include_str!("scenes/plate.json");

/// The L-shaped plate as a script writes it: six corners in the z = 0
/// plane, four triangles, OBJ's 1-based indices.
fn write_plate_obj(dir: &Path) {
    let corners = [[0, 0], [3, 0], [3, 1], [1, 1], [1, 3], [0, 3]];
    let mut obj = String::new();
    for [x, y] in corners {
        obj.push_str(&format!("v {x} {y} 0\n"));
    }
    for k in 2..=5 {
        obj.push_str(&format!("f 1 {k} {}\n", k + 1));
    }
    std::fs::write(dir.join("plate.obj"), obj).unwrap();
}

/// A scratch folder holding the three scenes (and the plate's OBJ).
fn scenes(name: &str) -> Scratch {
    let dir = Scratch::new(name);
    for (file, text) in [
        ("rod.json", ROD),
        ("ball.json", BALL),
        ("plate.json", PLATE),
    ] {
        std::fs::write(dir.join(file), text).unwrap();
    }
    write_plate_obj(&dir);
    dir
}

/// The JSON rows `vstf check FILE --quick --json -` writes for `file` in `dir`.
fn rows(dir: &Path, file: &str) -> Vec<serde_json::Value> {
    let run = vstf()
        .current_dir(dir)
        .args(["check", file, "--quick", "--json", "-"])
        .run();
    let json: serde_json::Value = serde_json::from_str(run.stdout())
        .unwrap_or_else(|e| panic!("{file}: no JSON ({e}):\n{}", run.stderr()));
    json["rows"].as_array().unwrap().clone()
}

/// The row named `name`.
fn row<'a>(rows: &'a [serde_json::Value], name: &str) -> &'a serde_json::Value {
    rows.iter()
        .find(|r| r["quantity"] == name)
        .unwrap_or_else(|| panic!("no row {name:?} in {rows:#?}"))
}

/// Every declared row of the three scenes passes at the camera times the
/// views ask for by what they show, and the rows record the times solved:
/// the rod's centre crosses x = 0 at t = 20 / 0.9, 10 l.units away, so it
/// is seen there at 20 / 0.9 + 10, and at once with infinitely fast light;
/// it is at azimuth 20 deg when x = 10 tan 20 deg, seen 10 / cos 20 deg later.
#[test]
fn a_new_users_scenes_check_at_solved_times() {
    let dir = scenes("scenes-pass");
    for (file, count) in [("rod.json", 3), ("ball.json", 4), ("plate.json", 2)] {
        let rows = rows(&dir, file);
        assert_eq!(rows.len(), count, "{file}: {rows:#?}");
        for r in &rows {
            assert_eq!(r["pass"], true, "{file}: {r:#}");
            assert!(r["camera_t"].is_f64(), "{file}: no solved time in {r:#}");
        }
    }
    let rod = rows(&dir, "rod.json");
    let t = |name: &str| row(&rod, name)["camera_t"].as_f64().unwrap();
    let crossing = 20.0 / 0.9;
    assert!((t("leading end on z = -9.75 at y = 0 (x)") - (crossing + 10.0)).abs() < 1e-9);
    assert!((t("infinite: leading end at row 120 (px)") - crossing).abs() < 1e-9);
    let az = 20f64.to_radians();
    let seen = (20.0 + 10.0 * az.tan()) / 0.9 + 10.0 / az.cos();
    assert!((t("at 20 deg: trailing end at row 120 (azimuth)") - seen).abs() < 1e-9);
}

/// Negative controls: the same scenes with a wrong camera time (the rod
/// not yet in view) or a wrong expectation (the rod's near end declared
/// where its far end makes the outline) fail those rows, and only those.
#[test]
fn wrong_times_and_wrong_expectations_fail() {
    let dir = scenes("scenes-fail");
    let early = ROD.replace(r#""t": "auto:rod" },"#, r#""t": 5 },"#);
    assert_ne!(early, ROD);
    std::fs::write(dir.join("early.json"), early).unwrap();
    let rows_early = rows(&dir, "early.json");
    let r = row(&rows_early, "leading end on z = -9.75 at y = 0 (x)");
    assert_eq!(r["pass"], false, "{r:#}");
    assert_eq!(
        row(&rows_early, "infinite: leading end at row 120 (px)")["pass"],
        true
    );
    let near = ROD.replace(
        "[[-2, -0.25, -0.25], [-2, 0.25, -0.25]]",
        "[[-2, -0.25, 0.25], [-2, 0.25, 0.25]]",
    );
    assert_ne!(near, ROD);
    std::fs::write(dir.join("near.json"), near).unwrap();
    let rows_near = rows(&dir, "near.json");
    let r = row(&rows_near, "at 20 deg: trailing end at row 120 (azimuth)");
    assert_eq!(r["pass"], false, "{r:#}");
    let late = BALL.replace(r#""t": "auto:ball""#, r#""t": 80"#);
    assert_ne!(late, BALL);
    std::fs::write(dir.join("late.json"), late).unwrap();
    let rows_late = rows(&dir, "late.json");
    assert_eq!(row(&rows_late, "crossing: outline radius")["pass"], false);
    assert_eq!(row(&rows_late, "-15 deg: outline width")["pass"], true);
}

/// A view's `t` that cannot be solved is an error at `views[i].t` with
/// what went wrong: a misspelt object (with the nearest name), a word that
/// is no time, an azimuth the object crosses only behind the camera.
#[test]
fn unsolvable_view_times_name_the_field() {
    let dir = scenes("scenes-errors");
    for (from, to, says) in [
        (
            r#""auto:rod" },"#,
            r#""auto:rods" },"#,
            "did you mean \"rod\"?",
        ),
        (r#""auto:rod" },"#, r#""soon" },"#, "\"auto:OBJECT\""),
        (
            r#""azimuth_deg": 20"#,
            r#""azimuth_deg": 180"#,
            "behind the camera",
        ),
        (
            r#""azimuth_deg": 20"#,
            r#""azimuth": 20"#,
            "unknown field `azimuth`",
        ),
    ] {
        let bad = ROD.replacen(from, to, 1);
        assert_ne!(bad, ROD);
        std::fs::write(dir.join("bad.json"), bad).unwrap();
        let run = vstf()
            .current_dir(&dir)
            .args(["check", "bad.json", "--quick"])
            .run();
        let field = if from.contains("azimuth") {
            "views[2].t"
        } else {
            "views[0].t"
        };
        run.fails_with(field).stderr_has(says);
    }
}

/// `vstf render` of `file` in `dir` at camera time `t` (`None`: the
/// fixture's own), small and quick.
fn render(dir: &Path, file: &str, t: Option<&str>) -> crate::support::Run {
    let mut c = vstf();
    c.current_dir(dir)
        .args(["render", file, "--out", "out.png", "--spp", "1"]);
    if let Some(t) = t {
        c.args(["--camera-t", t]);
    }
    c.run()
}

/// The sphere half in the image's left side (camera time 38) is in view:
/// no warning, and an outline check of that view measures it; at 36 it is
/// wholly outside, and the warning gives the camera time that shows it.
#[test]
fn half_an_object_is_in_view() {
    let dir = scenes("scenes-half");
    render(&dir, "ball.json", Some("38"))
        .succeeds()
        .stderr_lacks("out of view")
        .stderr_lacks("nothing is in view");
    render(&dir, "ball.json", Some("36"))
        .fails_with("nothing is in view")
        .stderr_has("\"ball\" is out of view")
        .stderr_has("try --camera-t auto:ball (t = 43.8");
    let half = BALL.replace(r#""t": "auto:ball""#, r#""t": 38"#);
    std::fs::write(dir.join("half.json"), half).unwrap();
    let rows = rows(&dir, "half.json");
    let r = row(&rows, "crossing: outline radius");
    assert_eq!(r["pass"], true, "{r:#}");
}

/// A camera looking away from the rod's path says so, naming
/// `camera.look_at` and `camera.vfov_deg` rather than a camera time, and
/// the render fails; a field of view in radians (0.7) and objects under a
/// pixel are warned of by field; the scene as written gets none of these.
#[test]
fn an_empty_or_unreadable_picture_names_the_field_to_change() {
    let dir = scenes("scenes-aim");
    render(&dir, "rod.json", Some("auto:rod"))
        .succeeds()
        .stderr_lacks("warning");
    let away = ROD.replace(r#""look_at": [0, 0, -10]"#, r#""look_at": [0, 0, 10]"#);
    assert_ne!(away, ROD);
    std::fs::write(dir.join("away.json"), away).unwrap();
    render(&dir, "away.json", Some("auto:rod"))
        .fails_with("nothing is in view")
        .stderr_has("point camera.look_at at the object's path or widen camera.vfov_deg")
        .stderr_lacks("try --camera-t");
    let radians = ROD.replace(r#""vfov_deg": 40"#, r#""vfov_deg": 0.7"#);
    std::fs::write(dir.join("radians.json"), radians).unwrap();
    render(&dir, "radians.json", Some("auto:rod"))
        .stderr_has("warning: camera.vfov_deg is 0.7: a field of view under 5 degrees");
    let checked = rows(&dir, "radians.json");
    let r = row(&checked, "at 20 deg: trailing end at row 120 (azimuth)");
    assert_eq!(r["pass"], false, "{r:#}");
    let error = r["error"].as_str().unwrap_or_default();
    assert!(error.contains("camera.vfov_deg is 0.7"), "{r:#}");
    let fine = rows(&dir, "rod.json");
    let error = row(&fine, "at 20 deg: trailing end at row 120 (azimuth)")
        .get("error")
        .cloned();
    assert_eq!(error, None);
    let tiny = ROD.replace(
        r#"{ "min": [-2, -0.25, -0.25], "max": [2, 0.25, 0.25] }"#,
        r#"{ "min": [-0.005, -0.005, -0.005], "max": [0.005, 0.005, 0.005] }"#,
    );
    assert_ne!(tiny, ROD);
    let tiny = tiny
        .split(r#"  "views""#)
        .next()
        .unwrap()
        .trim_end()
        .trim_end_matches(',');
    std::fs::write(dir.join("tiny.json"), format!("{tiny}\n}}\n")).unwrap();
    render(&dir, "tiny.json", Some("auto:rod"))
        .succeeds()
        .stderr_has("every object in view is smaller than a pixel");
}
