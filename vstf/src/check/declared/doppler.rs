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
//!
//! A static object seen by an accelerating camera ([`Panel::accelerating`])
//! is the same factor in the camera's instantaneous rest frame, where the
//! source moves with the camera's velocity reversed.

mod factor;

use factor::searchlight_factor;
pub(super) use factor::{quantisation, ColourScan};

use crate::check::path::BodyPath;
use crate::check::probe::{Effort, Probe};
use crate::check::row::Reading;
use crate::fixture::checks::DopplerFrom;
use crate::fixture::Fixture;
use crate::measure::colorimetry::Blackbody;
use crate::measure::{self, Pinhole};
use crate::observer::Observer;
use crate::oracle::schwarzschild as gr;
use crate::oracle::{body_point, doppler_factor, gamma_of_squared, retarded};
use glam::DVec3;
use image::RgbImage;
use renderer::{Shape, Spectrum, Window};

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

/// The centre pixels of one object's probes, looking at `look` with the
/// field `hfov_deg` at `size` x `size`, under each variant of the colour
/// effects (in the order of `variants`), and the lab direction they look
/// along.
fn panel_pixels(
    setup: &Observer,
    variants: &[Fixture],
    name: &str,
    (look, hfov_deg): (DVec3, f64),
    size: u32,
) -> Result<(Vec<DVec3>, DVec3), String> {
    let (model, tc) = (setup.model, setup.camera_t);
    let mut seen = Vec::new();
    for v in variants {
        let s = Observer {
            fixture: v,
            model,
            camera_t: tc,
        };
        let (img, camera) = s.probe(&Probe {
            keep: &[name],
            look_at: look,
            hfov_deg,
            size: (size, size),
            spp: 1,
        })?;
        seen.push(centre(&img, &camera));
    }
    Ok((seen.iter().map(|s| s.0).collect(), seen[0].1))
}

/// The colour of `name`'s inner centroid pixel under each variant of the
/// colour effects (in the order of `variants`), rendered alone through
/// the fixture's camera at `size`, and that pixel. The first variant's
/// whole image finds the pixel; the others render only it.
fn spot_pixels(
    measuring: &Observer,
    name: &str,
    size: (u32, u32),
) -> Result<(Vec<DVec3>, (u32, u32)), String> {
    let bg = measuring.fixture.spec.background;
    let mut pixels = Vec::new();
    let mut spot = None;
    for variant in variants(measuring.fixture) {
        let s = Observer {
            fixture: &variant,
            ..*measuring
        };
        let pixel = match spot {
            Some((x, y)) => {
                let only = Window {
                    x,
                    y,
                    width: 1,
                    height: 1,
                };
                let (img, _) = s.measuring_window(&[name], size, (1, 0), only)?;
                measure::color(&img, 0, 0)
            }
            None => {
                let (img, _) = s.measuring_render(&[name], size, 1)?;
                let (x, y) = *spot.insert(inner_centroid(&img, bg).ok_or_else(|| {
                    format!("{name:?} is not seen over 3 x 3 pixels in the view")
                })?);
                measure::color(&img, x, y)
            }
        };
        pixels.push(pixel);
    }
    Ok((pixels, spot.expect("four variants were rendered")))
}

/// The four variants of the colour effects, in the order of [`Panel`]'s pixels.
fn variants(f: &Fixture) -> [Fixture; 4] {
    [(false, false), (false, true), (true, false), (true, true)].map(|(d, s)| with_effects(f, d, s))
}

/// The blackbody an object glows as.
fn blackbody_of(f: &Fixture, name: &str) -> Result<Blackbody, String> {
    match f.object(name)?.material.emission {
        Some(Spectrum::Blackbody { kelvin, scale }) => Ok(Blackbody { kelvin, scale }),
        _ => Err(format!("{name} must glow as a blackbody")),
    }
}

/// The size of a probe aimed at one body point: odd, so that the centre
/// pixel's centre lies on the line of sight aimed at.
pub(super) const POINT_PROBE: u32 = 9;

/// The field of view of a probe aimed at one body point, degrees.
pub(super) const POINT_PROBE_FOV: f64 = 0.2;

/// One object's centre pixel under the four combinations of the colour
/// effects, measured once and read by every Doppler check of it, with the
/// factor D = 1 / (gamma (1 - u.k)) expected along its line of sight.
pub(super) struct Panel {
    /// Without effects, searchlight in RGB, shifted, shifted with searchlight.
    pixels: [DVec3; 4],
    source: Blackbody,
    expected: f64,
    /// How far the expectation may be off because the renderer follows the
    /// path through keyframes (0 for uniform motion), added to every
    /// reading's tolerance.
    slack: f64,
    /// Where the object's reference point is seen, to mark in the report.
    pub mark: Option<DVec3>,
}

/// D = 1 / (gamma (1 - v.k)) for a source point moving with `v`, light
/// leaving it along `k`, gamma that of |v| if `lorentzian` else 1; and
/// |dD/dv| = D^2 |d(gamma (1 - v.k))/dv| = D^2 |gamma^3 (1 - v.k) v - gamma k|.
fn point_factor(v: DVec3, k: DVec3, lorentzian: bool) -> (f64, f64) {
    let g = if lorentzian {
        gamma_of_squared(v.length_squared())
    } else {
        1.0
    };
    let approach = 1.0 - v.dot(k);
    let d = 1.0 / (g * approach);
    let grad = if lorentzian {
        v * (g * g * g * approach) - k * g
    } else {
        -k
    };
    (d, d * d * grad.length())
}

impl Panel {
    /// Measures the object `name` on probes of `measuring`; its emission
    /// and motion are read from `described`.
    pub(super) fn measure(
        measuring: &Observer,
        described: &Observer,
        name: &str,
        effort: &Effort,
    ) -> Result<Panel, String> {
        let f = described.fixture;
        let source = blackbody_of(f, name)?;
        let obj = f.object(name)?;
        let (start, u) = crate::observer::uniform(&obj.motion)
            .ok_or_else(|| format!("{name} must move uniformly"))?;
        let lorentz = described.model.lorentz;
        let middle = body_point(start.t, start.x, u, DVec3::ZERO, lorentz);
        let mark = retarded(&middle, described.camera_t, described.camera_x()).map(|r| r.direction);
        let aim = measuring.aim(&[name], 0.3)?;
        let (pixels, dir) = panel_pixels(
            measuring,
            &variants(measuring.fixture),
            name,
            aim,
            effort.probe / 4,
        )?;
        Ok(Panel {
            pixels: [pixels[0], pixels[1], pixels[2], pixels[3]],
            source,
            expected: doppler_factor(u, -dir),
            slack: 0.0,
            mark,
        })
    }

    /// Measures the body point at `r` (object coordinates) of the object
    /// `name`, moving uniformly or through keyframes (a spinning object's
    /// points move differently): probes aimed where the point is seen.
    /// Expected: D = 1 / (gamma (1 - v.k)), v the point's own velocity at
    /// the emission event and gamma that of its speed when the object's
    /// clocks are Lorentzian (a V_obj under the Lorentz transform), else 1;
    /// 1 with infinitely fast light. The keyframes' velocity slack
    /// ([`BodyPath::velocity_slack`]) is carried into D by |dD/dv|.
    pub(super) fn at_point(
        measuring: &Observer,
        described: &Observer,
        name: &str,
        r: DVec3,
    ) -> Result<Panel, String> {
        let f = described.fixture;
        let source = blackbody_of(f, name)?;
        let model = described.model;
        let path = BodyPath::of(f, name, model)?;
        let camera = described.camera_x();
        let seen = path
            .seen(r, described.camera_t, camera, model)
            .ok_or_else(|| format!("the point {r} of {name:?} is never seen from the camera"))?;
        let v = path.velocity(r, seen.t).unwrap_or(DVec3::ZERO);
        let lorentzian = model.lorentz && f.object(name)?.kind == renderer::ObjectKind::VObj;
        let k = (camera - seen.x).normalize();
        let (expected, slope) = if model.light_speed == renderer::LightSpeed::Infinite {
            (1.0, 0.0)
        } else {
            point_factor(v, k, lorentzian)
        };
        let aim = (seen.x, POINT_PROBE_FOV);
        let (pixels, _) = panel_pixels(
            measuring,
            &variants(measuring.fixture),
            name,
            aim,
            POINT_PROBE,
        )?;
        Ok(Panel {
            pixels: [pixels[0], pixels[1], pixels[2], pixels[3]],
            source,
            expected,
            slack: slope * path.velocity_slack(r, &seen, camera),
            mark: Some(seen.direction),
        })
    }

    /// Measures a static object `name` seen by the fixture's accelerating
    /// camera (docs/physics.md, "The accelerated observer"): the object
    /// alone through the fixture's own camera at the view's time, one
    /// sample per pixel, read at the pixel nearest the centroid of its
    /// image (it and its eight neighbours must see it). Expected from the
    /// oracle's worldline at the view's proper time (on keyframes, the
    /// oracle's own cubic at the view's lab time): in the camera's frame
    /// the source moves with -v (v = tanh(phi) along the acceleration), so
    /// D = 1 / (gamma (1 - v.n)), n the pixel's line of sight in the
    /// camera's own frame (towards the source). The sample lies somewhere
    /// in the pixel: the tolerance adds the largest change of D from the
    /// pixel's centre to its corners and edge midpoints.
    pub(super) fn accelerating(
        measuring: &Observer,
        described: &Observer,
        name: &str,
        effort: &Effort,
    ) -> Result<Panel, String> {
        let f = described.fixture;
        let source = blackbody_of(f, name)?;
        let path =
            crate::observer::camera_path(&f.spec.camera).ok_or("the camera has no worldline")?;
        let obj = f.object(name)?;
        let at = obj.motion.uniform().ok_or("the object moves")?.0.x;
        let (_, v) = path
            .at(described.camera_t)
            .ok_or("the view is outside the camera's keyframes")?;
        let size = measuring.size(effort.probe);
        let (pixels, (x, y)) = spot_pixels(measuring, name, size)?;
        let pinhole = super::marker_angle::rest_pinhole(measuring, size)?;
        let factor = |dx: f64, dy: f64| {
            let n = pinhole.rest_direction(f64::from(x) + dx, f64::from(y) + dy);
            doppler_factor(-v, -n)
        };
        let expected = factor(0.5, 0.5);
        let slack = [0.0, 0.5, 1.0]
            .iter()
            .flat_map(|&dx| [0.0, 0.5, 1.0].map(|dy| (dx, dy)))
            .map(|(dx, dy)| (factor(dx, dy) - expected).abs())
            .fold(0.0, f64::max);
        Ok(Panel {
            pixels: [pixels[0], pixels[1], pixels[2], pixels[3]],
            source,
            expected,
            slack,
            mark: Some((at - described.camera_x()).normalize()),
        })
    }

    /// Measures a static object `name` in the field of the fixture's mass
    /// (`m` at `centre`): the gravitational redshift of its light climbing
    /// to the camera at rest (docs/physics.md, "Gravitational redshift").
    /// The object must lie on the line from the camera to the mass, its
    /// centre (the mean of its vertices) in front of the mass: light from
    /// there runs radially and is not bent, so a probe of [`POINT_PROBE`]
    /// pixels across [`POINT_PROBE_FOV`] aimed at that centre sees the
    /// object at its centre pixel. Expected: D = sqrt((1 - 2M/r) / (1 -
    /// 2M/r_o)), r_o the camera's radius and r the radius of the point
    /// seen, which lies somewhere on the object: D is taken at the middle
    /// of its range over the object's radii (from the least distance of
    /// the mass to the planes of its triangles, or to a sphere's surface,
    /// to the farthest vertex), and half that range is the slack added to
    /// every reading's tolerance.
    pub(super) fn in_field(
        measuring: &Observer,
        described: &Observer,
        name: &str,
        (m, centre): (f64, DVec3),
    ) -> Result<Panel, String> {
        let f = described.fixture;
        let source = blackbody_of(f, name)?;
        let obj = f.object(name)?;
        let at = match obj.motion.uniform() {
            Some((start, v)) if v == DVec3::ZERO => start.x,
            _ => {
                return Err(format!(
                    "{name:?} moves: in a mass's field only a static object's redshift is expected"
                ))
            }
        };
        let (middle, r_lo, r_hi) = radii(&obj.shape, at, centre);
        let camera = described.camera_x();
        let (to_mass, to_object) = (centre - camera, middle - camera);
        let radial = to_object.normalize().dot(to_mass.normalize()) > 1.0 - 1e-12;
        if !radial || to_object.length() >= to_mass.length() {
            return Err(format!(
                "{name:?} must be centred on the line from the camera to the mass, in front of it, \
                 so that its light runs radially (unbent) to the camera"
            ));
        }
        if r_lo <= 2.0 * m {
            return Err(format!("{name:?} reaches the horizon r = 2M"));
        }
        let r_o = (camera - centre).length();
        let (lo, hi) = (
            gr::static_redshift(m, r_lo, r_o),
            gr::static_redshift(m, r_hi, r_o),
        );
        let (pixels, _) = panel_pixels(
            measuring,
            &variants(measuring.fixture),
            name,
            (middle, POINT_PROBE_FOV),
            POINT_PROBE,
        )?;
        Ok(Panel {
            pixels: [pixels[0], pixels[1], pixels[2], pixels[3]],
            source,
            expected: 0.5 * (lo + hi),
            slack: 0.5 * (hi - lo).abs(),
            mark: Some(to_object.normalize()),
        })
    }

    /// The factor D read `from` the colour or a searchlight ratio, and the
    /// factor expected.
    /// A pixel with a channel at full scale (clipped) reads no factor: an
    /// error, never a wrong value.
    pub(super) fn read(&self, from: DopplerFrom) -> Result<(Reading, f64), String> {
        let [plain, rgb_lit, shifted, shifted_lit] = self.pixels;
        let used: &[DVec3] = match from {
            DopplerFrom::Colour => &[shifted],
            DopplerFrom::SearchlightShifted => &[shifted, shifted_lit],
            DopplerFrom::SearchlightRgb => &[plain, rgb_lit],
        };
        if used.iter().any(|c| c.max_element() >= 1.0) {
            return Err(format!(
                "the pixel read is saturated (a channel at 255: {:?}), so its colour and \
                 brightness are clipped; lower the emission's scale",
                used.iter()
                    .map(|c| (*c * 255.0).round().to_array())
                    .collect::<Vec<_>>()
            ));
        }
        let reading = match from {
            DopplerFrom::Colour => {
                let scan = ColourScan::new(&self.source, (0.3, 3.0));
                let from_colour = |rgb: DVec3| scan.factor(rgb);
                Reading {
                    value: from_colour(shifted).unwrap_or(f64::NAN),
                    tolerance: quantisation(shifted, from_colour),
                }
            }
            DopplerFrom::SearchlightShifted => searchlight_factor(shifted_lit, shifted, 5.0),
            DopplerFrom::SearchlightRgb => searchlight_factor(rgb_lit, plain, 4.0),
        };
        let reading = Reading {
            tolerance: reading.tolerance + self.slack,
            ..reading
        };
        Ok((reading, self.expected))
    }
}

/// The pixel nearest the centroid of the image's non-background pixels,
/// if it and its eight neighbours all see something.
fn inner_centroid(img: &RgbImage, bg: DVec3) -> Option<(u32, u32)> {
    let seen = |x: u32, y: u32| !crate::observer::is_background(measure::color(img, x, y), bg);
    let (mut sx, mut sy, mut n) = (0.0, 0.0, 0.0);
    for (x, y, _) in img.enumerate_pixels() {
        if seen(x, y) {
            (sx, sy, n) = (sx + f64::from(x), sy + f64::from(y), n + 1.0);
        }
    }
    if n == 0.0 {
        return None;
    }
    let (x, y) = ((sx / n).round() as u32, (sy / n).round() as u32);
    let inside = x >= 1 && y >= 1 && x + 1 < img.width() && y + 1 < img.height();
    let all = inside && (x - 1..=x + 1).all(|i| (y - 1..=y + 1).all(|j| seen(i, j)));
    all.then_some((x, y))
}

/// The lab centre of an object at rest at `at` (the mean of its vertices,
/// or a sphere's centre) and bounds on the distance of its surface from
/// `mass`: below, the least distance to its triangles' planes (or to the
/// sphere); above, the farthest vertex (or the sphere's far side).
fn radii(shape: &Shape, at: DVec3, mass: DVec3) -> (DVec3, f64, f64) {
    match shape {
        Shape::Sphere { radius } => {
            let d = (at - mass).length();
            (at, d - radius, d + radius)
        }
        Shape::Mesh(mesh) => {
            let lab = |v: DVec3| at + v;
            let n = mesh.vertices.len() as f64;
            let middle = mesh.vertices.iter().map(|v| lab(*v)).sum::<DVec3>() / n;
            let hi = mesh
                .vertices
                .iter()
                .map(|v| (lab(*v) - mass).length())
                .fold(0.0, f64::max);
            let lo = (0..mesh.triangles.len())
                .map(|t| {
                    let [a, b, c] = mesh.corners(t).map(lab);
                    let normal = (b - a).cross(c - a).normalize();
                    (mass - a).dot(normal).abs()
                })
                .fold(f64::INFINITY, f64::min);
            (middle, lo, hi)
        }
    }
}
