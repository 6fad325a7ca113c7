//! `vstf bench`: rendering speed.

use std::path::Path;

/// Runs the benchmarks and prints their table.
pub fn run(root: Option<&Path>, quick: bool) -> Result<(), String> {
    let project = vstf::project::Project::locate(root)?;
    print!("{}", vstf::bench::run(&project, quick)?);
    Ok(())
}
