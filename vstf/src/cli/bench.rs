//! `vstf bench`: rendering speed.

/// Runs the benchmarks and prints their table.
pub fn run(quick: bool) -> Result<(), String> {
    print!("{}", vstf::bench::run(quick)?);
    Ok(())
}
