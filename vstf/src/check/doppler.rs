//! Doppler shift and searchlight (issue 6, item 2): self-luminous panels
//! glowing as a blackbody at T, approaching head-on, receding, and crossing
//! the line of sight. Measured at the centre pixel of each panel's probe:
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

use super::{Effort, FixtureReport, Row, Setup};
use crate::fixture::{Fixture, Overrides};
use crate::measure;
use crate::oracle::{body_point, retarded};
use glam::{DMat3, DVec3};
use image::RgbImage;
use renderer::Camera;
use renderer::{self as spectrum, Spectrum};

const NAME: &str = "doppler";
const PANELS: [&str; 3] = ["head-on", "receding", "transverse"];

/// The fixture with the colour effects set.
fn with_effects(f: &Fixture, doppler: bool, searchlight: bool) -> Fixture {
    let mut f = f.clone();
    f.spec.image.doppler = doppler;
    f.spec.image.searchlight = searchlight;
    f
}

/// Linear RGB of the centre pixel of a probe, and the lab direction it looks along.
fn centre(img: &RgbImage, camera: &Camera) -> (DVec3, DVec3) {
    let (x, y) = (img.width() / 2, img.height() / 2);
    (
        measure::color(img, x, y),
        camera.direction(f64::from(x) + 0.5, f64::from(y) + 0.5),
    )
}

/// Linear sRGB (as rendered) back to CIE XYZ.
fn rgb_to_xyz(rgb: DVec3) -> DVec3 {
    let m = DMat3::from_cols(
        spectrum::xyz_to_rgb(DVec3::X),
        spectrum::xyz_to_rgb(DVec3::Y),
        spectrum::xyz_to_rgb(DVec3::Z),
    );
    m.inverse() * rgb
}

/// The factor D by which the blackbody `source` must be shifted (sampled
/// at D lambda) to have the chromaticity of `rgb`: a scan, then golden-section refinement.
fn factor_from_colour(source: &Spectrum, rgb: DVec3) -> Option<f64> {
    let target = spectrum::chromaticity(rgb_to_xyz(rgb))?;
    let miss = |d: f64| {
        spectrum::chromaticity(spectrum::xyz(&source.sample_scaled(d))).map_or(f64::INFINITY, |c| {
            (c.0 - target.0).powi(2) + (c.1 - target.1).powi(2)
        })
    };
    let (lo, hi, steps) = (0.3f64, 3.0f64, 2700);
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
fn quantisation(rgb: DVec3, f: impl Fn(DVec3) -> Option<f64>) -> f64 {
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

pub fn run(effort: &Effort) -> Result<FixtureReport, String> {
    let f = Fixture::load(NAME).map_err(|e| e.to_string())?;
    let model = f
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let tc = f.spec.camera.t;
    let mut rows = Vec::new();
    let mut marks = Vec::new();
    let variants = [(false, false), (false, true), (true, false), (true, true)]
        .map(|(d, s)| with_effects(&f, d, s));
    for name in PANELS {
        let obj = f
            .scene
            .objects
            .iter()
            .find(|o| o.name == name)
            .ok_or_else(|| format!("{NAME}: no panel {name:?}"))?;
        let source = obj
            .material
            .emission
            .clone()
            .ok_or_else(|| format!("{NAME}: {name} must glow"))?;
        let (start, u) = obj
            .motion
            .uniform()
            .ok_or_else(|| format!("{NAME}: {name} must move uniformly"))?;
        let middle = body_point(start.t, start.x, u, DVec3::ZERO, model.lorentz);
        if let Some(r) = retarded(&middle, tc, f.spec.camera.position) {
            marks.push(r.direction);
        }
        let setup = Setup {
            fixture: &f,
            model,
            camera_t: tc,
        };
        let (look, vfov) = setup.aim(&[name], 0.3)?;
        let mut seen = Vec::new();
        for v in &variants {
            let s = Setup {
                fixture: v,
                model,
                camera_t: tc,
            };
            let (img, camera) =
                s.probe(&[name], look, vfov, effort.probe / 4, effort.probe / 4, 1)?;
            seen.push(centre(&img, &camera));
        }
        let [(plain, dir), (rgb_lit, _), (shifted, _), (shifted_lit, _)] =
            [seen[0], seen[1], seen[2], seen[3]];
        let gamma = 1.0 / (1.0 - u.length_squared()).sqrt();
        let expected = 1.0 / (gamma * (1.0 - u.dot(-dir)));
        let from_colour = |rgb: DVec3| factor_from_colour(&source, rgb);
        rows.push(Row::new(
            NAME,
            &format!("{name}: D from the colour (blackbody at D T)"),
            from_colour(shifted).unwrap_or(f64::NAN),
            expected,
            None,
            quantisation(shifted, from_colour),
            "factor",
        ));
        // The brightest channel of the pair carries the ratio best.
        let ratio = |on: DVec3, off: DVec3, power: f64| {
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
            (d, d / power * (h / a + h / b))
        };
        let (d5, t5) = ratio(shifted_lit, shifted, 5.0);
        rows.push(Row::new(
            NAME,
            &format!("{name}: D from the searchlight, shifted (D^5)"),
            d5,
            expected,
            None,
            t5,
            "factor",
        ));
        let (d4, t4) = ratio(rgb_lit, plain, 4.0);
        rows.push(Row::new(
            NAME,
            &format!("{name}: D from the searchlight, RGB (D^4)"),
            d4,
            expected,
            None,
            t4,
            "factor",
        ));
    }
    let setup = Setup {
        fixture: &f,
        model,
        camera_t: tc,
    };
    let mut views = vec![setup.full_view("doppler", &marks)?];
    let lit = Setup {
        fixture: &variants[3],
        model,
        camera_t: tc,
    };
    views.push(lit.full_view("doppler and searchlight", &marks)?);
    Ok(FixtureReport::new(NAME, &f.spec.description, views, rows))
}
