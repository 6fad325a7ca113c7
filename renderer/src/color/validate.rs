//! Checks that a [`Spectrum`] is physical: non-negative finite values,
//! positive wavelengths, widths and temperatures.

use super::Spectrum;
use std::fmt;

impl Spectrum {
    /// Rejects non-finite or negative values, a non-positive peak wavelength,
    /// width or temperature, sample wavelengths that are not positive, not
    /// strictly increasing or fewer than 2, and mismatched lengths. The error
    /// names the offending field relative to the spectrum, e.g.
    /// `"samples.nm[3]: ..."`.
    pub fn validate(&self) -> Result<(), String> {
        match self {
            Spectrum::Rgb(rgb) => {
                for (i, v) in rgb.to_array().into_iter().enumerate() {
                    non_negative(format_args!("rgb[{i}]"), v)?;
                }
                Ok(())
            }
            Spectrum::Gaussian {
                peak_nm,
                width_nm,
                scale,
            } => {
                positive(format_args!("gaussian.peak_nm"), *peak_nm)?;
                positive(format_args!("gaussian.width_nm"), *width_nm)?;
                non_negative(format_args!("gaussian.scale"), *scale)
            }
            Spectrum::Blackbody { kelvin, scale } => {
                positive(format_args!("blackbody.kelvin"), *kelvin)?;
                non_negative(format_args!("blackbody.scale"), *scale)
            }
            Spectrum::Samples { nm, values } => {
                if nm.len() < 2 {
                    return Err(format!(
                        "samples.nm: needs at least 2 wavelengths, got {}",
                        nm.len()
                    ));
                }
                if values.len() != nm.len() {
                    return Err(format!(
                        "samples.values: {} values for {} wavelengths in samples.nm",
                        values.len(),
                        nm.len()
                    ));
                }
                for (i, &x) in nm.iter().enumerate() {
                    positive(format_args!("samples.nm[{i}]"), x)?;
                    if i > 0 && x <= nm[i - 1] {
                        return Err(format!(
                            "samples.nm[{i}]: {x} nm does not exceed samples.nm[{}] = {} nm; \
                             wavelengths must be strictly increasing",
                            i - 1,
                            nm[i - 1]
                        ));
                    }
                }
                for (i, &v) in values.iter().enumerate() {
                    non_negative(format_args!("samples.values[{i}]"), v)?;
                }
                Ok(())
            }
        }
    }
}

fn positive(field: fmt::Arguments, v: f64) -> Result<(), String> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(format!(
            "{field}: must be a finite positive number, got {v}"
        ))
    }
}

fn non_negative(field: fmt::Arguments, v: f64) -> Result<(), String> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(format!(
            "{field}: must be a finite non-negative number, got {v}"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn validate_names_the_field() {
        let err = |s: Spectrum| s.validate().unwrap_err();
        let samples = |nm: Vec<f64>, values: Vec<f64>| Spectrum::Samples { nm, values };
        assert!(
            err(samples(vec![400.0, 500.0, 450.0], vec![1.0; 3])).starts_with("samples.nm[2]: ")
        );
        assert!(err(samples(vec![400.0, 400.0], vec![1.0; 2])).starts_with("samples.nm[1]: "));
        assert!(err(samples(vec![400.0, 500.0], vec![1.0; 3])).starts_with("samples.values: "));
        assert!(err(samples(vec![400.0], vec![1.0])).starts_with("samples.nm: "));
        assert!(
            err(samples(vec![400.0, 500.0], vec![1.0, -0.5])).starts_with("samples.values[1]: ")
        );
        assert!(err(samples(vec![-1.0, 500.0], vec![1.0; 2])).starts_with("samples.nm[0]: "));
        assert!(err(samples(vec![400.0, f64::NAN], vec![1.0; 2])).starts_with("samples.nm[1]: "));
        assert!(err(Spectrum::Rgb(DVec3::new(0.5, f64::NAN, 0.0))).starts_with("rgb[1]: "));
        assert!(err(Spectrum::Rgb(DVec3::new(0.5, 0.5, -0.1))).starts_with("rgb[2]: "));
        assert!(err(Spectrum::Gaussian {
            peak_nm: 500.0,
            width_nm: f64::NAN,
            scale: 1.0
        })
        .starts_with("gaussian.width_nm: "));
        assert!(err(Spectrum::Gaussian {
            peak_nm: 500.0,
            width_nm: 0.0,
            scale: 1.0
        })
        .starts_with("gaussian.width_nm: "));
        assert!(err(Spectrum::Gaussian {
            peak_nm: 500.0,
            width_nm: 10.0,
            scale: f64::INFINITY
        })
        .starts_with("gaussian.scale: "));
        assert!(err(Spectrum::Blackbody {
            kelvin: 0.0,
            scale: 1.0
        })
        .starts_with("blackbody.kelvin: "));
        assert!(err(Spectrum::Blackbody {
            kelvin: 3000.0,
            scale: -1.0
        })
        .starts_with("blackbody.scale: "));
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
