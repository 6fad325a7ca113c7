//! Per-point velocity (docs/physics.md, "Spinning objects"): the two
//! sides of a spinning disc are measured to shift oppositely, each by its
//! own velocity's Doppler factor; expected from the reference point's
//! velocity (at rest), as the renderer once shaded them, every row fails.

use renderer::{Step, Traversal};
use vstf::debug::trace_pixel;
use vstf::fixture::{Fixture, Overrides};
use workspace_tests::declared_rows as rows;

fn disc_with(edit: impl FnOnce(&mut serde_json::Value)) -> Fixture {
    workspace_tests::fixture_with("spinning-disc", edit)
}

#[test]
fn the_sides_of_a_spinning_disc_shift_oppositely() {
    let disc = disc_with(|_| {});
    let honest = rows(&disc, &disc);
    assert_eq!(honest.len(), 8);
    assert!(
        honest.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&honest)
    );
    let (approaching, receding) = (honest[0].measured, honest[2].measured);
    assert!(
        approaching > 1.3 && receding < 0.75,
        "{approaching} {receding}"
    );
    // Expected as if every point moved with the (resting) reference point:
    // D = 1 on both sides, and every row fails.
    let still = disc_with(|v| {
        for k in v["objects"][0]["worldline"]["keyframes"]
            .as_array_mut()
            .unwrap()
        {
            k["rotation"]["degrees"] = 0.0.into();
        }
    });
    let naive = rows(&disc, &still);
    for r in &naive {
        assert!(!r.pass, "the reference point's velocity passed: {r:?}");
        assert_eq!(r.expected, 1.0);
    }
}

/// The logged surface velocity at a hit on either side of the disc points
/// the way the disc turns there (+z on the left, -z on the right).
#[test]
fn each_sides_own_velocity_is_logged() {
    let disc = disc_with(|_| {});
    let view = vstf::run::view(
        &disc,
        &Overrides {
            width: Some(64),
            height: Some(36),
            ..Default::default()
        },
    )
    .unwrap();
    let db = vstf::run::database(&disc, view.model.lorentz, Traversal::Bvh).unwrap();
    let velocity_at = |x: u32| {
        let log = trace_pixel(&disc, &view, &db, x, 18).unwrap();
        log.steps
            .iter()
            .find_map(|s| match s {
                Step::Doppler {
                    surface_velocity, ..
                } => Some(*surface_velocity),
                _ => None,
            })
            .expect("no Doppler step: the pixel misses the disc")
    };
    let (left, right) = (velocity_at(20), velocity_at(44));
    assert!(left.z > 0.2 && right.z < -0.2, "{left} {right}");
}

/// A point off the object's surface is refused at load with its JSON path.
#[test]
fn a_point_off_the_surface_is_refused() {
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("spinning-disc.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    v["checks"][0]["measure"]["doppler"]["point"] = serde_json::json!([-1.6, 0.5, 0.0]);
    let e = Fixture::parse(&v.to_string(), &file)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("checks[0].measure.doppler.point: not on the surface of \"disc\"'s mesh"),
        "{e}"
    );
    v["checks"][0]["measure"]["doppler"]["point"] = serde_json::json!([-2.5, 0.0, 0.0]);
    assert!(
        Fixture::parse(&v.to_string(), &file).is_err(),
        "a point beyond the rim was accepted"
    );
}
