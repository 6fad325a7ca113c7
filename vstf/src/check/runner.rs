//! Running the checks: each fixture is loaded once and its declared checks
//! run ([`crate::check::declared`]), fixtures concurrently, and every view
//! is compared with its golden image.

use crate::budget::Budget;
use crate::check::findings::FixtureReport;
use crate::check::probe::Effort;
use crate::error::Error;
use crate::fixture::Fixture;
use crate::golden::Store;
use crate::project::Project;
use rayon::prelude::*;

/// Loads the fixture `name` (or file), runs its declared checks and
/// compares every view with its golden image in `store`.
fn run_one(
    project: &Project,
    name: &str,
    (effort, budget): (&Effort, &Budget),
    store: &Store,
) -> Result<FixtureReport, Error> {
    let fixture = project.load_within(name, budget)?;
    check_loaded(&fixture, effort, Some(store))
}

/// Runs the declared checks of a loaded fixture and, given a `store`,
/// compares every view with its golden image there (a front end holding a
/// scene that belongs to no project passes none).
pub fn check_loaded(
    fixture: &Fixture,
    effort: &Effort,
    store: Option<&Store>,
) -> Result<FixtureReport, Error> {
    let outcome = crate::check::declared::run(fixture, effort)?;
    let mut report = FixtureReport::new(&fixture.name, fixture, outcome);
    let Some(store) = store else {
        return Ok(report);
    };
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
) -> Result<Vec<FixtureReport>, Error> {
    run_within(project, names, effort, &Budget::DEFAULT)
}

/// [`run`], loading fixtures within `budget`.
pub fn run_within(
    project: &Project,
    names: &[String],
    effort: &Effort,
    budget: &Budget,
) -> Result<Vec<FixtureReport>, Error> {
    run_reporting(project, names, (effort, budget), &|_, _| {})
}

/// [`run_within`], calling `finished` with each fixture's report and its
/// time in seconds as soon as it is done (in the order they finish).
pub fn run_reporting(
    project: &Project,
    names: &[String],
    (effort, budget): (&Effort, &Budget),
    finished: &(dyn Fn(&FixtureReport, f64) + Sync),
) -> Result<Vec<FixtureReport>, Error> {
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
        return Err(Error::NoFixture {
            name: String::new(),
            message: format!(
                "no fixtures in {}: write one (docs/checks.md), or start from `vstf init`",
                project.fixtures_dir().display()
            ),
        });
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
