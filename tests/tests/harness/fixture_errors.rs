//! Bad fixtures get a clear error naming the file, the field and what was
//! expected; never a panic or a silently wrong picture. Here: the fixture
//! as a whole, its camera, image, light, materials and vectors; in the
//! submodules, how objects move and what they are made of.

use std::path::Path;
use vstf::fixture::Fixture;

/// Meshes (triangles, OBJ files) and the memory budget they are held to.
mod meshes;
/// Worldlines: uniform, keyframed and hyperbolic motion and light speed.
mod motion;
/// PLY meshes, and mesh files read only inside the project.
mod ply;

/// The flange fixture with `edit` applied to its JSON.
fn flange_with(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let text = std::fs::read_to_string(workspace_tests::repo().fixtures_dir().join("flange.json"))
        .unwrap();
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

/// A misspelt field or variant gets the nearest expected name as a hint;
/// a field near none of them (the control, `fov` above) gets none.
#[test]
fn misspelt_fields_get_a_did_you_mean() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        let w = v["objects"][i]["worldline"].as_object_mut().unwrap();
        let extrusion = w.remove("extrusion").unwrap();
        w.insert("extrusoin".into(), extrusion);
    }));
    assert!(
        e.contains("unknown field `extrusoin`, expected one of")
            && e.ends_with("; did you mean \"extrusion\"?"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        v["camera"]["look_att"] = serde_json::json!([0, 0, 0])
    }));
    assert!(e.ends_with("; did you mean \"look_at\"?"), "{e}");
    let e =
        error_of(&flange_with(
            |v| {
                v["objects"][0]["mesh"] =
                    serde_json::json!({"cubiod": {"min": [0, 0, 0], "max": [1, 1, 1]}})
            },
        ));
    assert!(e.ends_with("; did you mean \"cuboid\"?"), "{e}");
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
    assert!(!e.contains("did you mean"), "{e}");
    let e = error_of(&flange_with(|v| {
        v["objects"][1]["material"]["color"] = "red".into()
    }));
    assert!(e.contains("objects[1].material.color: invalid type"), "{e}");
    let e = error_of(&flange_with(|v| v["model"] = "newtonian".into()));
    assert!(e.contains("model: unknown model \"newtonian\""), "{e}");
}

#[test]
fn every_shipped_fixture_loads() {
    let names = workspace_tests::repo().fixture_names();
    assert!(names.contains(&"flange".to_string()));
    for name in names {
        workspace_tests::fixture(&name);
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

#[test]
fn bad_spectra_name_the_field() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["material"]["emission"] =
            serde_json::json!({ "samples": { "nm": [500, 450], "values": [1, 1] } });
    }));
    assert!(
        e.contains("material.emission") && e.contains("samples.nm[1]"),
        "{e}"
    );
    assert!(
        e.contains("450 nm does not exceed samples.nm[0] = 500 nm"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["material"]["emission"] =
            serde_json::json!({ "samples": { "nm": [400, 500], "values": [1] } });
    }));
    assert!(
        e.contains("samples.values: 1 values for 2 wavelengths in samples.nm"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        v["light"]["spectrum"] = serde_json::json!({ "blackbody": { "kelvin": -5 } });
    }));
    assert!(e.contains("light.spectrum"), "{e}");
    let e = error_of(&flange_with(|v| {
        v["light"]["spectrum"] = serde_json::json!({ "rainbow": {} });
    }));
    assert!(e.contains("light.spectrum"), "{e}");
}

#[test]
fn keeping_only_some_objects_names_a_missing_one() {
    let f = workspace_tests::fixture("flange");
    let only = f.only(&["flange"]).unwrap();
    assert_eq!(only.scene.objects.len(), 1);
    assert_eq!(only.spec.objects.len(), 1);
    assert_eq!(only.scene.objects[0].name, "flange");
    let e = f
        .only(&["flange", "no such thing"])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("flange.json: objects: no object named \"no such thing\""),
        "{e}"
    );
}

/// `unlit` is a whole material: with a colour field besides, the fixture
/// is refused at that field; alone it loads.
#[test]
fn unlit_with_another_colour_field_is_refused_at_that_field() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["material"]["unlit"] = serde_json::json!([1, 0.5, 0]);
    }));
    assert!(
        e.contains("objects[5].material.color: `unlit` is a whole material"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["material"] = serde_json::json!({"unlit": [1, 0.5, 0], "specular": 0.3});
    }));
    assert!(
        e.contains("objects[5].material.specular: `unlit` is a whole material"),
        "{e}"
    );
    Fixture::parse(
        &flange_with(|v| {
            let i = flange_index(v);
            v["objects"][i]["material"] = serde_json::json!({"unlit": [1, 0.5, 0]});
        }),
        Path::new("fixtures/flange.json"),
    )
    .unwrap();
}

/// A fixture may leave out `light`, but not a material's `color` unless it
/// gives `unlit`.
#[test]
fn light_may_be_omitted_and_color_only_for_unlit() {
    Fixture::parse(
        &flange_with(|v| {
            v.as_object_mut().unwrap().remove("light");
        }),
        Path::new("fixtures/flange.json"),
    )
    .unwrap();
    let e = error_of(&flange_with(|v| {
        v["objects"][0]["material"]
            .as_object_mut()
            .unwrap()
            .remove("color");
    }));
    assert!(
        e.contains(
            "objects[0].material: missing field `color`: give `color` [r, g, b], or `unlit`"
        ),
        "{e}"
    );
}

#[test]
fn out_of_range_materials_lights_and_grouped_spheres_are_refused_at_their_field() {
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["material"]["mirror"] = 1e308.into();
    }));
    assert!(
        e.contains("objects[5].material.mirror: 1e308 is out of range"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        v["objects"][0]["material"]["color"][2] = (-1e308).into()
    }));
    assert!(e.contains("objects[0].material.color[2]"), "{e}");
    let e = error_of(&flange_with(|v| v["light"]["ambient"] = (-0.5).into()));
    assert!(e.contains("light.ambient: -0.5 is out of range"), "{e}");
    let e = error_of(&flange_with(|v| {
        v["objects"][0]["mesh"] = serde_json::json!({"group": [
            {"cuboid": {"min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 1.0]}},
            {"analytic_sphere": {"radius": 1.0}}
        ]});
    }));
    assert!(
        e.contains("objects[0].mesh.group[1]: an analytic sphere is not a mesh"),
        "{e}"
    );
}

/// A pixel that is not a finite colour fails the render with the pixel, the
/// object its ray meets and the debug command, instead of a black pixel.
#[test]
fn a_non_finite_pixel_fails_the_render_and_says_where() {
    let mut f = workspace_tests::fixture("stage");
    let bars = f
        .scene
        .objects
        .iter()
        .position(|o| o.name == "stage floor")
        .unwrap();
    f.scene.objects[bars].material.color = glam::DVec3::splat(f64::NAN);
    let small = vstf::fixture::Overrides {
        width: Some(32),
        height: Some(24),
        spp: Some(1),
        ..Default::default()
    };
    let view = vstf::run::view(&f, &small).unwrap();
    let e = vstf::run::render(&f, &view, renderer::Traversal::Bvh).unwrap_err();
    assert!(
        matches!(&e, vstf::error::Error::NonFinite { message }
            if message.contains("not a finite colour")
            && message.contains("object \"stage floor\"")
            && message.contains("first not finite at its")
            && message.contains("vstf debug")),
        "{e}"
    );
    // The same scene with a finite colour renders.
    f.scene.objects[bars].material.color = glam::DVec3::splat(0.5);
    assert!(vstf::run::render(&f, &view, renderer::Traversal::Bvh).is_ok());
}

#[test]
fn an_absurd_unknown_key_is_named_briefly() {
    let e = error_of(&flange_with(|v| {
        v["camera"]["x".repeat(100_000)] = 1.into()
    }));
    assert!(
        e.len() < 400 && e.contains("(100000 characters)"),
        "{} characters",
        e.len()
    );
}

/// Every input the fuzzer once found failing (`fuzz/found/`) is now refused
/// or rendered, never a failure.
#[test]
fn inputs_the_fuzzer_found_are_handled() {
    let dir = workspace_tests::repo().root().join("fuzz/found");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        let text = std::fs::read_to_string(&p).unwrap();
        let outcome = vstf::fuzz::one(&text);
        assert!(
            !matches!(outcome, vstf::fuzz::Outcome::Failed(_)),
            "{}: {outcome:?}",
            p.display()
        );
        n += 1;
    }
    assert!(n >= 1, "no inputs in {}", dir.display());
}

#[test]
fn mirror_bounces_beyond_the_recursion_limit_are_refused() {
    let e = error_of(&flange_with(|v| v["image"]["max_depth"] = 100000.into()));
    assert!(
        e.contains("image.max_depth: 100000 mirror bounces: at most 64"),
        "{e}"
    );
}

/// A vector or event with too many numbers is named as such, with its
/// path (serde alone says "trailing characters"); too few says how many.
#[test]
fn vectors_of_the_wrong_length_say_how_long_they_should_be() {
    let e = error_of(&flange_with(|v| {
        v["camera"]["position"] = serde_json::json!([0.0, 9.0, 15.0, 1.0])
    }));
    assert!(
        e.contains("camera.position: too many numbers: a position, direction or velocity has 3"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        let i = flange_index(v);
        v["objects"][i]["worldline"]["start"] = serde_json::json!([0.0, 1.0, 2.0, 3.0, 4.0]);
    }));
    assert!(
        e.contains("worldline.start: too many numbers") && e.contains("[t, x, y, z]"),
        "{e}"
    );
    let e = error_of(&flange_with(|v| {
        v["camera"]["position"] = serde_json::json!([0.0, 9.0])
    }));
    assert!(
        e.contains("camera.position: invalid length 2, expected a sequence of 3"),
        "{e}"
    );
}
