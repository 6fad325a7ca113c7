//! Colorimetry: the observed band of wavelengths, the CIE 1931 colour
//! matching functions, and the conversions from band-sampled spectra to CIE
//! XYZ and linear sRGB.
//!
//! Normalisation: `xyz` is scaled so that the white uplift `Spectrum::Rgb(ONE)`
//! has Y = 1, and `xyz_to_rgb` is white-balanced so that the same white maps to
//! (1, 1, 1). That white is flat (equal-energy) over the visible, so its
//! chromaticity is that of illuminant E, (1/3, 1/3), up to the window's edges;
//! the white balance is a von Kries-style adaptation of E to the sRGB white.

use super::spectrum::{basis, window};
use crate::math;
use glam::{DMat3, DVec3};
use std::sync::OnceLock;

/// Number of observation wavelengths, 380..=780 nm every 5 nm.
pub const BAND_LEN: usize = 81;

const BAND_START_NM: f64 = 380.0;
const BAND_STEP_NM: f64 = 5.0;

/// The observation wavelengths in nm.
pub fn band_nm() -> [f64; BAND_LEN] {
    std::array::from_fn(band_wavelength_nm)
}

pub(super) fn band_wavelength_nm(i: usize) -> f64 {
    BAND_START_NM + BAND_STEP_NM * i as f64
}

/// Linear sRGB from CIE XYZ: the IEC 61966-2-1 matrix (D65 white, rows R, G, B).
const XYZ_TO_SRGB: DMat3 = DMat3::from_cols(
    DVec3::new(3.2406, -0.9689, 0.0557),
    DVec3::new(-1.5372, 1.8758, -0.2040),
    DVec3::new(-0.4986, 0.0415, 1.0570),
);

/// One lobe of the Wyman-Sloan-Shirley fit: a Gaussian of standard deviation
/// `below` to the left of `mu` and `above` to its right.
fn lobe(nm: f64, mu: f64, below: f64, above: f64) -> f64 {
    let t = (nm - mu) / if nm < mu { below } else { above };
    math::exp(-0.5 * t * t)
}

/// CIE 1931 2-degree colour matching functions (xbar, ybar, zbar) at `nm`, by
/// the multi-lobe piecewise-Gaussian fit of Wyman, Sloan and Shirley, "Simple
/// Analytic Approximations to the CIE XYZ Color Matching Functions", JCGT 2(2),
/// 2013. In this fit ybar, the photopic luminous efficiency, peaks at 0.998
/// at 554.2 nm (tabulated: 1 at 555 nm).
pub fn cmf(nm: f64) -> DVec3 {
    DVec3::new(
        1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7)
            - 0.065 * lobe(nm, 501.1, 20.4, 26.2),
        0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
        1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8),
    )
}

/// Tables derived once from the colour matching functions and the uplift.
pub(super) struct Colorimetry {
    /// cmf at the band wavelengths times the 5 nm step, divided by the Y of
    /// the white uplift, so that `xyz` is a dot product with these.
    weights: [DVec3; BAND_LEN],
    /// Per-channel factors applied after XYZ_TO_SRGB that map the white
    /// uplift to (1, 1, 1).
    white_balance: DVec3,
    /// M^-1: linear sRGB to uplift basis coefficients (k_r, k_g, k_b).
    pub(super) uplift: DMat3,
}

pub(super) fn colorimetry() -> &'static Colorimetry {
    static TABLES: OnceLock<Colorimetry> = OnceLock::new();
    TABLES.get_or_init(|| {
        let nm = band_nm();
        let white = nm.map(window);
        let raw: [DVec3; BAND_LEN] = std::array::from_fn(|i| cmf(nm[i]) * BAND_STEP_NM);
        let white_y: f64 = (0..BAND_LEN).map(|i| white[i] * raw[i].y).sum();
        let weights = raw.map(|w| w / white_y);
        let tristimulus = |value: &dyn Fn(usize) -> f64| {
            (0..BAND_LEN).fold(DVec3::ZERO, |acc, i| acc + weights[i] * value(i))
        };
        let white_balance = (XYZ_TO_SRGB * tristimulus(&|i| white[i])).recip();
        let basis_rgb =
            |j: usize| white_balance * (XYZ_TO_SRGB * tristimulus(&|i| basis(nm[i])[j] * white[i]));
        let m = DMat3::from_cols(basis_rgb(0), basis_rgb(1), basis_rgb(2));
        Colorimetry {
            weights,
            white_balance,
            uplift: m.inverse(),
        }
    })
}

/// XYZ of a band-sampled spectral radiance: the Riemann sum over the band
/// (5 nm steps) of the radiance times the colour matching functions,
/// normalised so that the white uplift `Spectrum::Rgb(DVec3::ONE)` has Y = 1.
pub fn xyz(values: &[f64; BAND_LEN]) -> DVec3 {
    values
        .iter()
        .zip(&colorimetry().weights)
        .fold(DVec3::ZERO, |acc, (&v, &w)| acc + w * v)
}

/// Linear sRGB (D65 primaries, IEC 61966-2-1 matrix) of XYZ, white-balanced by
/// a diagonal (von Kries-style) scaling of the RGB channels such that the white
/// uplift maps to (1, 1, 1): `xyz_to_rgb(xyz(&Spectrum::Rgb(ONE).sample_scaled(1.0)))`
/// is (1, 1, 1) up to rounding. Out-of-gamut colours have negative components.
pub fn xyz_to_rgb(xyz: DVec3) -> DVec3 {
    colorimetry().white_balance * (XYZ_TO_SRGB * xyz)
}

/// Linear sRGB of a band-sampled spectral radiance: `xyz_to_rgb(xyz(values))`.
pub fn to_rgb(values: &[f64; BAND_LEN]) -> DVec3 {
    xyz_to_rgb(xyz(values))
}

/// CIE chromaticity (x, y) = (X, Y) / (X + Y + Z); None if X + Y + Z <= 0.
pub fn chromaticity(xyz: DVec3) -> Option<(f64, f64)> {
    let sum = xyz.element_sum();
    if sum > 0.0 {
        Some((xyz.x / sum, xyz.y / sum))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::test_support::{argmax, sample};
    use crate::color::Spectrum;
    use approx::assert_abs_diff_eq;

    #[test]
    fn cmf_peaks() {
        let (y_nm, y_max) = argmax(|nm| cmf(nm).y, 360.0, 830.0, 0.1);
        assert_abs_diff_eq!(y_nm, 555.0, epsilon = 1.5);
        assert_abs_diff_eq!(y_max, 1.0, epsilon = 0.03);
        let (x_main_nm, _) = argmax(|nm| cmf(nm).x, 360.0, 830.0, 0.1);
        assert!(
            (x_main_nm - 599.0).abs() < 3.0,
            "xbar peaks at {x_main_nm} nm"
        );
        let (x_blue_nm, x_blue) = argmax(|nm| cmf(nm).x, 400.0, 480.0, 0.1);
        assert!(
            (x_blue_nm - 442.0).abs() < 3.0,
            "xbar's blue lobe at {x_blue_nm} nm"
        );
        assert!(cmf(x_blue_nm - 20.0).x < x_blue && cmf(x_blue_nm + 20.0).x < x_blue);
        let (z_nm, _) = argmax(|nm| cmf(nm).z, 360.0, 830.0, 0.1);
        assert_abs_diff_eq!(z_nm, 446.0, epsilon = 5.0);
    }

    #[test]
    fn rgb_round_trips() {
        let white = to_rgb(&sample(&Spectrum::Rgb(DVec3::ONE)));
        assert_abs_diff_eq!(white, DVec3::ONE, epsilon = 1e-12);
        for c in [
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.2, 0.5, 0.8),
            DVec3::new(0.9, 0.6, 0.1),
            DVec3::new(0.05, 0.05, 0.05),
            DVec3::new(3.0, 2.0, 0.5),
            DVec3::ZERO,
        ] {
            let back = to_rgb(&sample(&Spectrum::Rgb(c)));
            assert_abs_diff_eq!(back, c, epsilon = 1e-9);
        }
    }

    #[test]
    fn the_srgb_gamut_uplifts_without_clamping() {
        let m_inv = colorimetry().uplift;
        for j in 0..3 {
            assert!(m_inv.col(j).min_element() >= 0.0, "M^-1 = {m_inv}");
        }
        for c in [DVec3::X, DVec3::Y, DVec3::Z] {
            let k = m_inv * c;
            for nm in band_nm() {
                assert!(k.dot(basis(nm)) * window(nm) >= 0.0);
            }
        }
    }

    #[test]
    fn white_chromaticity_is_near_equal_energy() {
        let white = xyz(&sample(&Spectrum::Rgb(DVec3::ONE)));
        assert_abs_diff_eq!(white.y, 1.0, epsilon = 1e-12);
        let (x, y) = chromaticity(white).unwrap();
        assert!(
            (x - 0.33).abs() < 0.05 && (y - 0.33).abs() < 0.05,
            "({x}, {y})"
        );
        assert!(
            (x - 1.0 / 3.0).abs() < 0.002 && (y - 1.0 / 3.0).abs() < 0.002,
            "({x}, {y})"
        );
        assert_eq!(chromaticity(DVec3::ZERO), None);
        assert_eq!(chromaticity(DVec3::splat(f64::NAN)), None);
    }
}
