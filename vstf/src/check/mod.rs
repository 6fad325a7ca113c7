//! The VSTF checks: each fixture is rendered, measured from its images, and
//! compared with first-principles expectations ([`crate::oracle`]).
//!
//! Measurements are made on *probe* renders: the fixture's scene from the
//! fixture's camera event, with only the measured objects kept (so that edges
//! stand against the flat background) and the view turned and narrowed onto
//! the measured feature (so that a pixel is small). A probe changes neither
//! the camera event nor any worldline, so it sees exactly the events the full
//! view sees; the full view is rendered for the report.

use crate::fixture::{Fixture, Overrides, View};
use crate::golden::{Comparison, Store};
use crate::measure::{self, Kinematics, Pinhole, PolyFit, Scan};
use glam::DVec3;
use image::RgbImage;
use rayon::prelude::*;
use renderer::{Attitude, Camera, Database, Event, LightSpeed, Model, Traversal};
use serde::Serialize;

/// One checked quantity.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Row {
    pub fixture: String,
    pub quantity: String,
    pub measured: f64,
    pub expected: f64,
    /// The paper's printed figure, where it gives one.
    pub paper: Option<f64>,
    pub tolerance: f64,
    pub unit: String,
    pub pass: bool,
}

impl Row {
    pub fn new(
        fixture: &str,
        quantity: &str,
        measured: f64,
        expected: f64,
        paper: Option<f64>,
        tolerance: f64,
        unit: &str,
    ) -> Row {
        let pass = measured.is_finite() && (measured - expected).abs() <= tolerance;
        Row {
            fixture: fixture.into(),
            quantity: quantity.into(),
            measured,
            expected,
            paper,
            tolerance,
            unit: unit.into(),
            pass,
        }
    }

    /// Whether the paper's figure lies outside the tolerance around the
    /// first-principles value (explained in docs/physics.md).
    pub fn paper_disagrees(&self) -> bool {
        self.paper
            .is_some_and(|p| (p - self.expected).abs() > self.tolerance)
    }
}

/// A rendered view of a fixture for the report, with the expected points
/// (from the oracle) to mark on a copy of it.
pub struct ViewReport {
    pub name: String,
    pub image: RgbImage,
    pub markers: Vec<(f64, f64)>,
}

/// All results for one fixture.
pub struct FixtureReport {
    pub fixture: String,
    pub description: String,
    pub views: Vec<ViewReport>,
    pub rows: Vec<Row>,
    /// Each view against its golden image (filled in by [`run`]).
    pub goldens: Vec<Comparison>,
}

impl FixtureReport {
    pub fn new(
        fixture: &str,
        description: &str,
        views: Vec<ViewReport>,
        rows: Vec<Row>,
    ) -> FixtureReport {
        FixtureReport {
            fixture: fixture.into(),
            description: description.into(),
            views,
            rows,
            goldens: Vec::new(),
        }
    }

    pub fn passed(&self) -> bool {
        self.rows.iter().all(|r| r.pass) && self.goldens.iter().all(|g| g.pass)
    }
}

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
    pub const FULL: Effort = Effort { probe: 400, spp: 9 };
    pub const QUICK: Effort = Effort { probe: 200, spp: 9 };

    /// Strata per side.
    pub fn strata(&self) -> f64 {
        f64::from(self.spp).sqrt().floor()
    }
}

/// A fixture with a model and camera time chosen.
pub struct Setup<'a> {
    pub fixture: &'a Fixture,
    pub model: Model,
    pub camera_t: f64,
}

impl Setup<'_> {
    /// The camera position.
    pub fn camera_x(&self) -> DVec3 {
        self.fixture.spec.camera.position
    }

    /// The image size at `width` with the fixture's aspect ratio.
    fn size(&self, width: u32) -> (u32, u32) {
        let im = &self.fixture.spec.image;
        let height =
            ((f64::from(width) * f64::from(im.height) / f64::from(im.width)).round() as u32).max(1);
        (width, height)
    }

    /// How this setup's model turns a moving camera's lines of sight.
    fn kinematics(&self) -> Kinematics {
        Kinematics::of(
            self.model.light_speed == LightSpeed::Finite,
            self.model.lorentz,
        )
    }

    /// The measurements' model of the fixture's camera at `width` x
    /// `height`, built from the camera description as the fixture's view is.
    pub fn pinhole(&self, (width, height): (u32, u32)) -> Result<Pinhole, String> {
        let c = &self.fixture.spec.camera;
        let still = match (c.look_at, c.yaw_deg, c.pitch_deg) {
            (Some(look_at), _, _) => {
                Pinhole::looking_at(c.position, look_at, c.up, c.vfov_deg, (width, height))
            }
            (None, yaw, pitch) => Pinhole::yaw_pitch(
                c.position,
                (yaw.unwrap_or(0.0), pitch.unwrap_or(0.0)),
                c.vfov_deg,
                (width, height),
            ),
        };
        still
            .and_then(|p| p.moving(c.velocity.unwrap_or(DVec3::ZERO), self.kinematics()))
            .ok_or_else(|| format!("{}: degenerate camera", self.fixture.name))
    }

    fn view(&self, width: u32) -> Result<View, String> {
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
        crate::run::view(self.fixture, &o)
    }

    /// The full view at [`VIEW_WIDTH`], with `markers` at the pixels of
    /// the given lab directions.
    pub fn full_view(&self, name: &str, directions: &[DVec3]) -> Result<ViewReport, String> {
        let view = self.view(VIEW_WIDTH)?;
        let image = crate::run::render(self.fixture, &view, Traversal::Bvh)?.to_rgb8();
        let pinhole = self.pinhole(self.size(VIEW_WIDTH))?;
        let markers = directions
            .iter()
            .filter_map(|d| pinhole.pixel_of(*d))
            .collect();
        Ok(ViewReport {
            name: name.into(),
            image,
            markers,
        })
    }

    /// Renders only the objects named in `keep`, looking towards
    /// `look_at` (a direction in the camera's frame, from its position) with
    /// horizontal field of view `hfov_deg`, at `width` x `height`. The probe
    /// camera moves as the fixture's does. Returns the image and the
    /// measurements' own model of the probe camera, built from the same
    /// parameters.
    pub fn probe(
        &self,
        keep: &[&str],
        look_at: DVec3,
        hfov_deg: f64,
        width: u32,
        height: u32,
        spp: u32,
    ) -> Result<(RgbImage, Pinhole), String> {
        let mut scene = self.fixture.scene.clone();
        scene.objects.retain(|o| keep.contains(&o.name.as_str()));
        if scene.objects.len() != keep.len() {
            return Err(format!(
                "{}: probe needs objects {keep:?}",
                self.fixture.file.display()
            ));
        }
        let db = Database::build(&scene, self.model.lorentz)
            .map_err(|e| format!("{}: {e}", self.fixture.file.display()))?;
        let aspect = f64::from(width) / f64::from(height);
        let vfov_deg = 2.0
            * ((hfov_deg.to_radians() / 2.0).tan() / aspect)
                .atan()
                .to_degrees();
        let velocity = self.fixture.spec.camera.velocity.unwrap_or(DVec3::ZERO);
        let camera = Camera::new(
            Event::new(self.camera_t, self.camera_x()),
            Attitude::LookAt {
                look_at,
                up: DVec3::Y,
            },
            vfov_deg,
            width,
            height,
        )
        .ok_or("degenerate probe camera")?
        .moving(velocity, self.model)
        .ok_or("the camera moves at or above light speed")?;
        let pinhole = Pinhole::looking_at(
            self.camera_x(),
            look_at,
            DVec3::Y,
            vfov_deg,
            (width, height),
        )
        .and_then(|p| p.moving(velocity, self.kinematics()))
        .ok_or("degenerate probe camera")?;
        let settings = renderer::RenderSettings {
            spp,
            shutter: 0.0,
            seed: 1,
            max_depth: 0,
            shadows: false,
            effects: renderer::Effects {
                doppler: self.fixture.spec.image.doppler,
                searchlight: self.fixture.spec.image.searchlight,
            },
        };
        let img = renderer::render(&db, &scene, &camera, self.camera_t, self.model, &settings);
        Ok((img.to_rgb8(), pinhole))
    }

    /// Aims a probe at the kept objects: a coarse wide render finds their
    /// bounding box in the image; returns the look-at point (one l.unit
    /// along the central line of sight) and a field of view covering the box
    /// with `margin` (fraction) to spare.
    pub fn aim(&self, keep: &[&str], margin: f64) -> Result<(DVec3, f64), String> {
        let wide = self.fixture.spec.camera.vfov_deg.max(30.0);
        let look = self
            .fixture
            .spec
            .camera
            .look_at
            .unwrap_or(self.camera_x() + DVec3::NEG_Z);
        let (img, cam) = self.probe(keep, look, wide, 240, 240, 1)?;
        let bg = measure::color(&img, 0, 0);
        let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
        for (x, y, _) in img.enumerate_pixels() {
            if !is_background(measure::color(&img, x, y), bg) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
        if x0 > x1 {
            return Err(format!("{}: {keep:?} not in view", self.fixture.name));
        }
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
}

/// Whether a colour is the (flat) background of a probe.
pub fn is_background(c: DVec3, bg: DVec3) -> bool {
    (c - bg).abs().max_element() < 12.0 / 255.0
}

/// An edge traced down the image: for every row, the sub-pixel boundary
/// found by `find`, mapped onto `plane`, as (height coordinate, position
/// coordinate) pairs selected by `coords`, kept where the height lies in `range`.
pub struct EdgeTrace {
    pub points: Vec<(f64, f64)>,
    /// Mean footprint of a pixel across the edge on the plane, l.units.
    pub footprint: f64,
}

/// Traces an edge down `img` (see [`EdgeTrace`]), back-projecting through `camera`.
pub fn trace_rows(
    img: &RgbImage,
    camera: &Pinhole,
    plane: measure::Plane,
    find: impl Fn(Scan) -> Option<f64>,
    coords: impl Fn(DVec3) -> (f64, f64),
    range: (f64, f64),
) -> EdgeTrace {
    let mut points = Vec::new();
    let mut fp = Vec::new();
    for y in 0..img.height() {
        let scan = Scan {
            horizontal: true,
            at: y,
        };
        let Some(u) = find(scan) else { continue };
        let (px, py) = scan.point(u);
        let Some(p) = camera.on_plane(px, py, plane) else {
            continue;
        };
        let (h, x) = coords(p);
        if h >= range.0 && h <= range.1 {
            points.push((h, x));
            if let Some(f) = camera.footprint(px, py, true, plane) {
                fp.push(f);
            }
        }
    }
    let footprint = if fp.is_empty() {
        f64::NAN
    } else {
        fp.iter().sum::<f64>() / fp.len() as f64
    };
    EdgeTrace { points, footprint }
}

/// A value read off a fitted edge, with its 3-sigma uncertainty.
pub struct Reading {
    pub value: f64,
    pub tolerance: f64,
}

/// A fitted edge, able to read values and combinations of values off it
/// with their uncertainty: the fit's prediction error (3 sigma), with the
/// residual scatter floored at the area method's resolution (1/n pixel for
/// n x n strata, taken as a uniform error: /sqrt(12)), so that a perfectly
/// clean fit never claims more than the sampling can give.
pub struct Edge {
    pub fit: PolyFit,
    floor_scale: f64,
}

impl Edge {
    pub fn fit(trace: &EdgeTrace, degree: usize, effort: &Effort) -> Result<Edge, String> {
        let fit = PolyFit::fit_robust(&trace.points, degree)
            .ok_or_else(|| format!("too few edge points ({})", trace.points.len()))?;
        let floor = trace.footprint / effort.strata() / 12f64.sqrt();
        let floor_scale = fit.sigma.max(floor) / fit.sigma.max(1e-300);
        Ok(Edge { fit, floor_scale })
    }

    /// The value sum w_i f(x_i) of weighted readings.
    pub fn combine(&self, terms: &[(f64, f64)]) -> Reading {
        let value = terms.iter().map(|&(w, x)| w * self.fit.eval(x)).sum();
        Reading {
            value,
            tolerance: 3.0 * self.fit.stderr_of(terms) * self.floor_scale,
        }
    }

    pub fn at(&self, x: f64) -> Reading {
        self.combine(&[(1.0, x)])
    }
}

/// Two independent readings combined as a - b.
pub fn difference(a: &Reading, b: &Reading) -> Reading {
    Reading {
        value: a.value - b.value,
        tolerance: a.tolerance.hypot(b.tolerance),
    }
}

pub mod aberration;
pub mod accelerated;
pub mod blink;
pub mod doppler;
pub mod relativity;
pub mod retarded;
pub mod sphere;
pub mod stage;
pub mod teaser;
pub mod terrell;

/// The start event, lab velocity and whether it is Lorentz-contracted under
/// `model`, of the object named `name`, read from the fixture.
pub fn motion_of(
    fixture: &Fixture,
    name: &str,
    model: Model,
) -> Result<(Event, DVec3, bool), String> {
    let obj = fixture
        .scene
        .objects
        .iter()
        .find(|o| o.name == name)
        .ok_or_else(|| format!("{}: no object {name:?}", fixture.file.display()))?;
    let lorentz = model.lorentz && obj.kind == renderer::ObjectKind::VObj;
    let (start, velocity) = obj.motion.uniform().ok_or_else(|| {
        format!(
            "{}: object {name:?} does not move uniformly",
            fixture.file.display()
        )
    })?;
    Ok((start, velocity, lorentz))
}

/// The background colour of probes, as stored in 8 bits.
pub fn background(fixture: &Fixture) -> DVec3 {
    (fixture.scene.background.clamp(DVec3::ZERO, DVec3::ONE) * 255.0).round() / 255.0
}

/// A check: renders, measures and compares one fixture.
pub type Check = fn(&Effort) -> Result<FixtureReport, String>;

/// Every check, by fixture name, in report order.
pub const CHECKS: &[(&str, Check)] = &[
    ("stage", stage::run),
    ("flange", retarded::run),
    ("terrell-decoupled", terrell::decoupled),
    ("terrell-contracted", terrell::contracted),
    ("aberration", aberration::run),
    ("teaser", teaser::run),
    ("blink", blink::run),
    ("relativity", relativity::run),
    ("sphere-relativistic", sphere::relativistic),
    ("sphere-classical", sphere::classical),
    ("accelerated", accelerated::run),
    ("doppler", doppler::run),
];

/// Runs the checks of the named fixtures (all when empty), comparing
/// every view with its golden image in `store`.
pub fn run(names: &[String], effort: &Effort, store: &Store) -> Result<Vec<FixtureReport>, String> {
    for n in names {
        if !CHECKS.iter().any(|(c, _)| c == n) {
            let known: Vec<&str> = CHECKS.iter().map(|(c, _)| *c).collect();
            return Err(format!(
                "no check for fixture {n:?}; checked fixtures: {}",
                known.join(", ")
            ));
        }
    }
    let chosen: Vec<&(&str, Check)> = CHECKS
        .iter()
        .filter(|(c, _)| names.is_empty() || names.iter().any(|n| n == c))
        .collect();
    // The checks run concurrently (each renders in parallel too, so their
    // serial parts overlap); results come back in the table's order.
    chosen
        .par_iter()
        .map(|(name, check)| {
            let mut report = check(effort)?;
            let fuzzy = Fixture::load(name).map_err(|e| e.to_string())?.spec.fuzzy;
            for v in &report.views {
                report
                    .goldens
                    .push(store.check(&report.fixture, &v.name, &v.image, fuzzy)?);
            }
            Ok(report)
        })
        .collect()
}
