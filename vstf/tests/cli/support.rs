//! Running the built `vstf` and judging what it did; scratch folders and
//! copies of this repository's fixtures and goldens to run it in.

use std::ffi::OsStr;
use std::fmt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output};
use std::sync::Mutex;

/// The repository's root, where the paper's fixtures and goldens live.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap()
}

/// The built binary, run from this repository's root (the project of the
/// paper's fixtures), with none of the batch engines' shard variables set
/// (a sharded CI job would otherwise shard every run). Finish it with
/// [`RunExt::run`], or spawn it where a test talks to the process.
pub fn vstf() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_vstf"));
    c.current_dir(repo_root())
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("SLURM_ARRAY_TASK_MIN")
        .env_remove("JOB_COMPLETION_INDEX")
        .env_remove("AWS_BATCH_JOB_ARRAY_INDEX");
    c
}

/// Runs a command to its end, capturing what it wrote, or starts it.
pub trait RunExt {
    /// The finished run.
    fn run(&mut self) -> Run;

    /// The process started, with the pipes the command asked for.
    fn start(&mut self) -> Running;
}

impl RunExt for Command {
    fn run(&mut self) -> Run {
        let command = format!("{self:?}");
        let output = self
            .output()
            .unwrap_or_else(|e| panic!("{command} did not start: {e}"));
        Run::of(command, output)
    }

    fn start(&mut self) -> Running {
        let command = format!("{self:?}");
        let child = self
            .spawn()
            .unwrap_or_else(|e| panic!("{command} did not start: {e}"));
        Running { command, child }
    }
}

/// A `vstf` process that a test talks to (or signals) while it runs.
pub struct Running {
    command: String,
    /// The process, its pipes to take.
    pub child: Child,
}

impl Running {
    /// Waits for its end and collects what it wrote to the pipes.
    pub fn finish(self) -> Run {
        let output = self.child.wait_with_output().unwrap();
        Run::of(self.command, output)
    }
}

/// A finished run of `vstf`: its status and what it wrote. The assertions
/// print the command, its status, stdout and stderr when they fail.
pub struct Run {
    command: String,
    output: Output,
    stdout: String,
    stderr: String,
}

impl Run {
    fn of(command: String, output: Output) -> Self {
        Run {
            command,
            stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
            output,
        }
    }

    /// Whether it exited with status 0.
    pub fn success(&self) -> bool {
        self.output.status.success()
    }

    /// Its exit code (none if a signal ended it).
    pub fn code(&self) -> Option<i32> {
        self.output.status.code()
    }

    /// Its standard output, lossily decoded.
    pub fn stdout(&self) -> &str {
        &self.stdout
    }

    /// Its standard error, lossily decoded.
    pub fn stderr(&self) -> &str {
        &self.stderr
    }

    /// Its standard output as written.
    pub fn stdout_bytes(&self) -> &[u8] {
        &self.output.stdout
    }

    /// Asserts that it exited with status 0.
    #[track_caller]
    pub fn succeeds(&self) -> &Self {
        assert!(self.success(), "expected success: {self}");
        self
    }

    /// Asserts that it failed, as an error and not a panic.
    #[track_caller]
    pub fn fails(&self) -> &Self {
        assert!(!self.success(), "expected a failure: {self}");
        self.stderr_lacks("panicked")
    }

    /// Asserts that it failed (not in a panic) and that its stderr says
    /// `message`.
    #[track_caller]
    pub fn fails_with(&self, message: &str) -> &Self {
        self.fails().stderr_has(message)
    }

    /// Asserts that its stderr contains `text`.
    #[track_caller]
    pub fn stderr_has(&self, text: &str) -> &Self {
        self.says("stderr", &self.stderr, text, true)
    }

    /// Asserts that its stderr does not contain `text`.
    #[track_caller]
    pub fn stderr_lacks(&self, text: &str) -> &Self {
        self.says("stderr", &self.stderr, text, false)
    }

    /// Asserts that its stdout contains `text`.
    #[track_caller]
    pub fn stdout_has(&self, text: &str) -> &Self {
        self.says("stdout", &self.stdout, text, true)
    }

    /// Asserts that its stdout does not contain `text`.
    #[track_caller]
    pub fn stdout_lacks(&self, text: &str) -> &Self {
        self.says("stdout", &self.stdout, text, false)
    }

    /// Asserts that `stream` (one of its two, named `name`) contains `text`
    /// or, if not `has`, does not.
    #[track_caller]
    fn says(&self, name: &str, stream: &str, text: &str, has: bool) -> &Self {
        let what = if has { "lacks" } else { "has" };
        assert!(
            stream.contains(text) == has,
            "{name} {what} {text:?}: {self}"
        );
        self
    }
}

impl fmt::Display for Run {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}\n{}\n--- stdout\n{}\n--- stderr\n{}",
            self.command, self.output.status, self.stdout, self.stderr
        )
    }
}

/// A scratch folder of this test binary's process, empty when made and
/// removed when dropped, unless the test is failing (so that what the run
/// left can be looked at).
pub struct Scratch(PathBuf);

/// The scratch folders' names taken so far in this process.
static TAKEN: Mutex<Vec<String>> = Mutex::new(Vec::new());

impl Scratch {
    /// A fresh, empty folder for one test; `name` is unique to it.
    #[track_caller]
    pub fn new(name: &str) -> Self {
        let mut taken = TAKEN.lock().unwrap_or_else(|e| e.into_inner());
        assert!(
            !taken.iter().any(|t| t == name),
            "two tests use the scratch folder {name:?}"
        );
        taken.push(name.to_string());
        drop(taken);
        let dir = std::env::temp_dir().join(format!("vstf-cli-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    /// A fresh folder holding a copy of this repository's `fixtures/` and
    /// `golden/`: a project whose goldens a test may change.
    #[track_caller]
    pub fn repo_copy(name: &str) -> Self {
        let copy = Scratch::new(name);
        for dir in ["fixtures", "golden"] {
            copy_tree(&repo_root().join(dir), &copy.join(dir));
        }
        copy
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<OsStr> for Scratch {
    fn as_ref(&self) -> &OsStr {
        self.0.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            std::fs::remove_dir_all(&self.0).ok();
        }
    }
}

/// Copies the files of `from` into `to`, recursively.
pub fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).unwrap();
        }
    }
}

/// Flips one bit of one pixel of a PNG in place.
pub fn tamper(png: &Path) {
    let mut img = image::open(png).unwrap().to_rgb8();
    let p = img.get_pixel(10, 10).0;
    img.put_pixel(10, 10, image::Rgb([p[0] ^ 0x01, p[1], p[2]]));
    img.save(png).unwrap();
}

/// The RGB image of the PNG at `path`.
#[track_caller]
pub fn rgb(path: &Path) -> image::RgbImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
}

/// Sends SIGINT (a Ctrl-C) to the process `pid`.
pub fn interrupt(pid: u32) {
    Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
}

/// Whether every tool is on PATH; if not, a failure under
/// `VSTF_REQUIRE_MEDIA`, else a loud skip.
pub fn media(tools: &[&str], test: &str) -> bool {
    let path = std::env::var_os("PATH").unwrap_or_default();
    let missing: Vec<&str> = tools
        .iter()
        .copied()
        .filter(|t| !std::env::split_paths(&path).any(|d| d.join(t).is_file()))
        .collect();
    if missing.is_empty() {
        return true;
    }
    let msg = format!(
        "{} not on PATH: {test} did not run (apt-get install ffmpeg openimageio-tools)",
        missing.join(", ")
    );
    assert!(std::env::var_os("VSTF_REQUIRE_MEDIA").is_none(), "{msg}");
    eprintln!("SKIPPED: {msg}");
    false
}
