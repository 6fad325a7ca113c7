//! Sharded runs as a batch engine runs them: each shard a separate `vstf`
//! process, the shards' outputs merged by `vstf merge`, and the whole
//! compared with an unsharded run; merges of incomplete, duplicated or
//! mismatched shards refused.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The built binary, run from this repository's root.
fn vstf() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_vstf"));
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    c.env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("SLURM_ARRAY_TASK_MIN")
        .env_remove("JOB_COMPLETION_INDEX")
        .env_remove("AWS_BATCH_JOB_ARRAY_INDEX");
    c
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vstf-shards-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn ok(o: Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(o.status.success(), "{err}");
    err
}

fn refused(o: Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(!o.status.success(), "accepted: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

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
    let dir = scratch("anim");
    ok(animate(&dir.join("whole"), &[]).output().unwrap());
    // Shards 1 and 3 share a folder; shard 2 writes its own (another
    // machine), with its index from a Kubernetes Indexed Job's variable.
    ok(animate(&dir.join("shared"), &["--shard", "1/3"])
        .output()
        .unwrap());
    ok(animate(&dir.join("shared"), &["--shard", "3/3"])
        .output()
        .unwrap());
    ok(animate(&dir.join("other"), &["--shard", "3"])
        .env("JOB_COMPLETION_INDEX", "1")
        .output()
        .unwrap());
    let merge = |out: &Path, dirs: &[&str]| {
        let mut c = vstf();
        c.arg("merge").arg("--out").arg(out);
        c.args(dirs.iter().map(|d| dir.join(d)));
        c.output().unwrap()
    };
    let err = refused(merge(&dir.join("m"), &["shared"]));
    assert!(err.contains("missing shard(s) 2 of 3"), "{err}");
    ok(merge(&dir.join("merged"), &["shared", "other"]));
    assert_eq!(
        frames(&dir.join("merged")),
        frames(&dir.join("whole")),
        "merged frames differ from the unsharded run"
    );
    ok(merge(&dir.join("a.gif"), &["shared", "other"]));
    assert!(std::fs::metadata(dir.join("a.gif")).unwrap().len() > 0);
    // The same shard from two folders is a duplicate.
    ok(animate(&dir.join("again"), &["--shard", "2/3"])
        .output()
        .unwrap());
    let err = refused(merge(&dir.join("m"), &["shared", "other", "again"]));
    assert!(err.contains("shard 2/3 twice"), "{err}");
    // A shard of another animation (other samples) is refused.
    ok(
        animate(&dir.join("bigger"), &["--shard", "2/3", "--spp", "2"])
            .output()
            .unwrap(),
    );
    let err = refused(merge(&dir.join("m"), &["shared", "bigger"]));
    assert!(err.contains("not of one job"), "{err}");
    // A frame changed after its shard wrote it is refused.
    let frame = dir.join("other/frame-00001.png");
    let mut bytes = std::fs::read(&frame).unwrap();
    let last = bytes.len() - 20;
    bytes[last] ^= 1;
    std::fs::write(&frame, bytes).unwrap();
    let err = refused(merge(&dir.join("m"), &["shared", "other"]));
    assert!(err.contains("changed since shard 2/3 wrote it"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn shard_arguments_and_indices_are_checked() {
    let dir = scratch("args");
    for bad in ["0/3", "4/3", "a/3", "3"] {
        let err = refused(animate(&dir.join("x"), &["--shard", bad]).output().unwrap());
        assert!(err.contains("--shard"), "{bad}: {err}");
    }
    let err = refused(
        animate(&dir.join("x"), &["--shard", "3"])
            .env("AWS_BATCH_JOB_ARRAY_INDEX", "3")
            .output()
            .unwrap(),
    );
    assert!(err.contains("shard 4 of 3"), "{err}");
    let err = refused(
        vstf()
            .args(["merge", "--out"])
            .arg(dir.join("m"))
            .arg(&dir)
            .output()
            .unwrap(),
    );
    assert!(err.contains("no shard manifests"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn check_shards_merge_into_the_rows_of_an_unsharded_run() {
    let dir = scratch("check");
    let fixtures = ["flange", "blink", "doppler", "lit-plate"];
    let check = |extra: &[&str]| {
        let mut c = vstf();
        c.arg("check").args(fixtures).arg("--quick").args(extra);
        c.output().unwrap()
    };
    let whole = dir.join("whole.json");
    ok(check(&["--json", whole.to_str().unwrap()]));
    let shards = dir.join("shards");
    for i in 1..=3 {
        let out = ok(check(&[
            "--shard",
            &format!("{i}/3"),
            "--shard-dir",
            shards.to_str().unwrap(),
        ]));
        assert!(out.contains(&format!("shard {i}/3")), "{out}");
    }
    let merged = dir.join("merged.json");
    let report = dir.join("report");
    let said = ok(vstf()
        .arg("merge")
        .arg(&shards)
        .args([
            "--json",
            merged.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ])
        .output()
        .unwrap());
    assert!(said.contains("check: 4 fixtures"), "{said}");
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
    let err = refused(vstf().arg("merge").arg(&shards).output().unwrap());
    assert!(err.contains("missing shard(s) 2 of 3"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
