//! The `lensing` check kind (docs/checks.md): a mass's shadow, the Einstein
//! ring of a disc behind it, the deflection of a marker's light and the
//! image of a star of the sky are where the oracle puts them; rendered without the mass, or with a mass
//! 10% heavier, every row fails; declarations without a mass are refused.

use renderer::Spacetime;
use workspace_tests::{declared_rows as rows, fixture, fixture_with};

/// The fixture rendered with its mass scaled by `k` (0: flat).
fn with_mass(f: &vstf::Fixture, k: f64) -> vstf::Fixture {
    let mut g = f.clone();
    let Spacetime::Schwarzschild(s) = g.scene.spacetime else {
        panic!("{} has a mass", f.name);
    };
    g.scene.spacetime = Spacetime::of_mass(s.mass * k, s.centre);
    g
}

#[test]
fn the_shadow_ring_and_deflection_are_where_the_oracle_puts_them() {
    for name in [
        "black-hole",
        "lensed-marker",
        "black-hole-stars",
        "lensed-grid",
    ] {
        let f = fixture(name);
        let all = rows(&f, &f);
        assert!(!all.is_empty());
        for r in &all {
            assert!(r.pass, "{r:?}");
        }
    }
}

#[test]
fn rendered_flat_or_heavier_every_row_fails() {
    for name in [
        "black-hole",
        "lensed-marker",
        "black-hole-stars",
        "lensed-grid",
    ] {
        let f = fixture(name);
        for k in [0.0, 1.1] {
            for r in rows(&with_mass(&f, k), &f) {
                assert!(!r.pass, "mass x {k} went unnoticed: {r:?}");
            }
        }
    }
}

#[test]
fn a_massless_spacetime_is_flat_and_lensing_needs_a_mass() {
    let flat = fixture_with("black-hole", |v| {
        v["spacetime"]["schwarzschild"]["mass"] = 0.0.into();
        v["checks"] = serde_json::json!([]);
    });
    assert_eq!(flat.scene.spacetime, Spacetime::Flat);
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("black-hole.json");
    let refused = |edit: &dyn Fn(&mut serde_json::Value), expected: &str| {
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        edit(&mut v);
        let e = vstf::Fixture::parse(&v.to_string(), &file)
            .unwrap_err()
            .to_string();
        assert!(e.contains(expected), "{e}");
    };
    refused(
        &|v| v["spacetime"]["schwarzschild"]["mass"] = 0.0.into(),
        "checks[0].measure.lensing.read",
    );
    refused(
        &|v| v["spacetime"]["schwarzschild"]["mass"] = (-1.0).into(),
        "spacetime.schwarzschild.mass",
    );
    refused(
        &|v| v["checks"][1]["measure"]["lensing"]["marker"] = "nothing".into(),
        "checks[1].measure.lensing.marker",
    );
    refused(
        &|v| v["camera"]["position"] = serde_json::json!([0.0, 0.0, 2.5]),
        "camera.position",
    );
    let star = serde_json::json!({"view": "view", "read": "star", "star": [0.0, 0.0, -1.0]});
    refused(
        &|v| v["checks"][0]["measure"]["lensing"] = star.clone(),
        "checks[0].measure.lensing.star: the fixture has no sky",
    );
    refused(
        &|v| {
            v["checks"][0]["measure"]["lensing"]["star"] = serde_json::json!([0.0, 0.0, -1.0]);
        },
        "checks[0].measure.lensing.star",
    );
}
