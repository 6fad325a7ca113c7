//! `vstf check`: every fixture rendered, measured and checked against
//! first-principles physics and its golden images.

use super::args::CheckArgs;
use std::path::Path;
use std::time::Instant;
use vstf::check::{Effort, Row};
use vstf::golden::Comparison;
use vstf::project::Project;

/// Prints the table of rows and the golden comparisons, writes the JSON and
/// HTML reports asked for, and fails if any row or image fails.
pub fn run(root: Option<&Path>, args: CheckArgs) -> Result<(), String> {
    let CheckArgs {
        fixtures,
        json,
        report,
        quick,
        force,
    } = args;
    let effort = if quick { Effort::QUICK } else { Effort::FULL };
    let started = Instant::now();
    let project = Project::locate(root)?;
    let store = project.store();
    for p in store.remove_stale_temps() {
        eprintln!("removed {} (left by an interrupted write)", p.display());
    }
    let budget = vstf::Budget::forced(force);
    let reports = vstf::check::run_within(&project, &fixtures, &effort, &budget)?;
    let rows: Vec<Row> = reports.iter().flat_map(|r| r.rows.clone()).collect();
    // With `--json -` the JSON is all that goes to stdout; the table goes to stderr.
    let json_to_stdout = json.as_deref() == Some(Path::new("-"));
    let say = |line: &str| {
        if json_to_stdout {
            eprintln!("{line}");
        } else {
            println!("{line}");
        }
    };
    say(vstf::report::table(&rows).trim_end());
    let goldens: Vec<&Comparison> = reports.iter().flat_map(|r| &r.goldens).collect();
    for g in &goldens {
        say(&g.to_string());
    }
    let failed = goldens.iter().filter(|g| !g.pass).count();
    say(&format!(
        "golden: {} passed, {failed} failed",
        goldens.len() - failed
    ));
    if failed > 0 {
        eprintln!("golden images differ or are missing: look at the pending images under {}, then `vstf approve --list` and `vstf approve FIXTURE...` if the change is right", store.pending.display());
    }
    eprintln!(
        "checked {} fixtures in {:.1} s",
        reports.len(),
        started.elapsed().as_secs_f64()
    );
    match json {
        Some(_) if json_to_stdout => println!("{}", vstf::report::json(&rows)),
        Some(path) => vstf::output::write_atomic(&path, vstf::report::json(&rows).as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?,
        None => {}
    }
    if let Some(dir) = report {
        vstf::report::html(&dir, &reports)?;
        eprintln!("report: {}", dir.join("index.html").display());
    }
    if rows.iter().any(|r| !r.pass) || failed > 0 {
        return Err("some checks failed".into());
    }
    Ok(())
}
