//! The named kinds: measurements of the paper's scenes that the general
//! kinds cannot express, implemented in Rust and declared in the fixture
//! file with their parameters (docs/checks.md lists them).

use super::runner::Findings;
use super::setup::{fixture_model, Effort};
use super::{aberration, relativity, stage, teaser, terrell};
use crate::fixture::checks::NamedSpec;
use crate::fixture::Fixture;
use renderer::Model;

/// A view a named kind renders for its golden image: its name, the fixture
/// it renders (possibly a derived copy: the cube moving instead of the
/// camera, a season's speed), the model and the camera time.
pub struct NamedView {
    /// The view's name (also its golden image's).
    pub name: String,
    /// The fixture rendered.
    pub fixture: Fixture,
    /// The model rendered with.
    pub model: Model,
    /// The camera's lab time.
    pub camera_t: f64,
}

/// The views the named kind `n` renders on `f`, in the order it renders
/// them, so that `--view` can reproduce each.
pub fn views(f: &Fixture, n: &NamedSpec) -> Result<Vec<NamedView>, String> {
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
pub fn run(f: &Fixture, n: &NamedSpec, effort: &Effort) -> Result<Findings, String> {
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
