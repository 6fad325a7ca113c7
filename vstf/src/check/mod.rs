//! The VSTF checks: each fixture is rendered, measured from its images, and
//! compared with first-principles expectations ([`crate::oracle`]).
//!
//! - [`setup`]: how a check looks at its fixture (probe renders aimed at the
//!   measured objects, full views for the report);
//! - [`edge`]: edges traced to sub-pixel precision on a probe render and
//!   fitted ([`Probed`]: aim, render, sweep the rows, fit on a plane);
//! - [`row`]: readings, quantities and the judged rows of the check table;
//! - [`runner`]: loading each fixture, running the checks concurrently,
//!   comparing views with the golden images;
//! - [`sharded`]: one shard's reports stored for `vstf merge`, and merged;
//! - one module per scene, each a table of quantity, measurement,
//!   expectation and the paper's figure.

pub mod declared;
pub mod edge;
pub mod emulated;
pub mod named;
pub mod path;
pub mod row;
pub mod runner;
pub mod setup;
pub mod sharded;

pub mod aberration;
pub mod doppler;
pub mod lambert;
pub mod mirror;
pub mod outline;
pub mod period;
pub mod relativity;
pub mod stage;
pub mod teaser;
pub mod terrell;

pub use edge::{trace_rows, Edge, EdgeTrace, OnPlane, Probed, Sweep};
pub use row::{difference, Quantity, Reading, Row, Unit};
pub use runner::{run, run_reporting, run_within, Findings, FixtureReport, ViewReport};
pub use setup::{
    background, fixture_model, is_background, motion_of, uniform, Effort, Probe, Setup,
    UniformMotion, VIEW_WIDTH,
};
