//! Which side a moving two-sided face shows (docs/physics.md, "Which side
//! a moving surface shows"): a face flying at 0.9c along its normal is
//! seen, by aberration, from the side the lab would call hidden, and is
//! shaded as that side (the side its own frame shows), lit by a lamp
//! behind it; the lab's side would leave it unlit.

use glam::DVec3;
use renderer::{Model, Step, Traversal};
use vstf::check::{self, Effort};
use vstf::debug::trace_pixel;
use vstf::fixture::Overrides;
use vstf::oracle::{aberrate_galilean, aberrate_lorentz, body_point, retarded};

const CAMERA: DVec3 = DVec3::new(0.0, 0.0, 10.0);

#[test]
fn a_face_flying_along_its_normal_is_lit_on_the_side_its_frame_shows() {
    let face = workspace_tests::fixture("two-sided-face");
    let rows: Vec<_> = check::run_fixture(&face, &Effort::QUICK)
        .unwrap_or_else(|e| panic!("{e}"))
        .quantities
        .into_iter()
        .map(|q| q.judge("two-sided-face"))
        .collect();
    assert_eq!(rows.len(), 4);
    assert!(
        rows.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&rows)
    );
    // Negative control: the same rows expected with the side the lab sees
    // (the normal turned towards the camera in the lab, +x) fail, by far.
    let obj = face.object("face").unwrap();
    let (start, u) = obj.motion.uniform().unwrap();
    let (centre, corner) = (DVec3::ZERO, DVec3::new(0.0, 1.5, -1.5));
    let cases = [
        (centre, true),
        (corner, true),
        (centre, false),
        (corner, false),
    ];
    for (row, (p, lorentz)) in rows.iter().zip(cases) {
        let seen = retarded(&body_point(start.t, start.x, u, p, lorentz), 0.0, CAMERA).unwrap();
        let to_camera = -seen.direction;
        let to_lamp = (face.scene.light.position - seen.x).normalize();
        // Directions towards a source seen from the face's frame; the
        // viewer's is the reverse of the light leaving towards it.
        let frame = |d: DVec3| {
            if lorentz {
                aberrate_lorentz(d, u)
            } else {
                aberrate_galilean(d, u)
            }
        };
        let viewer = -frame(-to_camera);
        assert!(to_camera.x > 0.1, "{}: the lab sees +x", row.quantity);
        assert!(
            viewer.x < -0.3,
            "{}: the face's frame shows {viewer}, not -x",
            row.quantity
        );
        let lab_side = DVec3::X.dot(frame(to_lamp)).max(0.0);
        assert!(
            (row.measured - lab_side).abs() > 20.0 * row.tolerance,
            "{}: the lab side's cosine {lab_side} is as close as {}",
            row.quantity,
            row.measured
        );
    }
}

#[test]
fn the_facing_normal_is_the_side_the_face_frame_shows() {
    let face = workspace_tests::fixture("two-sided-face");
    for model in [Model::RELATIVISTIC, Model::CLASSICAL] {
        let view = vstf::run::view(
            &face,
            &Overrides {
                width: Some(64),
                height: Some(36),
                model: Some(model),
                ..Default::default()
            },
        )
        .unwrap();
        let db = vstf::run::database(&face, view.model.lorentz, Traversal::Bvh).unwrap();
        let log = trace_pixel(&face, &view, &db, 32, 18).unwrap();
        let (event, facing) = log
            .steps
            .iter()
            .find_map(|s| match s {
                Step::Hit {
                    event,
                    facing_normal,
                    ..
                } => Some((*event, *facing_normal)),
                _ => None,
            })
            .expect("the centre pixel misses the face");
        let (lambert, frame) = log
            .steps
            .iter()
            .find_map(|s| match s {
                Step::Shading {
                    lambert,
                    surface_frame,
                    ..
                } => Some((*lambert, *surface_frame)),
                _ => None,
            })
            .unwrap();
        let [n, _, v] = frame.expect("a moving face shades in its own frame");
        assert!((CAMERA - event.x).x > 0.0, "{model:?}: the lab sees +x");
        assert!(v.x < -0.5, "{model:?}: viewer in the frame {v}");
        assert!(n.x < -0.99 && facing.x < -0.99, "{model:?}: {n} {facing}");
        assert!(lambert > 0.4, "{model:?}: n'.l' = {lambert}");
    }
}
