//! The quadratic equations of the light-cone solves.

/// The real roots of a x^2 + b x + c = 0, computed stably: with
/// q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2 the roots are q / a and c / q, so
/// neither subtracts nearly equal numbers. Where |a| < `linear_below` the
/// equation is taken as linear, b x + c = 0. No roots when the discriminant
/// is negative or the equation degenerates to c = 0.
pub fn quadratic_roots(a: f64, b: f64, c: f64, linear_below: f64) -> Vec<f64> {
    if a.abs() < linear_below {
        return if b == 0.0 { vec![] } else { vec![-c / b] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut roots = vec![q / a];
    if q != 0.0 {
        roots.push(c / q);
    }
    roots
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn the_small_root_survives_cancellation() {
        // x^2 - 1e8 x + 1: roots 1e8 and 1e-8; (-b - sqrt(b^2 - 4ac)) / 2a loses the small one.
        let mut r = quadratic_roots(1.0, -1e8, 1.0, 1e-15);
        r.sort_by(f64::total_cmp);
        assert_abs_diff_eq!(r[0] / 1e-8, 1.0, epsilon = 1e-15);
        assert_abs_diff_eq!(r[1] / 1e8, 1.0, epsilon = 1e-15);
        assert_eq!(quadratic_roots(0.0, 2.0, -4.0, 1e-15), vec![2.0]);
        assert!(quadratic_roots(1.0, 0.0, 1.0, 1e-15).is_empty());
    }
}
