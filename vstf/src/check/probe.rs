//! How a check looks at its fixture: probe renders of the measured objects
//! and full views for the report.
//!
//! Measurements are made on *probe* renders: the fixture's scene from the
//! fixture's camera event, with only the measured objects kept (so that edges
//! stand against the flat background) and the view turned and narrowed onto
//! the measured feature (so that a pixel is small). A probe changes neither
//! the camera event nor any worldline, so it sees exactly the events the full
//! view sees; the full view is rendered for the report.

use crate::check::findings::ViewReport;
use crate::fixture::solve::line_of_sight;
use crate::fixture::{Overrides, View};
use crate::measure::{self, Pinhole};
use crate::observer::{is_background, Observer};
use crate::run::LazyImage;
use glam::DVec3;
use image::RgbImage;
use renderer::Traversal;
use std::sync::Arc;

/// A box of pixels: first column, first row, last column, last row.
type PixelBox = (u32, u32, u32, u32);

/// Width of the full views: the report's images and the golden images,
/// the same at every effort so that `cargo test` and `vstf check` compare
/// the same pictures.
pub const VIEW_WIDTH: u32 = 240;

/// How hard to look: probe size and samples per pixel. The default is the
/// main job's; tests use a smaller one.
#[derive(Clone, Copy, Debug)]
pub struct Effort {
    /// Probe image side, pixels.
    pub probe: u32,
    /// Samples per probe pixel (a square number: n x n strata).
    pub spp: u32,
}

impl Effort {
    /// The effort of `vstf check`: 400-pixel probes, 3 x 3 strata.
    pub const FULL: Effort = Effort { probe: 400, spp: 9 };
    /// The effort of the tests: 200-pixel probes, 3 x 3 strata.
    pub const QUICK: Effort = Effort { probe: 200, spp: 9 };

    /// Strata per side.
    pub fn strata(&self) -> f64 {
        f64::from(self.spp).sqrt().floor()
    }
}

/// A probe render's parameters: which objects it keeps, where it looks
/// (a point seen from the camera's position, in the camera's frame), its
/// horizontal field of view, image size and samples per pixel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Probe<'k> {
    /// The names of the objects rendered; every other object is removed.
    pub keep: &'k [&'k str],
    /// The point looked at.
    pub look_at: DVec3,
    /// Horizontal field of view, degrees.
    pub hfov_deg: f64,
    /// Image size (width, height), pixels.
    pub size: (u32, u32),
    /// Samples per pixel.
    pub spp: u32,
}

/// The renders a check makes as an [`Observer`]: full views for the
/// report and golden images, probes aimed at the measured objects.
impl Observer<'_> {
    /// The view rendered for the report and the golden image at `width`.
    pub(crate) fn report_view(&self, width: u32) -> Result<View, String> {
        let (width, height) = self.size(width);
        let o = Overrides {
            model: Some(self.model),
            camera_t: Some(self.camera_t),
            width: Some(width),
            height: Some(height),
            spp: None,
            doppler: false,
            searchlight: false,
        };
        Ok(crate::run::view(self.fixture, &o)?)
    }

    /// The full view at [`VIEW_WIDTH`], with `markers` at the pixels of
    /// the given lab directions.
    pub(crate) fn full_view(&self, name: &str, directions: &[DVec3]) -> Result<ViewReport, String> {
        let unlabelled: Vec<(DVec3, String)> =
            directions.iter().map(|d| (*d, String::new())).collect();
        self.full_view_labelled(name, &unlabelled)
    }

    /// [`Observer::full_view`] with each marker's row named (empty: none).
    pub(crate) fn full_view_labelled(
        &self,
        name: &str,
        marks: &[(DVec3, String)],
    ) -> Result<ViewReport, String> {
        let view = self.report_view(VIEW_WIDTH)?;
        let image = crate::output::rgb8(&*crate::run::render_shared(
            self.fixture,
            &view,
            Traversal::Bvh,
        )?);
        let pinhole = self.pinhole(self.size(VIEW_WIDTH))?;
        let (markers, rows) = marks
            .iter()
            .filter_map(|(d, row)| pinhole.pixel_of(*d).map(|p| (p, row.clone())))
            .unzip();
        Ok(ViewReport {
            name: name.into(),
            image,
            markers,
            rows,
            measured: Vec::new(),
        })
    }

    /// Renders the probe `p`: only its kept objects, looking its way. The
    /// probe camera moves as the fixture's does. Returns the image and the
    /// measurements' own model of the probe camera, built from the same
    /// parameters.
    pub(crate) fn probe(&self, p: &Probe) -> Result<(RgbImage, Pinhole), String> {
        let (probe, view, pinhole) = self.probe_view(p)?;
        let img = crate::run::render_shared(&probe, &view, Traversal::Bvh)?;
        Ok((crate::output::rgb8(&img), pinhole))
    }

    /// [`Observer::probe`] rendered as it is read ([`LazyImage`]).
    pub(crate) fn probe_lazy(&self, p: &Probe) -> Result<(Arc<LazyImage>, Pinhole), String> {
        let (probe, view, pinhole) = self.probe_view(p)?;
        Ok((crate::run::render_lazy(&probe, &view)?, pinhole))
    }

    /// The probe `p`'s fixture (its kept objects), its view, and the
    /// measurements' model of its camera.
    fn probe_view(&self, p: &Probe) -> Result<(crate::fixture::Fixture, View, Pinhole), String> {
        let (look_at, hfov_deg, (width, height)) = (p.look_at, p.hfov_deg, p.size);
        let aspect = f64::from(width) / f64::from(height);
        // libm: a probe renders the same pixels on every platform.
        let vfov_deg =
            2.0 * libm::atan(libm::tan(hfov_deg.to_radians() / 2.0) / aspect).to_degrees();
        let mut probe = self.fixture.only(p.keep).map_err(|e| e.to_string())?;
        let (camera, image) = (&mut probe.spec.camera, &mut probe.spec.image);
        (camera.t, camera.position) = (self.camera_t, self.camera_x());
        (camera.look_at, camera.up, camera.vfov_deg) = (Some(look_at), DVec3::Y, vfov_deg);
        (camera.yaw_deg, camera.pitch_deg) = (None, None);
        (image.shutter, image.seed, image.max_depth, image.shadows) = (0.0, 1, 0, false);
        let velocity = camera.velocity.unwrap_or(DVec3::ZERO);
        let view = crate::run::view(
            &probe,
            &Overrides {
                model: Some(self.model),
                width: Some(width),
                height: Some(height),
                spp: Some(p.spp),
                ..Overrides::default()
            },
        )?;
        let pinhole = Pinhole::looking_at(
            self.camera_x(),
            look_at,
            DVec3::Y,
            vfov_deg,
            (width, height),
        )
        .and_then(|p| p.moving(velocity, self.kinematics()))
        .ok_or("degenerate probe camera")?;
        Ok((probe, view, pinhole))
    }

    /// Renders only the objects `keep` through the fixture's own camera
    /// at `size` and `spp` (the view's measuring image), with the
    /// measurements' own model of that camera.
    pub(crate) fn measuring_render(
        &self,
        keep: &[&str],
        size: (u32, u32),
        spp: u32,
    ) -> Result<(RgbImage, Pinhole), String> {
        self.measuring_render_bouncing(keep, size, spp, 0)
    }

    /// [`Observer::measuring_render`] following `max_depth` mirror bounces.
    pub(crate) fn measuring_render_bouncing(
        &self,
        keep: &[&str],
        (width, height): (u32, u32),
        spp: u32,
        max_depth: u32,
    ) -> Result<(RgbImage, Pinhole), String> {
        let probe = self.fixture.only(keep).map_err(|e| e.to_string())?;
        self.probe_render(probe, (width, height), (spp, max_depth), None)
    }

    /// The pixels of `window` of [`Observer::measuring_render_bouncing`],
    /// the same to the bit, in an image of the window's size (its pixel
    /// (i, j) is the whole image's (x + i, y + j)); the pinhole is the
    /// whole image's. Nothing else is rendered.
    pub(crate) fn measuring_window(
        &self,
        keep: &[&str],
        size: (u32, u32),
        (spp, max_depth): (u32, u32),
        window: renderer::Window,
    ) -> Result<(RgbImage, Pinhole), String> {
        let probe = self.fixture.only(keep).map_err(|e| e.to_string())?;
        self.probe_render(probe, size, (spp, max_depth), Some(window))
    }

    /// [`Observer::measuring_render`] of the fixture's sky alone: no
    /// object, the sky kept.
    pub(crate) fn sky_render(&self, size: (u32, u32)) -> Result<(RgbImage, Pinhole), String> {
        let mut probe = self.fixture.only(&[]).map_err(|e| e.to_string())?;
        probe.spec.sky.clone_from(&self.fixture.spec.sky);
        probe.scene.sky.clone_from(&self.fixture.scene.sky);
        self.probe_render(probe, size, (1, 0), None)
    }

    /// `probe` rendered through the camera at this observer's time, model
    /// and size, without shutter time or shadows (only `window` of it, if
    /// given).
    fn probe_render(
        &self,
        mut probe: crate::fixture::Fixture,
        size: (u32, u32),
        (spp, max_depth): (u32, u32),
        window: Option<renderer::Window>,
    ) -> Result<(RgbImage, Pinhole), String> {
        let view = View {
            window,
            ..self.measuring_view(&mut probe, size, (spp, max_depth))?
        };
        let img = crate::run::render_shared(&probe, &view, Traversal::Bvh)?;
        Ok((crate::output::rgb8(&img), self.pinhole(size)?))
    }

    /// [`Observer::measuring_render`], rendered as it is read ([`LazyImage`]).
    pub(crate) fn measuring_lazy(
        &self,
        keep: &[&str],
        size: (u32, u32),
        spp: u32,
    ) -> Result<(Arc<LazyImage>, Pinhole), String> {
        let mut probe = self.fixture.only(keep).map_err(|e| e.to_string())?;
        let view = self.measuring_view(&mut probe, size, (spp, 0))?;
        Ok((crate::run::render_lazy(&probe, &view)?, self.pinhole(size)?))
    }

    /// The view of `probe` through the camera at this observer's time,
    /// model and size, without shutter time or shadows (which it takes off
    /// `probe`).
    fn measuring_view(
        &self,
        probe: &mut crate::fixture::Fixture,
        (width, height): (u32, u32),
        (spp, max_depth): (u32, u32),
    ) -> Result<View, String> {
        let image = &mut probe.spec.image;
        (image.shutter, image.seed, image.max_depth, image.shadows) = (0.0, 1, max_depth, false);
        let overrides = Overrides {
            model: Some(self.model),
            camera_t: Some(self.camera_t),
            width: Some(width),
            height: Some(height),
            spp: Some(spp),
            ..Overrides::default()
        };
        Ok(crate::run::view(probe, &overrides)?)
    }

    /// Aims a probe at the kept objects: a coarse wide render finds their
    /// bounding box in the image; returns the look-at point (one l.unit
    /// along the central line of sight) and a field of view covering the box
    /// with `margin` (fraction) to spare.
    pub(crate) fn aim(&self, keep: &[&str], margin: f64) -> Result<(DVec3, f64), String> {
        let camera = &self.fixture.spec.camera;
        let wide = camera.vfov_deg.max(30.0);
        let look = camera.look_at.unwrap_or(self.camera_x() + DVec3::NEG_Z);
        let found = self.find(keep, look, wide)?;
        // An object at the image's side may lie outside that square probe:
        // look again over the whole image, along the camera's own line of sight.
        let ((x0, y0, x1, y1), cam) = match found {
            (Some(b), cam) => (b, cam),
            (None, _) => match self.find(
                keep,
                self.camera_x() + line_of_sight(&self.fixture.spec.camera),
                self.whole_image_fov(),
            )? {
                (Some(b), cam) => (b, cam),
                (None, _) => {
                    return Err(format!(
                        "{}: {keep:?} not in view (no part of it is in the image)",
                        self.fixture.name
                    ))
                }
            },
        };
        let (cx, cy) = (
            (f64::from(x0) + f64::from(x1) + 1.0) / 2.0,
            (f64::from(y0) + f64::from(y1) + 1.0) / 2.0,
        );
        let centre = cam.direction(cx, cy);
        let corners = [(x0, y0), (x1 + 1, y0), (x0, y1 + 1), (x1 + 1, y1 + 1)];
        let half = corners
            .iter()
            .map(|&(x, y)| {
                cam.direction(f64::from(x), f64::from(y))
                    .angle_between(centre)
            })
            .fold(0.0, f64::max);
        Ok((
            self.camera_x() + centre,
            (2.0 * half.to_degrees() * (1.0 + margin)).min(170.0),
        ))
    }

    /// A square probe of `keep` looking at `look` across `hfov_deg`: the
    /// box of its pixels that are not background (none if all are), and
    /// the probe's camera.
    fn find(
        &self,
        keep: &[&str],
        look: DVec3,
        hfov_deg: f64,
    ) -> Result<(Option<PixelBox>, Pinhole), String> {
        let (img, cam) = self.probe(&Probe {
            keep,
            look_at: look,
            hfov_deg,
            size: (240, 240),
            spp: 1,
        })?;
        let bg = measure::color(&img, 0, 0);
        let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
        for (x, y, _) in img.enumerate_pixels() {
            if !is_background(measure::color(&img, x, y), bg) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
        Ok(((x0 <= x1).then_some((x0, y0, x1, y1)), cam))
    }

    /// The field of view (degrees) of a square probe that holds the
    /// fixture's whole image: its wider side, with 10 % to spare.
    fn whole_image_fov(&self) -> f64 {
        let (camera, image) = (&self.fixture.spec.camera, &self.fixture.spec.image);
        let aspect = f64::from(image.width) / f64::from(image.height);
        // libm: a probe renders the same pixels on every platform.
        let half = libm::tan(camera.vfov_deg.to_radians() / 2.0) * aspect.max(1.0);
        (2.0 * libm::atan(half).to_degrees() * 1.1).min(170.0)
    }
}
