//! Edges measured to sub-pixel precision: an edge is located in every image
//! row by the area method ([`crate::measure::edge`]), mapped through the
//! camera onto a known plane, and fitted by a polynomial; values read off
//! the fit carry the fit's prediction error.

use crate::check::probe::{Effort, Probe};
use crate::check::row::Reading;
use crate::measure::{self, Pinhole, PolyFit, Scan};
use crate::observer::{background, is_background, Observer};
use glam::DVec3;
use image::RgbImage;

/// An edge traced down the image: for every row, the sub-pixel boundary
/// found by `find`, mapped onto `plane`, as (height coordinate, position
/// coordinate) pairs selected by `coords`, kept where the height lies in `range`.
pub(super) struct EdgeTrace {
    /// The (height, position) points of the edge on the plane.
    pub points: Vec<(f64, f64)>,
    /// Mean footprint of a pixel across the edge on the plane, l.units.
    pub footprint: f64,
}

/// Traces an edge down the image rows onto a plane (see [`EdgeTrace`]).
pub(super) fn trace_rows(
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

/// A probe render ready for tracing edges: the image, the measurements'
/// own model of its camera, and the fixture's background colour.
pub(super) struct ProbeImage {
    /// The probe image.
    pub img: RgbImage,
    /// The measurements' model of the probe camera.
    pub camera: Pinhole,
    bg: DVec3,
}

/// Where an edge lies and how it is fitted: the plane its points are
/// mapped onto, the (height, position) coordinates read off that plane,
/// the heights kept, and the degree of the polynomial fitted.
pub(super) struct OnPlane<C> {
    /// The plane the edge lies on.
    pub plane: measure::Plane,
    /// (height, position) of a point on the plane.
    pub coords: C,
    /// The heights kept, (low, high).
    pub range: (f64, f64),
    /// Degree of the fitted polynomial.
    pub degree: usize,
}

/// Where a row scan starts (a column) and which way it steps (+1 rightwards,
/// -1 leftwards).
#[derive(Clone, Copy, Debug)]
pub(super) struct Sweep {
    /// The first column looked at.
    pub from: i64,
    /// The step between columns.
    pub step: i64,
}

impl ProbeImage {
    /// Renders the probe `p` of `setup`.
    pub(super) fn render(setup: &Observer, p: &Probe) -> Result<ProbeImage, String> {
        let (img, camera) = setup.probe(p)?;
        Ok(ProbeImage {
            img,
            camera,
            bg: background(setup.fixture),
        })
    }

    /// A square probe at `effort` aimed at the objects `keep`, covering
    /// them with `margin` (fraction) to spare ([`Observer::aim`]).
    pub(super) fn aimed(
        setup: &Observer,
        keep: &[&str],
        margin: f64,
        effort: &Effort,
    ) -> Result<ProbeImage, String> {
        let (look_at, hfov_deg) = setup.aim(keep, margin)?;
        ProbeImage::render(
            setup,
            &Probe {
                keep,
                look_at,
                hfov_deg,
                size: (effort.probe, effort.probe),
                spp: effort.spp,
            },
        )
    }

    /// Rows scanned rightwards from the left border.
    pub(super) fn sweep_rightwards(&self) -> Sweep {
        Sweep { from: 0, step: 1 }
    }

    /// Rows scanned leftwards from the right border.
    pub(super) fn sweep_leftwards(&self) -> Sweep {
        Sweep {
            from: i64::from(self.img.width()) - 1,
            step: -1,
        }
    }

    /// Whether a colour is this probe's background.
    pub(super) fn background(&self) -> impl Fn(DVec3) -> bool {
        let bg = self.bg;
        move |c| is_background(c, bg)
    }

    /// Traces an edge down the rows: each row scanned along `sweep` up to
    /// where `inside` stops holding, onto the plane of `on`.
    pub(super) fn trace(
        &self,
        on: &OnPlane<impl Fn(DVec3) -> (f64, f64)>,
        sweep: Sweep,
        inside: impl Fn(DVec3) -> bool,
    ) -> EdgeTrace {
        trace_rows(
            &self.img,
            &self.camera,
            on.plane,
            |s| measure::edge(&self.img, s, sweep.from, sweep.step, &inside),
            &on.coords,
            on.range,
        )
    }

    /// Traces an edge (see [`ProbeImage::trace`]) and fits it.
    pub(super) fn fit(
        &self,
        on: &OnPlane<impl Fn(DVec3) -> (f64, f64)>,
        sweep: Sweep,
        inside: impl Fn(DVec3) -> bool,
        effort: &Effort,
    ) -> Result<Edge, String> {
        Edge::fit(&self.trace(on, sweep, inside), on.degree, effort)
    }
}

/// A fitted edge, able to read values and combinations of values off it
/// with their uncertainty: the fit's prediction error (3 sigma), with the
/// residual scatter floored at the area method's resolution (1/n pixel for
/// n x n strata, taken as a uniform error: /sqrt(12)), so that a perfectly
/// clean fit never claims more than the sampling can give.
pub(super) struct Edge {
    /// The robust polynomial fit of position against height.
    pub fit: PolyFit,
    floor_scale: f64,
}

impl Edge {
    /// Fits a polynomial of `degree` to the traced edge.
    pub(super) fn fit(trace: &EdgeTrace, degree: usize, effort: &Effort) -> Result<Edge, String> {
        let fit = PolyFit::fit_robust(&trace.points, degree)
            .ok_or_else(|| format!("too few edge points ({})", trace.points.len()))?;
        let floor = trace.footprint / effort.strata() / 12f64.sqrt();
        let floor_scale = fit.sigma.max(floor) / fit.sigma.max(1e-300);
        Ok(Edge { fit, floor_scale })
    }

    /// The value sum w_i f(x_i) of weighted readings.
    pub(super) fn combine(&self, terms: &[(f64, f64)]) -> Reading {
        let value = terms.iter().map(|&(w, x)| w * self.fit.eval(x)).sum();
        Reading {
            value,
            tolerance: 3.0 * self.fit.stderr_of(terms) * self.floor_scale,
        }
    }

    /// The edge's position at height `x`.
    pub(super) fn at(&self, x: f64) -> Reading {
        self.combine(&[(1.0, x)])
    }
}
