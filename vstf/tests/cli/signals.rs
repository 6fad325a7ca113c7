//! How a run ends when it is interrupted (Ctrl-C, once or twice) or when
//! the reader of its output goes away.

use crate::support::{interrupt, rgb, vstf, RunExt, Scratch};
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// How many PNG files `dir` holds (none if it is not there yet).
fn pngs_in(dir: &Path) -> usize {
    std::fs::read_dir(dir).map_or(0, |d| {
        d.filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "png"))
        })
        .count()
    })
}

#[test]
fn ctrl_c_leaves_every_finished_frame() {
    let scratch = Scratch::new("int");
    // A folder not made yet: animate makes the folders it writes into.
    let dir = scratch.join("new");
    let gif = dir.join("long.gif");
    let running = vstf()
        .args([
            "animate", "flange", "--frames", "0..50000", "--step", "1", "--width", "64",
            "--height", "48", "--out",
        ])
        .arg(&gif)
        .stderr(Stdio::piped())
        .start();
    let frames = dir.join("long.gif.frames");
    let started = Instant::now();
    while pngs_in(&frames) < 3 {
        assert!(started.elapsed().as_secs() < 60, "no frames appeared");
        std::thread::sleep(Duration::from_millis(20));
    }
    interrupt(running.child.id());
    running.finish().fails_with("interrupted:");
    let names: Vec<_> = std::fs::read_dir(&frames)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !p.ends_with("animation.txt"))
        .collect();
    assert!(names.len() >= 3);
    for p in &names {
        assert!(
            p.extension().is_some_and(|e| e == "png"),
            "a partial file was left: {}",
            p.display()
        );
        rgb(p);
    }
}

/// A second Ctrl-C ends `animate` at once.
#[test]
fn a_second_ctrl_c_exits_at_once() {
    let dir = Scratch::new("twice");
    let mut child = vstf()
        .args([
            "animate", "teaser", "--frames", "0..50000", "--width", "320", "--height", "180",
            "--force", "--out",
        ])
        .arg(dir.join("frames"))
        .stderr(Stdio::null())
        .start()
        .child;
    let started = Instant::now();
    while std::fs::read_dir(dir.join("frames")).map_or(0, |d| d.count()) < 2 {
        assert!(started.elapsed().as_secs() < 60, "no frames appeared");
        assert!(child.try_wait().unwrap().is_none(), "animate ended early");
        std::thread::sleep(Duration::from_millis(20));
    }
    for _ in 0..2 {
        interrupt(child.id());
        std::thread::sleep(Duration::from_millis(50));
    }
    let asked = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(
            asked.elapsed().as_secs() < 5,
            "still running after two Ctrl-C"
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    assert_eq!(status.code(), Some(130));
}

/// Output into a pipe that is closed ends quietly with the status of a
/// SIGPIPE death (141), not in a panic (exit code 101).
#[test]
fn a_closed_pipe_ends_list_quietly() {
    let mut running = vstf()
        .args(["list"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .start();
    // Close the pipe before `list` has loaded its fixtures and printed.
    drop(running.child.stdout.take());
    let done = running.finish();
    done.stderr_lacks("panicked");
    assert_eq!(done.code(), Some(141), "{done}");
}
