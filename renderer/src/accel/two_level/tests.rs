//! The two-level structure's tests: moving objects' time slices.

use super::*;

/// A stretch of 20 prisms, each box the comoving cube [-1, 1]^3,
/// moving at 0.9 along x over lab times 0..100: 45 time slices.
fn moving_cubes() -> TwoLevel {
    let stretch = StretchPrisms {
        origin: Event::new(0.0, DVec3::ZERO),
        velocity: DVec3::new(0.9, 0.0, 0.0),
        span: (0.0, 100.0),
        prisms: 0..20,
        translation: true,
    };
    TwoLevel::build(std::iter::once(&stretch), |_, _| {
        (DVec3::splat(-1.0), DVec3::splat(1.0))
    })
}

/// How many times the ray `o + s d` tests each prism, the same at
/// every vector level the machine has.
fn times_tested(two: &TwoLevel, o: DVec4, d: DVec4) -> [u32; 20] {
    let mut counts = SimdLevel::supported().into_iter().map(|level| {
        let mut tested = [0; 20];
        two.closest(level, o, d, (0.0, f64::INFINITY), |_, _, items, _| {
            items.iter().for_each(|&p| tested[p as usize] += 1);
            None
        });
        tested
    });
    let first = counts.next().unwrap_or_default();
    counts.for_each(|c| assert_eq!(c, first));
    first
}

/// A ray that keeps pace with a moving object crosses all its time
/// slices inside their boxes: its stretch's tree is searched once, so
/// each prism is tested once (searched slice by slice, each would be
/// tested once a slice, 45 times).
#[test]
fn a_ray_crossing_a_moving_objects_slices_tests_each_prism_once() {
    let two = moving_cubes();
    assert_eq!(two.slices.len(), 45);
    // At lab time t the ray is at x = 0.9 t, the object's centre.
    let (o, d) = (
        DVec4::new(90.0, 0.0, 0.0, 100.0),
        DVec4::new(-0.9, 0.0, 1e-3, -1.0),
    );
    assert_eq!(times_tested(&two, o, d), [1; 20]);
}

/// A ray at one lab time (infinite light speed) meets one slice of
/// the moving object, and every prism once.
#[test]
fn a_ray_at_one_time_meets_one_slice() {
    let two = moving_cubes();
    let (o, d) = (
        DVec4::new(45.0, 0.0, 5.0, 50.5),
        DVec4::new(0.0, 0.0, -1.0, 0.0),
    );
    assert_eq!(times_tested(&two, o, d), [1; 20]);
}

/// Only a uniformly moving stretch of [`LARGE_FROM`] prisms or more has
/// leaves of [`LARGE_LEAF`]: one prism fewer, or a keyframe interval of as
/// many, keeps [`LEAF_SIZE`].
#[test]
fn only_a_large_uniform_stretch_has_large_leaves() {
    let stretch = |count: usize, translation: bool| StretchPrisms {
        origin: Event::new(0.0, DVec3::ZERO),
        velocity: DVec3::ZERO,
        span: (0.0, 1.0),
        prisms: 7..7 + count,
        translation,
    };
    assert_eq!(stretch(LARGE_FROM, true).leaf_size(), LARGE_LEAF);
    assert_eq!(stretch(LARGE_FROM - 1, true).leaf_size(), LEAF_SIZE);
    assert_eq!(stretch(LARGE_FROM, false).leaf_size(), LEAF_SIZE);
}
