//! `vstf serve` as a process: it runs with glibc's mmap threshold fixed,
//! so that the memory of the scenes its cache evicts goes back to the
//! system (docs/security.md, 'Limits'), unless the user set the threshold.

use crate::support::{vstf, Scratch};
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Stdio};

/// A server killed when the test ends, however it ends.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `vstf serve` in an empty project at `dir`, with `threshold` as the
/// environment's `MALLOC_MMAP_THRESHOLD_` (none: unset), once it serves;
/// the value its process runs with.
fn served_threshold(dir: &Path, threshold: Option<&str>) -> Option<String> {
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    let mut command = vstf();
    command
        .current_dir(dir)
        .args(["serve", "--port", "0"])
        .env_remove("MALLOC_MMAP_THRESHOLD_")
        .stdout(Stdio::piped());
    if let Some(t) = threshold {
        command.env("MALLOC_MMAP_THRESHOLD_", t);
    }
    let mut server = Server(command.spawn().unwrap());
    let mut line = String::new();
    BufReader::new(server.0.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert!(line.contains("http://127.0.0.1:"), "not serving: {line:?}");
    let environ = std::fs::read(format!("/proc/{}/environ", server.0.id())).unwrap();
    environ
        .split(|&b| b == 0)
        .filter_map(|v| v.strip_prefix(b"MALLOC_MMAP_THRESHOLD_="))
        .map(|v| String::from_utf8_lossy(v).into_owned())
        .next()
}

/// Started without the setting, the server runs with it (the same process,
/// started again: its first line comes from the restarted one).
#[test]
fn serve_runs_with_a_fixed_mmap_threshold() {
    let dir = Scratch::new("serve-threshold");
    assert_eq!(served_threshold(&dir, None).as_deref(), Some("131072"));
}

/// The control: a threshold the user chose is the one the server runs with.
#[test]
fn a_threshold_the_user_set_is_kept() {
    let dir = Scratch::new("serve-user-threshold");
    assert_eq!(
        served_threshold(&dir, Some("262144")).as_deref(),
        Some("262144")
    );
}
