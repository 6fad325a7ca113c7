//! Where along a straight edge a function of the seen point takes a given
//! value: the edge point whose retarded image lands on an image row, or on
//! a level of a plane.

/// Samples along [0, 1] before bisecting: enough to separate the crossings
/// of a gently curved image of an edge.
const SAMPLES: usize = 64;

/// The smallest s in [0, 1] with `f(s) = 0`, for `f` continuous where it is
/// defined (`None` where the point is not seen): the first sign change on a
/// grid of 64 steps, then bisection to rounding. `None` when `f`
/// does not change sign on [0, 1].
pub fn first_root(f: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let s_at = |k: usize| k as f64 / SAMPLES as f64;
    let mut previous: Option<(f64, f64)> = None;
    for k in 0..=SAMPLES {
        let s = s_at(k);
        let Some(v) = f(s) else {
            previous = None;
            continue;
        };
        if v == 0.0 {
            return Some(s);
        }
        if let Some((s0, v0)) = previous {
            if v0.signum() != v.signum() {
                return Some(bisect(&f, (s0, v0), s));
            }
        }
        previous = Some((s, v));
    }
    None
}

/// Bisects [lo, hi] (f(lo) = v_lo, of the other sign at hi) to rounding.
fn bisect(f: &impl Fn(f64) -> Option<f64>, (mut lo, v_lo): (f64, f64), mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        match f(mid) {
            Some(0.0) => return mid,
            Some(v) if v.signum() == v_lo.signum() => lo = mid,
            Some(_) => hi = mid,
            None => break,
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn finds_the_crossing_to_rounding_and_only_where_there_is_one() {
        let s = first_root(|s| Some((s - 0.3).powi(3) + 0.01 * (s - 0.3))).unwrap();
        assert_abs_diff_eq!(s, 0.3, epsilon = 1e-14);
        assert_eq!(first_root(|s| Some(s - 0.5)), Some(0.5));
        assert_eq!(first_root(|s| Some(s + 0.1)), None);
        assert_eq!(first_root(|_| None), None);
    }
}
