//! The named kinds: measurements of the paper's scenes that the general
//! kinds cannot express, implemented in Rust and declared in the fixture
//! file with their parameters (docs/checks.md lists them).

use super::runner::Findings;
use super::setup::Effort;
use super::{aberration, relativity, stage, teaser, terrell};
use crate::fixture::checks::NamedSpec;
use crate::fixture::Fixture;

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
