//! What the checks find, as the runner, the report and the shards see it:
//! each check kind's [`CheckOutcome`], the [`ViewReport`]s it rendered, and a
//! fixture's [`FixtureReport`] with its judged rows and golden comparisons.

use crate::check::row::{Quantity, Row};
use crate::fixture::Fixture;
use crate::golden::Comparison;
use image::RgbImage;

/// What a check finds: its views for the report and its table of quantities.
pub struct CheckOutcome {
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
    /// Each view against its golden image (filled in by [`crate::check::run`]).
    pub goldens: Vec<Comparison>,
    /// The views the fixture declares (which `vstf render --view` renders).
    pub declared_views: Vec<String>,
}

impl FixtureReport {
    /// The report of `fixture` (named `name`) from what its checks found,
    /// every quantity judged; goldens not yet compared.
    pub fn new(name: &str, fixture: &Fixture, outcome: CheckOutcome) -> FixtureReport {
        FixtureReport {
            fixture: name.into(),
            description: fixture.spec.description.clone(),
            views: outcome.views,
            rows: outcome
                .quantities
                .into_iter()
                .map(|q| {
                    let camera_t = solved_time(fixture, &q.name);
                    Row {
                        camera_t,
                        ..q.judge(name)
                    }
                })
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

/// The camera time of the view the declared check `name` is measured in,
/// where that view's `t` was solved rather than given as a number.
fn solved_time(fixture: &Fixture, name: &str) -> Option<f64> {
    let check = fixture.spec.checks.iter().find(|c| c.name == name)?;
    let view = check.measure.view()?;
    let v = fixture.spec.views.iter().find(|v| v.name == view)?;
    v.solved_t
}
