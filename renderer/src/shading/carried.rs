//! The colour types a ray carries: linear RGB, and spectral radiance for
//! the Doppler shift.

use super::shader::{sample, Band, Shader};
use crate::color::Spectrum;
use crate::geometry::Hit;
use crate::spacetime::Ray;
use crate::trace::Trace;
use glam::DVec3;

/// A colour a ray can carry back: what a miss gives and how a hit is
/// shaded. Linear RGB (wavelengths unshifted) and spectral radiance at a
/// band of lab wavelengths (Doppler shift) travel the same path,
/// [`Shader::carry`]; only the shading at a hit differs.
pub(super) trait Carried: Sized {
    /// What the colour is evaluated at: nothing for RGB, the lab
    /// wavelengths for a spectrum.
    type At: ?Sized;
    /// The colour where a ray meets nothing.
    fn background(shader: &Shader<'_>, band: &Self::At) -> Self;
    /// The colour leaving `hit` towards the ray's origin.
    fn shade<T: Trace>(
        shader: &Shader<'_>,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        band: &Self::At,
        trace: &mut T,
    ) -> Self;
}

impl Carried for DVec3 {
    type At = ();
    fn background(shader: &Shader<'_>, _: &()) -> DVec3 {
        shader.background
    }
    fn shade<T: Trace>(
        shader: &Shader<'_>,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        _: &(),
        trace: &mut T,
    ) -> DVec3 {
        shader.shade_traced(ray, hit, depth, trace)
    }
}

impl Carried for Band {
    type At = Band;
    fn background(shader: &Shader<'_>, nm: &Band) -> Band {
        sample(&Spectrum::Rgb(shader.background), nm)
    }
    fn shade<T: Trace>(
        shader: &Shader<'_>,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        nm: &Band,
        trace: &mut T,
    ) -> Band {
        shader.shade_spectral(ray, hit, depth, nm, trace)
    }
}
