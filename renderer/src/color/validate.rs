//! Checks that a [`Spectrum`] is physical: non-negative finite values,
//! positive wavelengths, widths and temperatures.

use super::Spectrum;
use std::fmt;

/// A spectrum that is not physical: the parameter at fault and what is wrong.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpectrumError {
    /// The parameter at fault.
    pub field: SpectrumField,
    /// What is wrong with it.
    pub kind: SpectrumErrorKind,
}

/// A parameter of a [`Spectrum`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpectrumField {
    /// One component (0 red, 1 green, 2 blue) of an RGB colour.
    Rgb(usize),
    /// The peak wavelength of a Gaussian.
    GaussianPeak,
    /// The width of a Gaussian.
    GaussianWidth,
    /// The scale of a Gaussian.
    GaussianScale,
    /// The temperature of a blackbody.
    BlackbodyKelvin,
    /// The scale of a blackbody.
    BlackbodyScale,
    /// The wavelength list of sampled values.
    SampleWavelengths,
    /// The value list of sampled values.
    SampleValues,
    /// One sample wavelength.
    SampleWavelength(usize),
    /// One sample value.
    SampleValue(usize),
}

/// What is wrong with a spectrum's parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpectrumErrorKind {
    /// Must be finite and positive.
    NotPositive(f64),
    /// Must be finite and non-negative.
    Negative(f64),
    /// Fewer than two sample wavelengths.
    TooFewSamples(usize),
    /// As many values as wavelengths are needed.
    LengthMismatch {
        /// Values given.
        values: usize,
        /// Wavelengths given.
        wavelengths: usize,
    },
    /// Sample wavelengths must increase strictly.
    NotIncreasing {
        /// The wavelength, nm.
        nm: f64,
        /// The wavelength before it, nm.
        previous: f64,
    },
}

impl fmt::Display for SpectrumField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpectrumField::Rgb(i) => write!(f, "RGB component {i}"),
            SpectrumField::GaussianPeak => write!(f, "Gaussian peak wavelength"),
            SpectrumField::GaussianWidth => write!(f, "Gaussian width"),
            SpectrumField::GaussianScale => write!(f, "Gaussian scale"),
            SpectrumField::BlackbodyKelvin => write!(f, "blackbody temperature"),
            SpectrumField::BlackbodyScale => write!(f, "blackbody scale"),
            SpectrumField::SampleWavelengths => write!(f, "sample wavelengths"),
            SpectrumField::SampleValues => write!(f, "sample values"),
            SpectrumField::SampleWavelength(i) => write!(f, "sample wavelength {i}"),
            SpectrumField::SampleValue(i) => write!(f, "sample value {i}"),
        }
    }
}

impl fmt::Display for SpectrumErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpectrumErrorKind::NotPositive(v) => {
                write!(f, "must be a finite positive number, got {v}")
            }
            SpectrumErrorKind::Negative(v) => {
                write!(f, "must be a finite non-negative number, got {v}")
            }
            SpectrumErrorKind::TooFewSamples(n) => {
                write!(f, "needs at least 2 wavelengths, got {n}")
            }
            SpectrumErrorKind::LengthMismatch {
                values,
                wavelengths,
            } => write!(f, "{values} values for {wavelengths} wavelengths"),
            SpectrumErrorKind::NotIncreasing { nm, previous } => write!(
                f,
                "{nm} nm does not exceed the wavelength before it, {previous} nm; \
                 wavelengths must be strictly increasing"
            ),
        }
    }
}

impl fmt::Display for SpectrumError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.kind)
    }
}

impl std::error::Error for SpectrumError {}

impl Spectrum {
    /// Rejects non-finite or negative values, a non-positive peak wavelength,
    /// width or temperature, sample wavelengths that are not positive, not
    /// strictly increasing or fewer than 2, and mismatched lengths.
    pub fn validate(&self) -> Result<(), SpectrumError> {
        use SpectrumField as F;
        match self {
            Spectrum::Rgb(rgb) => {
                for (i, v) in rgb.to_array().into_iter().enumerate() {
                    non_negative(F::Rgb(i), v)?;
                }
                Ok(())
            }
            Spectrum::Gaussian {
                peak_nm,
                width_nm,
                scale,
            } => {
                positive(F::GaussianPeak, *peak_nm)?;
                positive(F::GaussianWidth, *width_nm)?;
                non_negative(F::GaussianScale, *scale)
            }
            Spectrum::Blackbody { kelvin, scale } => {
                positive(F::BlackbodyKelvin, *kelvin)?;
                non_negative(F::BlackbodyScale, *scale)
            }
            Spectrum::Samples { nm, values } => validate_samples(nm, values),
        }
    }
}

fn validate_samples(nm: &[f64], values: &[f64]) -> Result<(), SpectrumError> {
    use SpectrumErrorKind as K;
    use SpectrumField as F;
    let bad = |field, kind| Err(SpectrumError { field, kind });
    if nm.len() < 2 {
        return bad(F::SampleWavelengths, K::TooFewSamples(nm.len()));
    }
    if values.len() != nm.len() {
        return bad(
            F::SampleValues,
            K::LengthMismatch {
                values: values.len(),
                wavelengths: nm.len(),
            },
        );
    }
    for (i, &x) in nm.iter().enumerate() {
        positive(F::SampleWavelength(i), x)?;
        if i > 0 && x <= nm[i - 1] {
            return bad(
                F::SampleWavelength(i),
                K::NotIncreasing {
                    nm: x,
                    previous: nm[i - 1],
                },
            );
        }
    }
    for (i, &v) in values.iter().enumerate() {
        non_negative(F::SampleValue(i), v)?;
    }
    Ok(())
}

fn positive(field: SpectrumField, v: f64) -> Result<(), SpectrumError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SpectrumError {
            field,
            kind: SpectrumErrorKind::NotPositive(v),
        })
    }
}

fn non_negative(field: SpectrumField, v: f64) -> Result<(), SpectrumError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SpectrumError {
            field,
            kind: SpectrumErrorKind::Negative(v),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn validate_names_the_field() {
        use SpectrumField as F;
        let field = |s: Spectrum| s.validate().unwrap_err().field;
        let samples = |nm: Vec<f64>, values: Vec<f64>| Spectrum::Samples { nm, values };
        let e = samples(vec![400.0, 500.0, 450.0], vec![1.0; 3])
            .validate()
            .unwrap_err();
        assert_eq!(e.field, F::SampleWavelength(2));
        assert_eq!(
            e.kind,
            SpectrumErrorKind::NotIncreasing {
                nm: 450.0,
                previous: 500.0
            }
        );
        assert!(
            e.to_string().starts_with("sample wavelength 2: 450 nm"),
            "{e}"
        );
        assert_eq!(
            field(samples(vec![400.0, 400.0], vec![1.0; 2])),
            F::SampleWavelength(1)
        );
        assert_eq!(
            field(samples(vec![400.0, 500.0], vec![1.0; 3])),
            F::SampleValues
        );
        assert_eq!(field(samples(vec![400.0], vec![1.0])), F::SampleWavelengths);
        assert_eq!(
            field(samples(vec![400.0, 500.0], vec![1.0, -0.5])),
            F::SampleValue(1)
        );
        assert_eq!(
            field(samples(vec![-1.0, 500.0], vec![1.0; 2])),
            F::SampleWavelength(0)
        );
        assert_eq!(
            field(samples(vec![400.0, f64::NAN], vec![1.0; 2])),
            F::SampleWavelength(1)
        );
        assert_eq!(
            field(Spectrum::Rgb(DVec3::new(0.5, f64::NAN, 0.0))),
            F::Rgb(1)
        );
        assert_eq!(field(Spectrum::Rgb(DVec3::new(0.5, 0.5, -0.1))), F::Rgb(2));
        assert_eq!(
            field(Spectrum::Gaussian {
                peak_nm: 500.0,
                width_nm: f64::NAN,
                scale: 1.0
            }),
            F::GaussianWidth
        );
        assert_eq!(
            field(Spectrum::Gaussian {
                peak_nm: 500.0,
                width_nm: 0.0,
                scale: 1.0
            }),
            F::GaussianWidth
        );
        assert_eq!(
            field(Spectrum::Gaussian {
                peak_nm: 500.0,
                width_nm: 10.0,
                scale: f64::INFINITY
            }),
            F::GaussianScale
        );
        assert_eq!(
            field(Spectrum::Blackbody {
                kelvin: 0.0,
                scale: 1.0
            }),
            F::BlackbodyKelvin
        );
        assert_eq!(
            field(Spectrum::Blackbody {
                kelvin: 3000.0,
                scale: -1.0
            }),
            F::BlackbodyScale
        );
        for ok in [
            Spectrum::Rgb(DVec3::new(0.0, 0.5, 2.0)),
            Spectrum::Gaussian {
                peak_nm: 500.0,
                width_nm: 10.0,
                scale: 0.0,
            },
            Spectrum::Blackbody {
                kelvin: 5800.0,
                scale: 1.0,
            },
            samples(vec![400.0, 500.0], vec![0.0, 1.0]),
        ] {
            assert_eq!(ok.validate(), Ok(()), "{ok:?}");
        }
    }

    #[cfg(feature = "serde")]
    #[test]
    fn serde_forms() {
        let parse = |json: &str| serde_json::from_str::<Spectrum>(json);
        assert_eq!(
            parse(r#"{"rgb": [0.25, 0.5, 1.0]}"#).unwrap(),
            Spectrum::Rgb(DVec3::new(0.25, 0.5, 1.0))
        );
        assert_eq!(
            parse(r#"{"gaussian": {"peak_nm": 532, "width_nm": 5, "scale": 3}}"#).unwrap(),
            Spectrum::Gaussian {
                peak_nm: 532.0,
                width_nm: 5.0,
                scale: 3.0
            }
        );
        assert_eq!(
            parse(r#"{"gaussian": {"peak_nm": 532, "width_nm": 5}}"#).unwrap(),
            Spectrum::Gaussian {
                peak_nm: 532.0,
                width_nm: 5.0,
                scale: 1.0
            }
        );
        assert_eq!(
            parse(r#"{"blackbody": {"kelvin": 5800}}"#).unwrap(),
            Spectrum::Blackbody {
                kelvin: 5800.0,
                scale: 1.0
            }
        );
        assert_eq!(
            parse(r#"{"blackbody": {"kelvin": 3000, "scale": 0.5}}"#).unwrap(),
            Spectrum::Blackbody {
                kelvin: 3000.0,
                scale: 0.5
            }
        );
        assert_eq!(
            parse(r#"{"samples": {"nm": [400, 700], "values": [1, 0]}}"#).unwrap(),
            Spectrum::Samples {
                nm: vec![400.0, 700.0],
                values: vec![1.0, 0.0]
            }
        );
        assert!(parse(r#"{"gaussian": {"peak_nm": 532, "width_nm": 5, "sigma": 1}}"#).is_err());
        assert!(parse(r#"{"blackbody": {"kelvin": 5800, "colour": 1}}"#).is_err());
        assert!(parse(r#"{"samples": {"nm": [400, 700], "values": [1, 0], "x": 0}}"#).is_err());
        assert!(parse(r#"{"blackbody": {"scale": 1}}"#).is_err());
        assert!(parse(r#"{"laser": {"nm": 532}}"#).is_err());
        let s = Spectrum::Gaussian {
            peak_nm: 532.0,
            width_nm: 5.0,
            scale: 3.0,
        };
        let json = serde_json::to_string(&s).unwrap();
        assert_eq!(
            json,
            r#"{"gaussian":{"peak_nm":532.0,"width_nm":5.0,"scale":3.0}}"#
        );
        assert_eq!(
            serde_json::to_string(&Spectrum::Rgb(DVec3::new(1.0, 0.5, 0.0))).unwrap(),
            r#"{"rgb":[1.0,0.5,0.0]}"#
        );
    }
}
