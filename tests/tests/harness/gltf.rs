//! glTF 2.0 meshes and image textures (docs/fixtures.md): a plate written
//! as a glTF file with a checkerboard base colour texture, in the three
//! ways a file can hold its data (external files, data URIs, one binary
//! GLB), renders its texture where its UVs put it, in linear light, and is
//! measured by declared checks; malformed files are refused naming the
//! file and the element.

use glam::DVec3;
use serde_json::json;
use std::path::{Path, PathBuf};
use vstf::fixture::Fixture;
use workspace_tests::declared_rows as rows;

/// A 4 x 2 plate in the plane z = 0 (object frame), corners (-2, -1) to
/// (2, 1), UVs across it: two triangles, 8-bit indices.
fn plate_bin() -> Vec<u8> {
    let positions: [[f32; 3]; 4] = [
        [-2.0, -1.0, 0.0],
        [2.0, -1.0, 0.0],
        [2.0, 1.0, 0.0],
        [-2.0, 1.0, 0.0],
    ];
    let uvs: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let mut b = Vec::new();
    for p in positions.iter().flatten().chain(uvs.iter().flatten()) {
        b.extend_from_slice(&p.to_le_bytes());
    }
    b.extend_from_slice(&[0u16, 1, 2, 0, 2, 3].map(u16::to_le_bytes).concat());
    b
}

/// A 4 x 2 checkerboard PNG of the two sRGB codes, each cell 4 x 4
/// texels (so that bilinear filtering inside a cell mixes one colour).
fn checker_png(a: [u8; 3], b: [u8; 3]) -> Vec<u8> {
    let img = image::RgbImage::from_fn(16, 8, |x, y| {
        image::Rgb(if (x / 4 + y / 4) % 2 == 0 { a } else { b })
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            s.push(if k <= c.len() {
                A[(n >> (18 - 6 * k)) as usize & 63] as char
            } else {
                '='
            });
        }
    }
    s
}

/// The glTF document of the plate, its buffer and image given by `buffer`
/// and `image` (a URI, or a bufferView for the image).
fn document(
    buffer: serde_json::Value,
    image: serde_json::Value,
    extra_views: serde_json::Value,
) -> serde_json::Value {
    let mut views = vec![
        json!({"buffer": 0, "byteOffset": 0, "byteLength": 48}),
        json!({"buffer": 0, "byteOffset": 48, "byteLength": 32}),
        json!({"buffer": 0, "byteOffset": 80, "byteLength": 12}),
    ];
    views.extend(extra_views.as_array().cloned().unwrap_or_default());
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"children": [1], "translation": [0.0, 0.5, 0.0]}, {"mesh": 0, "translation": [0.0, -0.5, 0.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 0.5, 1.0], "baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [image],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2.0, -1.0, 0.0], "max": [2.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
        ],
        "bufferViews": views,
        "buffers": [buffer],
    })
}

const A: [u8; 3] = [255, 255, 255];
const B: [u8; 3] = [188, 40, 10];

/// A GLB file: the JSON chunk and the binary chunk, each padded to 4.
fn glb(json: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut j = json.to_string().into_bytes();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// A fresh folder holding the plate's files in each form.
fn folder(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vstf-gltf-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let bin = plate_bin();
    let png = checker_png(A, B);
    std::fs::write(dir.join("plate.bin"), &bin).unwrap();
    std::fs::write(dir.join("checker.png"), &png).unwrap();
    let external = document(
        json!({"uri": "plate.bin", "byteLength": 92}),
        json!({"uri": "checker.png"}),
        json!([]),
    );
    std::fs::write(dir.join("external.gltf"), external.to_string()).unwrap();
    let embedded = document(
        json!({"uri": format!("data:application/octet-stream;base64,{}", base64(&bin)), "byteLength": 92}),
        json!({"uri": format!("data:image/png;base64,{}", base64(&png))}),
        json!([]),
    );
    std::fs::write(dir.join("embedded.gltf"), embedded.to_string()).unwrap();
    let mut all = bin.clone();
    all.extend_from_slice(&[0; 4]);
    let at = all.len();
    all.extend_from_slice(&png);
    let binary = document(
        json!({"byteLength": all.len()}),
        json!({"bufferView": 3, "mimeType": "image/png"}),
        json!([{"buffer": 0, "byteOffset": at, "byteLength": png.len()}]),
    );
    std::fs::write(dir.join("binary.glb"), glb(&binary, &all)).unwrap();
    dir
}

/// The fixture text of the plate from `mesh_file`, moving along x at
/// `speed` (at rest: 0), seen from (0, 0, 10) under ambient light 1.
fn fixture_text(mesh_file: &str, speed: f64) -> String {
    json!({
        "camera": {"position": [0.0, 0.0, 10.0], "t": 10.0, "look_at": [0.0, 0.0, 0.0], "vfov_deg": 30.0},
        "light": {"position": [0.0, 20.0, 20.0], "color": [0.0, 0.0, 0.0], "ambient": 1.0},
        "background": [0.0, 0.0, 0.0],
        "image": {"width": 160, "height": 120, "spp": 4},
        "objects": [{"name": "plate", "kind": "V_obj", "mesh": {"gltf": {"path": mesh_file}},
                     "worldline": {"start": [-100.0, -100.0 * speed, 0.0, 0.0], "velocity": [speed, 0.0, 0.0], "proper_lifetime": 300.0},
                     "material": {}}],
        "views": [{"name": "seen"}],
        "checks": [
            {"name": "left edge", "measure": {"edge": {"view": "seen", "object": "plate",
                "points": [[-2.0, -1.0, 0.0], [-2.0, 1.0, 0.0]], "side": "left", "at": {"row": 60}}}},
            {"name": "right edge", "measure": {"edge": {"view": "seen", "object": "plate",
                "points": [[2.0, -1.0, 0.0], [2.0, 1.0, 0.0]], "side": "right", "at": {"row": 60}}}},
            {"name": "width", "measure": {"difference": ["right edge", "left edge"]}}
        ]
    })
    .to_string()
}

fn load(dir: &Path, text: &str) -> Result<Fixture, String> {
    Fixture::parse(text, &dir.join("plate.json")).map_err(|e| e.to_string())
}

/// The linear value of an sRGB code.
fn linear(code: u8) -> f64 {
    let c = f64::from(code) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// At rest, each texel's centre shows its linear colour times the base
/// colour factor (1, 1, 0.5), in every form of the file; the texture is
/// where the UVs and the node transforms put it (its top-left texel at the
/// plate's top left).
#[test]
fn a_gltf_plates_checkerboard_shows_in_linear_light_where_its_uvs_put_it() {
    let dir = folder("rest");
    let factor = DVec3::new(1.0, 1.0, 0.5);
    let texel = |c: [u8; 3]| DVec3::new(linear(c[0]), linear(c[1]), linear(c[2])) * factor;
    for file in ["external.gltf", "embedded.gltf", "binary.glb"] {
        let f = load(&dir, &fixture_text(file, 0.0)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let view = vstf::run::view(
            &f,
            &vstf::fixture::Overrides {
                spp: Some(1),
                ..Default::default()
            },
        )
        .unwrap();
        let img = vstf::run::render(&f, &view, renderer::Traversal::Bvh).unwrap();
        // The plate spans x in [-2, 2] at depth 10: 4 texels across it, the
        // texel (i, j) centred at x = -1.5 + i, y = 0.5 - j.
        let half = (15f64.to_radians()).tan() * 10.0;
        let px = |x: f64, y: f64| {
            let (u, v) = (80.0 + x / half * 60.0, 60.0 - y / half * 60.0);
            img.pixels[(v as usize) * 160 + u as usize]
        };
        for i in 0..4 {
            for j in 0..2 {
                let seen = px(-1.5 + f64::from(i), 0.5 - f64::from(j));
                let want = texel(if (i + j) % 2 == 0 { A } else { B });
                assert!(
                    (seen - want).abs().max_element() < 1e-9,
                    "{file} texel ({i}, {j}): {seen} != {want}"
                );
            }
        }
        // The control: the colours are not the sRGB codes taken as linear.
        let raw = DVec3::new(188.0, 40.0, 10.0) / 255.0 * factor;
        assert!((px(-0.5, 0.5) - raw).abs().max_element() > 0.1);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A glTF file given as `{"file": {"path"}}` is chosen by its extension
/// (`.gltf`, `.glb`) or by `"format": "gltf"`, and renders exactly as the
/// same file given as `{"gltf": {"path"}}`, texture included; read as OBJ it
/// is refused, saying what it is (the control).
#[test]
fn a_gltf_file_is_chosen_by_its_extension_or_format() {
    let dir = folder("by-extension");
    let image = |text: String| {
        let f = load(&dir, &text).unwrap_or_else(|e| panic!("{e}"));
        let view = vstf::run::view(&f, &vstf::fixture::Overrides::default()).unwrap();
        vstf::run::render(&f, &view, renderer::Traversal::Bvh)
            .unwrap()
            .pixels
    };
    for file in ["external.gltf", "binary.glb"] {
        let as_gltf = fixture_text(file, 0.0);
        let expected = image(as_gltf.clone());
        let by_name = as_gltf.replace(r#"{"gltf":"#, r#"{"file":"#);
        assert_eq!(image(by_name.clone()), expected, "{file} by extension");
        let by_format = by_name.replace(r#""path":"#, r#""format":"gltf","path":"#);
        assert_eq!(image(by_format), expected, "{file} by format");
        let as_obj = by_name
            .replace(r#""path":"#, r#""format":"obj","path":"#)
            .replace(r#""material":{}"#, r#""material":{"color":[1.0,1.0,1.0]}"#);
        let e = load(&dir, &as_obj).unwrap_err();
        assert!(
            e.contains("objects[0].mesh.file.path") && e.contains("this is a glTF file"),
            "{e}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Moving at 0.8c, the textured glTF plate is measured by declared edge
/// checks, which pass; rendered 0.02 l.units elsewhere, its edges fail.
#[test]
fn a_moving_gltf_plate_is_measured() {
    let dir = folder("moving");
    for file in ["external.gltf", "binary.glb"] {
        let f = load(&dir, &fixture_text(file, 0.8)).unwrap();
        for r in rows(&f, &f) {
            assert!(r.pass, "{file}: {r:?}");
        }
        let mut shifted = f.clone();
        let renderer::Motion::Velocity { start, .. } = &mut shifted.scene.objects[0].motion else {
            panic!("moves by velocity");
        };
        start.x.x += 0.02;
        for r in rows(&shifted, &f) {
            if r.quantity.contains("edge") {
                assert!(!r.pass, "{file}: a 0.02 shift went unnoticed: {r:?}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Each malformed file is refused naming the file and the glTF element.
#[test]
fn malformed_gltf_files_name_the_file_and_element() {
    let dir = folder("bad");
    let bin = plate_bin();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("not-json.gltf", b"{ nope".to_vec(), "not-json.gltf: "),
        (
            "short.gltf",
            document(
                json!({"uri": "plate.bin", "byteLength": 400}),
                json!({"uri": "checker.png"}),
                json!([]),
            )
            .to_string()
            .into_bytes(),
            "buffers[0]: declares 400 bytes but holds 92",
        ),
        (
            "view.gltf",
            {
                let mut d = document(
                    json!({"uri": "plate.bin", "byteLength": 92}),
                    json!({"uri": "checker.png"}),
                    json!([]),
                );
                d["bufferViews"][2]["byteLength"] = json!(4);
                d.to_string().into_bytes()
            },
            "accessors[2]: its elements run past the end of its bufferView",
        ),
        (
            "index.gltf",
            {
                let mut b = bin.clone();
                b[84..86].copy_from_slice(&9u16.to_le_bytes());
                std::fs::write(dir.join("bad-index.bin"), &b).unwrap();
                document(
                    json!({"uri": "bad-index.bin", "byteLength": 92}),
                    json!({"uri": "checker.png"}),
                    json!([]),
                )
                .to_string()
                .into_bytes()
            },
            "meshes[0].primitives[0]: index 9 is out of range (it has 4 vertices)",
        ),
        (
            "lines.gltf",
            {
                let mut d = document(
                    json!({"uri": "plate.bin", "byteLength": 92}),
                    json!({"uri": "checker.png"}),
                    json!([]),
                );
                d["meshes"][0]["primitives"][0]["mode"] = json!(1);
                d.to_string().into_bytes()
            },
            "meshes[0].primitives[0]: mode Lines: only triangles are read",
        ),
        (
            "outside.gltf",
            document(
                json!({"uri": "../plate.bin", "byteLength": 92}),
                json!({"uri": "checker.png"}),
                json!([]),
            )
            .to_string()
            .into_bytes(),
            "buffers[0]: ",
        ),
        (
            "image.gltf",
            {
                std::fs::write(dir.join("not.png"), b"plain text").unwrap();
                document(
                    json!({"uri": "plate.bin", "byteLength": 92}),
                    json!({"uri": "not.png"}),
                    json!([]),
                )
                .to_string()
                .into_bytes()
            },
            "images[0]: not a PNG or JPEG image",
        ),
        (
            "plate.obj.gltf.txt",
            b"{}".to_vec(),
            "a glTF file ends in .gltf or .glb",
        ),
    ];
    let outside = dir.parent().unwrap().join("plate.bin");
    std::fs::write(&outside, &bin).unwrap();
    for (name, bytes, expected) in cases {
        std::fs::write(dir.join(name), bytes).unwrap();
        let e = load(&dir, &fixture_text(name, 0.0)).unwrap_err();
        assert!(e.contains("objects[0].mesh.gltf.path: "), "{name}: {e}");
        assert!(e.contains(name) || name.ends_with(".txt"), "{name}: {e}");
        assert!(e.contains(expected), "{name}: expected {expected:?} in {e}");
    }
    // The control: the well-formed file loads.
    load(&dir, &fixture_text("external.gltf", 0.0)).unwrap();
    std::fs::remove_file(&outside).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The same checkerboard as an `image` texture on an OBJ plate with `vt`
/// coordinates and on a `quad`, and a striped image on an analytic sphere
/// (its middle columns face the camera): each shows the texels' linear
/// colours; the sphere with the stripes moved to the image's sides (the
/// control) does not.
#[test]
fn image_textures_on_obj_quad_and_sphere_meshes() {
    let dir = folder("image");
    std::fs::write(
        dir.join("plate.obj"),
        "v -2 -1 0\nv 2 -1 0\nv 2 1 0\nv -2 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    let stripes = |middle: bool| {
        let img = image::RgbImage::from_fn(16, 8, |x, _| {
            image::Rgb(if (4..12).contains(&x) == middle { B } else { A })
        });
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    };
    std::fs::write(dir.join("middle.png"), stripes(true)).unwrap();
    std::fs::write(dir.join("sides.png"), stripes(false)).unwrap();
    let texel = |c: [u8; 3]| DVec3::new(linear(c[0]), linear(c[1]), linear(c[2]));
    let render = |mesh: serde_json::Value, image: &str| {
        let mut v: serde_json::Value =
            serde_json::from_str(&fixture_text("external.gltf", 0.0)).unwrap();
        v["objects"][0]["mesh"] = mesh;
        v["objects"][0]["material"] =
            json!({"color": [1.0, 1.0, 1.0], "texture": {"image": {"path": image}}});
        v["checks"] = json!([]);
        v["views"] = json!([]);
        let f = load(&dir, &v.to_string()).unwrap_or_else(|e| panic!("{e}"));
        let view = vstf::run::view(
            &f,
            &vstf::fixture::Overrides {
                spp: Some(1),
                ..Default::default()
            },
        )
        .unwrap();
        vstf::run::render(&f, &view, renderer::Traversal::Bvh).unwrap()
    };
    let half = (15f64.to_radians()).tan() * 10.0;
    let at = |img: &renderer::Image, x: f64, y: f64| {
        let (u, v) = (80.0 + x / half * 60.0, 60.0 - y / half * 60.0);
        img.pixels[(v as usize) * 160 + u as usize]
    };
    let quad =
        json!({"quad": {"corner": [-2.0, -1.0, 0.0], "u": [4.0, 0.0, 0.0], "v": [0.0, 2.0, 0.0]}});
    for (name, mesh) in [
        ("obj", json!({"obj": {"path": "plate.obj"}})),
        ("quad", quad),
    ] {
        let img = render(mesh, "checker.png");
        for i in 0..4 {
            for j in 0..2 {
                let want = texel(if (i + j) % 2 == 0 { A } else { B });
                let seen = at(&img, -1.5 + f64::from(i), 0.5 - f64::from(j));
                assert!(
                    (seen - want).abs().max_element() < 1e-9,
                    "{name} ({i}, {j}): {seen}"
                );
            }
        }
    }
    let sphere = json!({"analytic_sphere": {"radius": 2.0}});
    let facing = |image: &str| at(&render(sphere.clone(), image), 0.0, 0.0);
    assert!((facing("middle.png") - texel(B)).abs().max_element() < 1e-9);
    assert!((facing("sides.png") - texel(A)).abs().max_element() < 1e-9);
    // A mesh without texture coordinates is refused at the texture.
    let mut v: serde_json::Value =
        serde_json::from_str(&fixture_text("external.gltf", 0.0)).unwrap();
    v["objects"][0]["mesh"] =
        json!({"cuboid": {"min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0]}});
    v["objects"][0]["material"] =
        json!({"color": [1.0, 1.0, 1.0], "texture": {"image": {"path": "checker.png"}}});
    let e = load(&dir, &v.to_string()).unwrap_err();
    assert!(
        e.contains("objects[0].material.texture.image: this mesh has no texture coordinates"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
