//! The named kinds: measurements of the paper's scenes that the general
//! kinds cannot express, implemented in Rust and declared in the fixture
//! file with their parameters (docs/checks.md lists them).

mod aberration;
mod relativity;
mod stage;
mod teaser;
mod terrell;
mod view;

pub use view::NamedView;

use crate::check::findings::CheckOutcome;
use crate::check::probe::Effort;
use crate::fixture::checks::NamedSpec;
use crate::fixture::Fixture;
use crate::observer::fixture_model;

/// The views the named kind `n` renders on `f`, in the order it renders
/// them, so that `--view` can reproduce each.
pub(super) fn views(f: &Fixture, n: &NamedSpec) -> Result<Vec<NamedView>, String> {
    let own = |name: &str| NamedView {
        name: name.into(),
        fixture: f.clone(),
        model: fixture_model(f),
        camera_t: f.spec.camera.t,
    };
    match n {
        NamedSpec::Stage { .. } | NamedSpec::Terrell { .. } => Ok(vec![own("view")]),
        NamedSpec::Aberration { speeds } => aberration::views(f, speeds),
        NamedSpec::Teaser {} => teaser::views(f),
        NamedSpec::Relativity {} => relativity::views(f),
    }
}

/// Runs the named kind `n` on `f`.
pub(super) fn run(f: &Fixture, n: &NamedSpec, effort: &Effort) -> Result<CheckOutcome, String> {
    match n {
        NamedSpec::Stage { axes, grid, depth } => {
            let bars = stage::Bars {
                axes,
                grid,
                depth: *depth,
            };
            stage::run(f, &bars, effort)
        }
        NamedSpec::Terrell { front, side } => {
            terrell::run(f, &terrell::Faces { front, side }, effort)
        }
        NamedSpec::Aberration { speeds } => aberration::run(f, speeds, effort),
        NamedSpec::Teaser {} => teaser::run(f, effort),
        NamedSpec::Relativity {} => relativity::run(f, effort),
    }
}
