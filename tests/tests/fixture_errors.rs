//! Bad fixtures get a clear error naming the file, the field and what was
//! expected; never a panic or a silently wrong picture.

use std::path::Path;
use vstf::fixture::Fixture;

/// The flange fixture with `edit` applied to its JSON.
fn flange_with(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let text = std::fs::read_to_string(vstf::fixture::fixtures_dir().join("flange.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    edit(&mut v);
    serde_json::to_string_pretty(&v).unwrap()
}

fn error_of(text: &str) -> String {
    match Fixture::parse(text, Path::new("fixtures/bad.json")) {
        Ok(_) => panic!("a bad fixture was accepted"),
        Err(e) => e.to_string(),
    }
}

fn flange_index(v: &serde_json::Value) -> usize {
    v["objects"]
        .as_array()
        .unwrap()
        .iter()
        .position(|o| o["name"] == "flange")
        .unwrap()
}

#[test]
fn the_unmodified_fixture_loads() {
    Fixture::parse(&flange_with(|_| {}), Path::new("fixtures/flange.json")).unwrap();
}

#[test]
fn a_v_obj_at_or_above_light_speed_is_refused_by_name() {
    for dx in [2000.0, 2400.0] {
        let e = error_of(&flange_with(|v| {
            let i = flange_index(v);
            v["objects"][i]["worldline"]["extrusion"] = serde_json::json!([2000.0, dx, 0.0, 0.0]);
        }));
        assert!(e.starts_with("fixtures/bad.json: objects["), "{e}");
        assert!(
            e.contains("worldline") && e.contains("\"flange\"") && e.contains("slower than light"),
            "{e}"
        );
    }
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
fn nan_and_out_of_range_numbers_name_the_field() {
    let text = flange_with(|_| {}).replacen("\"t\": 940.0", "\"t\": NaN", 1);
    let e = error_of(&text);
    assert!(e.starts_with("fixtures/bad.json: camera.t: "), "{e}");
    let text = flange_with(|_| {}).replacen("\"t\": 940.0", "\"t\": 1e999", 1);
    let e = error_of(&text);
    assert!(e.contains("camera.t") && e.contains("out of range"), "{e}");
}

#[test]
fn a_degenerate_triangle_is_refused() {
    let e = error_of(&flange_with(|v| {
        v["objects"][0]["mesh"] = serde_json::json!({"triangles": {"vertices": [[0,0,0],[1,0,0],[2,0,0]], "indices": [[0,1,2]]}});
    }));
    assert!(
        e.contains("objects[0].mesh") && e.contains("degenerate"),
        "{e}"
    );
}

#[test]
fn zero_duration_and_absurd_resolution_and_unknown_fields_are_refused() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["worldline"]["extrusion"] = serde_json::json!([0.0, 0.0, 0.0, 0.0]);
    }));
    assert!(
        e.contains("worldline") && e.contains("zero-duration"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| v["image"]["width"] = 100000.into()));
    assert!(
        e.contains(": image: resolution 100000x480 is out of range"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| v["image"]["height"] = 0.into()));
    assert!(e.contains(": image: resolution"), "{e}");
    let e = error_of(&flange_with(|v| v["camera"]["fov"] = 3.into()));
    assert!(
        e.contains("camera.fov: unknown field `fov`, expected one of"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        v["objects"][1]["material"]["color"] = "red".into()
    }));
    assert!(e.contains("objects[1].material.color: invalid type"), "{e}");
    let e = error_of(&flange_with(|v| v["model"] = "newtonian".into()));
    assert!(e.contains("model: unknown model \"newtonian\""), "{e}");
}

#[test]
fn worldline_needs_exactly_one_form() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["worldline"]["velocity"] = serde_json::json!([0.5, 0.0, 0.0]);
    }));
    assert!(e.contains("worldline: give either extrusion"), "{e}");
}

#[test]
fn obj_meshes_load_relative_to_the_fixture_and_report_bad_lines() {
    let dir = std::env::temp_dir().join(format!("vstf-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nf 1 2 3\n").unwrap();
    let with_obj = |file: &str| {
        flange_with(|v| {
            v["objects"][0]["mesh"] = serde_json::json!({"obj": {"path": file}});
        })
    };
    Fixture::parse(&with_obj("tri.obj"), &dir.join("ok.json")).unwrap();
    let e = Fixture::parse(&with_obj("bad.obj"), &dir.join("x.json"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("objects[0].mesh.obj.path") && e.contains("OBJ line 2"),
        "{e}"
    );
    let e = Fixture::parse(&with_obj("missing.obj"), &dir.join("x.json"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("cannot read"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_shipped_fixture_loads() {
    let names = vstf::fixture::all_names();
    assert!(names.contains(&"flange".to_string()));
    for name in names {
        Fixture::load(&name).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn a_camera_at_or_above_light_speed_is_refused() {
    let e = error_of(&flange_with(|v| {
        v["camera"]["velocity"] = serde_json::json!([0.8, 0.6, 0.0])
    }));
    assert!(
        e.contains("camera.velocity: the camera moves at 1.000000c; it must be slower than light"),
        "{e}"
    );
    Fixture::parse(
        &flange_with(|v| v["camera"]["velocity"] = serde_json::json!([0.5, 0.0, 0.0])),
        Path::new("fixtures/ok.json"),
    )
    .unwrap();
}
