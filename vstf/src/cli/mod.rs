//! The `vstf` command line: [`args`] is its grammar, [`view`] turns the view
//! flags into a fixture's view and database, and each subcommand has its
//! module: [`render`], [`check`], [`approve`], [`debug`] (with
//! `debug-diff`), [`animate`], [`bench`], [`list`], [`init`] and [`fuzz`].

pub mod animate;
pub mod approve;
pub mod args;
pub mod bench;
pub mod check;
pub mod debug;
pub mod fuzz;
pub mod init;
pub mod list;
pub mod render;
pub mod view;
