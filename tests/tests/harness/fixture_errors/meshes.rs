//! Meshes: degenerate triangles, OBJ files (relative paths, bad lines,
//! byte order marks, FIFOs), and the memory budget a scene's prisms are
//! estimated against before anything is built.

use super::{error_of, flange_with};
use std::path::{Path, PathBuf};
use vstf::fixture::Fixture;

/// The flange fixture whose first object is the OBJ file at `path`.
fn flange_with_obj(path: &str) -> String {
    flange_with(|v| v["objects"][0]["mesh"] = serde_json::json!({"obj": {"path": path}}))
}

/// A fresh, empty scratch folder for OBJ files and the fixtures naming them.
fn obj_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vstf-obj-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
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
fn obj_meshes_load_relative_to_the_fixture_and_report_bad_lines() {
    let dir = obj_dir("lines");
    std::fs::write(dir.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nf 1 2 3\n").unwrap();
    Fixture::parse(&flange_with_obj("tri.obj"), &dir.join("ok.json")).unwrap();
    let e = Fixture::parse(&flange_with_obj("bad.obj"), &dir.join("x.json"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("objects[0].mesh.obj.path") && e.contains("OBJ line 2"),
        "{e}"
    );
    let e = Fixture::parse(&flange_with_obj("missing.obj"), &dir.join("x.json"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("cannot read"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A fixture in a scratch folder whose first object is the OBJ file
/// `mesh.obj` (written beside it by `make`), parsed.
fn with_obj(name: &str, make: impl FnOnce(&Path)) -> Result<Fixture, String> {
    let dir = obj_dir(name);
    make(&dir.join("mesh.obj"));
    let result = Fixture::parse(&flange_with_obj("mesh.obj"), &dir.join("scene.json"))
        .map_err(|e| e.to_string());
    std::fs::remove_dir_all(&dir).ok();
    result
}

#[test]
fn an_obj_with_a_byte_order_mark_keeps_its_first_vertex() {
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    let f = with_obj("bom", |p| {
        std::fs::write(p, format!("\u{feff}{quad}")).unwrap()
    })
    .unwrap();
    let plain = with_obj("plain", |p| std::fs::write(p, quad).unwrap()).unwrap();
    assert_eq!(f.scene.objects[0].shape, plain.scene.objects[0].shape);
}

#[test]
fn an_obj_path_naming_a_fifo_is_refused_not_read() {
    let e = with_obj("fifo", |p| {
        let made = std::process::Command::new("mkfifo").arg(p).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    })
    .unwrap_err();
    assert!(
        e.contains("objects[0].mesh.obj.path") && e.contains("not a regular file"),
        "{e}"
    );
}

/// A scene whose database would not fit the memory budget is refused at
/// load, with its estimate, before anything is built: a finely tessellated
/// sphere through ten keyframes (10 million keyframe prisms, about 10 GB).
#[test]
fn a_database_over_the_memory_budget_is_refused_with_its_estimate() {
    let keyframes: Vec<serde_json::Value> = (0..11)
        .map(
            |k| serde_json::json!({"t": f64::from(k), "position": [0.01 * f64::from(k), 0.0, 0.0]}),
        )
        .collect();
    let text = flange_with(|v| {
        v["objects"] = serde_json::json!([{"name": "ball", "mesh": {"sphere": {"radius": 1.0, "segments": 1024}},
            "worldline": {"keyframes": keyframes}, "material": {"color": [0.5, 0.5, 0.5]}}]);
    });
    let started = std::time::Instant::now();
    let e = error_of(&text);
    assert!(
        e.contains("fixtures/bad.json: objects: about 10465280 prisms")
            && e.contains("10465280 of them keyframe intervals'")
            && e.contains("over the budget of 8.0 GB")
            && e.contains("--force"),
        "{e}"
    );
    assert!(
        started.elapsed().as_secs() < 20,
        "the estimate took as long as a build"
    );
    let e = error_of(&flange_with(|v| {
        v["objects"][0]["mesh"] = serde_json::json!({"sphere": {"radius": 1.0, "segments": 4096}})
    }));
    assert!(e.contains("sphere.segments 4096: expected 4..=1024"), "{e}");
    let e = error_of(&flange_with(
        |v| v["objects"][0]["mesh"] = serde_json::json!({"bar_grid": {"count": 4000000000u32, "spacing": 1.0, "first": 0.0, "thickness": 0.1, "y": 0.0}}),
    ));
    assert!(
        e.contains("bar_grid.count 4000000000: expected 1..=10000"),
        "{e}"
    );
}

/// The memory budget's estimate of the prisms is never below what the
/// database holds, for every kind of motion (uniform, keyframed, hyperbolic
/// H_obj and Born-rigid V_obj) and either model, and not far above the
/// larger of the two (a Born-rigid V_obj, cut into many more triangles than
/// the same mesh inserted without the Lorentz transform, sets it).
#[test]
fn the_prism_estimate_bounds_the_database() {
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        let p = vstf::prisms(&f.scene);
        let estimate = p.translated + p.keyframed;
        let built = [false, true].map(|lorentz| f.database(lorentz).unwrap().prism_count() as u64);
        for b in built {
            assert!(estimate >= b, "{name}: estimate {estimate} < {b}");
        }
        let most = built[0].max(built[1]);
        assert!(
            estimate <= 2 * most.max(1),
            "{name}: estimate {estimate} >> {most}"
        );
    }
}
