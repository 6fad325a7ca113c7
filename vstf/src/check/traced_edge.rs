//! Edges measured to sub-pixel precision: an edge is located in every image
//! row by the area method ([`crate::measure::edge`]), mapped through the
//! camera onto a known plane, and fitted by a polynomial; values read off
//! the fit carry the fit's prediction error.

use crate::check::probe::{Effort, Probe};
use crate::check::row::Reading;
use crate::measure::{self, Pinhole, Pixels, PolyFit, Scan};
use crate::observer::{background, is_background, Observer};
use crate::run::LazyImage;
use glam::DVec3;
use image::RgbImage;
use std::sync::Arc;

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
    img: &(impl Pixels + ?Sized),
    camera: &Pinhole,
    plane: measure::Plane,
    find: impl Fn(Scan) -> Option<f64>,
    coords: impl Fn(DVec3) -> (f64, f64),
    range: (f64, f64),
) -> EdgeTrace {
    let mut points = Vec::new();
    let mut fp = Vec::new();
    for y in 0..img.dimensions().1 {
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

/// A probe render ready for tracing edges: the image (whole, or rendered
/// as it is read), the measurements' own model of its camera, and the
/// fixture's background colour.
pub(super) struct ProbeImage<I = RgbImage> {
    /// The probe image.
    pub img: I,
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

/// Whole probes: what the lazy ones are tested against.
#[cfg(test)]
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
    /// them with `margin` (fraction) to spare ([`Observer::aim`]), whole.
    pub(super) fn aimed(
        setup: &Observer,
        keep: &[&str],
        margin: f64,
        effort: &Effort,
    ) -> Result<ProbeImage, String> {
        ProbeImage::render(setup, &aimed(setup, keep, margin, effort)?)
    }
}

impl ProbeImage<Arc<LazyImage>> {
    /// A square probe at `effort` aimed at the objects `keep`, covering
    /// them with `margin` (fraction) to spare ([`Observer::aim`]), rendered
    /// as it is read: for edges traced from the side
    /// ([`ProbeImage::fit`]) and outlines, which never read the objects'
    /// insides.
    pub(super) fn aimed_lazy(
        setup: &Observer,
        keep: &[&str],
        margin: f64,
        effort: &Effort,
    ) -> Result<ProbeImage<Arc<LazyImage>>, String> {
        ProbeImage::render_lazy(setup, &aimed(setup, keep, margin, effort)?)
    }

    /// Renders the probe `p` of `setup` as it is read.
    pub(super) fn render_lazy(
        setup: &Observer,
        p: &Probe,
    ) -> Result<ProbeImage<Arc<LazyImage>>, String> {
        let (img, camera) = setup.probe_lazy(p)?;
        Ok(ProbeImage {
            img,
            camera,
            bg: background(setup.fixture),
        })
    }
}

impl Pixels for LazyImage {
    fn dimensions(&self) -> (u32, u32) {
        LazyImage::dimensions(self)
    }

    fn color(&self, x: u32, y: u32) -> DVec3 {
        measure::color_of(self.pixel(x, y))
    }

    fn failure(&self) -> Option<String> {
        LazyImage::failure(self)
    }
}

/// A square probe at `effort` aimed at the objects `keep`, covering them
/// with `margin` (fraction) to spare ([`Observer::aim`]).
fn aimed<'k>(
    setup: &Observer,
    keep: &'k [&'k str],
    margin: f64,
    effort: &Effort,
) -> Result<Probe<'k>, String> {
    let (look_at, hfov_deg) = setup.aim(keep, margin)?;
    Ok(Probe {
        keep,
        look_at,
        hfov_deg,
        size: (effort.probe, effort.probe),
        spp: effort.spp,
    })
}

impl<I: Pixels> ProbeImage<I> {
    /// Rows scanned rightwards from the left border.
    pub(super) fn sweep_rightwards(&self) -> Sweep {
        Sweep { from: 0, step: 1 }
    }

    /// Rows scanned leftwards from the right border.
    pub(super) fn sweep_leftwards(&self) -> Sweep {
        Sweep {
            from: i64::from(self.img.dimensions().0) - 1,
            step: -1,
        }
    }

    /// Whether a colour is this probe's background.
    pub(super) fn background(&self) -> impl Fn(DVec3) -> bool {
        let bg = self.bg;
        move |c| is_background(c, bg)
    }

    /// Traces an edge down the rows: each row scanned along `sweep` up to
    /// where `inside` stops holding, onto the plane of `on`; an error if a
    /// pixel read could not be rendered ([`Pixels::failure`]).
    pub(super) fn trace(
        &self,
        on: &OnPlane<impl Fn(DVec3) -> (f64, f64)>,
        sweep: Sweep,
        inside: impl Fn(DVec3) -> bool,
    ) -> Result<EdgeTrace, String> {
        let trace = trace_rows(
            &self.img,
            &self.camera,
            on.plane,
            |s| measure::edge(&self.img, s, sweep.from, sweep.step, &inside),
            &on.coords,
            on.range,
        );
        match self.img.failure() {
            Some(failure) => Err(failure),
            None => Ok(trace),
        }
    }

    /// Traces an edge (see [`ProbeImage::trace`]) and fits it.
    pub(super) fn fit(
        &self,
        on: &OnPlane<impl Fn(DVec3) -> (f64, f64)>,
        sweep: Sweep,
        inside: impl Fn(DVec3) -> bool,
        effort: &Effort,
    ) -> Result<Edge, String> {
        Edge::fit(&self.trace(on, sweep, inside)?, on.degree, effort)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixture::Fixture;
    use crate::measure::Plane;
    use std::path::Path;

    #[test]
    fn an_edge_traced_on_a_lazy_probe_is_the_whole_probes_and_skips_the_inside() {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/flange.json");
        let f = Fixture::load(&file).unwrap();
        let setup = Observer {
            fixture: &f,
            model: crate::observer::fixture_model(&f),
            camera_t: f.spec.camera.t,
        };
        let effort = Effort { probe: 256, spp: 1 };
        let keep = ["flange"];
        let whole = ProbeImage::aimed(&setup, &keep, 0.15, &effort).unwrap();
        let lazy = ProbeImage::aimed_lazy(&setup, &keep, 0.15, &effort).unwrap();
        let on = OnPlane {
            plane: Plane::z(2.0),
            coords: |q: DVec3| (q.y, q.x),
            range: (-1e9, 1e9),
            degree: 2,
        };
        for (sweep, lazy_sweep) in [
            (whole.sweep_rightwards(), lazy.sweep_rightwards()),
            (whole.sweep_leftwards(), lazy.sweep_leftwards()),
        ] {
            let a = whole.trace(&on, sweep, whole.background()).unwrap();
            let b = lazy.trace(&on, lazy_sweep, lazy.background()).unwrap();
            assert!(!a.points.is_empty());
            assert_eq!(format!("{:?}", a.points), format!("{:?}", b.points));
            assert_eq!(a.footprint.to_bits(), b.footprint.to_bits());
        }
        assert_eq!(lazy.img.failure(), None);
        // Both sides traced, and still the inside was never rendered.
        let (done, all) = lazy.img.rendered();
        assert!(done < all, "{done} of {all} tiles rendered");
        // Negative control: a trace on the wrong plane reads other points.
        let off = OnPlane {
            plane: Plane::z(0.0),
            ..on
        };
        let c = lazy
            .trace(&off, lazy.sweep_rightwards(), lazy.background())
            .unwrap();
        let a = whole
            .trace(&on, whole.sweep_rightwards(), whole.background())
            .unwrap();
        assert_ne!(format!("{:?}", a.points), format!("{:?}", c.points));
    }
}
