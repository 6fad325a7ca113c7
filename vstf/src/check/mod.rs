//! The VSTF checks: each fixture is rendered, measured from its images, and
//! compared with first-principles expectations ([`crate::oracle`]).
//!
//! By role, each importing only the rooms above it in this list:
//!
//! - results: [`row`] (readings, quantities with their [`Unit`], judged
//!   rows) and [`findings`] (what a check kind returns, a fixture's report);
//! - tools of the kinds: `probe` (probe renders aimed at the measured
//!   objects, full views for the report), `traced_edge` (an edge traced to
//!   sub-pixel precision on a probe render and fitted on a plane), `path`
//!   (where a body point is seen, for each kind of worldline);
//! - the kinds: `declared` (the general kinds a fixture declares, one file
//!   each, and the dispatcher that evaluates a fixture's declarations) and
//!   `named` (the paper's scenes, one module each);
//! - `views`: every view of a fixture by name, the one way the front ends
//!   find a view to render;
//! - running: `runner` (fixtures concurrently, views against their golden
//!   images) and [`sharded`] (one shard's reports stored for `vstf merge`,
//!   and merged).
//!
//! Outside `check/`, only what this module re-exports is used.

pub mod findings;
pub mod row;

mod cropped;
mod path;
mod probe;
mod traced_edge;

mod declared;
mod named;

mod views;

mod runner;
pub mod sharded;

pub use declared::{evaluate, run as run_fixture};
pub use findings::{CheckOutcome, FixtureReport, ViewReport};
pub use named::NamedView;
pub use probe::{Effort, VIEW_WIDTH};
pub use row::{difference, Quantity, Reading, Row, Unit};
pub use runner::{check_loaded, run, run_reporting, run_within};
pub use views::{golden_view, views_of, ViewEntry};
