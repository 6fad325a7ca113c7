//! Per-face materials: a cube as one object with a colour per face, from
//! the fixture's `materials` and `faces` or from an OBJ file's `usemtl`
//! groups with the `Kd` colours of its `.mtl`; misuse named at its field.

use std::path::{Path, PathBuf};
use vstf::fixture::Fixture;
use vstf::Overrides;

/// The six faces' colours, in the order of a cuboid's faces (-x, +x, -y,
/// +y, -z, +z); each is triangles 2k and 2k + 1 of `Mesh::cuboid`.
const COLOURS: [(&str, [f64; 3]); 6] = [
    ("red", [1.0, 0.0, 0.0]),
    ("green", [0.0, 1.0, 0.0]),
    ("blue", [0.0, 0.0, 1.0]),
    ("yellow", [1.0, 1.0, 0.0]),
    ("cyan", [0.0, 1.0, 1.0]),
    ("magenta", [1.0, 0.0, 1.0]),
];

/// The object's own material (material 0): grey.
const GREY: [f64; 3] = [0.5, 0.5, 0.5];

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vstf-faces-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    dir
}

/// A fixture of one unit cube seen from above its +x, +y, +z corner,
/// without a light (flat colours), the object's fields given by `object`.
fn text(object: serde_json::Value) -> String {
    let mut o = serde_json::json!({"name": "cube", "material": {"unlit": GREY}});
    for (k, v) in object.as_object().unwrap() {
        o[k] = v.clone();
    }
    serde_json::json!({
        "camera": {"position": [3.0, 2.5, 4.0], "t": 0, "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40},
        "model": "relativistic",
        "image": {"width": 80, "height": 60, "spp": 1},
        "objects": [o]
    })
    .to_string()
}

fn load(dir: &Path, object: serde_json::Value) -> Result<Fixture, String> {
    Fixture::parse(&text(object), &dir.join("fixtures/cube.json")).map_err(|e| e.to_string())
}

fn image(f: &Fixture) -> Vec<glam::DVec3> {
    let view = vstf::run::view(f, &Overrides::default()).unwrap();
    vstf::run::render(f, &view, renderer::Traversal::Bvh)
        .unwrap()
        .pixels
}

/// How many pixels are `c` (to the rounding of an emitted colour's
/// round trip through its spectrum, 1e-12).
fn count(pixels: &[glam::DVec3], c: [f64; 3]) -> usize {
    let c = glam::DVec3::from_array(c);
    pixels
        .iter()
        .filter(|p| (**p - c).abs().max_element() < 1e-12)
        .count()
}

fn json_materials() -> serde_json::Value {
    let mut m = serde_json::Map::new();
    for (name, c) in COLOURS {
        m.insert(name.into(), serde_json::json!({"unlit": c}));
    }
    serde_json::Value::Object(m)
}

fn json_faces() -> serde_json::Value {
    let mut m = serde_json::Map::new();
    for (k, (name, _)) in COLOURS.iter().enumerate() {
        m.insert((*name).into(), serde_json::json!([2 * k, 2 * k + 1]));
    }
    serde_json::Value::Object(m)
}

fn cube() -> serde_json::Value {
    serde_json::json!({"cuboid": {"min": [-1, -1, -1], "max": [1, 1, 1]}})
}

/// Each face seen shows its own colour and no other face's: the camera
/// sees +x, +y and +z (green, yellow, magenta), never the others, and no
/// pixel is the object's own grey. Control: without `faces` the cube is
/// grey all over.
#[test]
fn a_cube_shows_a_colour_per_face() {
    let dir = scratch("json");
    let f = load(
        &dir,
        serde_json::json!({"mesh": cube(), "materials": json_materials(), "faces": json_faces()}),
    )
    .unwrap();
    let px = image(&f);
    for (name, c) in COLOURS {
        let n = count(&px, c);
        let seen = matches!(name, "green" | "yellow" | "magenta");
        assert!(if seen { n > 100 } else { n == 0 }, "{name}: {n} pixels");
    }
    assert_eq!(count(&px, GREY), 0);
    let plain = image(&load(&dir, serde_json::json!({"mesh": cube()})).unwrap());
    assert!(count(&plain, GREY) > 600, "{}", count(&plain, GREY));
    assert_eq!(count(&plain, COLOURS[1].1), 0);
    std::fs::remove_dir_all(&dir).ok();
}

/// The same cube as an OBJ file with `usemtl` groups and the colours as
/// `Kd` in its `.mtl` renders bit for bit as the fixture's `materials` and
/// `faces` (an unlit object material takes the `Kd` as its flat colour).
#[test]
fn obj_usemtl_with_mtl_colours_renders_as_json_faces() {
    let dir = scratch("obj");
    let mesh = renderer::Mesh::cuboid(glam::DVec3::splat(-1.0), glam::DVec3::splat(1.0));
    let mut obj = String::from("mtllib colours.mtl\n");
    for v in &mesh.vertices {
        obj += &format!("v {:?} {:?} {:?}\n", v.x, v.y, v.z);
    }
    let mut mtl = String::new();
    for (k, (name, c)) in COLOURS.iter().enumerate() {
        obj += &format!("usemtl {name}\n");
        for t in [2 * k, 2 * k + 1] {
            let [a, b, c] = mesh.triangles[t].map(|i| i + 1);
            obj += &format!("f {a} {b} {c}\n");
        }
        mtl += &format!("newmtl {name}\nKa 0 0 0\nKd {} {} {}\n", c[0], c[1], c[2]);
    }
    let fixtures = dir.join("fixtures");
    std::fs::write(fixtures.join("cube.obj"), &obj).unwrap();
    std::fs::write(fixtures.join("colours.mtl"), &mtl).unwrap();
    let from_obj = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "cube.obj"}}}),
    )
    .unwrap();
    let from_json = load(
        &dir,
        serde_json::json!({"mesh": cube(), "materials": json_materials(), "faces": json_faces()}),
    )
    .unwrap();
    let px = image(&from_obj);
    assert!(
        px == image(&from_json),
        "the OBJ's faces are coloured otherwise"
    );
    // A byte-order mark before its first statement changes nothing.
    std::fs::write(fixtures.join("bom.obj"), format!("\u{feff}{obj}")).unwrap();
    let bom = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "bom.obj"}}}),
    )
    .unwrap();
    assert_eq!(bom.scene.objects, from_obj.scene.objects);
    assert!(count(&px, COLOURS[1].1) > 100);
    // The fixture's `materials` take precedence over the .mtl's Kd.
    let over = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "cube.obj"}},
            "materials": {"green": {"unlit": [0.25, 0.25, 0.25]}}}),
    )
    .unwrap();
    let px = image(&over);
    assert_eq!(count(&px, COLOURS[1].1), 0);
    assert!(count(&px, [0.25; 3]) > 100);
    // Control: the same OBJ without its usemtl lines is grey.
    let plain: String = obj
        .lines()
        .filter(|l| !l.starts_with("usemtl"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(fixtures.join("plain.obj"), plain).unwrap();
    let px = image(
        &load(
            &dir,
            serde_json::json!({"mesh": {"obj": {"path": "plain.obj"}}}),
        )
        .unwrap(),
    );
    assert_eq!(count(&px, COLOURS[1].1), 0);
    assert!(count(&px, GREY) > 600);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn misused_face_materials_are_named_at_their_field() {
    let dir = scratch("errors");
    let e = load(
        &dir,
        serde_json::json!({"mesh": cube(), "materials": {"red": {"unlit": [1, 0, 0]}}, "faces": {"redd": [0]}}),
    )
    .unwrap_err();
    assert!(
        e.contains("objects[0].faces.redd: no material \"redd\" in objects[0].materials; did you mean \"red\"?"),
        "{e}"
    );
    let e = load(&dir, serde_json::json!({"mesh": cube(), "materials": {"red": {"unlit": [1, 0, 0]}}, "faces": {"red": [0, 12]}}))
        .unwrap_err();
    assert!(
        e.contains(
            "objects[0].faces.red[1]: no triangle 12: the mesh has 12 triangles, counted from 0"
        ),
        "{e}"
    );
    let e = load(
        &dir,
        serde_json::json!({"mesh": cube(),
        "materials": {"red": {"unlit": [1, 0, 0]}, "blue": {"unlit": [0, 0, 1]}},
        "faces": {"red": [0, 1], "blue": [1]}}),
    )
    .unwrap_err();
    assert!(
        e.contains("objects[0].faces.red[1]: triangle 1 is already of material \"blue\""),
        "{e}"
    );
    let e = load(
        &dir,
        serde_json::json!({"mesh": cube(), "materials": {"red": {"unlit": [1, 0, 0]}}}),
    )
    .unwrap_err();
    assert!(
        e.contains("objects[0].materials.red: no triangle is of material \"red\""),
        "{e}"
    );
    let e = load(&dir, serde_json::json!({"mesh": cube(), "materials": {"red": {"colour": [1, 0, 0]}}, "faces": {"red": [0]}}))
        .unwrap_err();
    assert!(
        e.contains("objects[0].materials.red.colour: unknown field `colour`")
            && e.contains("did you mean \"color\""),
        "{e}"
    );
    let e = load(&dir, serde_json::json!({"mesh": cube(), "materials": {"red": {"unlit": [1, 0, -1]}}, "faces": {"red": [0]}}))
        .unwrap_err();
    assert!(e.contains("objects[0].materials.red.unlit"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn misused_obj_materials_are_named_at_the_mesh_path() {
    let dir = scratch("obj-errors");
    let fixtures = dir.join("fixtures");
    // usemtl of a name neither the .mtl nor the fixture has.
    std::fs::write(fixtures.join("one.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    std::fs::write(
        fixtures.join("tri.obj"),
        "mtllib one.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl redd\nf 1 2 3\n",
    )
    .unwrap();
    let e = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "tri.obj"}}}),
    )
    .unwrap_err();
    assert!(
        e.contains("objects[0].mesh.obj.path: ")
            && e.contains("tri.obj: line 5: usemtl \"redd\": no material \"redd\"")
            && e.contains("did you mean \"red\"?"),
        "{e}"
    );
    // A bad .mtl line, and an .mtl outside the project.
    std::fs::write(fixtures.join("bad.mtl"), "Kd 1 0 0\n").unwrap();
    std::fs::write(
        fixtures.join("b.obj"),
        "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
    )
    .unwrap();
    let e = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "b.obj"}}}),
    )
    .unwrap_err();
    assert!(
        e.contains("bad.mtl line 1: `Kd` before any `newmtl`"),
        "{e}"
    );
    let outside = scratch("errors-outside");
    std::fs::write(outside.join("x.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    std::fs::write(
        fixtures.join("o.obj"),
        format!(
            "mtllib {}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
            outside.join("x.mtl").display()
        ),
    )
    .unwrap();
    let e = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "o.obj"}}}),
    )
    .unwrap_err();
    assert!(
        e.contains("objects[0].mesh.obj.path") && e.contains("is outside"),
        "{e}"
    );
    // Control: the good .mtl's colour is taken.
    std::fs::write(
        fixtures.join("g.obj"),
        "mtllib one.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
    )
    .unwrap();
    let f = load(
        &dir,
        serde_json::json!({"mesh": {"obj": {"path": "g.obj"}}}),
    )
    .unwrap();
    assert_eq!(
        f.scene.objects[0].face_materials[0].emission,
        Some(renderer::Spectrum::Rgb(glam::DVec3::X))
    );
    std::fs::remove_dir_all(&dir).ok();
    std::fs::remove_dir_all(&outside).ok();
}

/// A check that reads one material refuses an object of several, at its
/// `object` field; the same check on a plain object gets past that field
/// (the control: refused only for not blinking).
#[test]
fn checks_reading_a_material_refuse_per_face_materials() {
    let dir = scratch("checks");
    let with_check = |object: serde_json::Value| {
        let mut v: serde_json::Value = serde_json::from_str(&text(object)).unwrap();
        v["views"] = serde_json::json!([{"name": "v"}]);
        v["checks"] = serde_json::json!([{"name": "p", "measure": {"period":
            {"view": "v", "object": "cube", "from": 0.0, "to": 1.0, "step": 0.1}}}]);
        Fixture::parse(&v.to_string(), &dir.join("fixtures/cube.json"))
            .unwrap_err()
            .to_string()
    };
    let e = with_check(
        serde_json::json!({"mesh": cube(), "materials": json_materials(), "faces": json_faces()}),
    );
    assert!(
        e.contains("checks[0].measure.period.object: \"cube\" has per-face materials"),
        "{e}"
    );
    let e = with_check(serde_json::json!({"mesh": cube()}));
    assert!(
        e.contains("checks[0].measure.period.object") && e.contains("does not blink"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
