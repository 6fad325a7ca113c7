//! Colour: spectra that can be Doppler shifted, and their conversion to
//! display colour through the CIE 1931 observer.

mod cie;
mod spectrum;
mod validate;

pub(crate) use cie::to_rgb;
pub use cie::{band_nm, chromaticity, cmf, xyz, xyz_to_rgb, BAND_LEN};
pub use spectrum::Spectrum;
pub use validate::{SpectrumError, SpectrumErrorKind, SpectrumField};

/// Helpers shared by the colour tests.
#[cfg(test)]
mod test_support {
    use super::{Spectrum, BAND_LEN};

    /// A spectrum's values over the observed band.
    pub(super) fn sample(s: &Spectrum) -> [f64; BAND_LEN] {
        s.sample_scaled(1.0)
    }

    /// The argmax of `f` on a grid of step `step` over [lo, hi].
    pub(super) fn argmax(f: impl Fn(f64) -> f64, lo: f64, hi: f64, step: f64) -> (f64, f64) {
        let n = ((hi - lo) / step).round() as usize;
        (0..=n)
            .map(|i| lo + step * i as f64)
            .map(|x| (x, f(x)))
            .fold(
                (lo, f64::NEG_INFINITY),
                |best, c| {
                    if c.1 > best.1 {
                        c
                    } else {
                        best
                    }
                },
            )
    }
}
