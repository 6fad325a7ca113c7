//! Sharding on a real batch engine: a one-machine Slurm cluster (Debian's
//! `slurm-wlm` and `munge`) started for the test in a scratch folder, the
//! job scripts of docs/scaling.md read from that page and submitted word
//! for word, and the merged animation (every frame and the GIF) and check
//! table (the printed table and the JSON rows) compared bit for bit with
//! unsharded runs of the same commands.
//!
//! Without Slurm's programs, as a user other than root, or when the
//! cluster does not start, the test says why (a daemon's own words) and
//! skips; with `VSTF_REQUIRE_SLURM` set (as `.ci/run` does once it has
//! installed them) each of these is a failure.

mod cluster;

use crate::support::{repo_root, vstf, RunExt, Scratch};
use cluster::{tail, Cluster, Job};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// How long the jobs may take before the test gives up, printing the
/// queue and the logs.
const TIMEOUT: Duration = Duration::from_secs(600);

/// Says why the test did not run: a failure under `VSTF_REQUIRE_SLURM`,
/// else a loud skip.
fn skip(why: &str) {
    let msg = format!("the Slurm test did not run: {why}");
    assert!(std::env::var_os("VSTF_REQUIRE_SLURM").is_none(), "{msg}");
    eprintln!("SKIPPED: {msg}");
}

/// The Slurm section of docs/scaling.md: each script under its file name
/// and each block of submission commands, as the page gives them.
struct Doc {
    scripts: Vec<(String, String)>,
    submissions: Vec<String>,
}

impl Doc {
    fn read() -> Doc {
        let page = std::fs::read_to_string(repo_root().join("docs/scaling.md")).unwrap();
        let start = page
            .find("\n## Slurm\n")
            .expect("docs/scaling.md has no Slurm section");
        let section = &page[start + 1..];
        let section = &section[..section[3..].find("\n## ").map_or(section.len(), |e| e + 3)];
        let mut doc = Doc {
            scripts: Vec::new(),
            submissions: Vec::new(),
        };
        let mut name: Option<String> = None;
        let mut lines = section.lines();
        while let Some(line) = lines.next() {
            if let Some(file) = line.strip_prefix('`').and_then(|l| l.strip_suffix("`:")) {
                name = Some(file.to_string());
            } else if line == "```bash" {
                let block: String = lines
                    .by_ref()
                    .take_while(|l| *l != "```")
                    .map(|l| format!("{l}\n"))
                    .collect();
                match name.take() {
                    Some(file) => doc.scripts.push((file, block)),
                    None => doc.submissions.push(block),
                }
            }
        }
        doc
    }

    /// The words of the `vstf COMMAND` line of the script `file`.
    fn vstf_line(&self, file: &str, command: &str) -> Words {
        let (_, script) = self
            .scripts
            .iter()
            .find(|(f, _)| f == file)
            .unwrap_or_else(|| panic!("docs/scaling.md gives no {file}"));
        let line = script
            .lines()
            .find(|l| l.starts_with(&format!("vstf {command} ")))
            .unwrap_or_else(|| panic!("{file} in docs/scaling.md runs no `vstf {command}`"));
        assert!(
            !line.contains(['"', '\'', '$']),
            "{file}: the test splits `{line}` at spaces"
        );
        Words(line.split_whitespace().skip(1).map(String::from).collect())
    }
}

/// A `vstf` command line's arguments.
struct Words(Vec<String>);

impl Words {
    /// The value given to `flag`.
    fn value(&self, flag: &str) -> &str {
        let i = self.0.iter().position(|w| w == flag);
        let value = i.and_then(|i| self.0.get(i + 1));
        value.unwrap_or_else(|| panic!("{:?} has no {flag} value", self.0))
    }

    /// The same command unsharded: `--shard N` left out and, if `out` is
    /// given, `--out` pointed there.
    fn unsharded(&self, out: Option<&str>) -> Vec<String> {
        let mut words = Vec::new();
        let mut it = self.0.iter();
        while let Some(w) = it.next() {
            match w.as_str() {
                "--shard" => {
                    it.next();
                }
                "--out" if out.is_some() => {
                    it.next();
                    words.extend(["--out".to_string(), out.unwrap().to_string()]);
                }
                _ => words.push(w.clone()),
            }
        }
        words
    }
}

/// A shell in the project `dir` with this cluster's configuration and the
/// built `vstf` first on PATH (jobs inherit both), and none of the batch
/// engines' shard variables of a run that is itself sharded.
fn shell(cluster: &Cluster, dir: &Path, script: &str) -> Command {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_vstf"));
    let path = std::env::var_os("PATH").unwrap_or_default();
    let path = std::env::join_paths(
        std::iter::once(bin.parent().unwrap().to_path_buf()).chain(std::env::split_paths(&path)),
    )
    .unwrap();
    let mut c = Command::new("bash");
    c.args(["-euo", "pipefail", "-c", script])
        .current_dir(dir)
        .env("PATH", path)
        .env("SLURM_CONF", cluster.conf())
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("SLURM_ARRAY_TASK_MIN")
        .env_remove("JOB_COMPLETION_INDEX")
        .env_remove("AWS_BATCH_JOB_ARRAY_INDEX");
    c
}

/// The tail of every job's log in the project `dir`.
fn job_logs(dir: &Path) -> String {
    let mut logs: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "log" || x == "err"))
        .collect();
    logs.sort();
    logs.iter()
        .map(|p| format!("--- {}\n{}\n", p.display(), tail(p, 15)))
        .collect()
}

/// The one file in `dir` whose name starts with `prefix` and ends with
/// `suffix`.
fn only(dir: &Path, prefix: &str, suffix: &str) -> PathBuf {
    let found: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let n = p.file_name().unwrap().to_string_lossy();
            n.starts_with(prefix) && n.ends_with(suffix)
        })
        .collect();
    assert_eq!(
        found.len(),
        1,
        "{prefix}*{suffix} in {}: {found:?}",
        dir.display()
    );
    found.into_iter().next().unwrap()
}

/// The animation frames in `dir`, by name, with their bytes.
fn frames(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut frames: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("frame-") && n.ends_with(".png"))
        .map(|n| (n.clone(), std::fs::read(dir.join(&n)).unwrap()))
        .collect();
    frames.sort();
    frames
}

/// The cluster's queue and logs, then the jobs' logs in `project`.
fn diagnosis(cluster: &Cluster, project: &Path) -> String {
    format!("{}\n{}", cluster.diagnosis(), job_logs(project))
}

/// How many jobs (array tasks) named `name` there are, asserting that each
/// completed.
fn completed(jobs: &[Job], name: &str, cluster: &Cluster, project: &Path) -> usize {
    let mine: Vec<&Job> = jobs.iter().filter(|j| j.name == name).collect();
    assert!(
        !mine.is_empty() && mine.iter().all(|j| j.state == "COMPLETED"),
        "{name}: {mine:?}\n{}",
        diagnosis(cluster, project)
    );
    mine.len()
}

/// The shards' frames and the merge job's GIF against unsharded runs of
/// the same `vstf animate` in the project `dir`.
fn animation_is_bit_identical(doc: &Doc, dir: &Path) {
    let anim = doc.vstf_line("animate.sbatch", "animate");
    let run = |args: Vec<String>| vstf().current_dir(dir).args(args).run();
    run(anim.unsharded(Some("whole-frames"))).succeeds();
    run(anim.unsharded(Some("whole.gif"))).succeeds();
    let sharded = frames(&dir.join(anim.value("--out")));
    let (a, b) = anim.value("--frames").split_once("..").unwrap();
    let step: f64 = anim.value("--step").parse().unwrap();
    let count = ((b.parse::<f64>().unwrap() - a.parse::<f64>().unwrap()) / step) as usize + 1;
    assert_eq!(sharded.len(), count, "frames of the sharded run");
    assert!(
        sharded == frames(&dir.join("whole-frames")),
        "the frames of the Slurm run differ from an unsharded run's"
    );
    let gif = doc.vstf_line("merge.sbatch", "merge");
    assert!(
        std::fs::read(dir.join(gif.value("--out"))).unwrap()
            == std::fs::read(dir.join("whole.gif")).unwrap(),
        "the merge job's GIF differs from an unsharded run's"
    );
}

/// The table the check merge job printed, its JSON rows and its report
/// against an unsharded run of the same `vstf check` in the project `dir`.
fn check_table_is_bit_identical(doc: &Doc, dir: &Path) {
    let check = doc.vstf_line("check.sbatch", "check");
    let whole = vstf()
        .current_dir(dir)
        .args(check.unsharded(None))
        .args(["--json", "whole.json"])
        .run();
    whole.succeeds();
    let table = std::fs::read_to_string(only(dir, "vstf-check-merge-", ".log")).unwrap();
    assert!(
        table
            .lines()
            .any(|l| l.starts_with("check: ") && l.ends_with(" passed, 0 failed")),
        "{table}"
    );
    assert_eq!(table, whole.stdout(), "the merged table differs");
    let merge = doc.vstf_line("check-merge.sbatch", "merge");
    assert!(
        std::fs::read(dir.join(merge.value("--json"))).unwrap()
            == std::fs::read(dir.join("whole.json")).unwrap(),
        "the merged JSON rows differ from an unsharded run's"
    );
    let report = dir.join(merge.value("--report")).join("index.html");
    assert!(report.is_file(), "no {}", report.display());
}

/// Negative control: an array wider than the shard count. Its task 1
/// renders shard 1 again; vstf refuses task 5 and Slurm reports it failed.
fn a_task_beyond_the_shards_fails(cluster: &mut Cluster, dir: &Path) {
    let out = shell(cluster, dir, "sbatch --parsable --array=1,5 animate.sbatch")
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let id = String::from_utf8_lossy(&out.stdout).trim().to_string();
    let jobs = cluster.wait(TIMEOUT).unwrap();
    let state = |task: u32| {
        let job = jobs.iter().find(|j| j.id == format!("{id}_{task}"));
        job.map_or_else(
            || format!("no task {id}_{task} in {jobs:?}"),
            |j| j.state.clone(),
        )
    };
    assert_eq!(state(1), "COMPLETED", "{}", diagnosis(cluster, dir));
    assert_eq!(state(5), "FAILED", "{}", diagnosis(cluster, dir));
    let log = std::fs::read_to_string(dir.join(format!("vstf-{id}_5.log"))).unwrap();
    assert!(log.contains("shard 5 of 4"), "{log}");
}

#[test]
fn the_documented_slurm_jobs_merge_bit_identical_to_unsharded_runs() {
    if let Some(why) = cluster::cannot_run_here() {
        return skip(&why);
    }
    let doc = Doc::read();
    let names: Vec<&str> = doc.scripts.iter().map(|(f, _)| f.as_str()).collect();
    assert_eq!(
        names,
        [
            "animate.sbatch",
            "merge.sbatch",
            "check.sbatch",
            "check-merge.sbatch"
        ],
        "the scripts of docs/scaling.md"
    );
    assert_eq!(doc.submissions.len(), 2, "docs/scaling.md's submissions");
    let project = Scratch::repo_copy("slurm-project");
    let state = Scratch::new("slurm-cluster");
    let started = Instant::now();
    let mut cluster = match Cluster::start(&state) {
        Ok(c) => c,
        Err(e) => return skip(&format!("the cluster did not start: {e}")),
    };
    let up = started.elapsed();
    for (file, text) in &doc.scripts {
        std::fs::write(project.join(file), text).unwrap();
    }
    let submitted = Instant::now();
    for block in &doc.submissions {
        let out = shell(&cluster, &project, block).output().unwrap();
        assert!(out.status.success(), "{block}: {out:?}");
    }
    let jobs = cluster
        .wait(TIMEOUT)
        .unwrap_or_else(|e| panic!("{e}\n{}", job_logs(&project)));
    let ran = submitted.elapsed();
    let shards: usize = doc
        .vstf_line("animate.sbatch", "animate")
        .value("--shard")
        .parse()
        .unwrap();
    let done = |name: &str| completed(&jobs, name, &cluster, &project);
    assert_eq!(done("vstf-animate"), shards);
    assert_eq!(done("vstf-check"), shards);
    assert_eq!(done("vstf-merge"), 1);
    assert_eq!(done("vstf-check-merge"), 1);
    let unsharded = Instant::now();
    animation_is_bit_identical(&doc, &project);
    check_table_is_bit_identical(&doc, &project);
    eprintln!(
        "slurm: cluster up in {:.1} s; {} jobs and array tasks ended {:.1} s after \
         submission; unsharded runs {:.1} s; frames, GIF, table and rows bit-identical",
        up.as_secs_f64(),
        jobs.len(),
        ran.as_secs_f64(),
        unsharded.elapsed().as_secs_f64()
    );
    a_task_beyond_the_shards_fails(&mut cluster, &project);
}
