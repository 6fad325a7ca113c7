//! The `vstf` command line.

mod cli;

use clap::Parser;
use cli::args::{Cli, Command};
use std::process::ExitCode;

fn main() -> ExitCode {
    cli::quiet_on_closed_pipe();
    let Cli {
        root,
        simd,
        command,
    } = Cli::parse();
    if let Some(level) = simd {
        renderer::SimdLevel::limit_process(level);
    }
    let root = root.as_deref();
    let result = match command {
        Command::Render(args) => cli::render::run(root, args),
        Command::Check(args) => cli::check::run(root, args),
        Command::Approve(args) => cli::approve::run(root, args),
        Command::Reject(args) => cli::approve::reject(root, args),
        Command::Review => cli::review::run(root),
        Command::Debug(args) => cli::debug::run(root, args),
        Command::DebugDiff(args) => cli::debug::diff(args),
        Command::Animate(args) => cli::animate::run(root, args),
        Command::Merge(args) => cli::merge::run(args),
        Command::Bench {
            quick,
            measure,
            against,
            frames,
        } => match measure {
            Some(fixture) => cli::bench::measure(&fixture, against.as_deref(), frames),
            None => cli::bench::run(root, quick),
        },
        Command::List { views } => cli::list::run(root, views),
        Command::Serve { port, cache_mb } => cli::serve::run(root, port, cache_mb),
        Command::Init(args) => cli::init::run(args),
        Command::Fuzz(args) => cli::fuzz::run(root, args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}
