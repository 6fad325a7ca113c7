//! A Born-rigid body is Born-rigid everywhere, not only at its vertices
//! (docs/physics.md, "The Born-rigid surface"): the `born-rigid-plate`
//! fixture's edges, tilted to the acceleration, are seen where the exact
//! body puts them; the flat triangles between the exactly placed vertices
//! (the body as it was drawn before the surface was cut) are seen elsewhere.

use vstf::check::{self, Effort, Row};

/// The rows of `f`'s checks at the quick effort.
fn rows(f: &vstf::Fixture, name: &str) -> Vec<Row> {
    check::run_fixture(f, &Effort::QUICK)
        .unwrap_or_else(|e| panic!("{e}"))
        .quantities
        .into_iter()
        .map(|q| q.judge(name))
        .collect()
}

/// The exact lab x at lab time `t` of the plate's rest point at x = `xi`
/// (from rest at x = -9, t = 0, proper acceleration 0.2 along x): on the
/// hyperbola (x + 9 - xi + 1/a)^2 - t^2 = (1/a + xi)^2.
fn exact_x(xi: f64, t: f64) -> f64 {
    let big_a = 5.0 + xi;
    -9.0 + ((big_a * big_a + t * t).sqrt() - 5.0)
}

/// The plate as flat triangles between its corners, each corner on its own
/// exact hyperbola: an H_obj keyframed every 0.1 t.units with the corners'
/// lab offsets from the reference point (straight between keyframes, within
/// 0.01^2 / (8 x 3) = 4e-6 of the hyperbolae).
fn flat_plate(v: &mut serde_json::Value) {
    let corners = [[-2.0, -1.5], [0.0, -1.5], [2.0, 1.5], [0.0, 1.5]];
    let keyframes: Vec<serde_json::Value> = (0..=250)
        .map(|k| {
            let t = 0.1 * f64::from(k);
            let reference = exact_x(0.0, t);
            let vertices: Vec<[f64; 3]> = corners
                .iter()
                .map(|[x, y]| [exact_x(*x, t) - reference, *y, 0.0])
                .collect();
            serde_json::json!({"t": t, "position": [reference, 0.0, 0.0], "vertices": vertices})
        })
        .collect();
    let plate = &mut v["objects"][0];
    plate["kind"] = "H_obj".into();
    plate["worldline"] = serde_json::json!({ "keyframes": keyframes });
}

#[test]
fn tilted_edges_are_where_the_exact_born_rigid_body_puts_them() {
    let exact = rows(
        &workspace_tests::fixture("born-rigid-plate"),
        "born-rigid-plate",
    );
    assert_eq!(exact.len(), 6);
    assert!(
        exact.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&exact)
    );
    // Negative control: the flat body is measured where its own oracle
    // (straight between the keyframed corners) puts it, and that is far
    // outside each row's tolerance about the exact body's edge.
    let flat = rows(
        &workspace_tests::fixture_with("born-rigid-plate", flat_plate),
        "flat",
    );
    assert!(
        flat.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&flat)
    );
    for (e, f) in exact.iter().zip(&flat) {
        let off = (f.measured - e.expected).abs();
        assert!(
            off > 5.0 * e.tolerance,
            "{}: the flat body is {off} off, within {} of the exact one",
            e.quantity,
            e.tolerance
        );
    }
}
