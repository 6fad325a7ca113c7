//! Least-squares polynomial fits of traced edges, with the prediction errors
//! that become the checks' tolerances.

use glam::{DMat4, DVec4};

/// A least-squares polynomial fit y = c0 + c1 x + ... of degree 1 to 3.
#[derive(Clone, Debug)]
pub struct PolyFit {
    /// Coefficients c0, c1, ... in increasing power.
    pub coef: Vec<f64>,
    /// Residual standard deviation.
    pub sigma: f64,
    /// Inverse of the normal matrix, for prediction errors.
    cov: DMat4,
    /// Number of points fitted.
    pub n: usize,
}

fn basis(x: f64, degree: usize) -> DVec4 {
    let p = [1.0, x, x * x, x * x * x];
    DVec4::from_array(std::array::from_fn(
        |i| if i <= degree { p[i] } else { 0.0 },
    ))
}

impl PolyFit {
    /// Fits a polynomial of `degree` 1..=3; `None` with too few points.
    pub fn fit(points: &[(f64, f64)], degree: usize) -> Option<PolyFit> {
        let k = degree + 1;
        if points.len() < k + 3 || !(1..=3).contains(&degree) {
            return None;
        }
        let mut ata = DMat4::ZERO;
        let mut aty = DVec4::ZERO;
        for &(x, y) in points {
            let b = basis(x, degree);
            ata += DMat4::from_cols(b * b.x, b * b.y, b * b.z, b * b.w);
            aty += b * y;
        }
        // Unused powers get a unit diagonal so that the matrix inverts.
        for i in k..4 {
            ata.col_mut(i)[i] = 1.0;
        }
        let cov = ata.inverse();
        let c = cov * aty;
        let resid: f64 = points
            .iter()
            .map(|&(x, y)| (y - basis(x, degree).dot(c)).powi(2))
            .sum();
        let sigma = (resid / (points.len() - k) as f64).sqrt();
        Some(PolyFit {
            coef: c.to_array()[..k].to_vec(),
            sigma,
            cov,
            n: points.len(),
        })
    }

    /// Fits, drops points whose residual exceeds 4 sigma (a scanline crossed
    /// by a shadow or another edge), and fits again.
    pub fn fit_robust(points: &[(f64, f64)], degree: usize) -> Option<PolyFit> {
        let first = PolyFit::fit(points, degree)?;
        let keep: Vec<(f64, f64)> = points
            .iter()
            .copied()
            .filter(|&(x, y)| (y - first.eval(x)).abs() <= 4.0 * first.sigma.max(1e-12))
            .collect();
        PolyFit::fit(&keep, degree)
    }

    /// The polynomial's degree.
    pub fn degree(&self) -> usize {
        self.coef.len() - 1
    }

    /// The fitted value at x.
    pub fn eval(&self, x: f64) -> f64 {
        self.coef.iter().rev().fold(0.0, |acc, c| acc * x + c)
    }

    /// Standard error of a linear combination of fitted values, sum w_i f(x_i).
    pub fn stderr_of(&self, terms: &[(f64, f64)]) -> f64 {
        let b = terms.iter().fold(DVec4::ZERO, |acc, &(w, x)| {
            acc + basis(x, self.degree()) * w
        });
        self.sigma * b.dot(self.cov * b).max(0.0).sqrt()
    }

    /// Standard error of the fitted value at x.
    pub fn stderr(&self, x: f64) -> f64 {
        self.stderr_of(&[(1.0, x)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn fits_recover_a_parabola_and_its_error_grows_off_the_data() {
        let pts: Vec<(f64, f64)> = (0..50)
            .map(|i| {
                let x = f64::from(i) / 10.0;
                (
                    x,
                    1.0 + 0.5 * x - 0.2 * x * x + if i % 2 == 0 { 1e-3 } else { -1e-3 },
                )
            })
            .collect();
        let f = PolyFit::fit(&pts, 2).unwrap();
        assert_abs_diff_eq!(f.eval(2.0), 1.0 + 1.0 - 0.8, epsilon = 2e-3);
        assert!(f.stderr(-2.0) > f.stderr(2.0));
    }
}
