//! The `vstf` command line.

mod cli;

use clap::Parser;
use cli::args::{Cli, Command};
use std::process::ExitCode;

fn main() -> ExitCode {
    let result = match Cli::parse().command {
        Command::Render(args) => cli::render::run(args),
        Command::Check(args) => cli::check::run(args),
        Command::Approve(args) => cli::approve::run(args),
        Command::Debug(args) => cli::debug::run(args),
        Command::DebugDiff(args) => cli::debug::diff(args),
        Command::Animate(args) => cli::animate::run(args),
        Command::Bench { quick } => cli::bench::run(quick),
        Command::List => cli::list::run(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
