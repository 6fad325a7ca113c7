//! Surface appearance and the light: what shading reads from the scene
//! (paper 3, item 5; time-dependent materials, paper 3, item 2d).

use super::texture::Texture;
use crate::color::Spectrum;
use glam::DVec3;
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};
use std::borrow::Cow;

/// A point light at rest in the lab frame.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Light {
    /// Lab position, l.units.
    pub position: DVec3,
    /// Linear RGB intensity.
    #[cfg_attr(feature = "serde", serde(default = "white"))]
    pub color: DVec3,
    /// Fraction of a material's colour seen without direct light.
    #[cfg_attr(feature = "serde", serde(default = "default_ambient"))]
    pub ambient: f64,
    /// The light's spectrum for Doppler rendering (default: the smooth
    /// spectrum of `color`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub spectrum: Option<Spectrum>,
}

impl Light {
    /// A white light with the given ambient fraction.
    pub fn white(position: DVec3, ambient: f64) -> Light {
        Light {
            position,
            color: DVec3::ONE,
            ambient,
            spectrum: None,
        }
    }

    /// The spectrum used when wavelengths are shifted.
    pub fn spectrum(&self) -> Cow<'_, Spectrum> {
        match &self.spectrum {
            Some(s) => Cow::Borrowed(s),
            None => Cow::Owned(Spectrum::Rgb(self.color)),
        }
    }
}

#[cfg(feature = "serde")]
fn white() -> DVec3 {
    DVec3::ONE
}
#[cfg(feature = "serde")]
fn default_ambient() -> f64 {
    0.25
}
fn default_diffuse() -> f64 {
    0.75
}
fn default_shininess() -> f64 {
    32.0
}

/// A colour that alternates with the object's own (proper) time, so that
/// time dilation is visible (paper 3, item 2d).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Blink {
    /// Period in the object's proper time, t.units.
    pub period: f64,
    /// Colour during the first half of each period (the base colour the rest).
    pub color: DVec3,
}

/// Surface appearance. Colours are linear RGB in [0, 1].
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Material {
    /// Base colour (albedo), linear RGB.
    pub color: DVec3,
    /// Weight of the Lambert term.
    #[cfg_attr(feature = "serde", serde(default = "default_diffuse"))]
    pub diffuse: f64,
    /// Weight of the Phong specular term.
    #[cfg_attr(feature = "serde", serde(default))]
    pub specular: f64,
    /// Phong exponent.
    #[cfg_attr(feature = "serde", serde(default = "default_shininess"))]
    pub shininess: f64,
    /// Fraction of the colour taken from the mirror reflection, 0..=1.
    #[cfg_attr(feature = "serde", serde(default))]
    pub mirror: f64,
    /// A colour alternating with the object's proper time.
    #[cfg_attr(feature = "serde", serde(default))]
    pub blink: Option<Blink>,
    /// The reflectance spectrum for Doppler rendering (default: the smooth
    /// spectrum of `color`, or of the blink colour while it shows).
    #[cfg_attr(feature = "serde", serde(default))]
    pub spectrum: Option<Spectrum>,
    /// Light the surface gives off itself, in its own frame: spectral
    /// radiance (its RGB is added when wavelengths are not shifted).
    #[cfg_attr(feature = "serde", serde(default))]
    pub emission: Option<Spectrum>,
    /// A colour varying over the surface, in place of `color` (and of
    /// `spectrum`: with wavelengths shifted, a textured point reflects the
    /// smooth spectrum of its colour) wherever it gives one; the blink
    /// colour still shows over it.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub texture: Option<Texture>,
}

impl Material {
    /// The emission in linear RGB: the spectrum integrated over the bands
    /// unshifted, the colour a surface adds where wavelengths are not
    /// shifted.
    pub fn emission_rgb(&self) -> Option<DVec3> {
        let e = self.emission.as_ref()?;
        Some(crate::color::to_rgb(&e.sample_scaled(1.0)))
    }

    /// A diffuse surface of the given colour with the default weights.
    pub fn matte(color: DVec3) -> Material {
        Material {
            color,
            diffuse: default_diffuse(),
            specular: 0.0,
            shininess: default_shininess(),
            mirror: 0.0,
            blink: None,
            spectrum: None,
            emission: None,
            texture: None,
        }
    }

    /// The reflectance spectrum at the object's proper time `tau`.
    pub fn reflectance_at(&self, tau: f64) -> Cow<'_, Spectrum> {
        match (&self.spectrum, self.blink) {
            (_, Some(b)) if (tau / b.period).rem_euclid(1.0) < 0.5 => {
                Cow::Owned(Spectrum::Rgb(b.color))
            }
            (Some(s), _) => Cow::Borrowed(s),
            (None, _) => Cow::Owned(Spectrum::Rgb(self.color)),
        }
    }

    /// Whether the blink colour shows at proper time `tau`.
    fn blinks(&self, tau: f64) -> bool {
        self.blink
            .is_some_and(|b| (tau / b.period).rem_euclid(1.0) < 0.5)
    }

    /// [`Material::reflectance_at`] at a point whose texture colour is
    /// `texel` (`None`: untextured there).
    pub fn reflectance_textured(&self, tau: f64, texel: Option<DVec3>) -> Cow<'_, Spectrum> {
        match texel {
            Some(c) if !self.blinks(tau) => Cow::Owned(Spectrum::Rgb(c)),
            _ => self.reflectance_at(tau),
        }
    }

    /// [`Material::color_at`] at a point whose texture colour is `texel`.
    pub fn color_textured(&self, tau: f64, texel: Option<DVec3>) -> DVec3 {
        match texel {
            Some(c) if !self.blinks(tau) => c,
            _ => self.color_at(tau),
        }
    }

    /// The colour at the object's proper time `tau`.
    pub fn color_at(&self, tau: f64) -> DVec3 {
        match self.blink {
            Some(b) if (tau / b.period).rem_euclid(1.0) < 0.5 => b.color,
            _ => self.color,
        }
    }
}
