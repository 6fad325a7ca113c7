//! Extremes of an expectation over a body's outline: over a polygon's
//! sides, or over a closed curve. Each is a scan of samples refined by
//! golden-section search between the best sample's neighbours, so that it
//! is the curve's own extreme, not the best of the samples: two samplings
//! of one curve agree to rounding.

use glam::DVec3;

/// The golden-section search for the greatest value of `g` on [lo, hi],
/// `g` unimodal there; the value at the bracket's end.
fn golden_max(g: impl Fn(f64) -> f64, (mut lo, mut hi): (f64, f64)) -> f64 {
    let phi = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (m1, m2) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
        if g(m1) < g(m2) {
            lo = m1
        } else {
            hi = m2
        }
    }
    g((lo + hi) / 2.0)
}

/// The least and greatest values of `f` over the boundary of the polygon
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
            let bracket = (
                ((i as f64) - 1.0).max(0.0) / n as f64,
                ((i as f64) + 1.0).min(n as f64) / n as f64,
            );
            best = best.max(golden_max(g, bracket)).max(g(0.0)).max(g(1.0));
        }
        sign * best
    };
    (extreme(-1.0), extreme(1.0))
}

/// The least and greatest values of `f` on a closed curve parametrised by
/// s in [0, 1) (`f` periodic), from the samples at the parameters `at`
/// (increasing, in [0, 1)), each extreme refined between the neighbours of
/// the best sample. The samples must resolve the curve: `f` unimodal
/// between the neighbours of each extreme.
pub fn extremes_on_loop(at: &[f64], f: impl Fn(f64) -> f64) -> (f64, f64) {
    let n = at.len();
    let extreme = |sign: f64| {
        let g = |s: f64| sign * f(s);
        let i = (0..n)
            .max_by(|i, j| g(at[*i]).total_cmp(&g(at[*j])))
            .unwrap_or(0);
        let before = if i == 0 { at[n - 1] - 1.0 } else { at[i - 1] };
        let after = if i + 1 == n { at[0] + 1.0 } else { at[i + 1] };
        sign * golden_max(g, (before, after)).max(g(at[i]))
    };
    (extreme(-1.0), extreme(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// A curve's height above a tilted plane, greatest off every sample.
    fn height(s: f64) -> f64 {
        let a = TAU * s;
        (a + 0.123).sin() + 0.3 * (2.0 * a).cos()
    }

    #[test]
    fn a_loop_sampled_two_ways_has_the_same_extremes() {
        let even: Vec<f64> = (0..720).map(|k| f64::from(k) / 720.0).collect();
        let crowded: Vec<f64> = (0..97).map(|k| (f64::from(k) / 97.0).powi(2)).collect();
        let (a, b) = (
            extremes_on_loop(&even, height),
            extremes_on_loop(&crowded, height),
        );
        assert!(
            (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
            "{a:?} {b:?}"
        );
        let best_sample = even.iter().map(|s| height(*s)).fold(f64::MIN, f64::max);
        assert!(
            a.1 - best_sample > 1e-9,
            "the samples alone miss the extreme"
        );
    }

    #[test]
    fn a_polygon_with_its_sides_split_has_the_same_extremes() {
        let square = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        ];
        let split: Vec<DVec3> = (0..4)
            .flat_map(|k| {
                let (a, b) = (square[k], square[(k + 1) % 4]);
                [a, a + (b - a) * 0.37]
            })
            .collect();
        let f = |p: DVec3| (p.x + 0.3).atan2(4.0 - p.y) + 0.2 * (p.y * 1.7).sin();
        let (a, b) = (
            extremes_on_polygon(&square, f),
            extremes_on_polygon(&split, f),
        );
        assert!(
            (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
            "{a:?} {b:?}"
        );
    }
}
