//! A circle on the sky fitted to directions, with no pole.
//!
//! A circle on the unit sphere of directions is the set of unit vectors d
//! with a . d = cos(rho): the sphere cut by a plane whose unit normal a is
//! the circle's centre on the sky (the axis of its cone) and whose distance
//! from the origin is cos(rho), rho the angular radius. The fit is the plane
//! nearest the points in the least-squares sense (total least squares: a is
//! the eigenvector of the points' scatter matrix about their centroid with
//! the least eigenvalue, and cos(rho) the mean of a . d). Points on one
//! circle lie in its plane, so however they are spread along it the fit is
//! that circle; and rotating the points rotates the fit, so no direction is
//! preferred. A stereographic projection, by contrast, keeps circles but not
//! their centres: a centre fitted in its plane and projected back moves with
//! the pole.

use glam::{DMat3, DVec3};

/// A circle on the sky fitted to unit directions.
#[derive(Clone, Copy, Debug)]
pub struct SkyCircle {
    /// The circle's centre on the sky: the unit axis of its cone.
    pub centre: DVec3,
    /// Angular radius, radians.
    pub radius: f64,
    /// RMS angular distance of the points from the circle, radians.
    pub rms: f64,
}

impl SkyCircle {
    /// Fits the circle to unit directions `dirs`; `None` for fewer than
    /// three, or for directions that fix no plane (one or two distinct
    /// directions: the scatter's two least eigenvalues are rounding).
    pub fn fit(dirs: &[DVec3]) -> Option<SkyCircle> {
        if dirs.len() < 3 {
            return None;
        }
        let n = dirs.len() as f64;
        let mean = dirs.iter().fold(DVec3::ZERO, |a, d| a + *d) / n;
        let scatter = dirs.iter().fold(DMat3::ZERO, |s, d| {
            let r = *d - mean;
            s + DMat3::from_cols(r * r.x, r * r.y, r * r.z)
        });
        let (values, vectors) = symmetric_eigen(scatter);
        let mut order = [0, 1, 2];
        order.sort_by(|i, j| values[*i].total_cmp(&values[*j]));
        let fixes_plane = values[order[1]] > 1e-12 * values[order[2]];
        if !fixes_plane {
            return None;
        }
        let axis = vectors[order[0]].try_normalize()?;
        let centre = if axis.dot(mean) < 0.0 { -axis } else { axis };
        let radius = centre.dot(mean).clamp(-1.0, 1.0).acos();
        let circle = SkyCircle {
            centre,
            radius,
            rms: 0.0,
        };
        let rms = (dirs.iter().map(|d| circle.off(*d).powi(2)).sum::<f64>() / n).sqrt();
        Some(SkyCircle { rms, ..circle })
    }

    /// The angular distance of the direction `d` from the circle, radians:
    /// positive outside it, negative inside.
    pub fn off(&self, d: DVec3) -> f64 {
        self.centre.cross(d).length().atan2(self.centre.dot(d)) - self.radius
    }
}

/// The eigenvalues of a symmetric 3 x 3 matrix and their unit eigenvectors,
/// unordered, by cyclic Jacobi rotations: each rotation in a coordinate
/// plane (p, q) zeroes the element (p, q), and the off-diagonal sum of
/// squares falls quadratically to zero.
fn symmetric_eigen(m: DMat3) -> ([f64; 3], [DVec3; 3]) {
    let at = |m: &DMat3, r: usize, c: usize| m.col(c)[r];
    let mut a = m;
    let mut v = DMat3::IDENTITY;
    for _ in 0..64 {
        let off = at(&a, 0, 1).powi(2) + at(&a, 0, 2).powi(2) + at(&a, 1, 2).powi(2);
        if off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = at(&a, p, q);
            if apq == 0.0 {
                continue;
            }
            let theta = (at(&a, q, q) - at(&a, p, p)) / (2.0 * apq);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            let mut j = DMat3::IDENTITY;
            j.col_mut(p)[p] = c;
            j.col_mut(q)[q] = c;
            j.col_mut(q)[p] = s;
            j.col_mut(p)[q] = -s;
            a = j.transpose() * a * j;
            a.col_mut(q)[p] = 0.0;
            a.col_mut(p)[q] = 0.0;
            v *= j;
        }
    }
    (
        [at(&a, 0, 0), at(&a, 1, 1), at(&a, 2, 2)],
        [v.col(0), v.col(1), v.col(2)],
    )
}

#[cfg(test)]
mod tests;
