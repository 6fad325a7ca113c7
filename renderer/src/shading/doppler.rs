//! Colour effects of motion: the Doppler shift of wavelengths and
//! the searchlight change of intensity, both off by default (paper 6: they
//! can hide the geometry). Derivations are in docs/physics.md.
//!
//! Light is followed by wavelength along its actual path, leg by leg: from
//! the light (at rest in the lab) to a surface, in the surface's frame; from
//! the surface back into the lab; from a mirror's frame and back; and into
//! the camera's frame. Across each leg frequencies scale by the factor
//! [`to_frame`]. Spectral radiance per unit wavelength scales by the fifth
//! power of that factor, because I_nu / nu^3 is invariant; frequency-
//! integrated radiance by the fourth. A point source's irradiance loses two
//! powers to aberration (its solid angle scales by the inverse square), so it
//! scales by the third per unit wavelength and the second integrated.

use glam::DVec3;

/// Which colour effects of motion are rendered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Effects {
    /// Shift wavelengths (spectral rendering; colours change).
    pub doppler: bool,
    /// Scale intensities by powers of the Doppler factor.
    pub searchlight: bool,
}

impl Effects {
    /// Both off.
    pub const NONE: Effects = Effects {
        doppler: false,
        searchlight: false,
    };

    /// Whether either effect is on.
    pub fn any(self) -> bool {
        self.doppler || self.searchlight
    }

    /// The intensity factor of a leg with frequency ratio `f`: f^exponent
    /// with the searchlight on, else 1. The exponent is that of spectral
    /// radiance (5) or irradiance (3) when wavelengths are shifted, one less
    /// when colours stay RGB (frequency-integrated).
    pub fn intensity(self, f: f64, leg: Leg) -> f64 {
        if !self.searchlight {
            return 1.0;
        }
        let spectral = if self.doppler { 1 } else { 0 };
        let exponent = match leg {
            Leg::Radiance => 4 + spectral,
            Leg::PointSource => 2 + spectral,
        };
        crate::math::powi(f, exponent)
    }
}

/// What crosses a change of frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leg {
    /// Radiance along a ray (from a surface, a mirror image, the background).
    Radiance,
    /// The irradiance of the point light.
    PointSource,
}

/// nu_frame / nu_lab for light propagating along the unit lab direction `k`,
/// received in a frame moving with lab velocity `velocity`:
/// gamma (1 - v.k) (relativistic Doppler, with the frame's gamma), or
/// 1 - v.k (classical Doppler, gamma = 1, for a Lorentz-decoupled object or
/// the classical model). Light emitted in that frame arrives in the lab with
/// the inverse factor.
pub(crate) fn to_frame(velocity: DVec3, gamma: f64, k: DVec3) -> f64 {
    gamma * (1.0 - velocity.dot(k))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::gamma;
    use approx::assert_abs_diff_eq;

    /// Head-on, receding and transverse emitters at speed b: the textbook
    /// factors sqrt((1+b)/(1-b)), sqrt((1-b)/(1+b)) and 1/gamma.
    #[test]
    fn classic_doppler_factors() {
        let b: f64 = 0.6;
        let u = DVec3::new(b, 0.0, 0.0);
        let g = gamma(u);
        let seen = |k: DVec3| 1.0 / to_frame(u, g, k);
        assert_abs_diff_eq!(
            seen(DVec3::X),
            ((1.0 + b) / (1.0 - b)).sqrt(),
            epsilon = 1e-12
        );
        assert_abs_diff_eq!(
            seen(-DVec3::X),
            ((1.0 - b) / (1.0 + b)).sqrt(),
            epsilon = 1e-12
        );
        assert_abs_diff_eq!(seen(DVec3::Y), 1.0 / g, epsilon = 1e-12);
    }

    #[test]
    fn searchlight_exponents() {
        let both = Effects {
            doppler: true,
            searchlight: true,
        };
        let rgb = Effects {
            doppler: false,
            searchlight: true,
        };
        assert_eq!(both.intensity(2.0, Leg::Radiance), 32.0);
        assert_eq!(both.intensity(2.0, Leg::PointSource), 8.0);
        assert_eq!(rgb.intensity(2.0, Leg::Radiance), 16.0);
        assert_eq!(rgb.intensity(2.0, Leg::PointSource), 4.0);
        assert_eq!(Effects::NONE.intensity(2.0, Leg::Radiance), 1.0);
    }
}
