//! Measuring an image: sub-pixel edges along scanlines, mapped back through
//! the camera model to positions on known planes or to directions.
//!
//! An edge between two flat-coloured regions is located by the area method:
//! with anti-aliasing, a pixel's value is the coverage-weighted mix of the
//! two colours (images are stored linearly), so the coverages summed across
//! the transition give the boundary's position to a fraction of a pixel.

use glam::{DMat4, DVec3, DVec4};
use image::RgbImage;
use renderer::Camera;

/// The colour of pixel (x, y) in [0, 1]^3.
pub fn color(img: &RgbImage, x: u32, y: u32) -> DVec3 {
    let p = img.get_pixel(x, y).0;
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])) / 255.0
}

/// A line of pixels to scan: a row (`horizontal`) or a column, at index `at`.
#[derive(Clone, Copy, Debug)]
pub struct Scan {
    pub horizontal: bool,
    pub at: u32,
}

impl Scan {
    fn len(&self, img: &RgbImage) -> i64 {
        i64::from(if self.horizontal {
            img.width()
        } else {
            img.height()
        })
    }

    fn get(&self, img: &RgbImage, i: i64) -> DVec3 {
        if self.horizontal {
            color(img, i as u32, self.at)
        } else {
            color(img, self.at, i as u32)
        }
    }

    /// Continuous pixel coordinates of position `u` along the scan.
    pub fn point(&self, u: f64) -> (f64, f64) {
        let c = f64::from(self.at) + 0.5;
        if self.horizontal {
            (u, c)
        } else {
            (c, u)
        }
    }
}

/// Half-width (pixels) of the window in which coverages are summed.
const HALF: i64 = 3;

/// The boundary where the scan, going from `from` in direction `step` (+1 or
/// -1), leaves the first run of pixels for which `inside` holds. Returns the
/// boundary's continuous coordinate along the scan, or `None` when no clean
/// transition is found: the run never starts or ends, the window leaves the
/// image, or the colours just beyond the window are not flat (another edge
/// nearby), so that the area method would be biased.
pub fn edge(
    img: &RgbImage,
    scan: Scan,
    from: i64,
    step: i64,
    inside: impl Fn(DVec3) -> bool,
) -> Option<f64> {
    let n = scan.len(img);
    let ok = |i: i64| (0..n).contains(&i);
    let mut i = from;
    while ok(i) && !inside(scan.get(img, i)) {
        i += step;
    }
    while ok(i) && inside(scan.get(img, i)) {
        i += step;
    }
    // i is the first pixel not inside: the boundary is near it.
    let (lo, hi) = (i - HALF * step, i + HALF * step);
    let (a1, a2, b1, b2) = (lo - step, lo - 2 * step, hi + step, hi + 2 * step);
    if ![a2, b2].iter().all(|&k| ok(k)) {
        return None;
    }
    let c_in = (scan.get(img, lo) + scan.get(img, a1) + scan.get(img, a2)) / 3.0;
    let c_out = (scan.get(img, hi) + scan.get(img, b1) + scan.get(img, b2)) / 3.0;
    let flat = |a: DVec3, b: DVec3| (a - b).abs().max_element() <= 2.5 / 255.0;
    if !(flat(scan.get(img, lo), scan.get(img, a2)) && flat(scan.get(img, hi), scan.get(img, b2))) {
        return None;
    }
    let contrast = c_in - c_out;
    if contrast.length_squared() < (20.0f64 / 255.0).powi(2) {
        return None;
    }
    let mut covered = 0.0;
    let mut k = lo;
    loop {
        let f = (scan.get(img, k) - c_out).dot(contrast) / contrast.length_squared();
        covered += f.clamp(0.0, 1.0);
        if k == hi {
            break;
        }
        k += step;
    }
    // Pixel k spans [k, k + 1]; the inside run ends `covered` pixels past the window's start.
    Some(if step > 0 {
        lo as f64 + covered
    } else {
        (lo + 1) as f64 - covered
    })
}

/// A plane in the lab: points p with normal.(p - point) = 0.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    pub point: DVec3,
    pub normal: DVec3,
}

impl Plane {
    pub fn x(x: f64) -> Plane {
        Plane {
            point: DVec3::new(x, 0.0, 0.0),
            normal: DVec3::X,
        }
    }
    pub fn y(y: f64) -> Plane {
        Plane {
            point: DVec3::new(0.0, y, 0.0),
            normal: DVec3::Y,
        }
    }
    pub fn z(z: f64) -> Plane {
        Plane {
            point: DVec3::new(0.0, 0.0, z),
            normal: DVec3::Z,
        }
    }
}

/// Where the line of sight through continuous pixel (px, py) meets `plane`:
/// the spatial position of the seen event, if the seen point lies on it.
pub fn on_plane(camera: &Camera, px: f64, py: f64, plane: Plane) -> Option<DVec3> {
    let d = camera.direction(px, py);
    let denom = plane.normal.dot(d);
    if denom.abs() < 1e-12 {
        return None;
    }
    let s = plane.normal.dot(plane.point - camera.event.x) / denom;
    (s > 0.0).then(|| camera.event.x + d * s)
}

/// Size on `plane` of one pixel step along the scan at (px, py): the
/// footprint that turns an edge uncertainty in pixels into l.units.
pub fn footprint(camera: &Camera, px: f64, py: f64, horizontal: bool, plane: Plane) -> Option<f64> {
    let (qx, qy) = if horizontal {
        (px + 1.0, py)
    } else {
        (px, py + 1.0)
    };
    Some((on_plane(camera, qx, qy, plane)? - on_plane(camera, px, py, plane)?).length())
}

/// Angle (radians) between the lines of sight of two neighbouring pixels at (px, py).
pub fn angular_footprint(camera: &Camera, px: f64, py: f64, horizontal: bool) -> f64 {
    let (qx, qy) = if horizontal {
        (px + 1.0, py)
    } else {
        (px, py + 1.0)
    };
    camera
        .direction(px, py)
        .angle_between(camera.direction(qx, qy))
}

/// A least-squares polynomial fit y = c0 + c1 x + ... of degree 1 to 3.
#[derive(Clone, Debug)]
pub struct PolyFit {
    pub coef: Vec<f64>,
    /// Residual standard deviation.
    pub sigma: f64,
    /// Inverse of the normal matrix, for prediction errors.
    cov: DMat4,
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

    pub fn degree(&self) -> usize {
        self.coef.len() - 1
    }

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

    /// A synthetic anti-aliased vertical edge at x = 10.3 between two colours.
    fn synthetic(edge_x: f64, a: [u8; 3], b: [u8; 3]) -> RgbImage {
        RgbImage::from_fn(24, 4, |x, _| {
            let f = (edge_x - f64::from(x)).clamp(0.0, 1.0);
            let mix = |i: usize| (f * f64::from(a[i]) + (1.0 - f) * f64::from(b[i])).round() as u8;
            image::Rgb([mix(0), mix(1), mix(2)])
        })
    }

    #[test]
    fn area_method_finds_a_sub_pixel_edge_from_either_side() {
        for edge_x in [10.3, 11.0, 12.77] {
            let img = synthetic(edge_x, [200, 40, 30], [10, 10, 20]);
            let red = |c: DVec3| c.x > 0.4;
            let x = edge(
                &img,
                Scan {
                    horizontal: true,
                    at: 1,
                },
                0,
                1,
                red,
            )
            .unwrap();
            assert!((x - edge_x).abs() < 0.01, "{x} vs {edge_x}");
            let dark = |c: DVec3| c.x < 0.4;
            let x = edge(
                &img,
                Scan {
                    horizontal: true,
                    at: 1,
                },
                23,
                -1,
                dark,
            )
            .unwrap();
            assert!((x - edge_x).abs() < 0.01, "{x} vs {edge_x}");
        }
    }

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
        assert!((f.eval(2.0) - (1.0 + 1.0 - 0.8)).abs() < 2e-3);
        assert!(f.stderr(-2.0) > f.stderr(2.0));
    }
}
