//! `vstf check`: the table, the JSON rows and golden lines it writes, a
//! check that cannot be measured failing alone, and a tampered golden
//! caught in a copy of this repository.

use crate::support::{repo_root, tamper, vstf, RunExt, Scratch};

#[test]
fn check_prints_the_table_and_writes_json_rows() {
    let dir = Scratch::new("rows");
    let json = dir.join("rows.json");
    let run = vstf()
        .args(["check", "stage", "--quick", "--json"])
        .arg(&json)
        .run();
    run.succeeds();
    let stdout = run.stdout();
    // The default table: the fixture, then its rows, every line within 100
    // columns; passing golden images only counted.
    assert_eq!(stdout.lines().next(), Some("stage"), "{stdout}");
    for line in stdout.lines() {
        assert!(
            line.chars().count() <= 100,
            "{} columns: {line}",
            line.chars().count()
        );
    }
    run.stdout_lacks("golden pass");
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("check: ") && l.ends_with(" passed, 0 failed")),
        "{stdout}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = report["rows"].as_array().unwrap();
    assert!(!rows.is_empty() && rows.iter().all(|r| r["fixture"] == "stage"));
    let goldens = report["goldens"].as_array().unwrap();
    assert_eq!(goldens.len(), 1, "{report}");
    assert_eq!(goldens[0]["pass"], true);
    assert_eq!(goldens[0]["size"], serde_json::json!([240, 180]));
    // --verbose: the full table with every column, and every image's line.
    let verbose = vstf()
        .args(["check", "stage", "--quick", "--verbose"])
        .run();
    let header = verbose.stdout().lines().next().unwrap();
    for col in [
        "fixture",
        "quantity",
        "measured",
        "expected",
        "paper",
        "tolerance",
        "unit",
        "result",
    ] {
        assert!(header.contains(col), "{header}");
    }
    verbose.stdout_has("golden pass fixture=stage");
}

#[test]
fn check_of_an_unknown_fixture_fails_clearly() {
    vstf()
        .args(["check", "nosuch", "--quick"])
        .run()
        .fails_with("no fixture \"nosuch\"")
        .stderr_has("fixtures here: aberration,");
}

/// `--json -` writes the JSON rows, and only them, to stdout.
#[test]
fn check_json_dash_writes_only_json_to_stdout() {
    let run = vstf()
        .args(["check", "stage", "--quick", "--json", "-"])
        .run();
    run.succeeds();
    let rows: serde_json::Value = serde_json::from_slice(run.stdout_bytes())
        .unwrap_or_else(|e| panic!("stdout is not JSON ({e}): {}", run.stdout()));
    assert_eq!(rows["rows"].as_array().unwrap().len(), 5);
    assert_eq!(rows["goldens"][0]["view"], "view");
    run.stderr_has("golden: 1 passed, 0 failed");
    assert!(
        !repo_root().join("-").exists(),
        "a file named - was written"
    );
    // Not a terminal: plain lines, no colour codes and no progress bar.
    assert!(
        !run.stderr().contains('\u{1b}'),
        "escape codes off a terminal"
    );
    run.stderr_has("pass stage ");
}

/// The binary built from this repository, run in a copy of it with one
/// golden tampered, compares against the copy's goldens (and so catches the
/// tamper), writes its pending images into the copy, and leaves the
/// repository's own golden/ and target/vstf/ alone.
#[test]
fn a_tampered_golden_in_a_copy_of_the_repository_is_caught() {
    let copy = Scratch::repo_copy("copy");
    tamper(&copy.join("golden/flange/frame-920.png"));
    let ours = repo_root().join("golden/flange/frame-920.png");
    let before = std::fs::read(&ours).unwrap();
    let run = vstf()
        .current_dir(copy.join("fixtures"))
        .args(["check", "flange", "--quick"])
        .run();
    let text = run.stdout();
    assert!(!run.success(), "the tamper passed:\n{text}");
    run.stdout_has("golden FAIL fixture=flange view=frame-920 max_diff=1 differing=1");
    assert!(
        !text.contains("golden pass fixture=flange view=frame-1151"),
        "passing images are listed only with --verbose:\n{text}"
    );
    // Each fixture's line as it finishes, the failure again with the command
    // that renders the view, and the closing summary.
    run.stderr_has("FAIL flange")
        .stderr_has("rows 3/3, golden images 1/2")
        .stderr_has("vstf render flange --view \"frame 920\" --out");
    // The command that debugs the pixel where the image changed most, at
    // the golden's resolution.
    let worst = text
        .split("worst_pixel=")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .expect("the failing line names its worst pixel");
    run.stderr_has(&format!(
        "vstf debug flange --view \"frame 920\" --pixel {worst}"
    ))
    .stderr_has("check: 1 fixtures, 3 rows (0 failed), 2 golden images (1 failed)");
    assert!(copy
        .join("target/vstf/flange/frame-920/actual.png")
        .is_file());
    assert_eq!(std::fs::read(&ours).unwrap(), before);
    // The untampered repository, checked through --root from elsewhere, passes.
    vstf()
        .current_dir(&copy)
        .arg("--root")
        .arg(repo_root())
        .args(["check", "flange", "--quick"])
        .run()
        .succeeds();
}

/// In a project from `vstf init`, the example cube with one edge moved to a
/// view the cube has left: that row fails with its reason in the table and
/// the JSON, the row before it is measured and passes, and `vstf check`
/// exits 1 with every golden image passing. The control: the example as
/// `init` writes it passes.
#[test]
fn a_check_that_cannot_be_measured_fails_its_row_and_the_run() {
    let dir = Scratch::new("local-error");
    let project = dir.join("p");
    vstf()
        .current_dir(&dir)
        .args(["init", "p"])
        .run()
        .succeeds();
    let run = |args: &[&str]| {
        vstf()
            .current_dir(&project)
            .env_remove("CI")
            .args(args)
            .run()
    };
    let file = project.join("fixtures/moving-cube.json");
    let mut cube: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    cube["checks"] = serde_json::json!([cube["checks"][0], cube["checks"][1]]);
    std::fs::write(&file, cube.to_string()).unwrap();
    run(&["check", "moving-cube", "--quick"]).fails();
    run(&["approve", "--all"]).succeeds();
    run(&["check", "moving-cube", "--quick"])
        .succeeds()
        .stdout_has("check: 2 passed, 0 failed");
    cube["views"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({"name": "late", "t": 60.0}));
    cube["checks"][1]["measure"]["edge"]["view"] = "late".into();
    std::fs::write(&file, cube.to_string()).unwrap();
    run(&["check", "moving-cube", "--quick"]).fails();
    run(&["approve", "--all"]).succeeds();
    let json = dir.join("rows.json");
    let failed = run(&[
        "check",
        "moving-cube",
        "--quick",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert_eq!(failed.code(), Some(1), "{failed}");
    failed
        .stdout_has("check: 1 passed, 1 failed")
        .stdout_has("    error: checks[1]: the edge is not visible in view \"late\"")
        .stdout_has("golden: 3 passed, 0 failed");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = &report["rows"];
    assert_eq!(rows[0]["pass"], true, "{report}");
    assert!(rows[0].get("error").is_none(), "{report}");
    assert_eq!(rows[1]["pass"], false, "{report}");
    assert!(
        rows[1]["error"]
            .as_str()
            .is_some_and(|e| e.starts_with("checks[1]: ")),
        "{report}"
    );
}
