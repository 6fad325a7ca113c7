//! The Shapiro delay (docs/checks.md, `lensing` with `read: delay`): a ball
//! switched on at t = 0 behind the mass is first and fully seen at camera
//! times whose mean is the quadrature's coordinate light time past the
//! mass, within the ball's radius; the flat straight-line time (no delay)
//! lies more than five tolerances away, and rendered without the mass the
//! row fails.

use renderer::Spacetime;
use workspace_tests::{declared_rows as rows, fixture};

#[test]
fn the_ball_is_first_seen_a_shapiro_delay_late() {
    let f = fixture("shapiro-delay");
    let all = rows(&f, &f);
    assert_eq!(all.len(), 1);
    let r = &all[0];
    assert!(r.pass, "{r:?}");
    let straight = glam::DVec3::new(14.999437506, 0.0, -999.887502109 - 1000.0).length();
    assert!(r.expected - straight > 10.0, "{r:?}");
    assert!((r.measured - straight).abs() > 5.0 * r.tolerance, "{r:?}");
    let mut flat = f.clone();
    flat.scene.spacetime = Spacetime::Flat;
    let r = &rows(&flat, &f)[0];
    // Unbent, its light misses the view looking where the lensed ball is seen.
    assert!(!r.pass, "no mass went unnoticed: {r:?}");
}
