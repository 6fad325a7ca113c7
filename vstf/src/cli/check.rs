//! `vstf check`: every fixture rendered, measured and checked against
//! first-principles physics and its golden images.

use super::args::CheckArgs;
use std::path::Path;
use std::time::Instant;
use vstf::check::{Effort, FixtureReport, Row};
use vstf::error::Error;
use vstf::golden::Comparison;
use vstf::project::Project;
use vstf::shard::Shard;

/// Prints the table of rows and the golden comparisons, writes the JSON and
/// HTML reports asked for, and fails if any row or image fails. A shard
/// checks its fixtures and stores its results for `vstf merge`.
pub fn run(root: Option<&Path>, args: CheckArgs) -> Result<(), Error> {
    let CheckArgs {
        fixtures,
        json,
        report,
        quick,
        force,
        verbose,
        shard,
        shard_dir,
    } = args;
    let effort = if quick { Effort::QUICK } else { Effort::FULL };
    let started = Instant::now();
    let project = match Project::locate(root) {
        Err(Error::NoProject { .. }) if root.is_none() && !fixtures.is_empty() => {
            Project::beside(&fixtures)?
        }
        found => found?,
    };
    let store = project.store();
    if store.writes_pending {
        for p in store.remove_stale_temps() {
            eprintln!("removed {} (left by an interrupted write)", p.display());
        }
    }
    let budget = vstf::Budget::forced(force);
    let shard = match shard {
        Some(s) => Some(Shard::parse(&s, |v| std::env::var(v).ok())?),
        None => None,
    };
    let chosen = project.fixtures_or_all(&fixtures);
    let mine: Vec<String> = match shard {
        Some(s) => chosen
            .iter()
            .filter(|n| s.owns_fixture(n))
            .cloned()
            .collect(),
        None => fixtures.clone(),
    };
    let reports = if shard.is_some() && mine.is_empty() {
        Vec::new()
    } else {
        checked(&project, &mine, (&effort, &budget))?
    };
    if let Some(s) = shard {
        let dir = project.root().join(&shard_dir);
        let scene = vstf::check::sharded::scene_hash(&project, &chosen);
        let at = vstf::check::sharded::store(&reports, &dir, (s, scene, chosen.len()))?;
        eprintln!(
            "shard {s}: {} of {} fixtures stored in {}; once every shard is done: vstf merge {}",
            reports.len(),
            chosen.len(),
            at.parent().unwrap_or(&dir).display(),
            dir.display()
        );
    }
    let asked = Asked {
        json,
        report,
        verbose,
        files: if store.writes_pending {
            Vec::new()
        } else {
            fixtures.clone()
        },
    };
    let pending = store.writes_pending.then_some(store.pending.as_path());
    if !store.writes_pending && reports.iter().any(|r| r.goldens.iter().any(|g| !g.pass)) {
        eprintln!("{}", approve_outside_a_project(project.root(), &fixtures));
    }
    conclude(&reports, &asked, pending, started)
}

/// What to run to approve the images of fixture files checked outside any
/// project, where nothing was written.
fn approve_outside_a_project(dir: &Path, files: &[String]) -> String {
    let stems: Vec<String> = files
        .iter()
        .filter_map(|f| Path::new(f).file_stem()?.to_str().map(String::from))
        .collect();
    format!(
        "no vstf project here: the golden images were read from {}, and nothing was written. \
         To approve these images make the folder a project, then check and approve:\n    \
         vstf init {dir}\n    vstf check --root {dir} {}\n    vstf approve --root {dir} {}",
        dir.join("golden").display(),
        files.join(" "),
        stems.join(" "),
        dir = dir.display(),
    )
}

/// The fixtures `names` checked, each fixture's line printed as it finishes
/// (under a progress bar on a terminal).
fn checked(
    project: &Project,
    names: &[String],
    (effort, budget): (&Effort, &vstf::Budget),
) -> Result<Vec<FixtureReport>, String> {
    let terminal = Terminal::stderr();
    let bar = terminal.progress(project.fixtures_or_all(names).len());
    let reports = vstf::check::run_reporting(project, names, (effort, budget), &|r, seconds| {
        let line = fixture_line(r, seconds, terminal.colour);
        if terminal.tty {
            bar.println(line);
            bar.inc(1);
        } else {
            eprintln!("{line}");
        }
    })?;
    bar.finish_and_clear();
    Ok(reports)
}

/// What the user asked to be written besides the table.
pub struct Asked {
    /// The JSON's file (`-`: stdout).
    pub json: Option<std::path::PathBuf>,
    /// The HTML report's folder.
    pub report: Option<std::path::PathBuf>,
    /// The full table and every golden line.
    pub verbose: bool,
    /// The fixture files checked outside any project, which the commands
    /// after a failure name instead of the fixtures' names.
    pub files: Vec<String>,
}

/// The table, the golden lines, the JSON and report asked for, the
/// failures with the commands that show them and the closing line; an
/// error when any row or golden image failed. `pending` is where the
/// pending images are.
pub fn conclude(
    reports: &[FixtureReport],
    asked: &Asked,
    pending: Option<&Path>,
    started: Instant,
) -> Result<(), Error> {
    let rows: Vec<Row> = reports.iter().flat_map(|r| r.rows.clone()).collect();
    // With `--json -` the JSON is all that goes to stdout; the table goes to stderr.
    let json_to_stdout = asked.json.as_deref() == Some(Path::new("-"));
    let say = |line: &str| {
        if json_to_stdout {
            eprintln!("{line}");
        } else {
            println!("{line}");
        }
    };
    let table = if asked.verbose {
        vstf::report::table(&rows)
    } else {
        vstf::report::summary_table(&rows)
    };
    say(table.trim_end());
    let goldens: Vec<&Comparison> = reports.iter().flat_map(|r| &r.goldens).collect();
    for g in goldens.iter().filter(|g| asked.verbose || !g.pass) {
        say(&g.to_string());
    }
    let failed = goldens.iter().filter(|g| !g.pass).count();
    say(&format!(
        "golden: {} passed, {failed} failed",
        goldens.len() - failed
    ));
    if let Some(pending) = pending.filter(|_| failed > 0) {
        eprintln!("golden images differ or are missing: look at the pending images under {}, then `vstf approve --list` and `vstf approve FIXTURE...` if the change is right", pending.display());
    }
    match &asked.json {
        Some(_) if json_to_stdout => println!("{}", vstf::report::check_json(&rows, &goldens)),
        Some(path) => {
            vstf::write_atomic(path, vstf::report::check_json(&rows, &goldens).as_bytes())
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?
        }
        None => {}
    }
    if let Some(dir) = &asked.report {
        vstf::report::html(dir, reports)?;
        eprintln!("report: {}", dir.join("index.html").display());
    }
    let failed_rows = rows.iter().filter(|r| !r.pass).count();
    if failed_rows > 0 || failed > 0 {
        eprintln!("{}", failures(reports, &asked.files));
    }
    eprintln!(
        "check: {} fixtures, {} rows ({failed_rows} failed), {} golden images ({failed} failed) in {:.1} s",
        reports.len(),
        rows.len(),
        goldens.len(),
        started.elapsed().as_secs_f64()
    );
    if failed_rows > 0 || failed > 0 {
        return Err(Error::Failed {
            message: "some checks failed".into(),
        });
    }
    Ok(())
}

/// Where the progress and the fixtures' lines go: a terminal (a progress
/// bar, and colour unless `NO_COLOR` is set) or not (plain lines).
struct Terminal {
    tty: bool,
    colour: bool,
}

impl Terminal {
    fn stderr() -> Terminal {
        use std::io::IsTerminal;
        let tty = std::io::stderr().is_terminal();
        let no_colour = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        Terminal {
            tty,
            colour: tty && !no_colour,
        }
    }

    /// A bar of `n` fixtures on a terminal; elsewhere one that only prints lines.
    fn progress(&self, n: usize) -> indicatif::ProgressBar {
        if !self.tty {
            return indicatif::ProgressBar::hidden();
        }
        let bar = indicatif::ProgressBar::new(n as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{bar:30} {pos}/{len} fixtures checked, {elapsed}",
        ) {
            bar.set_style(style);
        }
        bar
    }
}

/// One line for a fixture as it finishes: its rows and golden images
/// passed out of all, and its time; the verdict in colour if asked.
fn fixture_line(r: &FixtureReport, seconds: f64, colour: bool) -> String {
    let rows = r.rows.iter().filter(|x| x.pass).count();
    let goldens = r.goldens.iter().filter(|g| g.pass).count();
    let verdict = match (r.passed(), colour) {
        (true, false) => "pass",
        (false, false) => "FAIL",
        (true, true) => "\x1b[32mpass\x1b[0m",
        (false, true) => "\x1b[1;31mFAIL\x1b[0m",
    };
    format!(
        "{verdict} {:24} rows {rows}/{}, golden images {goldens}/{}, {seconds:.1} s",
        r.fixture,
        r.rows.len(),
        r.goldens.len()
    )
}

/// The failures again, after the table, with the commands that show them;
/// a fixture checked from its file outside any project is named by `files`.
fn failures(reports: &[FixtureReport], files: &[String]) -> String {
    let mut out = String::from("failures:");
    for r in reports {
        let fixture = files
            .iter()
            .find(|f| Path::new(f).file_stem().and_then(|s| s.to_str()) == Some(&r.fixture))
            .unwrap_or(&r.fixture);
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
                    "\n    vstf render {fixture} --view {:?} --out target/vstf/{}.png",
                    g.view,
                    vstf::golden::slug(&format!("{}-{}", r.fixture, g.view))
                ));
                if let Some((x, y)) = g.worst_at {
                    out.push_str(&format!(
                        "\n    vstf debug {fixture} --view {:?} --pixel {x},{y}   (the largest difference, at {}x{})",
                        g.view, g.size.0, g.size.1
                    ));
                }
            }
        }
    }
    out
}
