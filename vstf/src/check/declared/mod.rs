//! The checks a fixture file declares (`views` and `checks`, see
//! docs/checks.md), measured from probe renders and expected by the oracle
//! from the scene's description.
//!
//! Each general check gives one row. Edges and corners (`edge.rs`) find the
//! edge point whose seen image lands where it is read by a root search along
//! the edge over the point's worldline against the camera's past light cone;
//! the measurement traces the edge to sub-pixel precision and fits it, so
//! that the tolerance is the fit's prediction error. Outlines, Doppler
//! factors and blink periods are measured once per view and object
//! (`outline.rs`, `doppler.rs`, `period.rs`) and read by
//! every check of them. Differences, ratios and velocities combine earlier
//! rows, their uncertainties in quadrature. A check that cannot be
//! measured fails alone, as its row. Named kinds ([`crate::check::named`])
//! give the rows of the paper's scenes.

mod edge;

mod combine;
mod delay;
mod doppler;
mod emulated;
mod grid_line;
mod lambert;
mod lensing;
mod marker_angle;
mod mirror;
mod outline;
mod period;

use crate::aim::narrow_field_of_view;
use crate::check::findings::{CheckOutcome, ViewReport};
use crate::check::probe::Effort;
use crate::check::row::{difference, Quantity, Reading, Unit};
use crate::check::views::{own_observer, with_view_effects, OWN_VIEW};
use crate::error::Error;
use crate::fixture::checks::{
    dimensions, CheckSpec, DopplerSpec, LensRead, LensingSpec, MeasureSpec,
};
use crate::fixture::checks::{ToleranceSpec, ViewSpec};
use crate::fixture::Fixture;
use crate::measure::Pinhole;
use crate::observer::Observer;
use combine::{atan_degrees, ratio, same_unit, velocity, EarlierRow};
use doppler::Panel;
use glam::DVec3;
use image::RgbImage;
use outline::Outline;

/// The declared checks of `f`, rendered and expected from `f`; a check that
/// cannot be measured gives its failing row with the reason (see [`evaluate`]).
pub fn run(f: &Fixture, effort: &Effort) -> Result<CheckOutcome, Error> {
    evaluate(f, f, effort)
}

/// The declared checks of `described`, measured on renders of `rendered`
/// (the same scene, or a deliberately altered copy of it) and expected from
/// `described`'s scene data. A check that cannot be measured (an object
/// out of view, too few edge points, ...) becomes a failing row whose
/// error names it (`checks[i]: ...`), and so does every later combination
/// of it; the other rows are measured as usual. Only a failure to render
/// the report's views is an error.
pub fn evaluate(
    rendered: &Fixture,
    described: &Fixture,
    effort: &Effort,
) -> Result<CheckOutcome, Error> {
    let spec = &described.spec;
    let mut run = Evaluation {
        rendered,
        described,
        effort,
        done: Vec::new(),
        failed: Vec::new(),
        marks: vec![Vec::new(); spec.views.len()],
        outlines: Vec::new(),
        panels: Vec::new(),
        lensed: Vec::new(),
    };
    let mut outcome = CheckOutcome {
        views: Vec::new(),
        quantities: Vec::new(),
    };
    let mut named_views = Vec::new();
    let units = dimensions(&spec.checks).into_iter().map(Unit::of);
    for ((i, c), unit) in spec.checks.iter().enumerate().zip(units) {
        let failed = |message: String| {
            let hint = narrow_field_of_view(described).map_or(String::new(), |w| format!(" ({w})"));
            Quantity::failed(&c.name, unit, format!("checks[{i}]: {message}{hint}"))
        };
        if let MeasureSpec::Named(n) = &c.measure {
            let found = match crate::check::named::run(rendered, n, effort) {
                Ok(found) => found,
                Err(message) => {
                    outcome.quantities.push(failed(message));
                    continue;
                }
            };
            let rows: Vec<String> = found.quantities.iter().map(|q| q.name.clone()).collect();
            named_views.extend(found.views.into_iter().map(|mut v| {
                if v.measured.is_empty() {
                    v.measured.clone_from(&rows);
                }
                v
            }));
            outcome.quantities.extend(found.quantities);
            continue;
        }
        match run.check(c) {
            Ok(done) => {
                outcome.quantities.push(Quantity {
                    name: c.name.clone(),
                    measured: adjusted(done.measured, c.tolerance.as_ref()),
                    expected: done.expected,
                    paper: c.paper,
                    unit: done.unit,
                    error: None,
                });
                run.done.push(done);
            }
            Err(message) => {
                outcome.quantities.push(failed(message));
                run.failed.push(c.name.clone());
            }
        }
    }
    outcome.views = run.full_views().map_err(Error::Other)?;
    let measured = measured_in(&spec.checks);
    for v in &mut outcome.views {
        v.measured = measured
            .iter()
            .filter(|(_, views)| views.contains(&v.name))
            .map(|(row, _)| row.clone())
            .collect();
    }
    outcome.views.extend(named_views);
    Ok(outcome)
}

/// The views each declared check (not a named kind) is measured in: its
/// own, or for a combination, those of the rows it combines.
fn measured_in(checks: &[CheckSpec]) -> Vec<(String, Vec<String>)> {
    let mut found: Vec<(String, Vec<String>)> = Vec::new();
    for c in checks {
        let views = match (c.measure.view(), c.measure.operands()) {
            (Some(v), _) => vec![v.to_string()],
            (None, Some(operands)) => {
                let mut views: Vec<String> = found
                    .iter()
                    .filter(|(row, _)| operands.contains(row))
                    .flat_map(|(_, v)| v.iter().cloned())
                    .collect();
                views.sort();
                views.dedup();
                views
            }
            (None, None) => continue,
        };
        found.push((c.name.clone(), views));
    }
    found
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

/// One evaluation of a fixture's declarations: what has been measured so
/// far, the marks for each view, and the measurements shared by checks.
struct Evaluation<'a> {
    rendered: &'a Fixture,
    described: &'a Fixture,
    effort: &'a Effort,
    done: Vec<EarlierRow>,
    /// The checks that could not be measured, by name.
    failed: Vec<String>,
    /// Each view's marks: a direction and the row it belongs to.
    marks: Vec<Vec<(DVec3, String)>>,
    outlines: Vec<(usize, String, Outline)>,
    panels: Vec<(usize, String, Panel)>,
    /// The renders of lensing checks, by view and marker.
    lensed: Vec<(usize, String, (RgbImage, Pinhole))>,
}

/// A view: its index, declaration, and setups for measuring (on the
/// rendered fixture) and for expectations (from the described one).
struct ViewObservers<'a> {
    index: usize,
    spec: &'a ViewSpec,
    measuring: Observer<'a>,
    described: Observer<'a>,
}

impl<'a> Evaluation<'a> {
    fn view(&self, name: &str) -> Result<ViewObservers<'a>, String> {
        let (index, spec) = self
            .described
            .spec
            .views
            .iter()
            .enumerate()
            .find(|(_, v)| v.name == name)
            .ok_or_else(|| format!("no view named {name:?}"))?;
        Ok(ViewObservers {
            index,
            spec,
            measuring: Observer::declared(self.rendered, spec),
            described: Observer::declared(self.described, spec),
        })
    }

    fn earlier(&self, name: &str) -> Result<&EarlierRow, String> {
        if self.failed.iter().any(|f| f == name) {
            return Err(format!("depends on {name:?}, which could not be measured"));
        }
        self.done
            .iter()
            .find(|d| d.name == name)
            .ok_or_else(|| format!("no earlier check named {name:?}"))
    }

    fn mark(&mut self, view: usize, direction: Option<DVec3>, row: &str) {
        self.marks[view].extend(direction.map(|d| (d, row.to_string())));
    }

    /// Measures one general check into its row.
    fn check(&mut self, c: &CheckSpec) -> Result<EarlierRow, String> {
        let row = |(measured, expected, unit): (Reading, f64, Unit)| EarlierRow {
            name: c.name.clone(),
            measured,
            expected,
            unit,
            camera_t: None,
        };
        match &c.measure {
            MeasureSpec::Edge(e) => {
                let v = self.view(&e.view)?;
                let (reading, mark) =
                    edge::edge(&v.measuring, &v.described, v.spec, e, self.effort)?;
                self.mark(v.index, Some(mark), &c.name);
                Ok(EarlierRow {
                    camera_t: Some(v.measuring.camera_t),
                    ..row(reading)
                })
            }
            MeasureSpec::Corner(k) => {
                let v = self.view(&k.view)?;
                let (reading, mark) =
                    edge::corner(&v.measuring, &v.described, v.spec, k, self.effort)?;
                self.mark(v.index, Some(mark), &c.name);
                Ok(EarlierRow {
                    camera_t: Some(v.measuring.camera_t),
                    ..row(reading)
                })
            }
            MeasureSpec::Outline(o) => {
                let v = self.view(&o.view)?;
                let effort = self.effort;
                let (outline, new) = shared(&mut self.outlines, (v.index, &o.object), || {
                    Outline::measure(&v.measuring, &v.described, &o.object, effort)
                })?;
                let reading = outline.read(o.read)?;
                if new {
                    let marks = outline.marks.iter().map(|m| (*m, c.name.clone()));
                    self.marks[v.index].extend(marks.collect::<Vec<_>>());
                }
                Ok(row(reading))
            }
            MeasureSpec::Doppler(d) => Ok(row(self.doppler(d, &c.name)?)),
            MeasureSpec::Period(p) => {
                let v = self.view(&p.view)?;
                let (reading, expected, mark) = period::measure(&v.measuring, &v.described, p)?;
                self.mark(v.index, mark, &c.name);
                Ok(row((reading, expected, Unit::TUnits)))
            }
            MeasureSpec::Emulator(e) => {
                let v = self.view(&e.view)?;
                let (found, marks) = emulated::measure(&v.measuring, &v.described, e, v.spec)?;
                self.marks[v.index].extend(marks.into_iter().map(|m| (m, c.name.clone())));
                Ok(row(found))
            }
            MeasureSpec::Lambert(l) => {
                let v = self.view(&l.view)?;
                let (reading, mark) = lambert::measure(&v.measuring, &v.described, l)?;
                self.mark(v.index, Some(mark), &c.name);
                Ok(row(reading))
            }
            MeasureSpec::Lensing(l) => Ok(row(self.lensing(l, &c.name)?)),
            MeasureSpec::GridLine(g) => {
                let v = self.view(&g.view)?;
                let (reading, mark) =
                    grid_line::measure(&v.measuring, &v.described, v.spec, g, self.effort)?;
                self.mark(v.index, Some(mark), &c.name);
                Ok(row(reading))
            }
            MeasureSpec::Reflection(r) => {
                let v = self.view(&r.view)?;
                let (reading, mark) =
                    mirror::measure(&v.measuring, &v.described, r, v.spec, self.effort)?;
                self.mark(v.index, Some(mark), &c.name);
                Ok(row(reading))
            }
            MeasureSpec::MarkerAngle(m) => {
                let v = self.view(&m.view)?;
                let (r, mark) = marker_angle::measure(&v.measuring, &v.described, m, self.effort)?;
                self.mark(v.index, Some(mark), &c.name);
                Ok(row(r))
            }
            MeasureSpec::Difference(_)
            | MeasureSpec::Ratio(_)
            | MeasureSpec::Atan(_)
            | MeasureSpec::Velocity(_) => Ok(row(self.combination(&c.measure)?)),
            MeasureSpec::Named(_) => unreachable!("named kinds are run by the caller"),
        }
    }

    /// A combination of two earlier rows: their difference, ratio, atan of
    /// the ratio, or the velocity between two views' times.
    fn combination(&self, m: &MeasureSpec) -> Result<(Reading, f64, Unit), String> {
        match m {
            MeasureSpec::Difference([a, b]) => {
                let (a, b) = (self.earlier(a)?, self.earlier(b)?);
                same_unit(a, b)?;
                Ok((
                    difference(&a.measured, &b.measured),
                    a.expected - b.expected,
                    a.unit,
                ))
            }
            MeasureSpec::Ratio([a, b]) => {
                let (a, b) = (self.earlier(a)?, self.earlier(b)?);
                same_unit(a, b)?;
                Ok((
                    ratio(&a.measured, &b.measured),
                    a.expected / b.expected,
                    Unit::Ratio,
                ))
            }
            MeasureSpec::Atan([a, b]) => {
                let (a, b) = (self.earlier(a)?, self.earlier(b)?);
                same_unit(a, b)?;
                Ok((
                    atan_degrees(&ratio(&a.measured, &b.measured)),
                    (a.expected / b.expected).atan().to_degrees(),
                    Unit::Degrees,
                ))
            }
            MeasureSpec::Velocity([a, b]) => {
                let (a, b) = (self.earlier(a)?, self.earlier(b)?);
                velocity(a, b)
            }
            _ => Err("not a combination of earlier rows".into()),
        }
    }

    /// A lensing check's reading: the delay by its own renders; the
    /// angles from the render shared by the checks of one view and marker.
    fn lensing(&mut self, l: &LensingSpec, row: &str) -> Result<(Reading, f64, Unit), String> {
        let v = self.view(&l.view)?;
        let effort = self.effort;
        let (reading, mark) = if l.read == LensRead::Delay {
            delay::measure(&v.measuring, &v.described, l, effort)?
        } else {
            let key = lensing::render_key(l);
            let (rendered, _) = shared(&mut self.lensed, (v.index, &key), || {
                lensing::render(&v.measuring, l, effort)
            })?;
            lensing::measure(&v.measuring, &v.described, l, rendered)?
        };
        self.mark(v.index, Some(mark), row);
        Ok(reading)
    }

    /// A Doppler check's row: the object's panel (or the panel of one
    /// point of it), measured once per view and read by every check of it.
    fn doppler(&mut self, d: &DopplerSpec, row: &str) -> Result<(Reading, f64, Unit), String> {
        let v = self.view(&d.view)?;
        let effort = self.effort;
        let (panel, new) = match d.point {
            None => shared(&mut self.panels, (v.index, &d.object), || {
                if let renderer::Spacetime::Schwarzschild(s) = v.described.fixture.scene.spacetime {
                    Panel::in_field(&v.measuring, &v.described, &d.object, (s.mass, s.centre))
                } else if crate::observer::camera_path(&v.described.fixture.spec.camera).is_some() {
                    Panel::accelerating(&v.measuring, &v.described, &d.object, effort)
                } else {
                    Panel::measure(&v.measuring, &v.described, &d.object, effort)
                }
            })?,
            Some(r) => {
                let key = format!("{} at {r:?}", d.object);
                shared(&mut self.panels, (v.index, &key), || {
                    Panel::at_point(&v.measuring, &v.described, &d.object, r)
                })?
            }
        };
        let ((reading, expected), mark) = (panel.read(d.from)?, panel.mark);
        if new {
            self.mark(v.index, mark, row);
        }
        Ok((reading, expected, Unit::Factor))
    }

    /// The expected points to mark in view `k`: its checks', or where no
    /// check measures in it, those of the views from the same camera event
    /// under the same model (they see the same events).
    fn marks_of(&self, k: usize) -> Vec<(DVec3, String)> {
        if !self.marks[k].is_empty() {
            return self.marks[k].clone();
        }
        let views = &self.described.spec.views;
        let event = |v: &ViewSpec| {
            let s = Observer::declared(self.described, v);
            (s.camera_t, s.model)
        };
        views
            .iter()
            .zip(&self.marks)
            .filter(|(v, _)| event(v) == event(&views[k]))
            .flat_map(|(_, m)| m.iter().cloned())
            .collect()
    }

    /// Each declared view at the report's size, marked where the checks
    /// expect their points; the fixture's own view when it declares
    /// neither views nor checks.
    fn full_views(&self) -> Result<Vec<ViewReport>, String> {
        let spec = &self.described.spec;
        let mut views = Vec::new();
        for (k, v) in spec.views.iter().enumerate() {
            let marks = self.marks_of(k);
            let with_effects;
            let f = match with_view_effects(self.rendered, v) {
                Some(f) => {
                    with_effects = f;
                    &with_effects
                }
                None => self.rendered,
            };
            views.push(Observer::declared(f, v).full_view_labelled(&v.name, &marks)?);
        }
        if let Some(own) = own_observer(self.rendered) {
            views.push(own.full_view(OWN_VIEW, &[])?);
        }
        Ok(views)
    }
}

/// The measurement of (`view`, `object`) in `cache`, made by `measure` the
/// first time it is asked for and shared by every later check of it; and
/// whether it was made just now.
fn shared<'c, T>(
    cache: &'c mut Vec<(usize, String, T)>,
    (view, object): (usize, &str),
    measure: impl FnOnce() -> Result<T, String>,
) -> Result<(&'c T, bool), String> {
    let found = cache.iter().position(|(i, n, _)| *i == view && n == object);
    let (k, new) = match found {
        Some(k) => (k, false),
        None => {
            cache.push((view, object.to_string(), measure()?));
            (cache.len() - 1, true)
        }
    };
    Ok((&cache[k].2, new))
}
