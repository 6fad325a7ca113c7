//! The Visual Software Test Fixture (paper section 4): loads scene fixtures,
//! renders them with the `renderer` crate, and checks what the images show.
//!
//! Data flows one way: a fixture ([`fixture`]) is rendered ([`run`]), the
//! image is measured ([`measure`]), the measurements are compared with
//! first-principles expectations ([`oracle`], and for whole images the
//! slice-by-slice [`emulator`]) scene by scene ([`check`]),
//! and the views with their approved images ([`golden`]); [`report`]
//! presents the verdict. Beside that: [`debug`] logs the variables along a
//! pixel's rays, [`animate`] renders frame sequences, [`shard`] splits
//! animations and check suites over a batch engine's array jobs,
//! [`mod@bench`] measures speed, and [`output`] writes files atomically.

pub mod aim;
pub mod animate;
pub mod bench;
pub mod budget;
pub mod check;
pub mod debug;
pub mod emulator;
pub mod fixture;
pub mod fuzz;
pub mod golden;
pub mod label;
pub mod measure;
pub mod oracle;
pub mod output;
pub mod project;
pub mod report;
pub mod run;
pub mod serve;
pub mod shard;

pub use budget::Budget;
pub use check::{Effort, FixtureReport, Row, Unit};
pub use fixture::{FieldError, Fixture, FixtureError, Overrides, View};
pub use golden::{Comparison, Fuzzy, Store};
pub use project::Project;
