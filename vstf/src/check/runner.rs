//! Running the checks: each fixture is loaded once and handed to its check,
//! the checks run concurrently, and every view is compared with its golden
//! image.

use super::row::{Quantity, Row};
use super::setup::Effort;
use super::CHECKS;
use crate::fixture::Fixture;
use crate::golden::{Comparison, Store};
use crate::project::Project;
use image::RgbImage;
use rayon::prelude::*;

/// A check: renders, measures and compares one fixture.
pub type Check = fn(&Fixture, &Effort) -> Result<Findings, String>;

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
        }
    }

    /// Whether every row and every golden comparison passed.
    pub fn passed(&self) -> bool {
        self.rows.iter().all(|r| r.pass) && self.goldens.iter().all(|g| g.pass)
    }
}

/// Loads the fixture `name`, runs `check` on it and compares every view
/// with its golden image in `store`.
fn run_one(
    project: &Project,
    name: &str,
    check: Check,
    effort: &Effort,
    store: &Store,
) -> Result<FixtureReport, String> {
    let fixture = project.load(name).map_err(|e| e.to_string())?;
    let mut report = FixtureReport::new(name, &fixture, check(&fixture, effort)?);
    for v in &report.views {
        report
            .goldens
            .push(store.check(&report.fixture, &v.name, &v.image, fixture.spec.fuzzy)?);
    }
    Ok(report)
}

/// Runs the checks of the named fixtures (all when empty), comparing
/// every view with its golden image in `store`.
pub fn run(
    project: &Project,
    names: &[String],
    effort: &Effort,
) -> Result<Vec<FixtureReport>, String> {
    let store = &project.store();
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
        .map(|(name, check)| run_one(project, name, *check, effort, store))
        .collect()
}
