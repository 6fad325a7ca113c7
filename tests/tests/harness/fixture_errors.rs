//! Bad fixtures get a clear error naming the file, the field and what was
//! expected; never a panic or a silently wrong picture.

use std::path::Path;
use vstf::fixture::Fixture;

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
    assert!(e.contains("worldline: give one of: extrusion"), "{e}");
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

/// A fixture in a scratch folder whose first object is the OBJ file `obj`
/// (written beside it by `make`), parsed.
fn with_obj(name: &str, make: impl FnOnce(&Path)) -> Result<Fixture, String> {
    let dir = std::env::temp_dir().join(format!("vstf-obj-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    make(&dir.join("mesh.obj"));
    let text =
        flange_with(|v| v["objects"][0]["mesh"] = serde_json::json!({"obj": {"path": "mesh.obj"}}));
    let result = Fixture::parse(&text, &dir.join("scene.json")).map_err(|e| e.to_string());
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

/// The memory budget's estimate of the prisms is never below what the
/// database holds, for every kind of motion (uniform, keyframed, hyperbolic
/// H_obj and Born-rigid V_obj), and not far above it.
#[test]
fn the_prism_estimate_bounds_the_database() {
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        let p = vstf::prisms(&f.scene);
        let estimate = p.translated + p.keyframed;
        for lorentz in [false, true] {
            let built = f.database(lorentz).unwrap().prism_count() as u64;
            assert!(estimate >= built, "{name}: estimate {estimate} < {built}");
            assert!(
                estimate <= 2 * built.max(1),
                "{name}: estimate {estimate} >> {built}"
            );
        }
    }
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
