//! Shading in the surface's frame (docs/physics.md): a matte plate sliding
//! at 0.6c under a lamp is as bright as the Lambert law in its own frame
//! says, and measurably not as the lab-frame law (the renderer's old one)
//! says; the debug log shows the directions it shaded with.

use glam::DVec3;
use renderer::{Step, Traversal};
use vstf::check::{self, Effort};
use vstf::debug::trace_pixel;
use vstf::fixture::Overrides;
use vstf::oracle::{body_point, retarded};

#[test]
fn a_sliding_plate_follows_the_lambert_law_in_its_own_frame() {
    let plate = workspace_tests::fixture("lit-plate");
    let rows: Vec<_> = check::run_fixture(&plate, &Effort::QUICK)
        .unwrap_or_else(|e| panic!("{e}"))
        .quantities
        .into_iter()
        .map(|q| q.judge("lit-plate"))
        .collect();
    assert_eq!(rows.len(), 6);
    assert!(
        rows.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&rows)
    );
    // The lab-frame cosine at the same emission events (relativistic
    // rows): a V_obj contracted by 0.8 along x, seen from (0, 6, 12) at t = 0.
    let obj = plate.object("plate").unwrap();
    let (start, u) = obj.motion.uniform().unwrap();
    for (row, x) in rows.iter().take(3).zip([-4.0, 0.0, 4.0]) {
        let p = body_point(start.t, start.x, u, DVec3::new(x, 0.0, 0.0), true);
        let seen = retarded(&p, 0.0, DVec3::new(0.0, 6.0, 12.0)).unwrap();
        let lab = (plate.scene.light.position - seen.x).normalize().y;
        assert!(
            (row.measured - lab).abs() > 20.0 * row.tolerance,
            "{}: the lab-frame cosine {lab} is as close as {}",
            row.quantity,
            row.measured
        );
    }
}

#[test]
fn the_surface_frame_directions_are_logged() {
    let plate = workspace_tests::fixture("lit-plate");
    let view = vstf::run::view(
        &plate,
        &Overrides {
            width: Some(64),
            height: Some(36),
            ..Default::default()
        },
    )
    .unwrap();
    let db = vstf::run::database(&plate, view.model.lorentz, Traversal::Bvh).unwrap();
    let log = trace_pixel(&plate, &view, &db, 32, 18).unwrap();
    let (lambert, frame, light) = log
        .steps
        .iter()
        .find_map(|s| match s {
            Step::Shading {
                lambert,
                surface_frame,
                light_vector,
                ..
            } => Some((*lambert, *surface_frame, *light_vector)),
            _ => None,
        })
        .expect("the centre pixel misses the plate");
    let [n, l, _] = frame.expect("a moving plate shades in its own frame");
    assert_abs_diff_eq!(lambert, n.dot(l), epsilon = 1e-12);
    assert!(
        l.x > light.x + 0.3,
        "the lamp is not seen ahead: lab {light}, plate {l}"
    );
    let text = vstf::debug::describe(&log);
    assert!(text.contains("in the surface's frame: normal"), "{text}");
}

/// A Lambert check of a surface that is not matte is refused at load.
#[test]
fn a_shiny_plate_is_refused() {
    let file = workspace_tests::repo()
        .fixtures_dir()
        .join("lit-plate.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    v["objects"][0]["material"]["specular"] = 0.3.into();
    let e = vstf::fixture::Fixture::parse(&v.to_string(), &file)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("checks[0].measure.lambert.object: \"plate\" must be matte"),
        "{e}"
    );
}
