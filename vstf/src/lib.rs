//! The Visual Software Test Fixture (paper section 4): loads scene fixtures,
//! renders them with the `renderer` crate, and checks what the images show.
//!
//! fixture ([`fixture`]) -> scene -> 4D database -> image ([`output`]).

pub mod animate;
pub mod bench;
pub mod check;
pub mod debug;
pub mod fixture;
pub mod golden;
pub mod measure;
pub mod oracle;
pub mod output;
pub mod report;
pub mod run;
