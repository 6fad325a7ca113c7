//! The checks a fixture file declares (`views` and `checks`, see
//! docs/checks.md), measured from probe renders and expected by the oracle
//! from the scene's description.
//!
//! An edge check finds the edge point whose seen image lands where the edge
//! is read (a plane's level, an image row or column) by a root search along
//! the edge ([`crate::oracle::first_root`]) over the point's worldline
//! against the camera's past light cone ([`BodyPath`]); the measurement
//! traces the edge to sub-pixel precision and fits it ([`Edge`]), so that
//! its tolerance is the fit's prediction error. Differences, ratios and
//! velocities combine earlier checks, their uncertainties in quadrature.

use super::edge::{Edge, EdgeTrace, OnPlane, Probed, Sweep};
use super::path::BodyPath;
use super::row::{difference, Quantity, Reading, Unit};
use super::runner::Findings;
use super::setup::{fixture_model, Effort, Setup};
use crate::fixture::checks::{
    edge_ends, view_size, Axis, AxisValue, CheckSpec, EdgeAt, EdgeSpec, MeasureSpec, PlaneAt, Side,
    ToleranceSpec, ViewSpec,
};
use crate::fixture::Fixture;
use crate::measure::{self, Plane, Scan};
use crate::oracle::{first_root, Retarded};
use glam::DVec3;

/// A declared check's result, kept for the checks that combine it.
struct Done {
    name: String,
    measured: Reading,
    expected: f64,
    unit: Unit,
    /// The camera time of the view measured in (edges only).
    camera_t: Option<f64>,
}

/// The declared checks of `f`, rendered from `f` and expected from `f`.
pub fn run(f: &Fixture, effort: &Effort) -> Result<Findings, String> {
    evaluate(f, f, effort)
}

/// The declared checks of `described`, measured on renders of `rendered`
/// (the same scene, or a deliberately altered copy of it) and expected from
/// `described`'s scene data.
pub fn evaluate(
    rendered: &Fixture,
    described: &Fixture,
    effort: &Effort,
) -> Result<Findings, String> {
    let spec = &described.spec;
    let mut done: Vec<Done> = Vec::new();
    let mut marks: Vec<Vec<DVec3>> = vec![Vec::new(); spec.views.len()];
    let mut findings = Findings {
        views: Vec::new(),
        quantities: Vec::new(),
    };
    let mut named_views = Vec::new();
    for (i, c) in spec.checks.iter().enumerate() {
        let fail = |e: String| {
            format!(
                "{}: checks[{i}] {:?}: {e}",
                described.file.display(),
                c.name
            )
        };
        if let MeasureSpec::Named(n) = &c.measure {
            let found = super::named::run(rendered, n, effort)?;
            named_views.extend(found.views);
            findings.quantities.extend(found.quantities);
            continue;
        }
        let (result, mark) = measure(rendered, described, c, &done, effort).map_err(fail)?;
        if let Some((view, direction)) = mark {
            marks[view].push(direction);
        }
        findings.quantities.push(Quantity {
            name: c.name.clone(),
            measured: adjusted(result.measured, c.tolerance.as_ref()),
            expected: result.expected,
            paper: c.paper,
            unit: result.unit,
        });
        done.push(result);
    }
    for (v, marks) in spec.views.iter().zip(&marks) {
        findings
            .views
            .push(setup_of(rendered, v).full_view(&v.name, marks)?);
    }
    findings.views.extend(named_views);
    if spec.views.is_empty() && spec.checks.is_empty() {
        let own = Setup {
            fixture: rendered,
            model: fixture_model(rendered),
            camera_t: spec.camera.t,
        };
        findings.views.push(own.full_view("view", &[])?);
    }
    Ok(findings)
}

/// The tolerance after a declaration's change: at most `at_most`, plus `add`.
fn adjusted(r: Reading, t: Option<&ToleranceSpec>) -> Reading {
    let Some(t) = t else { return r };
    let tightened = t.at_most.map_or(r.tolerance, |m| r.tolerance.min(m));
    Reading {
        value: r.value,
        tolerance: tightened + t.add.unwrap_or(0.0),
    }
}

/// The setup of a declared view: its camera time and model.
fn setup_of<'f>(f: &'f Fixture, v: &ViewSpec) -> Setup<'f> {
    let mut model = match v.model {
        Some(m) => m.model(),
        None => fixture_model(f),
    };
    if let Some(l) = v.lorentz {
        model.lorentz = l;
    }
    Setup {
        fixture: f,
        model,
        camera_t: v.t.unwrap_or(f.spec.camera.t),
    }
}

/// A view's index and declaration.
fn view_named<'s>(f: &'s Fixture, name: &str) -> Result<(usize, &'s ViewSpec), String> {
    f.spec
        .views
        .iter()
        .enumerate()
        .find(|(_, v)| v.name == name)
        .ok_or_else(|| format!("no view named {name:?}"))
}

/// A general check's result, and for an edge the view and lab direction
/// of its expected point, to mark in the report.
type Measured = (Done, Option<(usize, DVec3)>);

/// Measures one general check.
fn measure(
    rendered: &Fixture,
    described: &Fixture,
    c: &CheckSpec,
    done: &[Done],
    effort: &Effort,
) -> Result<Measured, String> {
    let find = |name: &str| {
        done.iter()
            .find(|d| d.name == name)
            .ok_or_else(|| format!("no earlier check named {name:?}"))
    };
    let combined = |measured: Reading, expected: f64, unit: Unit| Done {
        name: c.name.clone(),
        measured,
        expected,
        unit,
        camera_t: None,
    };
    match &c.measure {
        MeasureSpec::Edge(e) => edge(rendered, described, c, e, effort),
        MeasureSpec::Difference([a, b]) => {
            let (a, b) = (find(a)?, find(b)?);
            same_unit(a, b)?;
            let d = combined(
                difference(&a.measured, &b.measured),
                a.expected - b.expected,
                a.unit,
            );
            Ok((d, None))
        }
        MeasureSpec::Ratio([a, b]) => {
            let (a, b) = (find(a)?, find(b)?);
            same_unit(a, b)?;
            Ok((
                combined(
                    ratio(&a.measured, &b.measured),
                    a.expected / b.expected,
                    Unit::Ratio,
                ),
                None,
            ))
        }
        MeasureSpec::Velocity([a, b]) => {
            let (a, b) = (find(a)?, find(b)?);
            same_unit(a, b)?;
            if a.unit != Unit::LUnits {
                return Err(format!(
                    "a velocity needs positions in l.units, not {}",
                    a.unit
                ));
            }
            let dt = b
                .camera_t
                .zip(a.camera_t)
                .map(|(tb, ta)| tb - ta)
                .ok_or("a velocity needs two edge checks")?;
            let d = difference(&b.measured, &a.measured);
            let measured = Reading {
                value: d.value / dt,
                tolerance: d.tolerance / dt.abs(),
            };
            Ok((
                combined(
                    measured,
                    (b.expected - a.expected) / dt,
                    Unit::LUnitsPerTUnit,
                ),
                None,
            ))
        }
        MeasureSpec::Named(_) => unreachable!("named kinds are run by the caller"),
    }
}

fn same_unit(a: &Done, b: &Done) -> Result<(), String> {
    if a.unit == b.unit {
        Ok(())
    } else {
        Err(format!(
            "{:?} is in {} and {:?} in {}",
            a.name, a.unit, b.name, b.unit
        ))
    }
}

/// a / b of two independent readings (relative uncertainties in quadrature).
fn ratio(a: &Reading, b: &Reading) -> Reading {
    let value = a.value / b.value;
    Reading {
        value,
        tolerance: value.abs() * (a.tolerance / a.value).hypot(b.tolerance / b.value),
    }
}

/// The edge of an edge check, as the oracle sees it from the view's camera
/// event: the point at parameter s along it, and where that point is seen.
struct SeenEdge<'a> {
    ends: [DVec3; 2],
    path: BodyPath,
    setup: Setup<'a>,
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

    /// The first point along the edge whose `level_of` is `level`.
    fn crossing(
        &self,
        level_of: impl Fn(&Retarded) -> Option<f64>,
        level: f64,
    ) -> Option<(f64, Retarded)> {
        let s = first_root(|s| self.seen(s).and_then(|r| level_of(&r)).map(|v| v - level))?;
        Some((s, self.seen(s)?))
    }
}

/// An edge check: the oracle's crossing, the measured one, and the mark.
fn edge(
    rendered: &Fixture,
    described: &Fixture,
    c: &CheckSpec,
    e: &EdgeSpec,
    effort: &Effort,
) -> Result<Measured, String> {
    let (index, view) = view_named(described, &e.view)?;
    let expected_setup = setup_of(described, view);
    let obj = described
        .scene
        .objects
        .iter()
        .find(|o| o.name == e.object)
        .ok_or_else(|| format!("no object named {:?}", e.object))?;
    let ends = edge_ends(obj, e).map_err(|(field, m)| format!("{field}: {m}"))?;
    let path = BodyPath::of(described, &e.object, expected_setup.model)?;
    let seen = SeenEdge {
        ends,
        path,
        setup: expected_setup,
    };
    let keep: Vec<&str> = match &e.keep {
        Some(k) => k.iter().map(String::as_str).collect(),
        None => vec![e.object.as_str()],
    };
    let measuring = setup_of(rendered, view);
    let at = e.at.resolve().map_err(|(_, m)| m)?;
    let (measured, expected, unit, direction) = match at {
        EdgeAt::Plane(p) => plane_edge(&measuring, &seen, e, &p, &keep, effort)?,
        EdgeAt::Row(r) => pixel_edge(&measuring, &seen, e, (true, r), &keep, view, effort)?,
        EdgeAt::Column(col) => pixel_edge(&measuring, &seen, e, (false, col), &keep, view, effort)?,
    };
    let done = Done {
        name: c.name.clone(),
        measured,
        expected,
        unit,
        camera_t: Some(measuring.camera_t),
    };
    Ok((done, Some((index, direction))))
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
    setup: &Setup,
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
    let probe = Probed::aimed(setup, keep, e.margin, effort)?;
    let on = OnPlane {
        plane: plane_of(p.plane),
        coords: |q: DVec3| (along.of(q), read.of(q)),
        range,
        degree: e.degree,
    };
    let sweep = match e.side {
        Side::Left => probe.from_left(),
        _ => probe.from_right(),
    };
    let fitted = probe
        .fit(&on, sweep, probe.background(), effort)
        .map_err(|err| format!("the edge is not visible in view {:?}: {err}", e.view))?;
    let reading = fitted.at(p.level);
    let shift = seen
        .path
        .keyframe_shift(seen.point(s), &at, setup.camera_x());
    let measured = Reading {
        value: reading.value,
        tolerance: reading.tolerance + shift,
    };
    Ok((measured, read.of(at.x), Unit::LUnits, at.direction))
}

/// An edge read in pixels where it crosses an image row (`horizontal`) or
/// column of the view's measuring image: the positions traced line by line
/// across the edge's image, fitted against the line's centre.
fn pixel_edge(
    setup: &Setup,
    seen: &SeenEdge,
    e: &EdgeSpec,
    (horizontal, line): (bool, u32),
    keep: &[&str],
    view: &ViewSpec,
    effort: &Effort,
) -> Result<EdgeResult, String> {
    let size = view_size(&setup.fixture.spec, view);
    let spp = view.spp.unwrap_or(effort.spp);
    let (img, camera) = setup.measuring_render(keep, size, spp)?;
    let split = move |(px, py): (f64, f64)| if horizontal { (py, px) } else { (px, py) };
    let level_of = |r: &Retarded| camera.pixel_of(r.direction).map(|p| split(p).0);
    let range = seen.range(level_of, e.trim)?;
    let centre = f64::from(line) + 0.5;
    let (_, at) = seen.crossing(level_of, centre).ok_or_else(|| {
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
        .map(|p| split(p).1)
        .ok_or("the edge point is behind the camera")?;
    let (w, h) = (i64::from(img.width()), i64::from(img.height()));
    let sweep = match e.side {
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
    let bg = super::setup::background(setup.fixture);
    let lines = if horizontal {
        img.height()
    } else {
        img.width()
    };
    let points: Vec<(f64, f64)> = (0..lines)
        .filter(|&i| (range.0..=range.1).contains(&(f64::from(i) + 0.5)))
        .filter_map(|i| {
            let scan = Scan { horizontal, at: i };
            let u = measure::edge(&img, scan, sweep.from, sweep.step, |c| {
                super::setup::is_background(c, bg)
            })?;
            Some((f64::from(i) + 0.5, u))
        })
        .collect();
    let trace = EdgeTrace {
        points,
        footprint: 1.0,
    };
    let strata = Effort { probe: 0, spp };
    let fitted = Edge::fit(&trace, e.degree, &strata)
        .map_err(|err| format!("the edge is not visible in view {:?}: {err}", e.view))?;
    Ok((fitted.at(centre), expected, Unit::Pixels, at.direction))
}
