//! `vstf bench`: rendering speed.

use std::path::Path;
use vstf::error::Error;

/// Runs the benchmarks and prints their table.
pub fn run(root: Option<&Path>, quick: bool) -> Result<(), Error> {
    let project = vstf::project::Project::locate(root)?;
    print!("{}", vstf::bench::run(&project, quick)?);
    Ok(())
}

/// One side of the Embree comparison, for the benchmark's own child
/// process: the fixture's load, build, frames and peak memory as JSON.
pub fn measure(fixture: &Path, frames: usize) -> Result<(), Error> {
    let m = vstf::bench::embree::measure(fixture, frames)?;
    println!("{}", serde_json::to_string(&m).map_err(|e| e.to_string())?);
    Ok(())
}
