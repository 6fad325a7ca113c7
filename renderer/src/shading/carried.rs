//! The colour types a ray carries: linear RGB, and spectral radiance for
//! the Doppler shift.

use super::doppler::Effects;
use super::lit::Lit;
use super::shader::{scaled, Band, Shader};
use crate::color::{Spectrum, BAND_LEN};
use crate::scene::Material;
use crate::trace::{Step, Trace};
use glam::DVec3;

/// A colour a ray can carry back. Linear RGB (wavelengths unshifted) and
/// spectral radiance at a band of lab wavelengths (Doppler shift) travel
/// the same path, [`Shader::carry`], and are shaded by the same steps
/// ([`Shader::shade_hit`]); the colour supplies only what differs
/// physically: the local term, which frequency factors it carries, the
/// wavelengths a mirror ray is evaluated at, and what is recorded.
pub(super) trait Carried: Copy {
    /// What the colour is evaluated at: nothing for RGB, the lab
    /// wavelengths for a spectrum.
    type At;
    /// What the local term leaves for the mirror ray and the record: the
    /// terms of the RGB sum, or the wavelengths in the surface's frame.
    type Local;
    /// No light at all.
    const ZERO: Self;
    /// The colour of the linear RGB `seen` where a ray meets nothing.
    fn background(seen: DVec3, band: &Self::At) -> Self;
    /// [`Carried::background`] of `seen` at `band` where the shader found
    /// it before the render (`None` otherwise).
    fn background_known(shader: &Shader<'_>, seen: DVec3, band: &Self::At) -> Option<Self>;
    /// Whether the colour carries the surface's frequency factors (paper 6):
    /// a spectrum always does (its wavelengths shift); RGB only through the
    /// searchlight's change of intensity.
    fn carries_factors(effects: Effects) -> bool;
    /// Ambient, Lambert and Phong terms and the emission at the hit, in the
    /// frame of the surface, with the light's gain `lamp_gain` (`None` when
    /// the colour does not carry it).
    fn local(
        shader: &Shader<'_>,
        m: &Material,
        lit: &Lit,
        band: &Self::At,
        lamp_gain: Option<f64>,
    ) -> (Self, Self::Local);
    /// Where the mirror ray's colour is evaluated, for light whose
    /// frequency the surface sees scaled by `f` (nu_surface / nu_lab).
    fn mirror_band(local: &Self::Local, f: f64) -> Self::At;
    /// Where the colour is evaluated at its emitter, for light whose
    /// frequency its observer sees scaled by `f` (nu_observer / nu_emitter):
    /// wavelengths times `f`.
    fn emitted_band(band: &Self::At, f: f64) -> Self::At;
    /// The colour scaled by `gain`.
    fn times(self, gain: f64) -> Self;
    /// `self * (1 - mirror) + seen * mirror`.
    fn mix(self, seen: Self, mirror: f64) -> Self;
    /// Records the shading of one hit.
    fn record<T: Trace>(shader: &Shader<'_>, shaded: &Shaded<'_, Self>, trace: &mut T);

    /// The colour scaled by `gain` when there is one.
    fn with_gain(self, gain: Option<f64>) -> Self {
        match gain {
            Some(g) => self.times(g),
            None => self,
        }
    }
}

/// One shaded hit, as recorded: the local term, the colour after the mirror
/// mix (in the surface's frame), and the colour leaving towards the ray's
/// origin.
pub(super) struct Shaded<'a, C: Carried> {
    pub(super) depth: u32,
    pub(super) lit: &'a Lit,
    pub(super) mirror: f64,
    /// nu_surface / nu_lab for the mirrored light, when a mirror ray left.
    pub(super) from_mirror: Option<f64>,
    pub(super) local: C,
    pub(super) detail: &'a C::Local,
    pub(super) mixed: C,
    pub(super) color: C,
}

/// The terms of the RGB local sum, kept for the record.
pub(super) struct RgbLocal {
    albedo: DVec3,
    ambient: DVec3,
    diffuse: DVec3,
    specular: f64,
}

impl Carried for DVec3 {
    type At = ();
    type Local = RgbLocal;
    const ZERO: DVec3 = DVec3::ZERO;
    fn background(seen: DVec3, _: &()) -> DVec3 {
        seen
    }
    fn background_known(_: &Shader<'_>, _: DVec3, _: &()) -> Option<DVec3> {
        None
    }
    fn carries_factors(effects: Effects) -> bool {
        effects.searchlight
    }
    /// The albedo times the light's colour; with the searchlight the light's
    /// irradiance scales by (nu_s/nu_lab)^2.
    fn local(
        shader: &Shader<'_>,
        m: &Material,
        lit: &Lit,
        _: &(),
        lamp_gain: Option<f64>,
    ) -> (DVec3, RgbLocal) {
        let albedo = m.color_textured(lit.tau, lit.texel);
        let ambient = albedo * shader.light.ambient;
        let (mut diffuse, mut specular) = (DVec3::ZERO, 0.0);
        if lit.faces_light() && !lit.shadowed {
            specular = lit.specular;
            diffuse = albedo * (m.diffuse * lit.lambert);
        }
        let direct = shader.light.color * (diffuse + DVec3::splat(specular));
        let mut local = match lamp_gain {
            Some(g) => ambient + direct * g,
            None => ambient + direct,
        };
        let record = &shader.db.objects()[lit.object as usize];
        if let Some(e) = record.emission_rgb_of(lit.triangle) {
            local += e;
        }
        let terms = RgbLocal {
            albedo,
            ambient,
            diffuse,
            specular,
        };
        (local, terms)
    }
    fn mirror_band(_: &RgbLocal, _: f64) {}
    fn emitted_band(_: &(), _: f64) {}
    fn times(self, gain: f64) -> DVec3 {
        self * gain
    }
    fn mix(self, seen: DVec3, mirror: f64) -> DVec3 {
        self * (1.0 - mirror) + seen * mirror
    }
    fn record<T: Trace>(shader: &Shader<'_>, s: &Shaded<'_, DVec3>, trace: &mut T) {
        trace.record(Step::Shading {
            depth: s.depth,
            albedo: s.detail.albedo,
            ambient: s.detail.ambient,
            light_vector: s.lit.l,
            light_distance: s.lit.light_distance,
            lambert: s.lit.lambert,
            surface_frame: s.lit.surface_frame,
            in_shadow: s.lit.shadowed,
            diffuse: s.detail.diffuse,
            specular: s.detail.specular,
            mirror: s.mirror,
            local: s.local,
            color: s.color,
        });
        if shader.effects.any() {
            trace.record(shader.doppler_step(s.depth, s.lit, s.from_mirror, None));
        }
    }
}

impl Carried for Band {
    type At = Band;
    /// The band's wavelengths in the surface's frame.
    type Local = Band;
    const ZERO: Band = [0.0; BAND_LEN];
    fn background(seen: DVec3, nm: &Band) -> Band {
        Spectrum::Rgb(seen).at_each(nm)
    }
    fn background_known(shader: &Shader<'_>, seen: DVec3, nm: &Band) -> Option<Band> {
        shader.background_band.as_ref()?.at(seen, nm)
    }
    fn carries_factors(_: Effects) -> bool {
        true
    }
    /// In the surface's frame the lab wavelengths `nm` are
    /// nm * (nu_lab / nu_s); there the surface reflects the light (its
    /// spectrum evaluated at the wavelengths that left the lamp, times
    /// (nu_s/nu_lab)^3 with the searchlight) and emits.
    fn local(
        shader: &Shader<'_>,
        m: &Material,
        lit: &Lit,
        nm: &Band,
        lamp_gain: Option<f64>,
    ) -> (Band, Band) {
        let surface_nm = scaled(nm, lit.out);
        let (reflectance, white) = m
            .reflectance_textured(lit.tau, lit.texel)
            .at_each_with_white(&surface_nm);
        let lamp = shader
            .light
            .spectrum()
            .at_each(&scaled(&surface_nm, lit.from_light));
        let direct = if lit.faces_light() && !lit.shadowed {
            (m.diffuse * lit.lambert, lit.specular)
        } else {
            (0.0, 0.0)
        };
        let emission = m.emission.as_ref().map(|e| e.at_each(&surface_nm));
        let local = std::array::from_fn(|i| {
            let lamp = lamp_gain.map_or(lamp[i], |g| lamp[i] * g);
            reflectance[i] * (shader.light.ambient * white[i] + direct.0 * lamp)
                + direct.1 * lamp
                + emission.as_ref().map_or(0.0, |e| e[i])
        });
        (local, surface_nm)
    }
    fn mirror_band(surface_nm: &Band, f: f64) -> Band {
        scaled(surface_nm, f)
    }
    fn emitted_band(nm: &Band, f: f64) -> Band {
        scaled(nm, f)
    }
    fn times(self, gain: f64) -> Band {
        self.map(|l| l * gain)
    }
    fn mix(self, seen: Band, mirror: f64) -> Band {
        std::array::from_fn(|i| self[i] * (1.0 - mirror) + seen[i] * mirror)
    }
    fn record<T: Trace>(shader: &Shader<'_>, s: &Shaded<'_, Band>, trace: &mut T) {
        trace.record(shader.doppler_step(
            s.depth,
            s.lit,
            s.from_mirror,
            Some((s.detail, &s.mixed)),
        ));
    }
}
