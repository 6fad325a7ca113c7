//! Extremes of an expectation over a body's outline.

use glam::DVec3;

/// The least and greatest values of `f` over the boundary of the square
/// with corners `corners` (in order), by a dense scan of each side refined by
/// golden-section search.
pub fn extremes_on_polygon(corners: &[DVec3], f: impl Fn(DVec3) -> f64) -> (f64, f64) {
    let extreme = |sign: f64| {
        let mut best = f64::NEG_INFINITY;
        for k in 0..corners.len() {
            let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
            let g = |s: f64| sign * f(a + (b - a) * s);
            let n = 400;
            let i = (0..=n)
                .max_by(|i, j| g(*i as f64 / n as f64).total_cmp(&g(*j as f64 / n as f64)))
                .unwrap_or(0);
            let (mut lo, mut hi) = (
                ((i as f64) - 1.0).max(0.0) / n as f64,
                ((i as f64) + 1.0).min(n as f64) / n as f64,
            );
            let phi = (5f64.sqrt() - 1.0) / 2.0;
            for _ in 0..100 {
                let (m1, m2) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
                if g(m1) < g(m2) {
                    lo = m1
                } else {
                    hi = m2
                }
            }
            best = best.max(g((lo + hi) / 2.0)).max(g(0.0)).max(g(1.0));
        }
        sign * best
    };
    (extreme(-1.0), extreme(1.0))
}
