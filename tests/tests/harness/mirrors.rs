//! Moving mirrors (docs/physics.md, "Moving mirrors"): the reflected
//! marker's edge and the reflected light's Doppler factor, measured from
//! the renders of the three mirror fixtures, against Einstein's law; a
//! mirror rendered moving other than it is declared, or a scene expected
//! by the static law, fails.

use vstf::fixture::Fixture;
use workspace_tests::{declared_rows as rows, fixture_with as mirror_with};

/// The mirror's velocity along z set to `w`, its position at t = 0 kept
/// (z = -10).
fn with_mirror_speed(name: &str, w: f64) -> Fixture {
    mirror_with(name, |v| {
        let wl = &mut v["objects"][0]["worldline"];
        let t0 = wl["start"][0].as_f64().unwrap();
        wl["start"][3] = (-10.0 + w * t0).into();
        wl["velocity"] = serde_json::json!([0.0, 0.0, w]);
    })
}

#[test]
fn each_mirror_passes_and_a_slower_mirror_fails() {
    for (name, w) in [("mirror-approaching", 0.5), ("mirror-receding", -0.5)] {
        let declared = mirror_with(name, |_| {});
        let honest = rows(&declared, &declared);
        assert_eq!(honest.len(), 4);
        assert!(
            honest.iter().all(|r| r.pass),
            "{}",
            vstf::report::table(&honest)
        );
        // Rendered at 0.45c where 0.5c is declared: both edge rows and
        // both Doppler rows fail.
        let slower = rows(&with_mirror_speed(name, 0.9 * w), &declared);
        for r in &slower {
            assert!(!r.pass, "{name}: a slower mirror went unnoticed: {r:?}");
        }
    }
}

/// The receding mirror's render, expected as if the mirror stood still
/// where it is at t = 0 (the lab-frame law the renderer once used for
/// every mirror): the edge is tens of pixels off. A mirror moving in its
/// own plane sweeps out the same world-sheet as a static one, so the
/// parallel mirror's render passes the static mirror's expectations.
#[test]
fn the_static_law_is_refuted_except_for_motion_in_the_plane() {
    let moving = mirror_with("mirror-receding", |_| {});
    let still = with_mirror_speed("mirror-receding", 0.0);
    let r = rows(&moving, &still);
    let off = (r[0].measured - r[0].expected).abs();
    assert!(!r[0].pass && off > 20.0, "{r:?}");
    let parallel = mirror_with("mirror-parallel", |_| {});
    let static_mirror = mirror_with("mirror-parallel", |v| {
        v["objects"][0]["worldline"]["start"] = serde_json::json!([-30.0, 0.0, 0.0, -10.0]);
        v["objects"][0]["worldline"]["velocity"] = serde_json::json!([0.0, 0.0, 0.0]);
    });
    let r = rows(&parallel, &static_mirror);
    assert!(r.iter().all(|r| r.pass), "{}", vstf::report::table(&r));
}

/// Declarations a reflection cannot be expected from are refused at load,
/// naming the file and the JSON path.
#[test]
fn bad_reflection_declarations_name_the_file_and_json_path() {
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("mirror-approaching.json");
    let text = std::fs::read_to_string(&file).unwrap();
    type Edit = Box<dyn Fn(&mut serde_json::Value)>;
    let cases: Vec<(Edit, &str)> = vec![
        (
            Box::new(|v| v["objects"][0]["material"]["mirror"] = 0.5.into()),
            "checks[0].measure.reflection.mirror: \"mirror\" must reflect fully",
        ),
        (
            Box::new(|v| {
                v["objects"][1]["worldline"] = serde_json::json!({"start": [0.0, 16.0, 0.0, 2.0], "velocity": [0.1, 0.0, 0.0], "proper_lifetime": 10.0});
                v["objects"][1].as_object_mut().unwrap().remove("position");
            }),
            "checks[0].measure.reflection.marker: \"marker\" must be static",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["reflection"]["row"] = 160.into()),
            "checks[0].measure.reflection.row: outside the view's 320x160 image",
        ),
        (
            Box::new(|v| v["checks"][0]["measure"]["reflection"]["column"] = 3.into()),
            "checks[0].measure.reflection.column: a column reading finds its column",
        ),
        (
            Box::new(|v| {
                v["checks"][2]["measure"]["reflection"]
                    .as_object_mut()
                    .unwrap()
                    .remove("column");
            }),
            "checks[2].measure.reflection.column: read: doppler needs the column",
        ),
        (
            Box::new(|v| v["checks"][2]["measure"]["reflection"]["view"] = "relativistic".into()),
            "checks[2].measure.reflection.view: view \"relativistic\" does not shift wavelengths",
        ),
        (
            Box::new(|v| {
                v["checks"][0]["measure"]["reflection"]["edge"] =
                    serde_json::json!([[0.0, -20.0, 0.0], [40.0, 20.0, 0.0]])
            }),
            "checks[0].measure.reflection.edge: not along an edge of \"marker\"'s mesh",
        ),
        (
            Box::new(|v| v["image"]["max_depth"] = 0.into()),
            "checks[0].measure.reflection.mirror: the fixture follows no mirror bounces",
        ),
    ];
    for (edit, expected) in cases {
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        edit(&mut v);
        let e = match Fixture::parse(&v.to_string(), &file) {
            Ok(_) => panic!("accepted; expected {expected:?}"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(expected), "expected {expected:?} in:\n{e}");
        assert!(e.starts_with(&file.display().to_string()), "{e}");
    }
}
