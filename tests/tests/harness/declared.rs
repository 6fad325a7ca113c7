//! Declared checks (docs/checks.md): declarations that refer to what the
//! fixture does not have are refused at load with the file and JSON path;
//! an edge the view does not show is a failing row with its reason, never a
//! pass, and fails alone; a scene
//! rendered elsewhere than its declaration says fails its rows. (Moving
//! scenes' declarations in `declared_motion`.)

use std::path::Path;
use vstf::check::{self, Effort};
use vstf::fixture::Fixture;
use workspace_tests::declared_rows as rows;

/// The example of `vstf init`: a cube at 0.8c with a check of every general kind.
fn cube_text() -> String {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../vstf/src/cli/init-moving-cube.json");
    std::fs::read_to_string(file).unwrap()
}

/// The cube fixture with `edit` applied to its JSON.
fn cube_with(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut v: serde_json::Value = serde_json::from_str(&cube_text()).unwrap();
    edit(&mut v);
    serde_json::to_string_pretty(&v).unwrap()
}

fn parse(text: &str) -> Result<Fixture, String> {
    Fixture::parse(text, Path::new("fixtures/cube.json")).map_err(|e| e.to_string())
}

/// A change to a fixture's JSON.
type Edit = dyn FnOnce(&mut serde_json::Value);

/// Each edit must be refused at load with its message, naming the file.
fn assert_refused(cases: Vec<(Box<Edit>, &str)>) {
    for (edit, expected) in cases {
        let e = match parse(&cube_with(edit)) {
            Ok(_) => panic!("accepted; expected {expected:?}"),
            Err(e) => e,
        };
        assert!(e.contains(expected), "expected {expected:?} in:\n{e}");
        assert!(e.starts_with("fixtures/cube.json: "), "{e}");
    }
}

#[test]
fn bad_edge_declarations_name_the_file_and_json_path() {
    assert_refused(vec![
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["object"] = "nope".into()),
            "fixtures/cube.json: checks[0].measure.edge.object: no object named \"nope\"",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["view"] = "t = 99".into()),
            "checks[0].measure.edge.view: no view named \"t = 99\"",
        ),
        (
            Box::new(|v| {
                v["checks"][2]["measure"]["edge"]["points"] =
                    serde_json::json!([[-1.0, -1.0, -1.0], [-1.0, 0.0, 0.0]])
            }),
            "checks[2].measure.edge.points: not along an edge of \"trailing face\"'s mesh",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["vertices"] = serde_json::json!([0, 9])),
            "checks[0].measure.edge.vertices[1]: no vertex 9: `vertices` count from 0, and the mesh has 4 vertices (0 to 3); an OBJ file's faces count from 1: give those as `obj_index`",
        ),
        (
            Box::new(|v| {
                let e = v["checks"][0]["measure"]["edge"].as_object_mut().unwrap();
                e.remove("vertices");
                e.insert("obj_index".into(), serde_json::json!([0, 4]));
            }),
            "checks[0].measure.edge.obj_index[0]: no vertex 0: `obj_index` counts from 1, as an OBJ file's faces do, and the mesh has 4 vertices (1 to 4)",
        ),
        (
            Box::new(|v| {
                let e = v["checks"][0]["measure"]["edge"].as_object_mut().unwrap();
                e.remove("vertices");
                e.insert("obj_index".into(), serde_json::json!([1, 5]));
            }),
            "checks[0].measure.edge.obj_index[1]: no vertex 5: `obj_index` counts from 1",
        ),
        (
            Box::new(|v| {
                let e = v["checks"][0]["measure"]["edge"].as_object_mut().unwrap();
                e.remove("vertices");
                e.insert("obj_index".into(), serde_json::json!([1, 3]));
            }),
            "checks[0].measure.edge.obj_index: obj_index 1 and 3 (counted from 1, as in an OBJ file): not along an edge",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["vertices"] = serde_json::json!([0, 2])),
            "checks[0].measure.edge.vertices: vertices 0 and 2 (counted from 0): not along an edge",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["obj_index"] = serde_json::json!([1, 4])),
            "checks[0].measure.edge.points: give the edge's ends once: as points, as vertices (counted from 0) or as obj_index (counted from 1, as in an OBJ file)",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["at"] = serde_json::json!({"row": 240})),
            "checks[0].measure.edge.at.row: row 240 is outside the 320x240 image of view \"t = 10\"",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["side"] = "top".into()),
            "checks[0].measure.edge.side: rows and planes are scanned from the left or the right",
        ),
        (
            Box::new(|v| {
                v["checks"][0]["measure"]["edge"]["at"] = serde_json::json!({"plane": {"z": 1.0}})
            }),
            "checks[0].measure.edge.at: give plane, level and read together, or row, or column",
        ),
        (
            Box::new(|v| v["checks"][4]["measure"]["difference"][1] = "later".into()),
            "checks[4].measure.difference[1]: no earlier check named \"later\"",
        ),
        (
            Box::new(|v| v["checks"][0]["tolerance"] = serde_json::json!({"add": 0.5})),
            "checks[0].tolerance.reason: loosening a derived tolerance (add) needs a stated reason",
        ),
        (
            Box::new(|v| v["views"][1]["t"] = 10.0.into()),
            "checks[12].measure.velocity: the two checks' views have the same camera time",
        ),
        (
            Box::new(|v| v["views"][1]["name"] = "t = 10".into()),
            "views[1].name: view name \"t = 10\" is empty or used twice",
        ),
        (
            Box::new(|v| v["checks"][1]["name"] = v["checks"][0]["name"].clone()),
            "checks[1].name: check name",
        ),
    ]);
}

/// `obj_index` counts from 1, as an OBJ file does: the edge given as
/// `obj_index` [1, 4] is the one `vertices` [0, 3] gives, measured the same.
#[test]
fn obj_index_is_vertices_counted_from_one() {
    let with_index = parse(&cube_with(|v| {
        let e = v["checks"][0]["measure"]["edge"].as_object_mut().unwrap();
        e.remove("vertices");
        e.insert("obj_index".into(), serde_json::json!([1, 4]));
    }))
    .unwrap();
    let plain = parse(&cube_text()).unwrap();
    let (a, b) = (rows(&with_index, &with_index), rows(&plain, &plain));
    assert_eq!(
        (a[0].measured, a[0].expected),
        (b[0].measured, b[0].expected)
    );
    assert!(a[0].pass, "{:?}", a[0]);
    // Control: the numbers [1, 2] as `vertices` name another edge (the
    // right one), and the row scanning for the left edge fails.
    let shifted = parse(&cube_with(|v| {
        v["checks"][0]["measure"]["edge"]["vertices"] = serde_json::json!([1, 2])
    }))
    .unwrap();
    let other = &rows(&shifted, &shifted)[0];
    assert_ne!(other.expected, b[0].expected);
    assert!(!other.pass, "{other:?}");
}

#[test]
fn bad_declarations_of_other_kinds_name_the_file_and_json_path() {
    assert_refused(vec![
        (
            Box::new(|v| {
                v["checks"][0]["measure"] = serde_json::json!({"outline":
                    {"view": "t = 10", "object": "front face", "read": "radius"}})
            }),
            "checks[0].measure.outline.object: \"front face\" is a mesh: outlines are expected for analytic spheres",
        ),
        (
            Box::new(|v| {
                v["checks"][0]["measure"] = serde_json::json!({"doppler":
                    {"view": "t = 10", "object": "front face", "from": "colour"}})
            }),
            "checks[0].measure.doppler.object: \"front face\" does not glow as a blackbody",
        ),
        (
            Box::new(|v| {
                v["checks"][0]["measure"] = serde_json::json!({"period":
                    {"view": "t = 10", "object": "front face", "from": 0.0, "to": 1.0, "step": 0.1}})
            }),
            "checks[0].measure.period.object: \"front face\" does not blink",
        ),
        (
            Box::new(|v| v["checks"][8]["measure"]["corner"]["columns"]["points"] = serde_json::json!([[1.0, 1.0, 1.0], [-1.0, 1.0, 1.0]])),
            "checks[8].measure.corner.columns.points: both edges must start at the same corner",
        ),
        (
            Box::new(|v| v["checks"][8]["measure"]["corner"]["columns"]["side"] = "left".into()),
            "checks[8].measure.corner.columns.side: columns are scanned from the top or the bottom",
        ),
        (
            Box::new(|v| {
                v["checks"][10]["measure"]["edge"]["at"]["report"] = "angle".into()
            }),
            "checks[10].measure.edge.at.report: a plane reading is reported in l.units",
        ),
        (
            Box::new(|v| {
                let (a, b) = (v["checks"][10]["name"].clone(), v["checks"][0]["name"].clone());
                v["checks"][12]["measure"] = serde_json::json!({"difference": [a, b]});
            }),
            "checks[12].measure.difference[1]: \"leading edge on the plane z = 1 at y = 0, t = 10 (x)\" is in Length and \"front face, left edge at row 120 (px)\" in Pixels"),
        (
            Box::new(|v| v["views"][0]["spp"] = 8.into()),
            "views[0].spp: expected a square number of samples",
        ),
        (
            Box::new(|v| {
                v["checks"][0]["paper"] = 1.0.into();
                v["checks"][0]["measure"] = serde_json::json!({"named": {"relativity": {}}});
            }),
            "checks[0].paper: a named kind gives its rows' paper figures and tolerances itself",
        ),
        (
            Box::new(|v| {
                v["camera"]["velocity"] = serde_json::json!([0.1, 0.0, 0.0]);
                v["checks"][0]["measure"] = serde_json::json!({"doppler":
                    {"view": "t = 10", "object": "front face", "from": "colour"}});
            }),
            "checks[0].measure.doppler.view: doppler checks expect a camera at rest",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["colour"] = "red".into()),
            "checks[0].measure.edge.colour: unknown field `colour`",
        ),
    ]);
}

#[test]
fn the_example_passes_every_row_and_a_wrong_side_fails_its_row() {
    let cube = parse(&cube_text()).unwrap();
    let honest = rows(&cube, &cube);
    assert_eq!(honest.len(), 14);
    assert!(
        honest.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&honest)
    );
    // Negative control: the left edge declared as seen from the right is
    // measured where the right edge is, and fails.
    let wrong = parse(&cube_with(|v| {
        v["checks"][0]["measure"]["edge"]["side"] = "right".into()
    }))
    .unwrap();
    let r = &rows(&wrong, &wrong)[0];
    assert!(!r.pass, "{r:?}");
    assert_abs_diff_eq!(r.measured, honest[1].measured, epsilon = 1e-9);
}

/// Mutation: the cube rendered 0.01 l.units further along its motion than
/// its declaration puts it. Every row of a position along the motion fails;
/// positions across it (the top edge, the corner's y) and the combinations
/// that cancel a common shift (widths, their ratio, the velocity) still pass.
#[test]
fn a_cube_rendered_a_hundredth_elsewhere_fails_its_edge_rows() {
    let cube = parse(&cube_text()).unwrap();
    let mut shifted = cube.clone();
    for o in &mut shifted.scene.objects {
        let renderer::Motion::Extrusion { start, .. } = &mut o.motion else {
            panic!("the cube moves by extrusion");
        };
        start.x.x += 0.01;
    }
    let moved = rows(&shifted, &cube);
    let along = [
        "left edge",
        "right edge",
        "corner (x",
        "leading edge on the plane",
    ];
    for r in &moved {
        if along.iter().any(|a| r.quantity.contains(a)) {
            assert!(!r.pass, "a 0.01 shift went unnoticed: {r:?}");
        } else {
            assert!(r.pass, "{r:?}");
        }
    }
}

/// A misspelt object, view or earlier check is refused with the nearest
/// name as a hint; a name near none (the control) gets no hint.
#[test]
fn misspelt_names_in_checks_get_a_did_you_mean() {
    assert_refused(vec![
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["object"] = "frnt face".into()),
            "checks[0].measure.edge.object: no object named \"frnt face\"; did you mean \"front face\"? (objects: front face, trailing face)",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["edge"]["view"] = "t=10".into()),
            "checks[0].measure.edge.view: no view named \"t=10\" in views; did you mean \"t = 10\"?",
        ),
        (
            Box::new(|v| {
                v["checks"][4]["measure"]["difference"][1] =
                    "front face, left edge at row 12 (px)".into()
            }),
            "no earlier check named \"front face, left edge at row 12 (px)\"; did you mean \"front face, left edge at row 120 (px)\"?",
        ),
    ]);
    let e = parse(&cube_with(|v| {
        v["checks"][0]["measure"]["edge"]["object"] = "nope".into()
    }))
    .err()
    .unwrap();
    assert!(!e.contains("did you mean"), "{e}");
}

/// An edge the view does not show (the cube has long left the picture) is
/// a failing row with the reason, naming the check, never a pass.
#[test]
fn an_edge_out_of_view_is_a_failing_row_not_a_pass() {
    for check in [0, 8] {
        let late = parse(&cube_with(|v| {
            v["views"][0]["t"] = 60.0.into();
            let keep = v["checks"][check].clone();
            v["checks"] = serde_json::json!([keep]);
        }))
        .unwrap();
        let found = check::run_fixture(&late, &Effort::QUICK).unwrap_or_else(|e| panic!("{e}"));
        let row = found.quantities[0].clone().judge("cube");
        assert!(!row.pass, "an unseen edge passed: {row:?}");
        let error = row.error.as_deref().unwrap_or_default();
        assert!(error.starts_with("checks[0]: "), "{row:?}");
    }
}

/// The cube's left and right edges and the width between them, the right
/// edge measured in `view`.
fn good_and_bad(view: &'static str) -> Fixture {
    parse(&cube_with(|v| {
        v["views"]
            .as_array_mut()
            .unwrap()
            .push(serde_json::json!({"name": "late", "t": 60.0}));
        v["checks"][1]["measure"]["edge"]["view"] = view.into();
        let keep = [0, 1, 4].map(|i| v["checks"][i].clone());
        v["checks"] = serde_json::json!(keep);
    }))
    .unwrap()
}

/// One check that cannot be measured fails alone: the check before it is
/// measured and passes, it fails with its reason, and the difference that
/// uses it fails naming it. The control: measured in a view that shows the
/// cube, all three pass with no error.
#[test]
fn a_check_that_cannot_be_measured_fails_alone() {
    let f = good_and_bad("late");
    let r = rows(&f, &f);
    let table = vstf::report::table(&r);
    assert!(r[0].pass && r[0].error.is_none(), "{table}");
    assert!(!r[1].pass, "{table}");
    let error = r[1].error.as_deref().unwrap_or_default();
    assert!(
        error.starts_with("checks[1]: ") && error.contains("not visible in view \"late\""),
        "{table}"
    );
    assert!(table.contains(&format!("  error: {error}")), "{table}");
    let error = r[2].error.as_deref().unwrap_or_default();
    assert!(!r[2].pass, "{table}");
    assert!(
        error.starts_with("checks[2]: depends on \"front face, right edge at row 120 (px)\""),
        "{table}"
    );
    let json: serde_json::Value = serde_json::from_str(&vstf::report::json(&r)).unwrap();
    assert!(json[0].get("error").is_none(), "{json}");
    assert_eq!(json[1]["measured"], serde_json::Value::Null, "{json}");
    let back: Vec<vstf::Row> = serde_json::from_value(json).unwrap();
    assert_eq!(back[1].error, r[1].error);
    let control = good_and_bad("t = 10");
    let r = rows(&control, &control);
    assert!(
        r.iter().all(|r| r.pass && r.error.is_none()),
        "{}",
        vstf::report::table(&r)
    );
}

/// A declaration may tighten a tolerance, and loosen it only with a reason;
/// both show in the row.
#[test]
fn declared_tolerances_tighten_or_loosen_with_a_reason() {
    let base = rows(&parse(&cube_text()).unwrap(), &parse(&cube_text()).unwrap())[0].tolerance;
    let tight = parse(&cube_with(|v| {
        v["checks"][0]["tolerance"] = serde_json::json!({"at_most": 1e-9})
    }))
    .unwrap();
    let r = &rows(&tight, &tight)[0];
    assert_eq!(r.tolerance, 1e-9);
    assert!(
        !r.pass,
        "a tolerance below the measurement's resolution should fail: {r:?}"
    );
    let loose = parse(&cube_with(|v| {
        v["checks"][0]["tolerance"] = serde_json::json!({"add": 0.5, "reason": "a test"})
    }))
    .unwrap();
    assert_abs_diff_eq!(
        rows(&loose, &loose)[0].tolerance,
        base + 0.5,
        epsilon = 1e-12
    );
}
