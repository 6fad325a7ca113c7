//! `vstf fuzz`: the stable, seeded, time-bounded fuzz run of the fixture
//! path over the project's `fuzz/corpus/` (seed fixtures), `fuzz/found/`
//! (inputs that once failed, kept as regression seeds) and `fixtures/`.

use super::args::FuzzArgs;
use std::path::Path;
use vstf::error::Error;
use vstf::project::Project;

/// Runs the fuzzer and prints its summary; fails on any failure.
pub fn run(root: Option<&Path>, args: FuzzArgs) -> Result<(), Error> {
    let project = Project::locate(root)?;
    if !(args.seconds.is_finite() && args.seconds > 0.0) {
        return Err(Error::usage(format!(
            "--seconds {}: expected a positive time",
            args.seconds
        )));
    }
    let fuzz = project.root().join("fuzz");
    let dirs: Vec<_> = [
        fuzz.join("corpus"),
        fuzz.join("found"),
        project.fixtures_dir(),
    ]
    .into_iter()
    .filter(|d| d.is_dir())
    .collect();
    let seeds = vstf::fuzz::seeds(&dirs)?;
    let save = args
        .save
        .unwrap_or_else(|| project.root().join("target").join("fuzz-failures"));
    let max = args.max_inputs.unwrap_or(u64::MAX);
    let s = vstf::fuzz::run(&seeds, args.seed, args.seconds, max, &save);
    println!(
        "fuzz: seed {}, {} seed fixtures: {} inputs in {:.1} s ({:.0} per second, slowest {:.3} s): \
         {} refused with an error, {} rendered, {} failures",
        args.seed,
        seeds.len(),
        s.inputs,
        s.seconds,
        s.inputs as f64 / s.seconds.max(1e-9),
        s.slowest,
        s.refused,
        s.rendered,
        s.failures.len()
    );
    for (path, why) in &s.failures {
        println!("FAIL {}: {why}", path.display());
    }
    if s.failures.is_empty() {
        Ok(())
    } else {
        Err(Error::Failed {
            message: format!(
                "{} failing inputs saved in {}",
                s.failures.len(),
                save.display()
            ),
        })
    }
}
