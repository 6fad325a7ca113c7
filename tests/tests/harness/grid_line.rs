//! The `grid_line` check kind (docs/checks.md): a grid texture's lines on a
//! plate moving at 0.9c are seen where the oracle puts them; a plate
//! rendered a little elsewhere, or not Lorentz-contracted, fails the rows
//! that see the difference; declarations without a grid line are refused
//! at their JSON path.

use workspace_tests::{declared_rows as rows, fixture, fixture_with};

#[test]
fn the_grid_plates_lines_are_where_the_oracle_sees_them() {
    let plate = fixture("grid-plate");
    let all = rows(&plate, &plate);
    assert_eq!(all.len(), 20);
    for r in &all {
        assert!(r.pass, "{r:?}");
    }
}

/// Rendered 0.05 l.units (about 1.6 px) further along: every centre fails.
#[test]
fn a_plate_rendered_elsewhere_fails_its_centre_rows() {
    let plate = fixture("grid-plate");
    let mut shifted = plate.clone();
    let renderer::Motion::Velocity { start, .. } = &mut shifted.scene.objects[0].motion else {
        panic!("the plate moves by velocity");
    };
    start.x.x += 0.05;
    for r in rows(&shifted, &plate) {
        if r.quantity.contains("centre") {
            assert!(!r.pass, "a 0.05 shift went unnoticed: {r:?}");
        }
    }
}

/// Rendered decoupled (its rest-frame grid uncontracted, 2.29 times wider
/// in the lab) but expected contracted: the spacing and width rows of the
/// relativistic views fail; the classical view contracts nothing in
/// either and still passes.
#[test]
fn an_uncontracted_grid_fails_its_spacing() {
    let plate = fixture("grid-plate");
    let mut decoupled = plate.clone();
    decoupled.scene.objects[0].kind = renderer::ObjectKind::HObj;
    for r in rows(&decoupled, &plate) {
        let relativistic = !r.quantity.starts_with("classical");
        if relativistic && (r.quantity.contains("spacing") || r.quantity.contains("width")) {
            assert!(!r.pass, "{r:?}");
        }
        if !relativistic {
            assert!(r.pass, "{r:?}");
        }
    }
}

#[test]
fn a_grid_line_check_needs_a_grid_line() {
    fn check(v: &mut serde_json::Value) -> &mut serde_json::Value {
        &mut v["checks"][0]["measure"]["grid_line"]
    }
    let refused = |edit: &dyn Fn(&mut serde_json::Value), expected: &str| {
        let file = workspace_tests::repo()
            .fixtures_dir()
            .join("grid-plate.json");
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        edit(&mut v);
        let e = vstf::Fixture::parse(&v.to_string(), &file)
            .unwrap_err()
            .to_string();
        assert!(e.contains(expected), "expected {expected:?} in:\n{e}");
    };
    refused(
        &|v| check(v)["points"] = serde_json::json!([[0.5, -1.5, 0], [0.5, 1.5, 0]]),
        "checks[0].measure.grid_line.points: not along a line",
    );
    refused(
        &|v| check(v)["points"] = serde_json::json!([[0, -1.5, 0], [0, 1.5, 2]]),
        "checks[0].measure.grid_line.points: not on the surface",
    );
    refused(
        &|v| {
            v["objects"][0]["material"]["texture"] = serde_json::json!(
                {"checkerboard": {"size": 1, "colors": [[0, 0, 0], [1, 1, 1]]}})
        },
        "checks[0].measure.grid_line.object: \"plate\" has no grid texture",
    );
    refused(
        &|v| {
            v["objects"][0]["material"]["texture"]["grid"]["color"] =
                serde_json::json!([0.85, 0.85, 0.8])
        },
        "checks[0].measure.grid_line.object: \"plate\"'s grid lines are read against its colour",
    );
    // The control: the fixture as it is loads.
    let _ = fixture_with("grid-plate", |_| {});
}
