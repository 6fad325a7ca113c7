//! `vstf debug` (one pixel, or a region logged) and `vstf debug-diff`
//! (two logs compared).

use crate::support::{vstf, RunExt, Scratch};

#[test]
fn debug_prints_a_pixel_and_logs_a_region_that_debug_diff_compares() {
    let short = vstf().args(["debug", "flange", "--pixel", "300,200"]).run();
    short.succeeds().stdout_has("Primary ray");
    let text = short.stdout();
    assert!(
        text.starts_with("pixel (300, 200) of flange, relativistic model"),
        "{short}"
    );
    // Compact by default: the candidates tested only with --candidates.
    short.stdout_lacks("rejected:");
    let long = vstf()
        .args(["debug", "flange", "--pixel", "300,200", "--candidates"])
        .run();
    long.stdout_has("rejected:");
    assert!(long.stdout().lines().count() > text.lines().count() + 10);
    let dir = Scratch::new("debug");
    let (a, b) = (dir.join("a.jsonl"), dir.join("b.jsonl"));
    for (path, extra) in [(&a, None), (&b, Some("--brute-force"))] {
        vstf()
            .args(["debug", "flange", "--width", "64", "--height", "48"])
            .args(["--region", "10,10,13,12", "--candidates", "--log"])
            .arg(path)
            .args(extra)
            .run()
            .succeeds();
    }
    assert_eq!(std::fs::read_to_string(&a).unwrap().lines().count(), 12);
    let diff = |args: &[&str]| vstf().arg("debug-diff").args(args).arg(&a).arg(&b).run();
    diff(&["--ignore", "candidate"]).succeeds();
    diff(&[])
        .fails()
        .stdout_has("(kind of step): miss vs candidate");
    diff(&["--ignore", "candidat"])
        .fails_with("candidat")
        .stderr_has("candidate");
    vstf()
        .args(["debug", "flange", "--pixel", "5000,1"])
        .run()
        .fails_with("outside the 640x480 image");
}

/// `debug-diff --tol` takes only a finite tolerance of 0 or more.
#[test]
fn debug_diff_refuses_a_tolerance_that_is_not_a_number() {
    for bad in ["nan", "-1", "inf"] {
        vstf()
            .args(["debug-diff", "a.jsonl", "b.jsonl", "--tol", bad])
            .run()
            .fails_with("expected a finite tolerance");
    }
}
