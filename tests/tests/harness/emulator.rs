//! The slice-by-slice emulator of Hornof et al. 2025 as a second oracle for
//! whole images (docs/physics.md, "The 2025 Terrell-Penrose experiment"):
//! it agrees with the 4D tracer pixel by pixel on the cube, and a cube
//! rendered slower than declared disagrees away from every edge.

use vstf::fixture::Fixture;
use workspace_tests::declared_rows as rows;

/// The hornof-2025 fixture with only its checks named in `keep`, and the
/// cube's speed set to `speed` (its faces cross x = 0 at t = 0 whatever it).
fn hornof(speed: f64, keep: &[&str]) -> Fixture {
    workspace_tests::fixture_with("hornof-2025", |v| {
        for o in v["objects"].as_array_mut().unwrap() {
            if o["name"].as_str().unwrap().starts_with("cube") {
                let t0 = o["worldline"]["start"][0].as_f64().unwrap();
                o["worldline"]["start"][1] = (-speed * t0).into();
                o["worldline"]["velocity"] = serde_json::json!([-speed, 0.0, 0.0]);
            }
        }
        let checks: Vec<serde_json::Value> = v["checks"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| keep.contains(&c["name"].as_str().unwrap()))
            .cloned()
            .collect();
        assert_eq!(checks.len(), keep.len());
        v["checks"] = checks.into();
    })
}

const PIXELS: [&str; 2] = [
    "emulator, 400 slices: fraction of pixels disagreeing",
    "emulator, 400 slices: pixels disagreeing away from edges",
];

#[test]
fn the_emulator_agrees_with_the_tracer_and_catches_a_slower_cube() {
    let declared = hornof(0.8, &PIXELS);
    let honest = rows(&declared, &declared);
    assert!(
        honest.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&honest)
    );
    assert_eq!(honest[1].measured, 0.0);
    let slower = rows(&hornof(0.7, &PIXELS), &declared);
    assert!(
        !slower[1].pass && slower[1].measured > 100.0,
        "a cube rendered at 0.7c passed the emulator of 0.8c: {:?}",
        slower[1]
    );
}

/// The gate's blur: the thicker the slices, the farther the emulated left
/// edge (each within its derived bound); a pixel comparison at a gate
/// that blurs by more than a pixel is refused, not passed.
#[test]
fn thicker_slices_blur_more_and_pixel_comparisons_need_thin_ones() {
    let names = [
        "emulator, 400 slices: left edge shift",
        "emulator, 20 slices, 17 cm gate: left edge shift",
    ];
    let f = hornof(0.8, &names);
    let r = rows(&f, &f);
    assert!(r.iter().all(|r| r.pass), "{}", vstf::report::table(&r));
    assert!(r[1].measured.abs() > 2.0 * r[0].measured.abs(), "{r:?}");
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("hornof-2025.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let mut thick = v["checks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == PIXELS[1])
        .unwrap()
        .clone();
    thick["measure"]["emulator"]["slices"] = 20.into();
    v["checks"] = serde_json::json!([thick]);
    let f = Fixture::parse(&v.to_string(), &file).unwrap();
    let r = rows(&f, &f);
    assert!(!r[0].pass, "a torn comparison passed: {r:?}");
    assert!(
        r[0].error
            .as_deref()
            .is_some_and(|e| e.contains("blur the emulated image by")),
        "{r:?}"
    );
}
