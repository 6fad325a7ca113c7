//! Doppler shift and searchlight: a self-luminous object glowing as a
//! blackbody at T, moving uniformly. Measured at the centre pixel of a
//! probe aimed at it, rendered with and without each colour effect:
//! - the Doppler factor from the colour: a blackbody seen Doppler-shifted is
//!   a blackbody at D T, so D is the temperature whose chromaticity matches
//!   the pixel's, over T;
//! - the Doppler factor from the searchlight: the pixel's value with the
//!   searchlight on over off is D^5 with wavelengths shifted (per unit
//!   wavelength) and D^4 without (integrated).
//!
//! Expected from first principles: for a source moving with u, light
//! leaving it along the unit vector k (towards the camera, the reverse of
//! the pixel's lab direction) arrives with D = 1 / (gamma (1 - u.k)).
//! Tolerances follow from the 8-bit quantisation of the measured pixels
//! (half a step on each channel).

use super::{Effort, Probe, Reading, Setup};
use crate::fixture::checks::DopplerFrom;
use crate::fixture::Fixture;
use crate::measure::colorimetry::{xyz_of_rgb, Blackbody, Chromaticity};
use crate::measure::{self, Pinhole};
use crate::oracle::{body_point, doppler_factor, retarded};
use glam::DVec3;
use image::RgbImage;
use renderer::Spectrum;

/// The fixture with the colour effects set.
fn with_effects(f: &Fixture, doppler: bool, searchlight: bool) -> Fixture {
    let mut f = f.clone();
    f.spec.image.doppler = doppler;
    f.spec.image.searchlight = searchlight;
    f
}

/// Linear RGB of the centre pixel of a probe, and the lab direction it looks along.
fn centre(img: &RgbImage, camera: &Pinhole) -> (DVec3, DVec3) {
    let (x, y) = (img.width() / 2, img.height() / 2);
    (
        measure::color(img, x, y),
        camera.direction(f64::from(x) + 0.5, f64::from(y) + 0.5),
    )
}

/// The factor D by which the blackbody `source` must be shifted (sampled
/// at D lambda) to have the chromaticity of `rgb`: a scan, then golden-section refinement.
pub(super) fn factor_from_colour(
    source: &Blackbody,
    rgb: DVec3,
    (lo, hi): (f64, f64),
) -> Option<f64> {
    let target = Chromaticity::of(xyz_of_rgb(rgb))?;
    let miss = |d: f64| {
        Chromaticity::of(source.xyz_shifted(d))
            .map_or(f64::INFINITY, |c| c.distance_squared(target))
    };
    let steps = 2700;
    let grid = |i: usize| lo * (hi / lo).powf(i as f64 / steps as f64);
    let best = (0..=steps)
        .min_by(|a, b| miss(grid(*a)).total_cmp(&miss(grid(*b))))
        .unwrap();
    let (mut a, mut b) = (grid(best.saturating_sub(1)), grid((best + 1).min(steps)));
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (c, d) = (b - r * (b - a), a + r * (b - a));
        if miss(c) < miss(d) {
            b = d;
        } else {
            a = c;
        }
    }
    Some(0.5 * (a + b))
}

/// The largest change of `f(rgb)` when each channel moves by half an 8-bit step.
pub(super) fn quantisation(rgb: DVec3, f: impl Fn(DVec3) -> Option<f64>) -> f64 {
    let h = 0.5 / 255.0;
    let at = f(rgb).unwrap_or(f64::NAN);
    (0..8)
        .map(|k| {
            let s = |bit: usize| if k >> bit & 1 == 1 { h } else { -h };
            let moved = rgb + DVec3::new(s(0), s(1), s(2));
            (f(moved).unwrap_or(f64::NAN) - at).abs()
        })
        .fold(0.0, f64::max)
}

/// The Doppler factor D read from the searchlight ratio `on / off` = D^power
/// in the brightest channel of `off` (which carries the ratio best), with
/// its uncertainty from half an 8-bit step on each value.
fn searchlight_factor(on: DVec3, off: DVec3, power: f64) -> Reading {
    let c = if off.x >= off.y.max(off.z) {
        0
    } else if off.y >= off.z {
        1
    } else {
        2
    };
    let (a, b) = (on[c], off[c]);
    let d = (a / b).powf(1.0 / power);
    let h = 0.5 / 255.0;
    Reading {
        value: d,
        tolerance: d / power * (h / a + h / b),
    }
}

/// The centre pixels of one object's probes under each variant of the
/// colour effects (in the order of `variants`), and the lab direction they
/// look along.
fn panel_pixels(
    setup: &Setup,
    variants: &[Fixture],
    name: &str,
    effort: &Effort,
) -> Result<(Vec<DVec3>, DVec3), String> {
    let (model, tc) = (setup.model, setup.camera_t);
    let (look, vfov) = setup.aim(&[name], 0.3)?;
    let mut seen = Vec::new();
    for v in variants {
        let s = Setup {
            fixture: v,
            model,
            camera_t: tc,
        };
        let (img, camera) = s.probe(&Probe {
            keep: &[name],
            look_at: look,
            hfov_deg: vfov,
            size: (effort.probe / 4, effort.probe / 4),
            spp: 1,
        })?;
        seen.push(centre(&img, &camera));
    }
    Ok((seen.iter().map(|s| s.0).collect(), seen[0].1))
}

/// One object's centre pixel under the four combinations of the colour
/// effects, measured once and read by every Doppler check of it, with the
/// factor D = 1 / (gamma (1 - u.k)) expected along its line of sight.
pub struct Panel {
    /// Without effects, searchlight in RGB, shifted, shifted with searchlight.
    pixels: [DVec3; 4],
    source: Blackbody,
    expected: f64,
    /// Where the object's reference point is seen, to mark in the report.
    pub mark: Option<DVec3>,
}

impl Panel {
    /// Measures the object `name` on probes of `measuring`; its emission
    /// and motion are read from `described`.
    pub fn measure(
        measuring: &Setup,
        described: &Setup,
        name: &str,
        effort: &Effort,
    ) -> Result<Panel, String> {
        let f = described.fixture;
        let obj = f.object(name)?;
        let source = match obj.material.emission {
            Some(Spectrum::Blackbody { kelvin, scale }) => Blackbody { kelvin, scale },
            _ => return Err(format!("{name} must glow as a blackbody")),
        };
        let (start, u) =
            super::uniform(&obj.motion).ok_or_else(|| format!("{name} must move uniformly"))?;
        let lorentz = described.model.lorentz;
        let middle = body_point(start.t, start.x, u, DVec3::ZERO, lorentz);
        let mark = retarded(&middle, described.camera_t, described.camera_x()).map(|r| r.direction);
        let variants = [(false, false), (false, true), (true, false), (true, true)]
            .map(|(d, s)| with_effects(measuring.fixture, d, s));
        let (pixels, dir) = panel_pixels(measuring, &variants, name, effort)?;
        Ok(Panel {
            pixels: [pixels[0], pixels[1], pixels[2], pixels[3]],
            source,
            expected: doppler_factor(u, -dir),
            mark,
        })
    }

    /// The factor D read `from` the colour or a searchlight ratio, and the
    /// factor expected.
    pub fn read(&self, from: DopplerFrom) -> (Reading, f64) {
        let [plain, rgb_lit, shifted, shifted_lit] = self.pixels;
        let from_colour = |rgb: DVec3| factor_from_colour(&self.source, rgb, (0.3, 3.0));
        let reading = match from {
            DopplerFrom::Colour => Reading {
                value: from_colour(shifted).unwrap_or(f64::NAN),
                tolerance: quantisation(shifted, from_colour),
            },
            DopplerFrom::SearchlightShifted => searchlight_factor(shifted_lit, shifted, 5.0),
            DopplerFrom::SearchlightRgb => searchlight_factor(rgb_lit, plain, 4.0),
        };
        (reading, self.expected)
    }
}
