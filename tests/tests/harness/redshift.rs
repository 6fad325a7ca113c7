//! Gravitational redshift (docs/checks.md, `doppler` in a mass's field): a
//! static panel glowing as a blackbody 4 M from a mass is seen by a static
//! camera at r = 100 M with its frequencies scaled by
//! sqrt((1 - 2M/r_e) / (1 - 2M/r_o)), read from its colour and from the
//! searchlight's ratios. Rendered without the mass (no redshift) or with a
//! mass 10% heavier every row fails, the Newtonian 1 - M/r lies outside
//! every reading, and a panel that moves or is off the radial line is an
//! error, not a row.

use renderer::Spacetime;
use vstf::oracle::schwarzschild::{newtonian_redshift, static_redshift};
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
fn the_panel_is_seen_redshifted_by_the_static_observers_clock_ratio() {
    let f = fixture("redshift-panel");
    let all = rows(&f, &f);
    assert_eq!(all.len(), 3);
    let expected = static_redshift(1.0, 4.0, 100.0);
    let newtonian = newtonian_redshift(1.0, 4.0, 100.0);
    for r in &all {
        assert!(r.pass, "{r:?}");
        assert!((r.expected - expected).abs() < 2e-3, "{r:?}");
        assert!(r.tolerance < 0.01, "{r:?}");
        assert!(
            (r.measured - newtonian).abs() > r.tolerance,
            "the Newtonian factor {newtonian} is not told apart: {r:?}"
        );
        assert!((r.measured - 1.0).abs() > r.tolerance, "{r:?}");
    }
}

#[test]
fn rendered_flat_or_heavier_every_row_fails() {
    let f = fixture("redshift-panel");
    for k in [0.0, 1.1] {
        for r in rows(&with_mass(&f, k), &f) {
            assert!(!r.pass, "mass x {k} went unnoticed: {r:?}");
        }
    }
}

#[test]
fn a_moving_or_off_axis_panel_is_an_error() {
    let moving = fixture_with("redshift-panel", |v| {
        let panel = &mut v["objects"][0];
        panel["worldline"] = serde_json::json!({
            "start": [-100.0, 0.0, 0.0, 4.0], "velocity": [0.0, 0.1, 0.0], "proper_lifetime": 300.0
        });
        panel.as_object_mut().unwrap().remove("position");
        panel["kind"] = "V_obj".into();
    });
    let off_axis = fixture_with("redshift-panel", |v| {
        v["objects"][0]["position"] = serde_json::json!([0.0, 6.0, 4.0]);
    });
    for (f, says) in [(moving, "moves"), (off_axis, "radially")] {
        for r in rows(&f, &f) {
            assert!(!r.pass, "{r:?}");
            let e = r.error.as_deref().unwrap_or_default();
            assert!(e.contains(says), "{e}");
        }
    }
}

#[test]
fn a_redshift_read_at_a_point_is_refused() {
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("redshift-panel.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    v["checks"][0]["measure"]["doppler"]["point"] = serde_json::json!([0.0, 0.0, 0.0]);
    let e = vstf::Fixture::parse(&v.to_string(), &file)
        .unwrap_err()
        .to_string();
    assert!(e.contains("checks[0].measure.doppler.point"), "{e}");
}
