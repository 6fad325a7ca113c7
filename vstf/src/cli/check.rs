//! `vstf check`: every fixture rendered, measured and checked against
//! first-principles physics and its golden images.

use super::args::CheckArgs;
use std::path::Path;
use std::time::Instant;
use vstf::check::{Effort, FixtureReport, Row};
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
    let reports =
        vstf::check::run_reporting(&project, &fixtures, (&effort, &budget), &|r, seconds| {
            eprintln!("{}", fixture_line(r, seconds));
        })?;
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
    let failed_rows = rows.iter().filter(|r| !r.pass).count();
    if failed_rows > 0 || failed > 0 {
        eprintln!("{}", failures(&reports));
    }
    eprintln!(
        "check: {} fixtures, {} rows ({failed_rows} failed), {} golden images ({failed} failed) in {:.1} s",
        reports.len(),
        rows.len(),
        goldens.len(),
        started.elapsed().as_secs_f64()
    );
    if failed_rows > 0 || failed > 0 {
        return Err("some checks failed".into());
    }
    Ok(())
}

/// One line for a fixture as it finishes: its rows and golden images
/// passed out of all, and its time.
fn fixture_line(r: &FixtureReport, seconds: f64) -> String {
    let rows = r.rows.iter().filter(|x| x.pass).count();
    let goldens = r.goldens.iter().filter(|g| g.pass).count();
    let verdict = if r.passed() { "pass" } else { "FAIL" };
    format!(
        "{verdict} {:24} rows {rows}/{}, golden images {goldens}/{}, {seconds:.1} s",
        r.fixture,
        r.rows.len(),
        r.goldens.len()
    )
}

/// The failures again, after the table, with the commands that show them.
fn failures(reports: &[FixtureReport]) -> String {
    let mut out = String::from("failures:");
    for r in reports {
        for row in r.rows.iter().filter(|x| !x.pass) {
            out.push_str(&format!(
                "\n  {} {}: measured {} expected {} (tolerance {} {})",
                r.fixture, row.quantity, row.measured, row.expected, row.tolerance, row.unit
            ));
        }
        for g in r.goldens.iter().filter(|g| !g.pass) {
            out.push_str(&format!("\n  {g}"));
            if r.declared_views.contains(&g.view) {
                out.push_str(&format!(
                    "\n    vstf render {} --view {:?} --out target/vstf/{}.png",
                    r.fixture,
                    g.view,
                    vstf::golden::slug(&format!("{}-{}", r.fixture, g.view))
                ));
            }
        }
    }
    out
}
