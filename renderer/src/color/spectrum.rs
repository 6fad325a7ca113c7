//! Spectral colour, so that light can be Doppler shifted.
//!
//! The camera observes a fixed band of wavelengths ([`band_nm`](super::band_nm), 380..=780 nm
//! every 5 nm). Relative motion between emitter and observer rescales
//! wavelengths: light received at wavelength lambda_obs left its source at
//! lambda_em = D lambda_obs, where D = nu_obs / nu_em is the Doppler factor.
//! A surface's colour is therefore a [`Spectrum`] that can be evaluated at any
//! wavelength, far outside the visible included, and the observed band is
//! sampled from it with [`Spectrum::sample_scaled`]. The samples are turned
//! into CIE XYZ with the CIE 1931 2-degree observer ([`cmf`](super::cmf), [`xyz`](super::xyz)) and into
//! display colour with [`xyz_to_rgb`](super::xyz_to_rgb).
//!
//! Colours given as linear sRGB are uplifted to smooth spectra that vanish
//! outside the visible (see [`Spectrum::Rgb`]), so an RGB surface shifted far
//! enough goes dark, while a [`Spectrum::Blackbody`] stays a blackbody at a
//! different temperature.

use super::cie::{band_wavelength_nm, colorimetry, BAND_LEN};
use crate::math;
use glam::DVec3;
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// The second radiation constant c2 = h c / k_B in nm K (exact in the 2019 SI).
const SECOND_RADIATION_NM_K: f64 = 1.438_776_877_503_933_8e7;

/// The x = c2 / (lambda T) at which x^5 / (e^x - 1), Planck's law per unit
/// wavelength at fixed temperature, is largest: the root of x = 5 (1 - e^-x).
/// Wien's displacement constant is c2 / x = 2.897771955e6 nm K.
const WIEN_X: f64 = 4.965_114_231_744_276;

/// The uplift window rises from 0 to 1 over this range of wavelengths (nm).
const WINDOW_RISE_NM: (f64, f64) = (380.0, 405.0);
/// The uplift window falls from 1 to 0 over this range of wavelengths (nm).
const WINDOW_FALL_NM: (f64, f64) = (690.0, 730.0);
/// Centre of the uplift basis' blue-to-green transition (nm).
const BLUE_GREEN_NM: f64 = 493.0;
/// Centre of the uplift basis' green-to-red transition (nm).
const GREEN_RED_NM: f64 = 588.0;
/// Half-width of both basis transitions (nm).
const TRANSITION_HALF_WIDTH_NM: f64 = 12.0;

/// A spectrum: a non-negative function of wavelength (nm), e.g. a spectral
/// radiance or a reflectance.
///
/// Every spectrum is 0 at wavelengths that are not positive (and at NaN).
///
/// Serde: externally tagged in snake_case, i.e. JSON `{"rgb": [r, g, b]}`,
/// `{"gaussian": {"peak_nm": .., "width_nm": .., "scale": ..}}`,
/// `{"blackbody": {"kelvin": .., "scale": ..}}` or
/// `{"samples": {"nm": [..], "values": [..]}}`; unknown fields are rejected and
/// `scale` defaults to 1.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum Spectrum {
    /// The smooth spectrum of a linear-sRGB colour, zero outside the visible.
    ///
    /// Uplift: three smooth basis spectra b_r, b_g, b_b form a partition of
    /// unity (b_r + b_g + b_b = 1): b_b falls from 1 to 0 and b_g rises over
    /// 493 +- 12 nm, b_g falls and b_r rises over 588 +- 12 nm, each transition
    /// a C1 smoothstep. They are multiplied by a window W(nm), a C1 smoothstep
    /// rising over 380..405 nm and falling over 690..730 nm, exactly 0 outside
    /// 380..730 nm. The spectrum of colour c is
    /// `sum_j k_j b_j(nm) W(nm)` with `k = M^-1 c`, where column j of M is
    /// `to_rgb` of the sampled b_j W. Hence `to_rgb` of the sampled spectrum
    /// is c again, and white (1, 1, 1) uplifts to W itself.
    ///
    /// M^-1 has no negative entry, so every colour with non-negative
    /// components (the whole sRGB gamut, and brighter) has non-negative
    /// coefficients and round-trips exactly. A colour with a negative component
    /// may give negative coefficients; the spectrum is then clamped at 0 and the
    /// round trip is only approximate.
    Rgb(DVec3),
    /// `scale * exp(-(nm - peak_nm)^2 / (2 width_nm^2))`: a line or band of
    /// light with standard deviation `width_nm`.
    Gaussian {
        /// Wavelength of the peak, nm.
        peak_nm: f64,
        /// Standard deviation, nm.
        width_nm: f64,
        /// Peak value (default 1).
        #[cfg_attr(feature = "serde", serde(default = "unit_scale"))]
        scale: f64,
    },
    /// Planck's law for the spectral radiance per unit wavelength of a black
    /// body at `kelvin`, normalised so that its peak over all wavelengths (at
    /// Wien's lambda_max = 2.897771955e6 nm K / kelvin) is `scale`, so that
    /// shapes at different temperatures are comparable.
    ///
    /// The normalised value depends on nm and kelvin only through their
    /// product, so `at(s * nm)` at temperature T equals `at(nm)` at s T: a
    /// blackbody seen with its wavelengths rescaled by s (see
    /// [`Spectrum::sample_scaled`]) is the blackbody at s T with the same peak.
    Blackbody {
        /// Temperature, K.
        kelvin: f64,
        /// Peak value (default 1).
        #[cfg_attr(feature = "serde", serde(default = "unit_scale"))]
        scale: f64,
    },
    /// Piecewise linear through (`nm[i]`, `values[i]`), zero outside
    /// `nm[0]..=nm[last]`.
    Samples {
        /// Sample wavelengths, nm, strictly increasing.
        nm: Vec<f64>,
        /// Values at those wavelengths.
        values: Vec<f64>,
    },
}

#[cfg(feature = "serde")]
fn unit_scale() -> f64 {
    1.0
}

impl Spectrum {
    /// The spectrum's value at wavelength `nm`; 0 unless `nm` is positive.
    pub fn at(&self, nm: f64) -> f64 {
        if nm.is_nan() || nm <= 0.0 {
            return 0.0;
        }
        match self {
            Spectrum::Rgb(rgb) => uplift(colorimetry().uplift * *rgb, nm),
            Spectrum::Gaussian {
                peak_nm,
                width_nm,
                scale,
            } => {
                let t = (nm - peak_nm) / width_nm;
                scale * math::exp(-0.5 * t * t)
            }
            Spectrum::Blackbody { kelvin, scale } => scale * planck_relative(nm * kelvin),
            Spectrum::Samples { nm: xs, values } => piecewise_linear(xs, values, nm),
        }
    }

    /// Values at the band wavelengths each multiplied by `scale` before
    /// evaluation: `out[i] = self.at(band_nm()[i] * scale)`.
    ///
    /// With `scale` = D = nu_obs / nu_em, the Doppler factor from emitter to
    /// observer, `out` is the emitted spectrum as it arrives in the observed
    /// band: a Gaussian emitted at 500 nm is seen at 500 / D nm. Only the
    /// wavelength axis is rescaled. Spectral radiance per unit wavelength also
    /// changes, by D^5 (I_nu / nu^3 is invariant); that factor is the caller's.
    pub fn sample_scaled(&self, scale: f64) -> [f64; BAND_LEN] {
        self.at_each(&std::array::from_fn(|i| band_wavelength_nm(i) * scale))
    }

    /// [`Spectrum::at`] of each of the wavelengths `nm`, the same values;
    /// an RGB spectrum's uplift coefficients are found once for all of
    /// them.
    pub fn at_each<const N: usize>(&self, nm: &[f64; N]) -> [f64; N] {
        match self {
            Spectrum::Rgb(rgb) => {
                let k = colorimetry().uplift * *rgb;
                nm.map(|x| if x > 0.0 { uplift(k, x) } else { 0.0 })
            }
            _ => nm.map(|x| self.at(x)),
        }
    }

    /// [`Spectrum::at_each`] of this spectrum and of white (the uplift of
    /// (1, 1, 1)) at the same wavelengths, the same values to the bit: for
    /// an RGB spectrum the basis and the window, four smoothsteps a
    /// wavelength, are found once for both.
    pub fn at_each_with_white<const N: usize>(&self, nm: &[f64; N]) -> ([f64; N], [f64; N]) {
        let Spectrum::Rgb(rgb) = self else {
            return (self.at_each(nm), Spectrum::Rgb(DVec3::ONE).at_each(nm));
        };
        let (k, white) = (
            colorimetry().uplift * *rgb,
            colorimetry().uplift * DVec3::ONE,
        );
        let (mut own, mut whites) = ([0.0; N], [0.0; N]);
        for (i, &x) in nm.iter().enumerate() {
            let w = if x > 0.0 { window(x) } else { 0.0 };
            if w > 0.0 {
                let b = basis(x);
                (own[i], whites[i]) = ((k.dot(b) * w).max(0.0), (white.dot(b) * w).max(0.0));
            }
        }
        (own, whites)
    }
}

/// The C1 smoothstep 3t^2 - 2t^3 of t = (x - edge0) / (edge1 - edge0),
/// clamped to 0 below edge0 and to 1 above edge1.
fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The uplift window W: 1 over 405..690 nm, exactly 0 outside 380..730 nm.
pub(super) fn window(nm: f64) -> f64 {
    smoothstep(WINDOW_RISE_NM.0, WINDOW_RISE_NM.1, nm)
        * (1.0 - smoothstep(WINDOW_FALL_NM.0, WINDOW_FALL_NM.1, nm))
}

/// The uplift basis (b_r, b_g, b_b) at `nm`, a partition of unity.
pub(super) fn basis(nm: f64) -> DVec3 {
    let h = TRANSITION_HALF_WIDTH_NM;
    let green_or_red = smoothstep(BLUE_GREEN_NM - h, BLUE_GREEN_NM + h, nm);
    let red = smoothstep(GREEN_RED_NM - h, GREEN_RED_NM + h, nm);
    DVec3::new(red, green_or_red - red, 1.0 - green_or_red)
}

/// The uplift spectrum with basis coefficients `k` = (k_r, k_g, k_b) at `nm`,
/// clamped at 0.
fn uplift(k: DVec3, nm: f64) -> f64 {
    let w = window(nm);
    if w <= 0.0 {
        return 0.0;
    }
    (k.dot(basis(nm)) * w).max(0.0)
}

/// Planck's law per unit wavelength at the product `nm_kelvin` = lambda T,
/// relative to its peak. With x = c2 / (lambda T), B_lambda is proportional to
/// T^5 x^5 / (e^x - 1), and the peak at fixed T is at x = WIEN_X.
fn planck_relative(nm_kelvin: f64) -> f64 {
    let x = SECOND_RADIATION_NM_K / nm_kelvin;
    if !(x.is_finite() && x > 0.0) {
        return 0.0;
    }
    static PEAK: OnceLock<f64> = OnceLock::new();
    let shape = |x: f64| math::powi(x, 5) / math::exp_m1(x);
    shape(x) / *PEAK.get_or_init(|| shape(WIEN_X))
}

fn piecewise_linear(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len().min(ys.len());
    if n < 2 || !(xs[0]..=xs[n - 1]).contains(&x) {
        return 0.0;
    }
    let i = xs[..n].partition_point(|&p| p <= x).max(1);
    if i == n {
        return ys[n - 1];
    }
    let (x0, x1, y0, y1) = (xs[i - 1], xs[i], ys[i - 1], ys[i]);
    y0 + (y1 - y0) * (x - x0) / (x1 - x0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::test_support::{argmax, sample};
    use crate::color::{band_nm, to_rgb};
    use approx::assert_abs_diff_eq;

    #[test]
    fn white_uplifts_to_the_window() {
        let white = Spectrum::Rgb(DVec3::ONE);
        for nm in [
            375.0, 390.0, 420.0, 493.0, 550.0, 588.0, 650.0, 700.0, 725.0,
        ] {
            assert_abs_diff_eq!(white.at(nm), window(nm), epsilon = 1e-12);
        }
        assert_abs_diff_eq!(window(550.0), 1.0, epsilon = 1e-15);
    }

    #[test]
    fn negative_coefficients_are_clamped() {
        let c = DVec3::new(-0.5, 1.0, 0.0);
        let k = colorimetry().uplift * c;
        assert!((400..700).any(|nm| k.dot(basis(nm as f64)) < 0.0));
        let s = Spectrum::Rgb(c);
        assert!((300..900).all(|nm| s.at(nm as f64) >= 0.0));
    }

    #[test]
    fn rgb_spectra_vanish_outside_the_visible() {
        for c in [DVec3::ONE, DVec3::X, DVec3::Y, DVec3::Z, DVec3::splat(10.0)] {
            let s = Spectrum::Rgb(c);
            for nm in [1.0, 300.0, 379.0, 380.0, 730.0, 731.0, 900.0, 1e6] {
                assert_eq!(s.at(nm), 0.0, "{c} at {nm} nm");
            }
        }
        let far = Spectrum::Rgb(DVec3::ONE).sample_scaled(2.0);
        assert!(far.iter().all(|&v| v == 0.0));
        assert_eq!(to_rgb(&far), DVec3::ZERO);
    }

    #[test]
    fn scaling_moves_a_gaussian_line() {
        let line = Spectrum::Gaussian {
            peak_nm: 500.0,
            width_nm: 10.0,
            scale: 2.0,
        };
        assert_eq!(line.at(500.0), 2.0);
        assert_abs_diff_eq!(line.at(510.0), 2.0 * math::exp(-0.5), epsilon = 1e-15);
        let nm = band_nm();
        for d in [0.8, 1.0, 1.1, 1.25] {
            let s = line.sample_scaled(d);
            let peak = (0..BAND_LEN)
                .max_by(|&a, &b| s[a].total_cmp(&s[b]))
                .unwrap();
            assert!(
                (nm[peak] - 500.0 / d).abs() <= 2.5,
                "D = {d}: peak at {} nm",
                nm[peak]
            );
        }
    }

    /// `at_each` is `at` at every wavelength, to the bit, for every kind
    /// of spectrum, at the band shifted either way, at the window's edges
    /// and at wavelengths that are not (NaN, zero, negative, infinite);
    /// the values differ from one wavelength to the next, so a value put
    /// in another's place would show.
    #[test]
    fn at_each_is_at_at_every_wavelength_to_the_bit() {
        let spectra = [
            Spectrum::Rgb(DVec3::new(0.9, 0.2, 0.05)),
            Spectrum::Rgb(DVec3::new(-0.5, 2.0, 0.0)),
            Spectrum::Gaussian {
                peak_nm: 520.0,
                width_nm: 15.0,
                scale: 1.5,
            },
            Spectrum::Blackbody {
                kelvin: 3200.0,
                scale: 1.0,
            },
            Spectrum::Samples {
                nm: vec![400.0, 500.0, 600.0],
                values: vec![1.0, 3.0, 0.0],
            },
        ];
        let odd = [
            f64::NAN,
            0.0,
            -0.0,
            -450.0,
            f64::INFINITY,
            380.0,
            405.0,
            690.0,
            730.0,
        ];
        for s in &spectra {
            let mut values = Vec::new();
            for d in [0.5, 0.93, 1.0, 1.7] {
                let nm: [f64; BAND_LEN] = std::array::from_fn(|i| band_nm()[i] * d);
                let each = s.at_each(&nm);
                for (x, v) in nm.iter().zip(each) {
                    assert_eq!(v.to_bits(), s.at(*x).to_bits(), "{s:?} at {x} nm");
                }
                values.extend(each);
            }
            assert!(values.windows(2).any(|w| w[0] != w[1]), "{s:?}: flat");
            for (x, v) in odd.iter().zip(s.at_each(&odd)) {
                assert_eq!(v.to_bits(), s.at(*x).to_bits(), "{s:?} at {x} nm");
            }
        }
    }

    /// `at_each_with_white` is `at_each` of the spectrum and of white, to
    /// the bit, for every kind, at the band shifted either way and at
    /// wavelengths that are not; a coloured spectrum differs from white,
    /// so the two put in each other's place would show.
    #[test]
    fn at_each_with_white_is_both_at_each_to_the_bit() {
        let spectra = [
            Spectrum::Rgb(DVec3::new(0.9, 0.2, 0.05)),
            Spectrum::Rgb(DVec3::new(-0.5, 2.0, 0.0)),
            Spectrum::Blackbody {
                kelvin: 3200.0,
                scale: 1.0,
            },
        ];
        let white = Spectrum::Rgb(DVec3::ONE);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for s in &spectra {
            for d in [0.5, 0.93, 1.0, 1.7] {
                let nm: [f64; BAND_LEN] = std::array::from_fn(|i| band_nm()[i] * d);
                let (own, whites) = s.at_each_with_white(&nm);
                assert_eq!(bits(&own), bits(&s.at_each(&nm)), "{s:?} x {d}");
                assert_eq!(bits(&whites), bits(&white.at_each(&nm)), "{s:?} x {d}");
                assert_ne!(bits(&own), bits(&whites), "{s:?} x {d}: white itself");
            }
            let odd = [f64::NAN, 0.0, -0.0, -450.0, f64::INFINITY, 380.0, 730.0];
            let (own, whites) = s.at_each_with_white(&odd);
            assert_eq!(bits(&own), bits(&s.at_each(&odd)), "{s:?}");
            assert_eq!(bits(&whites), bits(&white.at_each(&odd)), "{s:?}");
        }
    }

    #[test]
    fn samples_interpolate_linearly() {
        let s = Spectrum::Samples {
            nm: vec![400.0, 500.0, 600.0],
            values: vec![1.0, 3.0, 0.0],
        };
        assert_eq!(s.at(400.0), 1.0);
        assert_eq!(s.at(450.0), 2.0);
        assert_eq!(s.at(500.0), 3.0);
        assert_eq!(s.at(575.0), 0.75);
        assert_eq!(s.at(600.0), 0.0);
        assert_eq!(s.at(399.9), 0.0);
        assert_eq!(s.at(600.1), 0.0);
        assert_eq!(s.at(f64::NAN), 0.0);
    }

    #[test]
    fn blackbody_peaks_at_wiens_wavelength() {
        for kelvin in [1000.0, 3000.0, 5800.0, 10_000.0, 30_000.0] {
            let s = Spectrum::Blackbody { kelvin, scale: 2.0 };
            let wien = 2.897771955e6 / kelvin;
            let (nm, peak) = argmax(|nm| s.at(nm), 0.5 * wien, 2.0 * wien, wien * 1e-4);
            assert!(
                (nm / wien - 1.0).abs() < 0.005,
                "{kelvin} K peaks at {nm} nm"
            );
            assert_abs_diff_eq!(peak, 2.0, epsilon = 1e-6);
            assert_abs_diff_eq!(s.at(wien), 2.0, epsilon = 1e-9);
        }
    }

    #[test]
    fn blackbody_follows_plancks_law() {
        let (h, c, k) = (6.626_070_15e-34, 299_792_458.0, 1.380_649e-23);
        let planck = |nm: f64, kelvin: f64| {
            let m = nm * 1e-9;
            2.0 * h * c * c / math::powi(m, 5) / (math::exp(h * c / (m * k * kelvin)) - 1.0)
        };
        let kelvin = 4000.0;
        let s = Spectrum::Blackbody { kelvin, scale: 1.0 };
        let ratio = s.at(500.0) / planck(500.0, kelvin);
        for nm in [200.0, 380.0, 724.5, 1500.0, 10_000.0] {
            let r = s.at(nm) / planck(nm, kelvin);
            assert_abs_diff_eq!(r / ratio, 1.0, epsilon = 1e-9);
        }
    }

    #[test]
    fn a_rescaled_blackbody_is_a_blackbody_at_the_rescaled_temperature() {
        let kelvin = 4000.0;
        let s = Spectrum::Blackbody { kelvin, scale: 1.5 };
        for d in [0.5, 0.9, 1.3, 2.0] {
            let shifted = s.sample_scaled(d);
            let hotter = sample(&Spectrum::Blackbody {
                kelvin: d * kelvin,
                scale: 1.5,
            });
            for (a, b) in shifted.iter().zip(&hotter) {
                assert_abs_diff_eq!(a / b, 1.0, epsilon = 1e-12);
            }
            let colder = sample(&Spectrum::Blackbody {
                kelvin: kelvin / d,
                scale: 1.5,
            });
            let spread = (shifted[BAND_LEN - 1] / colder[BAND_LEN - 1]) / (shifted[0] / colder[0]);
            assert!(
                (spread - 1.0).abs() > 0.1,
                "D = {d}: T/D has the same shape"
            );
        }
    }
}
