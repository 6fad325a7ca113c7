//! The Visual Software Test Fixture (paper section 4): loads scene fixtures,
//! renders them with the `renderer` crate, and checks what the images show.
//!
//! Data flows one way: a fixture ([`fixture`]) is rendered ([`run`]), the
//! image is measured ([`measure`]), the measurements are compared with
//! first-principles expectations ([`oracle`], and for whole images a
//! slice-by-slice emulator sharing no code with the renderer) fixture by
//! fixture ([`check`]), and the views with their approved images
//! ([`golden`]); [`report`] presents the verdict. Beside that: [`debug`]
//! logs the variables along a pixel's rays, [`aov`] reads per-pixel
//! arrays (the hit's event, proper time, Doppler factor) from the same
//! record, [`animate`] renders frame
//! sequences, [`shard`] splits animations and check suites over a batch
//! engine's array jobs, [`mod@bench`] measures speed, [`serve`] is the
//! local viewer, and [`fuzz`] mutates fixtures through the whole path.
//!
//! Every fallible call at this boundary returns an [`Error`], whose
//! variant says what kind of thing went wrong (a fixture, a missing file, a
//! check that cannot be measured, a verdict that failed). The items below
//! the modules are the rest of what front ends use; everything else is
//! private to the harness.

mod aim;
mod budget;
mod confine;
mod emulator;
mod label;
mod observer;
mod output;
mod spelling;

pub mod animate;
pub mod aov;
pub mod bench;
pub mod check;
pub mod debug;
pub mod error;
pub mod fixture;
pub mod fuzz;
pub mod golden;
pub mod measure;
pub mod oracle;
pub mod project;
pub mod report;
pub mod run;
pub mod serve;
pub mod shard;

pub use aim::{nothing_in_view_at_all, out_of_view, resolve_camera_time};
pub use aov::{aovs, PixelAov};
pub use budget::{prisms, Budget, Prisms};
pub use check::{Effort, FixtureReport, Row, Unit};
pub use error::Error;
pub use fixture::{CameraTime, FieldError, Fixture, FixtureError, Overrides, View};
pub use golden::{Comparison, Fuzzy, Store};
pub use label::{draw_label, label_scale};
pub use output::{
    rgb8, video, writable_file, write_8bit, write_atomic, write_exr, write_jpeg, write_png,
    ExrMeta, StillFormat, AOV_CHANNELS, JPEG_QUALITY, STILL_EXTENSIONS,
};
pub use project::Project;
