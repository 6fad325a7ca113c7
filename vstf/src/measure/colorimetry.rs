//! Colours back to physics: the colorimetry that turns a measured pixel into
//! a chromaticity, and a blackbody into the chromaticity it should show,
//! written from the standards rather than borrowed from the ray tracer.
//!
//! - The observer: the CIE 1931 2-degree colour matching functions, by the
//!   multi-lobe piecewise-Gaussian fit of Wyman, Sloan and Shirley, "Simple
//!   Analytic Approximations to the CIE XYZ Color Matching Functions",
//!   JCGT 2(2), 2013, sampled at 380..=780 nm every 5 nm.
//! - The display: linear sRGB by the IEC 61966-2-1 matrix, white-balanced
//!   per channel (von Kries) so that the ray tracer's white, a flat spectrum
//!   under a window rising as a C1 smoothstep over 380..405 nm and falling
//!   over 690..730 nm, shows as (1, 1, 1). That window is the display's
//!   definition of white (the fixture format's `rgb` white), not a
//!   standard; it is restated here from its definition.
//! - The source: Planck's law per unit wavelength, B ~ x^5 / (e^x - 1) with
//!   x = c2 / (lambda T), relative to its peak at x = 4.965114... (Wien).
//!
//! Chromaticity does not depend on brightness, so the inversion of a pixel
//! needs only the matrices; the normalisations are kept so that the numbers
//! are the ray tracer's to the last bit when both are right.

use glam::{DMat3, DVec3};
use std::sync::OnceLock;

/// Number of sampled wavelengths, 380..=780 nm every 5 nm.
const BAND_LEN: usize = 81;
const BAND_START_NM: f64 = 380.0;
const BAND_STEP_NM: f64 = 5.0;

/// The second radiation constant c2 = h c / k_B in nm K, from the exact
/// 2019 SI values h = 6.62607015e-34 J s, c = 299792458 m/s and
/// k_B = 1.380649e-23 J/K.
const C2_NM_K: f64 = 1.438_776_877_503_933_8e7;

/// The x at which x^5 / (e^x - 1) peaks: the root of x = 5 (1 - e^-x).
const WIEN_X: f64 = 4.965_114_231_744_276;

/// Linear sRGB from CIE XYZ (IEC 61966-2-1, D65), columns X, Y, Z.
const SRGB_FROM_XYZ: DMat3 = DMat3::from_cols(
    DVec3::new(3.2406, -0.9689, 0.0557),
    DVec3::new(-1.5372, 1.8758, -0.2040),
    DVec3::new(-0.4986, 0.0415, 1.0570),
);

fn wavelength_nm(i: usize) -> f64 {
    BAND_START_NM + BAND_STEP_NM * i as f64
}

/// A Gaussian lobe exp(-t^2 / 2) with t = (nm - mu) / sigma, sigma being
/// `below` left of `mu` and `above` right of it (the fit's g(x; mu, s1, s2)).
fn lobe(nm: f64, mu: f64, below: f64, above: f64) -> f64 {
    let t = (nm - mu) / if nm < mu { below } else { above };
    (-0.5 * t * t).exp()
}

/// (xbar, ybar, zbar) at `nm`: Wyman, Sloan and Shirley's multi-lobe fit,
/// their eq. (2) with the coefficients of their Table 1.
pub fn observer(nm: f64) -> DVec3 {
    DVec3::new(
        1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7)
            - 0.065 * lobe(nm, 501.1, 20.4, 26.2),
        0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
        1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8),
    )
}

/// 3t^2 - 2t^3 of t = (x - lo) / (hi - lo) clamped to [0, 1].
fn smoothstep(lo: f64, hi: f64, x: f64) -> f64 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The display white's spectrum: 1 over 405..690 nm, 0 outside 380..730 nm.
fn white(nm: f64) -> f64 {
    smoothstep(380.0, 405.0, nm) * (1.0 - smoothstep(690.0, 730.0, nm))
}

/// Planck's law per unit wavelength at the product lambda T (nm K),
/// relative to its peak over wavelength; 0 where x is not finite and positive.
pub fn planck_relative(nm_kelvin: f64) -> f64 {
    let x = C2_NM_K / nm_kelvin;
    if !(x.is_finite() && x > 0.0) {
        return 0.0;
    }
    static PEAK: OnceLock<f64> = OnceLock::new();
    let shape = |x: f64| x.powi(5) / x.exp_m1();
    shape(x) / *PEAK.get_or_init(|| shape(WIEN_X))
}

/// The observer and display tables, built once.
struct Tables {
    /// The matching functions at the sampled wavelengths times the step,
    /// over the white's Y: XYZ is a dot product with these.
    weights: [DVec3; BAND_LEN],
    /// CIE XYZ from the display's linear RGB: (diag(white balance) SRGB_FROM_XYZ)^-1.
    xyz_from_rgb: DMat3,
}

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let raw: [DVec3; BAND_LEN] =
            std::array::from_fn(|i| observer(wavelength_nm(i)) * BAND_STEP_NM);
        let white_y: f64 = (0..BAND_LEN)
            .map(|i| white(wavelength_nm(i)) * raw[i].y)
            .sum();
        let weights = raw.map(|w| w / white_y);
        let white_xyz = (0..BAND_LEN).fold(DVec3::ZERO, |acc, i| {
            acc + weights[i] * white(wavelength_nm(i))
        });
        let balance = (SRGB_FROM_XYZ * white_xyz).recip();
        let rgb_from_xyz = DMat3::from_cols(
            balance * SRGB_FROM_XYZ.x_axis,
            balance * SRGB_FROM_XYZ.y_axis,
            balance * SRGB_FROM_XYZ.z_axis,
        );
        Tables {
            weights,
            xyz_from_rgb: rgb_from_xyz.inverse(),
        }
    })
}

/// CIE XYZ of the display's linear RGB.
pub fn xyz_of_rgb(rgb: DVec3) -> DVec3 {
    tables().xyz_from_rgb * rgb
}

/// A blackbody source as the fixture describes it: its temperature and the
/// radiance of its peak.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blackbody {
    /// Temperature, K.
    pub kelvin: f64,
    /// Spectral radiance at the peak, in the units of the images.
    pub scale: f64,
}

impl Blackbody {
    /// CIE XYZ of the source seen with every wavelength divided by `d`
    /// (light received at lambda left at d lambda): the Riemann sum over the
    /// band of its radiance at d lambda times the matching functions.
    pub fn xyz_shifted(&self, d: f64) -> DVec3 {
        let weights = &tables().weights;
        (0..BAND_LEN).fold(DVec3::ZERO, |acc, i| {
            let nm = wavelength_nm(i) * d;
            let radiance = if nm.is_nan() || nm <= 0.0 {
                0.0
            } else {
                self.scale * planck_relative(nm * self.kelvin)
            };
            acc + weights[i] * radiance
        })
    }
}

/// CIE chromaticity coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chromaticity {
    /// X / (X + Y + Z).
    pub x: f64,
    /// Y / (X + Y + Z).
    pub y: f64,
}

impl Chromaticity {
    /// The chromaticity of `xyz`; `None` unless X + Y + Z > 0.
    pub fn of(xyz: DVec3) -> Option<Chromaticity> {
        let sum = xyz.x + xyz.y + xyz.z;
        (sum > 0.0).then(|| Chromaticity {
            x: xyz.x / sum,
            y: xyz.y / sum,
        })
    }

    /// Squared distance in the (x, y) plane.
    pub fn distance_squared(&self, other: Chromaticity) -> f64 {
        (self.x - other.x).powi(2) + (self.y - other.y).powi(2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn wien_x_solves_its_equation_and_c2_is_h_c_over_k() {
        assert_abs_diff_eq!(WIEN_X, 5.0 * (1.0 - (-WIEN_X).exp()), epsilon = 1e-14);
        let (h, c, k) = (6.626_070_15e-34, 299_792_458.0, 1.380_649e-23);
        assert_abs_diff_eq!(h * c / k * 1e9 / C2_NM_K, 1.0, epsilon = 1e-15);
    }

    #[test]
    fn the_display_white_is_rgb_one_with_y_one() {
        let t = tables();
        let xyz = (0..BAND_LEN).fold(DVec3::ZERO, |acc, i| {
            acc + t.weights[i] * white(wavelength_nm(i))
        });
        assert_abs_diff_eq!(xyz.y, 1.0, epsilon = 1e-12);
        let rgb = t.xyz_from_rgb.inverse() * xyz;
        assert!((rgb - DVec3::ONE).abs().max_element() < 1e-12, "{rgb}");
    }

    #[test]
    fn a_shifted_blackbody_is_a_blackbody_at_the_shifted_temperature() {
        let b = Blackbody {
            kelvin: 4000.0,
            scale: 1.0,
        };
        let hotter = Blackbody {
            kelvin: 5200.0,
            scale: 1.0,
        };
        let (a, c) = (b.xyz_shifted(1.3), hotter.xyz_shifted(1.0));
        assert!((a - c).abs().max_element() < 1e-12 * c.max_element());
        // Hotter is bluer: the chromaticity moves towards smaller x.
        let (ca, cb) = (
            Chromaticity::of(a).unwrap(),
            Chromaticity::of(b.xyz_shifted(1.0)).unwrap(),
        );
        assert!(ca.x < cb.x);
    }
}
