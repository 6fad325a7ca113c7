//! `vstf approve`, `reject` and `review`: pending golden images approved,
//! rejected and listed one view at a time, refused under CI, and the
//! temporary files of a killed write cleaned up.

use crate::support::{repo_root, tamper, vstf, Run, RunExt, Scratch};
use std::path::Path;

#[test]
fn approve_is_refused_under_ci_and_list_works() {
    vstf()
        .args(["approve", "--all"])
        .env("CI", "true")
        .run()
        .fails_with("refusing to approve golden images with CI set");
    vstf().args(["approve", "--list"]).run().succeeds();
    let run = vstf().args(["approve"]).run();
    assert!(
        !run.success(),
        "approve with neither fixtures nor --all must not approve everything: {run}"
    );
}

/// A copy of this repository with both of the flange's goldens tampered.
fn flange_tampered(name: &str) -> Scratch {
    let copy = Scratch::repo_copy(name);
    for view in ["frame-920", "frame-1151"] {
        tamper(&copy.join(format!("golden/flange/{view}.png")));
    }
    copy
}

/// `vstf ARGS` in `project`, with CI unset.
fn in_project(project: &Path, args: &[&str]) -> Run {
    vstf()
        .current_dir(project)
        .env_remove("CI")
        .args(args)
        .run()
}

/// One view at a time: `approve FIXTURE/VIEW` approves that view only,
/// `reject` drops a pending change and leaves its golden, and `approve
/// --list` says where each change is.
#[test]
fn approve_and_reject_one_view_at_a_time() {
    let copy = flange_tampered("perview");
    let run = |args: &[&str]| in_project(&copy, args);
    run(&["check", "flange", "--quick"]).fails();
    run(&["approve", "--list"])
        .stdout_has("flange/frame-920")
        .stdout_has("1 pixels differ (worst by 1) within x 10..=10, y 10..=10 of 240x180");
    let before_1151 = std::fs::read(copy.join("golden/flange/frame-1151.png")).unwrap();
    run(&["approve", "flange/frame-920"]).succeeds();
    assert_eq!(
        std::fs::read(copy.join("golden/flange/frame-1151.png")).unwrap(),
        before_1151
    );
    run(&["reject", "flange/frame-1151"]).succeeds();
    assert_eq!(
        std::fs::read(copy.join("golden/flange/frame-1151.png")).unwrap(),
        before_1151
    );
    run(&["approve", "--list"]).stdout_has("nothing pending");
    // frame 920 now passes against its approved (rendered) image; 1151 still
    // fails against the tampered golden that was kept.
    run(&["check", "flange", "--quick", "--verbose"])
        .stdout_has("golden pass fixture=flange view=frame-920")
        .stdout_has("golden FAIL fixture=flange view=frame-1151");
}

/// `vstf review` in `project` answering `answers` on stdin, with CI set to
/// `ci` or unset.
fn review(project: &Path, answers: &str, ci: Option<&str>) -> Run {
    use std::io::Write;
    use std::process::Stdio;
    let mut cmd = vstf();
    cmd.current_dir(project).arg("review").env_remove("CI");
    if let Some(v) = ci {
        cmd.env("CI", v);
    }
    let mut running = cmd
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .start();
    running
        .child
        .stdin
        .take()
        .unwrap()
        .write_all(answers.as_bytes())
        .ok(); // a refusal exits before reading: the pipe may be closed
    running.finish()
}

/// `vstf review`: each pending image shown with its change and files, and
/// accepted, rejected or skipped by the answer read from stdin (nonsense
/// is asked again); CI refuses it.
#[test]
fn review_accepts_and_rejects_one_image_at_a_time() {
    let copy = flange_tampered("review");
    vstf()
        .current_dir(&copy)
        .args(["check", "flange", "--quick"])
        .run()
        .fails();
    review(&copy, "a\na\n", Some("true")).fails_with("CI set");
    review(&copy, "maybe\na\nr\n", None)
        .succeeds()
        .stdout_has("[1/2] changed: flange / frame 1151")
        .stdout_has("1 pixels differ (worst by 1)")
        .stdout_has("diff.png")
        .stdout_has("\"maybe\": answer a, r, s or q")
        .stdout_has("review: 1 accepted, 1 rejected, 0 left pending");
    let golden = |v: &str| std::fs::read(copy.join(format!("golden/flange/{v}.png"))).unwrap();
    let ours = |v: &str| std::fs::read(repo_root().join(format!("golden/flange/{v}.png"))).unwrap();
    assert_eq!(
        golden("frame-1151"),
        ours("frame-1151"),
        "the accepted render is the golden"
    );
    assert_ne!(
        golden("frame-920"),
        ours("frame-920"),
        "the rejected change left the golden alone"
    );
    review(&copy, "", None).stdout_has("nothing pending");
}

/// A write that was killed leaves a recognisable temporary file: `approve
/// --list` reports it, `approve` removes it, and a live writer's is kept.
#[test]
fn stale_temporary_files_are_reported_and_removed() {
    let dir = Scratch::new("stale");
    vstf()
        .current_dir(&dir)
        .args(["init", "p"])
        .run()
        .succeeds();
    let project = dir.join("p");
    std::fs::create_dir_all(project.join("golden/moving-cube")).unwrap();
    // No process has this id.
    let stale = project.join(format!(
        "golden/moving-cube/.t-10.png.vstf-tmp-{}",
        u32::MAX - 1
    ));
    std::fs::write(&stale, "half a png").unwrap();
    vstf()
        .current_dir(&project)
        .args(["approve", "--list"])
        .run()
        .stdout_has("stale")
        .stdout_has(".t-10.png.vstf-tmp-");
    assert!(stale.exists(), "--list removed it");
    in_project(&project, &["approve", "--all"]).succeeds();
    assert!(!stale.exists());
}
