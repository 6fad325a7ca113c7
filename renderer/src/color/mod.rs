//! Colour: spectra that can be Doppler shifted, and their conversion to
//! display colour through the CIE 1931 observer.

mod cie;
mod spectrum;
mod validate;

pub use cie::{band_nm, chromaticity, cmf, to_rgb, xyz, xyz_to_rgb, BAND_LEN};
pub use spectrum::Spectrum;
pub use validate::{SpectrumError, SpectrumErrorKind, SpectrumField};
