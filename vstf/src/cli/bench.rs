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
/// process: the fixture's load, build, frames and peak memory as JSON;
/// with `against`, the two fixtures' tracing, frames in turn, as JSON.
pub fn measure(fixture: &Path, against: Option<&Path>, frames: usize) -> Result<(), Error> {
    let json = match against {
        Some(still) => {
            let (measured, _) = vstf::bench::paired::on_one_core(|| {
                vstf::bench::paired::measure(fixture, still, frames)
            })?;
            serde_json::to_string(&measured?)
        }
        None => serde_json::to_string(&vstf::bench::embree::measure(fixture, frames)?),
    };
    println!("{}", json.map_err(|e| e.to_string())?);
    Ok(())
}
