//! Worldlines: objects at or beyond light speed, the forms a worldline
//! takes (extrusion, keyframes, hyperbolic motion), and validation that
//! agrees with building the database.

use super::{error_of, flange_index, flange_with};
use std::path::Path;
use vstf::fixture::Fixture;

#[test]
fn a_v_obj_at_or_above_light_speed_is_refused_by_name() {
    for dx in [2000.0, 2400.0] {
        let e = error_of(&flange_with(|v| {
            let i = flange_index(v);
            v["objects"][i]["worldline"]["extrusion"] = serde_json::json!([2000.0, dx, 0.0, 0.0]);
        }));
        assert!(e.starts_with("fixtures/bad.json: objects["), "{e}");
        assert!(
            e.contains("worldline.extrusion: ")
                && e.contains("\"flange\"")
                && e.contains("slower than light")
                && !e.contains("fractions of light speed"),
            "{e}"
        );
    }
}

/// A velocity in m/s is refused at `worldline.velocity`, with the reminder
/// that velocities are fractions of c; one just over c (the control) gets
/// the field but no reminder.
#[test]
fn a_velocity_in_metres_per_second_names_the_field_and_the_unit() {
    let moving = |speed: f64| {
        error_of(&flange_with(|v| {
            let i = flange_index(v);
            v["objects"][i]["worldline"] = serde_json::json!({
                "start": [0.0, -8.0, 0.0, 0.0],
                "velocity": [speed, 0.0, 0.0],
                "proper_lifetime": 50.0
            });
        }))
    };
    let e = moving(270_000_000.0);
    assert!(
        e.contains("].worldline.velocity: ") && e.contains("moves at 270000000.000000c"),
        "{e}"
    );
    assert!(
        e.contains("velocities are fractions of light speed (c = 1), not m/s"),
        "{e}"
    );
    let e = moving(1.2);
    assert!(
        e.contains("].worldline.velocity: ") && e.contains("slower than light"),
        "{e}"
    );
    assert!(!e.contains("fractions of light speed"), "{e}");
    let e = error_of(&flange_with(|v| {
        v["camera"]["velocity"] = serde_json::json!([0.0, 0.0, -3.0e5])
    }));
    assert!(
        e.contains("camera.velocity: ") && e.contains("fractions of light speed"),
        "{e}"
    );
}

#[test]
fn a_superluminal_h_obj_is_allowed() {
    let text = flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["kind"] = "H_obj".into();
        v["objects"][i]["worldline"]["extrusion"] = serde_json::json!([20.0, 40.0, 0.0, 0.0]);
    });
    Fixture::parse(&text, Path::new("fixtures/fast.json")).unwrap();
}

#[test]
fn worldline_needs_exactly_one_form() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["worldline"]["velocity"] = serde_json::json!([0.5, 0.0, 0.0]);
    }));
    assert!(e.contains("worldline: give one of: extrusion"), "{e}");
}

/// The flange given keyframes instead of its worldline.
fn keyframed(kind: &str, frames: serde_json::Value) -> String {
    flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["kind"] = kind.into();
        v["objects"][i]["worldline"] = serde_json::json!({ "keyframes": frames });
    })
}

#[test]
fn keyframes_load_and_out_of_order_ones_are_refused() {
    let good = serde_json::json!([
        { "t": 0, "position": [0, 0, 0] },
        { "t": 10, "position": [5, 0, 0], "rotation": { "axis": [0, 1, 0], "degrees": 20 } },
        { "t": 20, "position": [6, 0, 0] }
    ]);
    Fixture::parse(&keyframed("V_obj", good), Path::new("fixtures/k.json")).unwrap();
    let e = error_of(&keyframed(
        "H_obj",
        serde_json::json!([
            { "t": 0, "position": [0, 0, 0] },
            { "t": 10, "position": [1, 0, 0] },
            { "t": 5, "position": [2, 0, 0] }
        ]),
    ));
    assert!(
        e.contains("worldline.keyframes[2].t") && e.contains("out of time order"),
        "{e}"
    );
    let e = error_of(&keyframed(
        "H_obj",
        serde_json::json!([{ "t": 0, "position": [0, 0, 0] }]),
    ));
    assert!(e.contains("at least 2"), "{e}");
}

#[test]
fn a_keyframed_v_obj_whose_vertices_outrun_light_is_refused() {
    // The reference point moves at 0.5c, but the flange (2 wide) turns half
    // a revolution in 2 t.units: its far corner moves faster than light.
    let frames = serde_json::json!([
        { "t": 0, "position": [0, 0, 0] },
        { "t": 2, "position": [1, 0, 0], "rotation": { "axis": [0, 1, 0], "degrees": 180 } }
    ]);
    let e = error_of(&keyframed("V_obj", frames.clone()));
    assert!(
        e.contains("worldline.keyframes[1]")
            && e.contains("vertex")
            && e.contains("slower than light"),
        "{e}"
    );
    Fixture::parse(&keyframed("H_obj", frames), Path::new("fixtures/k.json")).unwrap();
    let e = error_of(&keyframed(
        "V_obj",
        serde_json::json!([
            { "t": 0, "position": [0, 0, 0] },
            { "t": 1, "position": [1.5, 0, 0] }
        ]),
    ));
    assert!(e.contains("slower than light"), "{e}");
}

#[test]
fn bad_hyperbolic_motion_names_the_field() {
    let with = |h: serde_json::Value, start: bool| {
        flange_with(|v| {
            let i = flange_index(v);
            let mut w = serde_json::json!({ "hyperbolic": h });
            if start {
                w["start"] = serde_json::json!([0, -8, 0, 0]);
            }
            v["objects"][i]["worldline"] = w;
        })
    };
    let ok = serde_json::json!({ "acceleration": [0.1, 0, 0], "duration": 20 });
    Fixture::parse(&with(ok.clone(), true), Path::new("fixtures/h.json")).unwrap();
    let e = error_of(&with(ok, false));
    assert!(
        e.contains("worldline.start") && e.contains("missing"),
        "{e}"
    );
    let e = error_of(&with(
        serde_json::json!({ "acceleration": [0, 0, 0], "duration": 20 }),
        true,
    ));
    assert!(e.contains("hyperbolic.acceleration"), "{e}");
    let e = error_of(&with(
        serde_json::json!({ "acceleration": [0.1, 0, 0], "duration": 20, "initial_velocity": 1.0 }),
        true,
    ));
    assert!(
        e.contains("hyperbolic.initial_velocity") && e.contains("slower than light"),
        "{e}"
    );
    let e = error_of(&with(
        serde_json::json!({ "acceleration": [0.1, 0, 0], "duration": 20, "tolerance": 1e-15 }),
        true,
    ));
    assert!(
        e.contains("hyperbolic.tolerance") && e.contains("keyframes"),
        "{e}"
    );
    // Born rigidity needs every point in front of the horizon, 1/a behind
    // the reference point: accelerated along -x at 2, the flange (x in
    // [0, 2]) reaches 2 l.units behind its reference point, beyond 1/a = 0.5.
    let e = error_of(&with(
        serde_json::json!({ "acceleration": [-2.0, 0, 0], "duration": 2 }),
        true,
    ));
    assert!(e.contains("horizon"), "{e}");
    // In front of the horizon, but nearer it than the first level of the
    // cut of its curved surface (about 1.15 times the tolerance): 1e-5 in
    // front at the default tolerance 1e-4. The error names the tolerance
    // and a finer one that would allow it (the unit test of the cut builds
    // with it).
    let near = serde_json::json!({ "acceleration": [-1.0 / (2.0 + 1e-5), 0, 0], "duration": 2 });
    let e = error_of(&with(near, true));
    assert!(
        e.contains("hyperbolic.tolerance") && e.contains("too near it"),
        "{e}"
    );
    let limit: f64 = e
        .rsplit("a tolerance below ")
        .next()
        .unwrap()
        .split(|c: char| c.is_whitespace() || c == ';')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(limit > 0.0 && limit < 1e-4, "{e}");
}

#[test]
fn validation_without_the_acceleration_structure_agrees_with_building() {
    use renderer::Database;
    let good = Fixture::parse(&flange_with(|_| {}), Path::new("fixtures/flange.json")).unwrap();
    for lorentz in [false, true] {
        assert!(Database::validate(&good.scene, lorentz).is_ok());
        assert!(Database::build(&good.scene, lorentz).is_ok());
    }
    // A V_obj past light speed: refused the same way by both.
    let mut fast = good.scene.clone();
    let i = fast
        .objects
        .iter()
        .position(|o| o.name == "flange")
        .unwrap();
    fast.objects[i].kind = renderer::ObjectKind::VObj;
    if let renderer::Motion::Extrusion { extrusion, .. } = &mut fast.objects[i].motion {
        extrusion.x.x = 1.5 * extrusion.t;
    } else {
        panic!("the flange moves by extrusion");
    }
    let (validated, built) = (
        Database::validate(&fast, true).unwrap_err(),
        Database::build(&fast, true).err().unwrap(),
    );
    assert_eq!(validated, built);
    assert_eq!(validated.object, i);
}
