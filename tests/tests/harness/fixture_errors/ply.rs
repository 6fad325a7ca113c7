//! PLY meshes: ASCII and binary of both byte orders render bit for bit as
//! the same mesh given as OBJ; every malformed file is an error naming the
//! file, the field and the element; files outside the project are refused.

use std::path::{Path, PathBuf};
use vstf::fixture::Fixture;
use vstf::Overrides;

/// A fresh, empty scratch folder (its own project: it holds `fixtures/`).
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vstf-ply-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    dir
}

/// A closed prism over a pentagon (so one face is fanned), with coordinates
/// that are not round in binary.
fn house() -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let base = [
        [-0.7, -0.6],
        [0.7, -0.6],
        [0.7, 0.3],
        [0.0, 0.9],
        [-0.7, 0.3],
    ];
    let mut v: Vec<[f64; 3]> = base.iter().map(|p| [p[0], p[1], -0.45]).collect();
    v.extend(base.iter().map(|p| [p[0], p[1], 0.45]));
    let mut f: Vec<Vec<u32>> = vec![vec![4, 3, 2, 1, 0], vec![5, 6, 7, 8, 9]];
    for i in 0..5u32 {
        let j = (i + 1) % 5;
        f.push(vec![i, j, j + 5, i + 5]);
    }
    (v, f)
}

fn obj_text(v: &[[f64; 3]], f: &[Vec<u32>]) -> String {
    let mut s = String::new();
    for p in v {
        s += &format!("v {:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    for face in f {
        let idx: Vec<String> = face.iter().map(|i| (i + 1).to_string()).collect();
        s += &format!("f {}\n", idx.join(" "));
    }
    s
}

fn ply_header(format: &str, v: usize, f: usize) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment written by a test\nelement vertex {v}\n\
         property double x\nproperty double y\nproperty double z\nelement face {f}\n\
         property list uchar int vertex_indices\nend_header\n"
    )
}

fn ply_ascii(v: &[[f64; 3]], f: &[Vec<u32>]) -> Vec<u8> {
    let mut s = ply_header("ascii", v.len(), f.len());
    for p in v {
        s += &format!("{:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    for face in f {
        let idx: Vec<String> = face.iter().map(u32::to_string).collect();
        s += &format!("{} {}\n", face.len(), idx.join(" "));
    }
    s.into_bytes()
}

fn ply_binary(v: &[[f64; 3]], f: &[Vec<u32>], big: bool) -> Vec<u8> {
    let name = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut b = ply_header(name, v.len(), f.len()).into_bytes();
    for x in v.iter().flatten() {
        b.extend(if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        });
    }
    for face in f {
        b.push(face.len() as u8);
        for &i in face {
            let i = i as i32;
            b.extend(if big {
                i.to_be_bytes()
            } else {
                i.to_le_bytes()
            });
        }
    }
    b
}

/// A fixture whose one object, moving at 0.6c, is `mesh`.
fn fixture_text(mesh: serde_json::Value) -> String {
    serde_json::json!({
        "camera": {"position": [0, 0.5, 6], "t": 24, "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40},
        "light": {"position": [3, 5, 8], "color": [1, 1, 1], "ambient": 0.2},
        "model": "relativistic",
        "image": {"width": 96, "height": 72, "spp": 1},
        "objects": [{"name": "house", "kind": "V_obj", "mesh": mesh,
            "material": {"color": [0.8, 0.6, 0.3]},
            "worldline": {"start": [0, -11, 0, 0], "velocity": [0.6, 0, 0], "proper_lifetime": 100}}]
    })
    .to_string()
}

fn load(dir: &Path, mesh: serde_json::Value) -> Result<Fixture, String> {
    Fixture::parse(&fixture_text(mesh), &dir.join("fixtures/scene.json")).map_err(|e| e.to_string())
}

fn pixels(f: &Fixture) -> Vec<u8> {
    let view = vstf::run::view(f, &Overrides::default()).unwrap();
    let image = vstf::run::render(f, &view, renderer::Traversal::Bvh).unwrap();
    image
        .pixels
        .iter()
        .flat_map(|p| p.to_array().map(f64::to_bits))
        .flat_map(u64::to_le_bytes)
        .collect()
}

#[test]
fn a_ply_renders_bit_for_bit_as_the_same_obj() {
    let dir = scratch("same");
    let (v, f) = house();
    let fixtures = dir.join("fixtures");
    std::fs::write(fixtures.join("house.obj"), obj_text(&v, &f)).unwrap();
    std::fs::write(fixtures.join("ascii.ply"), ply_ascii(&v, &f)).unwrap();
    std::fs::write(fixtures.join("little.ply"), ply_binary(&v, &f, false)).unwrap();
    std::fs::write(fixtures.join("big.ply"), ply_binary(&v, &f, true)).unwrap();
    let obj = load(&dir, serde_json::json!({"obj": {"path": "house.obj"}})).unwrap();
    let expected = pixels(&obj);
    let meshes = [
        serde_json::json!({"ply": {"path": "ascii.ply"}}),
        serde_json::json!({"file": {"path": "little.ply"}}),
        serde_json::json!({"file": {"path": "big.ply", "format": "ply"}}),
    ];
    for mesh in meshes {
        let ply = load(&dir, mesh.clone()).unwrap();
        assert_eq!(
            ply.scene.objects[0].shape, obj.scene.objects[0].shape,
            "{mesh}"
        );
        assert!(
            pixels(&ply) == expected,
            "{mesh} renders otherwise than the OBJ"
        );
    }
    // Control: the object is in view, and one vertex moved by a hundredth
    // changes the picture.
    let background = pixels(
        &load(
            &dir,
            serde_json::json!({"triangles": {
        "vertices": [[40, 40, 0], [41, 40, 0], [40, 41, 0]], "indices": [[0, 1, 2]]}}),
        )
        .unwrap(),
    );
    assert!(background != expected, "the house is not in view");
    let mut moved = v.clone();
    moved[3][1] += 0.01;
    std::fs::write(fixtures.join("moved.ply"), ply_binary(&moved, &f, true)).unwrap();
    let other = load(&dir, serde_json::json!({"file": {"path": "moved.ply"}})).unwrap();
    assert!(
        pixels(&other) != expected,
        "a moved vertex left the picture as it was"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn malformed_plys_name_the_file_field_and_element() {
    let dir = scratch("bad");
    let (v, f) = house();
    let fixtures = dir.join("fixtures");
    let good = ply_ascii(&v, &f);
    let text = String::from_utf8(good.clone()).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "header.ply",
            text.replace("format ascii", "format asci").into_bytes(),
            "PLY header line 2:",
        ),
        (
            "truncated.ply",
            {
                let b = ply_binary(&v, &f, false);
                b[..b.len() - 10].to_vec()
            },
            "PLY face",
        ),
        (
            "range.ply",
            text.replace("4 4 0 5 9", "4 4 0 5 10").into_bytes(),
            "PLY face 6 (line 27): vertex index 10 is out of range: the file has 10 vertices",
        ),
        ("nofaces.ply", ply_ascii(&v, &[]), "0 faces"),
    ];
    for (name, bytes, says) in cases {
        std::fs::write(fixtures.join(name), bytes).unwrap();
        let e = load(&dir, serde_json::json!({"ply": {"path": name}})).unwrap_err();
        assert!(
            e.contains("scene.json: objects[0].mesh.ply.path: ")
                && e.contains(&format!("fixtures/{name}: "))
                && e.contains(says),
            "{name}: {e}"
        );
    }
    // A PLY given as OBJ is told as such, not "no triangles".
    std::fs::write(fixtures.join("house.obj"), &good).unwrap();
    let e = load(&dir, serde_json::json!({"obj": {"path": "house.obj"}})).unwrap_err();
    assert!(
        e.contains("objects[0].mesh.obj.path") && e.contains("this is a PLY file"),
        "{e}"
    );
    let e = load(&dir, serde_json::json!({"file": {"path": "house.obj"}})).unwrap_err();
    assert!(e.contains("this is a PLY file"), "{e}");
    // ... and as PLY it loads (the control).
    load(
        &dir,
        serde_json::json!({"file": {"path": "house.obj", "format": "ply"}}),
    )
    .unwrap();
    let e = load(&dir, serde_json::json!({"file": {"path": "house.stl"}})).unwrap_err();
    assert!(
        e.contains("objects[0].mesh.file.path") && e.contains("extension"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Mesh files are read only inside the fixture's project: not by `..`,
/// an absolute path or a link leading out.
#[test]
fn mesh_files_outside_the_project_are_refused() {
    let dir = scratch("confined");
    let outside = scratch("outside");
    let (v, f) = house();
    std::fs::write(outside.join("house.ply"), ply_ascii(&v, &f)).unwrap();
    std::fs::write(dir.join("house.ply"), ply_ascii(&v, &f)).unwrap();
    std::os::unix::fs::symlink(outside.join("house.ply"), dir.join("fixtures/link.ply")).unwrap();
    let out = outside.join("house.ply");
    let up = format!(
        "../../{}/house.ply",
        outside.file_name().unwrap().to_str().unwrap()
    );
    for path in [out.to_str().unwrap(), &up, "link.ply"] {
        let e = load(&dir, serde_json::json!({"ply": {"path": path}})).unwrap_err();
        assert!(
            e.contains("objects[0].mesh.ply.path") && e.contains("is outside"),
            "{path}: {e}"
        );
    }
    // Control: a file of the project above the fixture's folder is read.
    load(&dir, serde_json::json!({"ply": {"path": "../house.ply"}})).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    std::fs::remove_dir_all(&outside).ok();
}
