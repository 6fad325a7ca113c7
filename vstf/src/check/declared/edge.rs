//! Edges and corners: the oracle's seen edge (the point at parameter s
//! along a straight edge of an object, on its worldline, seen from the
//! view's camera event), and the measurement of where the edge's image lies
//! on a lab plane, at an image row or column, or where two edges meet.

use crate::check::path::BodyPath;
use crate::check::probe::Effort;
use crate::check::row::{Reading, Unit};
use crate::check::traced_edge::{Edge, EdgeTrace, OnPlane, ProbeImage, Sweep};
use crate::fixture::checks::{
    edge_ends, view_size, Axis, AxisValue, CornerEdge, CornerSpec, EdgeAt, EdgeSpec, ImageReport,
    PixelAxis, PlaneAt, Side, ViewSpec,
};
use crate::measure::{self, azimuth, elevation, Pinhole, Pixels, Plane, Scan};
use crate::observer::{background, is_background, Observer};
use crate::oracle::{first_root, Retarded};
use crate::run::LazyImage;
use glam::DVec3;
use std::sync::Arc;

/// A row's reading, its expectation and unit.
type Row = (Reading, f64, Unit);

/// The edge of an edge check, as the oracle sees it from the view's camera
/// event: the point at parameter s along it, and where that point is seen.
pub(super) struct SeenEdge<'a> {
    ends: [DVec3; 2],
    path: BodyPath,
    setup: Observer<'a>,
}

impl SeenEdge<'_> {
    fn point(&self, s: f64) -> DVec3 {
        self.ends[0] + (self.ends[1] - self.ends[0]) * s
    }

    fn seen(&self, s: f64) -> Option<Retarded> {
        let s_ = &self.setup;
        self.path
            .seen(self.point(s), s_.camera_t, s_.camera_x(), s_.model)
    }

    /// The kept range of `level_of` the seen points: the edge's image from
    /// end to end, less `trim` of it at each end.
    fn range(
        &self,
        level_of: impl Fn(&Retarded) -> Option<f64>,
        trim: f64,
    ) -> Result<(f64, f64), String> {
        let end = |s: f64| {
            self.seen(s)
                .and_then(|r| level_of(&r))
                .ok_or("an end of the edge is never seen")
        };
        let (a, b) = (end(0.0)?, end(1.0)?);
        let (lo, hi) = (a.min(b), a.max(b));
        Ok((lo + trim * (hi - lo), hi - trim * (hi - lo)))
    }

    /// The keyframe bound of the path at parameter `s`, seen at `at`
    /// ([`BodyPath::keyframe_shift`]), l.units.
    fn shift(&self, s: f64, at: &Retarded) -> f64 {
        self.path
            .keyframe_shift(self.ends, s, at, self.setup.camera_x())
    }

    /// The same bound as an offset in the image of `camera` along its rows
    /// (`horizontal`) or columns, pixels: the angle it subtends at the
    /// camera over the angle of one pixel there.
    fn shift_px(&self, s: f64, at: &Retarded, camera: &Pinhole, horizontal: bool) -> f64 {
        let shift = self.shift(s, at);
        if shift == 0.0 {
            return 0.0;
        }
        let Some((px, py)) = camera.pixel_of(at.direction) else {
            return f64::INFINITY;
        };
        let angle = shift / (at.x - self.setup.camera_x()).length();
        angle / camera.angular_footprint(px, py, horizontal)
    }

    /// The first point along the edge whose `level_of` is `level`.
    pub(super) fn crossing(
        &self,
        level_of: impl Fn(&Retarded) -> Option<f64>,
        level: f64,
    ) -> Option<(f64, Retarded)> {
        let s = first_root(|s| self.seen(s).and_then(|r| level_of(&r)).map(|v| v - level))?;
        Some((s, self.seen(s)?))
    }
}

/// The objects a check renders: `keep`, or the measured object alone.
fn kept<'k>(keep: &'k Option<Vec<String>>, object: &'k str) -> Vec<&'k str> {
    match keep {
        Some(k) => k.iter().map(String::as_str).collect(),
        None => vec![object],
    }
}

/// The seen edge from `from` to `to` of the object `object`, as the oracle
/// sees it from `described`'s camera event.
pub(super) fn seen_edge<'a>(
    described: &Observer<'a>,
    object: &str,
    ends: [DVec3; 2],
) -> Result<SeenEdge<'a>, String> {
    let path = BodyPath::of(described.fixture, object, described.model)?;
    Ok(SeenEdge {
        ends,
        path,
        setup: Observer { ..*described },
    })
}

/// An edge check: the measured reading beside the oracle's, and the lab
/// direction of the expected point, to mark.
pub(super) fn edge(
    measuring: &Observer,
    described: &Observer,
    view: &ViewSpec,
    e: &EdgeSpec,
    effort: &Effort,
) -> Result<(Row, DVec3), String> {
    let obj = described.fixture.object(&e.object)?;
    let ends = edge_ends(obj, e).map_err(|(field, m)| format!("{field}: {m}"))?;
    let seen = seen_edge(described, &e.object, ends)?;
    let keep = kept(&e.keep, &e.object);
    let at = e.at.resolve().map_err(|(_, m)| m)?;
    let (measured, expected, unit, direction) = match at {
        EdgeAt::Plane(p) => plane_edge(measuring, &seen, e, &p, &keep, effort)?,
        EdgeAt::Row(r) => pixel_edge(measuring, &seen, e, (true, r), &keep, view, effort)?,
        EdgeAt::Column(c) => pixel_edge(measuring, &seen, e, (false, c), &keep, view, effort)?,
    };
    Ok(((measured, expected, unit), direction))
}

/// The lab plane of a declaration.
fn plane_of(v: AxisValue) -> Plane {
    match v {
        AxisValue::X(x) => Plane::x(x),
        AxisValue::Y(y) => Plane::y(y),
        AxisValue::Z(z) => Plane::z(z),
    }
}

type EdgeResult = (Reading, f64, Unit, DVec3);

/// An edge read on a lab plane: traced on a probe aimed at the kept
/// objects, back-projected through the measurement's pinhole onto the
/// plane, fitted as `read` against `along` and read at `level`.
fn plane_edge(
    setup: &Observer,
    seen: &SeenEdge,
    e: &EdgeSpec,
    p: &PlaneAt,
    keep: &[&str],
    effort: &Effort,
) -> Result<EdgeResult, String> {
    let (along, read): (Axis, Axis) = (p.along, p.read);
    let level_of = |r: &Retarded| Some(along.of(r.x));
    let range = seen.range(level_of, e.trim)?;
    let (s, at) = seen.crossing(level_of, p.level).ok_or_else(|| {
        format!(
            "the edge's image does not reach {along:?} = {} in view {:?} (it spans {:.6} to {:.6} there, trimmed)",
            p.level, e.view, range.0, range.1
        )
    })?;
    let probe = ProbeImage::aimed_lazy(setup, keep, e.margin, effort)?;
    let on = OnPlane {
        plane: plane_of(p.plane),
        coords: |q: DVec3| (along.of(q), read.of(q)),
        range,
        degree: e.degree,
    };
    let sweep = match e.side {
        Side::Left => probe.sweep_rightwards(),
        _ => probe.sweep_leftwards(),
    };
    let fitted = probe
        .fit(&on, sweep, probe.background(), effort)
        .map_err(|err| format!("the edge is not visible in view {:?}: {err}", e.view))?;
    let reading = fitted.at(p.level);
    let shift = seen.shift(s, &at);
    let measured = Reading {
        value: reading.value,
        tolerance: reading.tolerance + shift,
    };
    Ok((measured, read.of(at.x), Unit::LUnits, at.direction))
}

/// The measuring image of a view: the kept objects through the
/// fixture's own camera at the view's size, rendered as it is read (a
/// line's scan reads it from the side to the edge), and the measurement's
/// pinhole.
fn measuring_image(
    setup: &Observer,
    keep: &[&str],
    view: &ViewSpec,
    effort: &Effort,
) -> Result<(Arc<LazyImage>, Pinhole, u32), String> {
    let size = view_size(&setup.fixture.spec, view);
    let spp = view.spp.unwrap_or(effort.spp);
    let (img, camera) = setup.measuring_lazy(keep, size, spp)?;
    Ok((img, camera, spp))
}

/// An edge traced line by line (rows when `horizontal`, else columns)
/// across the image, as (line centre, boundary) pairs for the lines whose
/// centre lies in `range`, scanned from `side`, and fitted by a polynomial
/// of `degree` with the area method's resolution at `spp` as its floor.
struct LineTrace<'i, I> {
    img: &'i I,
    bg: DVec3,
    horizontal: bool,
    range: (f64, f64),
}

impl<I: Pixels> LineTrace<'_, I> {
    fn fit(&self, side: Side, degree: usize, spp: u32) -> Result<Edge, String> {
        let (w, h) = self.img.dimensions();
        let (w, h) = (i64::from(w), i64::from(h));
        let sweep = match side {
            Side::Left | Side::Top => Sweep { from: 0, step: 1 },
            Side::Right => Sweep {
                from: w - 1,
                step: -1,
            },
            Side::Bottom => Sweep {
                from: h - 1,
                step: -1,
            },
        };
        let lines = if self.horizontal { h as u32 } else { w as u32 };
        let points: Vec<(f64, f64)> = (0..lines)
            .filter(|&i| (self.range.0..=self.range.1).contains(&(f64::from(i) + 0.5)))
            .filter_map(|i| {
                let scan = Scan {
                    horizontal: self.horizontal,
                    at: i,
                };
                let u = measure::edge(self.img, scan, sweep.from, sweep.step, |c| {
                    is_background(c, self.bg)
                })?;
                Some((f64::from(i) + 0.5, u))
            })
            .collect();
        if let Some(failure) = self.img.failure() {
            return Err(failure);
        }
        let trace = EdgeTrace {
            points,
            footprint: 1.0,
        };
        Edge::fit(&trace, degree, &Effort { probe: 0, spp })
    }
}

/// (height, position) of a pixel for a scan along rows (`horizontal`:
/// height y, position x) or columns (height x, position y).
fn split(horizontal: bool, (px, py): (f64, f64)) -> (f64, f64) {
    if horizontal {
        (py, px)
    } else {
        (px, py)
    }
}

/// An edge read in pixels where it crosses an image row (`horizontal`) or
/// column of the view's measuring image: the positions traced line by line
/// across the edge's image, fitted against the line's centre.
fn pixel_edge(
    setup: &Observer,
    seen: &SeenEdge,
    e: &EdgeSpec,
    (horizontal, line): (bool, u32),
    keep: &[&str],
    view: &ViewSpec,
    effort: &Effort,
) -> Result<EdgeResult, String> {
    let (img, camera, spp) = measuring_image(setup, keep, view, effort)?;
    let level_of = |r: &Retarded| camera.pixel_of(r.direction).map(|p| split(horizontal, p).0);
    let range = seen.range(level_of, e.trim)?;
    let centre = f64::from(line) + 0.5;
    let (s, at) = seen.crossing(level_of, centre).ok_or_else(|| {
        format!(
            "the edge's image does not cross {} {line} in view {:?} (it spans {:.2} to {:.2} px there, trimmed)",
            if horizontal { "row" } else { "column" },
            e.view,
            range.0,
            range.1
        )
    })?;
    let expected = camera
        .pixel_of(at.direction)
        .map(|p| split(horizontal, p).1)
        .ok_or("the edge point is behind the camera")?;
    let trace = LineTrace {
        img: &img,
        bg: background(setup.fixture),
        horizontal,
        range,
    };
    let fitted = trace
        .fit(e.side, e.degree, spp)
        .map_err(|err| format!("the edge is not visible in view {:?}: {err}", e.view))?;
    let reading = fitted.at(centre);
    let tolerance = reading.tolerance + seen.shift_px(s, &at, &camera, horizontal);
    let crossing = if horizontal {
        (reading.value, centre)
    } else {
        (centre, reading.value)
    };
    if e.at.report.unwrap_or_default() == ImageReport::Pixels {
        let measured = Reading {
            value: reading.value,
            tolerance,
        };
        return Ok((measured, expected, Unit::Pixels, at.direction));
    }
    // The same crossing as the direction of its line of sight; a pixel's
    // worth of angle is the change between its neighbours half a pixel
    // either side along the scan (an azimuth step grows off the horizon).
    let angle = |d: &DVec3| if horizontal { azimuth(d) } else { elevation(d) };
    let along = |u: f64| {
        let (px, py) = if horizontal {
            (crossing.0 + u, crossing.1)
        } else {
            (crossing.0, crossing.1 + u)
        };
        angle(&camera.direction(px, py))
    };
    let per_px = wrapped(along(0.5) - along(-0.5)).abs();
    let expected = angle(&at.direction);
    let measured = Reading {
        value: expected + wrapped(along(0.0) - expected),
        tolerance: tolerance * per_px,
    };
    Ok((measured, expected, Unit::Degrees, at.direction))
}

/// An angle difference brought into [-180, 180) degrees.
fn wrapped(d: f64) -> f64 {
    (d + 180.0).rem_euclid(360.0) - 180.0
}

/// One edge of a corner, fitted (position against height in the image),
/// and the keyframe bound of its path at the corner, pixels.
fn corner_edge(
    img: &Arc<LazyImage>,
    camera: &Pinhole,
    described: &Observer,
    object: &str,
    edge: &CornerEdge,
    (horizontal, degree, trim, spp): (bool, usize, f64, u32),
) -> Result<(Edge, f64), String> {
    let seen = seen_edge(described, object, edge.points)?;
    let bound = seen
        .seen(0.0)
        .map_or(0.0, |at| seen.shift_px(0.0, &at, camera, horizontal));
    let level_of = |r: &Retarded| camera.pixel_of(r.direction).map(|p| split(horizontal, p).0);
    let trace = LineTrace {
        img,
        bg: background(described.fixture),
        horizontal,
        range: seen.range(level_of, trim)?,
    };
    let fitted = trace.fit(edge.side, degree, spp).map_err(|err| {
        let lines = if horizontal { "rows" } else { "columns" };
        format!("the edge along the {lines} is not visible: {err}")
    })?;
    Ok((fitted, bound))
}

/// Where x = f(y) meets y = g(x), by iterating from `start` (a contraction
/// where |f' g'| < 1); `None` if it does not settle.
fn meet(f: &Edge, g: &Edge, start: (f64, f64)) -> Option<(f64, f64)> {
    let (mut x, mut y) = start;
    for _ in 0..200 {
        let (nx, ny) = (f.fit.eval(y), g.fit.eval(f.fit.eval(y)));
        let settled = (nx - x).abs().max((ny - y).abs()) < 1e-12;
        (x, y) = (nx, ny);
        if settled {
            return (x.is_finite() && y.is_finite()).then_some((x, y));
        }
    }
    None
}

/// A corner check: where the edge crossed by rows (x = f(y)) and the edge
/// crossed by columns (y = g(x)) meet, found by iterating the two fits from
/// the expected corner; its uncertainty propagates both fits' (each with its
/// path's keyframe bound) through the intersection, in quadrature:
/// sqrt(tf^2 + (f' tg)^2) / |1 - f' g'| for x, and likewise for y.
pub(super) fn corner(
    measuring: &Observer,
    described: &Observer,
    view: &ViewSpec,
    k: &CornerSpec,
    effort: &Effort,
) -> Result<(Row, DVec3), String> {
    let keep = kept(&k.keep, &k.object);
    let (img, camera, spp) = measuring_image(measuring, &keep, view, effort)?;
    let path = BodyPath::of(described.fixture, &k.object, described.model)?;
    let corner = path
        .seen(
            k.rows.points[0],
            described.camera_t,
            described.camera_x(),
            described.model,
        )
        .ok_or("the corner is never seen")?;
    let (ex, ey) = camera
        .pixel_of(corner.direction)
        .ok_or("the corner is behind the camera")?;
    let fit = (k.degree, k.trim, spp);
    let (f, bound_f) = corner_edge(
        &img,
        &camera,
        described,
        &k.object,
        &k.rows,
        (true, fit.0, fit.1, fit.2),
    )?;
    let (g, bound_g) = corner_edge(
        &img,
        &camera,
        described,
        &k.object,
        &k.columns,
        (false, fit.0, fit.1, fit.2),
    )?;
    let slope = |e: &Edge, at: f64| e.fit.eval(at + 0.5) - e.fit.eval(at - 0.5);
    if (slope(&f, ey) * slope(&g, ex)).abs() >= 0.9 {
        return Err(
            "the two edges do not meet at a clear angle: the rows edge must be \
                    steeper than 45 degrees in the image and the columns edge flatter"
                .into(),
        );
    }
    let (x, y) = meet(&f, &g, (ex, ey))
        .ok_or("the fits of the two edges do not meet near the expected corner")?;
    let (fp, gp) = (slope(&f, y), slope(&g, x));
    let (tf, tg) = (f.at(y).tolerance + bound_f, g.at(x).tolerance + bound_g);
    let gain = (1.0 - fp * gp).abs();
    let reading = match k.read {
        PixelAxis::X => (x, tf.hypot(fp * tg) / gain, ex),
        PixelAxis::Y => (y, tg.hypot(gp * tf) / gain, ey),
    };
    let row = (
        Reading {
            value: reading.0,
            tolerance: reading.1,
        },
        reading.2,
        Unit::Pixels,
    );
    Ok((row, corner.direction))
}
