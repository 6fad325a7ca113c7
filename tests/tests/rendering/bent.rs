//! Bent primary rays: the chords of a geodesic that pass clear of every
//! object are not searched, so each must be one that no search could meet.

use glam::DVec3;
use renderer::{Event, Geodesic, Leg, LightSpeed, Spacetime, Traversal};

/// Every chord of `lensed-flange`'s geodesics (a 24 x 18 grid of
/// directions over its view, sized to a 1920 x 1080 pixel) that the
/// geodesic says passed clear meets nothing in the database; the search
/// does meet objects on other chords, and most chords pass clear (the
/// test is not vacuous).
#[test]
fn chords_that_pass_clear_meet_nothing() {
    let f = workspace_tests::fixture("lensed-flange");
    let view = vstf::run::view(&f, &Default::default()).unwrap();
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    let Spacetime::Schwarzschild(hole) = f.scene.spacetime else {
        panic!("lensed-flange has a mass");
    };
    let (lo, hi) = db.spatial_bounds();
    let eye = Event::new(view.camera_t, f.spec.camera.position);
    let forward = (hole.centre - eye.x).normalize();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let pixel = 2.0 * (8.0_f64).to_radians().tan() / 1080.0;
    let (mut clear, mut searched, mut met) = (0, 0, 0);
    for j in 0..18 {
        for i in 0..24 {
            let (x, y) = (f64::from(i) / 23.0 - 0.5, f64::from(j) / 17.0 - 0.5);
            let d = (forward + right * (x * 0.5) + up * (y * 0.28)).normalize();
            let mut geodesic = Geodesic::backwards(
                &hole,
                eye,
                d,
                LightSpeed::Finite,
                db.reach_from(hole.centre),
            )
            .sized_to_pixel(pixel)
            .with_geometry_in(lo, hi);
            while let Some(Leg::Chord(chord, len)) = geodesic.next() {
                let hit = db.closest_hit(&chord, (0.0, len));
                if geodesic.passed_clear() {
                    clear += 1;
                    assert!(hit.is_none(), "a clear chord met {hit:?}");
                } else {
                    searched += 1;
                    met += usize::from(hit.is_some());
                }
                if hit.is_some() || len.is_infinite() {
                    break;
                }
            }
        }
    }
    assert!(met > 200, "{met} of 432 rays met an object");
    assert!(
        clear > searched,
        "{clear} clear chords against {searched} searched"
    );
}
