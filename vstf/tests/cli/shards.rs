//! Sharded runs as a batch engine runs them: each shard a separate `vstf`
//! process, the shards' outputs merged by `vstf merge`, and the whole
//! compared with an unsharded run; merges of incomplete, duplicated or
//! mismatched shards refused.

use crate::support::{vstf, Run, RunExt, Scratch};
use std::path::Path;
use std::process::Command;

/// `vstf animate` of seven small teaser frames into `out`, with `extra`.
fn animate(out: &Path, extra: &[&str]) -> Command {
    let mut c = vstf();
    c.args([
        "animate", "teaser", "--frames", "10..16", "--width", "48", "--height", "27", "--out",
    ])
    .arg(out)
    .args(extra);
    c
}

fn frames(dir: &Path) -> Vec<Vec<u8>> {
    (0..7)
        .map(|i| std::fs::read(dir.join(format!("frame-{i:05}.png"))).unwrap())
        .collect()
}

#[test]
fn animation_shards_in_separate_processes_merge_bit_identical() {
    let dir = Scratch::new("shards-anim");
    animate(&dir.join("whole"), &[]).run().succeeds();
    // Shards 1 and 3 share a folder; shard 2 writes its own (another
    // machine), with its index from a Kubernetes Indexed Job's variable.
    animate(&dir.join("shared"), &["--shard", "1/3"])
        .run()
        .succeeds();
    animate(&dir.join("shared"), &["--shard", "3/3"])
        .run()
        .succeeds();
    animate(&dir.join("other"), &["--shard", "3"])
        .env("JOB_COMPLETION_INDEX", "1")
        .run()
        .succeeds();
    let merge = |out: &Path, dirs: &[&str]| -> Run {
        vstf()
            .arg("merge")
            .arg("--out")
            .arg(out)
            .args(dirs.iter().map(|d| dir.join(d)))
            .run()
    };
    merge(&dir.join("m"), &["shared"]).fails_with("missing shard(s) 2 of 3");
    merge(&dir.join("merged"), &["shared", "other"]).succeeds();
    assert_eq!(
        frames(&dir.join("merged")),
        frames(&dir.join("whole")),
        "merged frames differ from the unsharded run"
    );
    merge(&dir.join("a.gif"), &["shared", "other"]).succeeds();
    assert!(std::fs::metadata(dir.join("a.gif")).unwrap().len() > 0);
    // The same shard from two folders is a duplicate.
    animate(&dir.join("again"), &["--shard", "2/3"])
        .run()
        .succeeds();
    merge(&dir.join("m"), &["shared", "other", "again"]).fails_with("shard 2/3 twice");
    // A shard of another animation (other samples) is refused.
    animate(&dir.join("bigger"), &["--shard", "2/3", "--spp", "2"])
        .run()
        .succeeds();
    merge(&dir.join("m"), &["shared", "bigger"]).fails_with("not of one job");
    // A frame changed after its shard wrote it is refused.
    let frame = dir.join("other/frame-00001.png");
    let mut bytes = std::fs::read(&frame).unwrap();
    let last = bytes.len() - 20;
    bytes[last] ^= 1;
    std::fs::write(&frame, bytes).unwrap();
    merge(&dir.join("m"), &["shared", "other"]).fails_with("changed since shard 2/3 wrote it");
}

#[test]
fn shard_arguments_and_indices_are_checked() {
    let dir = Scratch::new("shards-args");
    for bad in ["0/3", "4/3", "a/3", "3"] {
        animate(&dir.join("x"), &["--shard", bad])
            .run()
            .fails_with("--shard");
    }
    animate(&dir.join("x"), &["--shard", "3"])
        .env("AWS_BATCH_JOB_ARRAY_INDEX", "3")
        .run()
        .fails_with("shard 4 of 3");
    vstf()
        .args(["merge", "--out"])
        .arg(dir.join("m"))
        .arg(&dir)
        .run()
        .fails_with("no shard manifests");
}

#[test]
fn check_shards_merge_into_the_rows_of_an_unsharded_run() {
    let dir = Scratch::new("shards-check");
    let fixtures = ["flange", "blink", "doppler", "lit-plate"];
    let check = |extra: &[&str]| {
        vstf()
            .arg("check")
            .args(fixtures)
            .arg("--quick")
            .args(extra)
            .run()
    };
    let whole = dir.join("whole.json");
    check(&["--json", whole.to_str().unwrap()]).succeeds();
    let shards = dir.join("shards");
    for i in 1..=3 {
        check(&[
            "--shard",
            &format!("{i}/3"),
            "--shard-dir",
            shards.to_str().unwrap(),
        ])
        .succeeds()
        .stderr_has(&format!("shard {i}/3"));
    }
    let merged = dir.join("merged.json");
    let report = dir.join("report");
    vstf()
        .arg("merge")
        .arg(&shards)
        .args([
            "--json",
            merged.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ])
        .run()
        .succeeds()
        .stderr_has("check: 4 fixtures");
    let rows = |p: &Path| {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
        let mut rows = v["rows"].as_array().unwrap().clone();
        rows.sort_by_key(|r| format!("{}/{}", r["fixture"], r["quantity"]));
        rows
    };
    assert_eq!(
        rows(&merged),
        rows(&whole),
        "merged rows differ from the unsharded run"
    );
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    for f in fixtures {
        assert!(
            html.contains(&format!("<section id=\"{f}\">")),
            "{f} missing from the report"
        );
    }
    // Without one shard's folder the merge is refused.
    std::fs::remove_dir_all(shards.join("check-2-of-3")).unwrap();
    vstf()
        .arg("merge")
        .arg(&shards)
        .run()
        .fails_with("missing shard(s) 2 of 3");
}
