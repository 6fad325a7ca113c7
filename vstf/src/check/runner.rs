//! Running the checks: each fixture is loaded once and its declared checks
//! run ([`super::declared`]), fixtures concurrently, and every view is compared with its golden
//! image.

use super::row::{Quantity, Row};
use super::setup::Effort;
use crate::budget::Budget;
use crate::fixture::Fixture;
use crate::golden::{Comparison, Store};
use crate::project::Project;
use image::RgbImage;
use rayon::prelude::*;

/// What a check finds: its views for the report and its table of quantities.
pub struct Findings {
    /// The full views, with the expected points to mark.
    pub views: Vec<ViewReport>,
    /// The checked quantities, in table order.
    pub quantities: Vec<Quantity>,
}

/// A rendered view of a fixture for the report, with the expected points
/// (from the oracle) to mark on a copy of it.
pub struct ViewReport {
    /// The view's name (also names its golden image).
    pub name: String,
    /// The rendered view.
    pub image: RgbImage,
    /// Pixel positions where first principles put the marked points.
    pub markers: Vec<(f64, f64)>,
    /// For each marker, the row it belongs to (empty when none names it).
    pub rows: Vec<String>,
    /// The rows measured in this view (by quantity name), which the report
    /// shows beside it.
    pub measured: Vec<String>,
}

/// All results for one fixture.
pub struct FixtureReport {
    /// The fixture's name.
    pub fixture: String,
    /// The fixture's description.
    pub description: String,
    /// The rendered views.
    pub views: Vec<ViewReport>,
    /// The judged quantities.
    pub rows: Vec<Row>,
    /// Each view against its golden image (filled in by [`run`]).
    pub goldens: Vec<Comparison>,
    /// The views the fixture declares (which `vstf render --view` renders).
    pub declared_views: Vec<String>,
}

impl FixtureReport {
    /// The report of `fixture` (named `name`) from what its check found,
    /// every quantity judged; goldens not yet compared.
    pub fn new(name: &str, fixture: &Fixture, findings: Findings) -> FixtureReport {
        FixtureReport {
            fixture: name.into(),
            description: fixture.spec.description.clone(),
            views: findings.views,
            rows: findings
                .quantities
                .into_iter()
                .map(|q| q.judge(name))
                .collect(),
            goldens: Vec::new(),
            declared_views: fixture.spec.views.iter().map(|v| v.name.clone()).collect(),
        }
    }

    /// Whether every row and every golden comparison passed.
    pub fn passed(&self) -> bool {
        self.rows.iter().all(|r| r.pass) && self.goldens.iter().all(|g| g.pass)
    }
}

/// Loads the fixture `name` (or file), runs its declared checks and
/// compares every view with its golden image in `store`.
fn run_one(
    project: &Project,
    name: &str,
    (effort, budget): (&Effort, &Budget),
    store: &Store,
) -> Result<FixtureReport, String> {
    let fixture = project
        .load_within(name, budget)
        .map_err(|e| e.to_string())?;
    let findings = super::declared::run(&fixture, effort)?;
    let mut report = FixtureReport::new(&fixture.name, &fixture, findings);
    for v in &report.views {
        report
            .goldens
            .push(store.check(&report.fixture, &v.name, &v.image, fixture.spec.fuzzy)?);
    }
    Ok(report)
}

/// Runs the declared checks of the named fixtures (names in the project's
/// `fixtures/`, or files; all of the project's when empty), comparing every
/// view with its golden image in the project's `golden/`.
pub fn run(
    project: &Project,
    names: &[String],
    effort: &Effort,
) -> Result<Vec<FixtureReport>, String> {
    run_within(project, names, effort, &Budget::DEFAULT)
}

/// [`run`], loading fixtures within `budget`.
pub fn run_within(
    project: &Project,
    names: &[String],
    effort: &Effort,
    budget: &Budget,
) -> Result<Vec<FixtureReport>, String> {
    run_reporting(project, names, (effort, budget), &|_, _| {})
}

/// [`run_within`], calling `finished` with each fixture's report and its
/// time in seconds as soon as it is done (in the order they finish).
pub fn run_reporting(
    project: &Project,
    names: &[String],
    (effort, budget): (&Effort, &Budget),
    finished: &(dyn Fn(&FixtureReport, f64) + Sync),
) -> Result<Vec<FixtureReport>, String> {
    let store = &project.store();
    let mut chosen = project.fixtures_or_all(names);
    // A fixture named twice (or by name and by path) is checked once: two
    // runs of it at once would write the same pending images.
    let mut seen = std::collections::HashSet::new();
    chosen.retain(|n| {
        let file = project.resolve(n).ok().and_then(|p| p.canonicalize().ok());
        seen.insert(file.unwrap_or_else(|| n.into()))
    });
    if chosen.is_empty() {
        return Err(format!(
            "no fixtures in {}: write one (docs/checks.md), or start from `vstf init`",
            project.fixtures_dir().display()
        ));
    }
    // The fixtures run concurrently (each renders in parallel too, so their
    // serial parts overlap); results come back in the order asked.
    chosen
        .par_iter()
        .map(|name| {
            let started = std::time::Instant::now();
            let report = run_one(project, name, (effort, budget), store)?;
            finished(&report, started.elapsed().as_secs_f64());
            Ok(report)
        })
        .collect()
}
