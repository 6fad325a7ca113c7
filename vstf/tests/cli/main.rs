//! The `vstf` binary as a user runs it: one test binary (linked once), its
//! modules by command, all running the built executable through `support`.

mod support;

/// `vstf animate`: sequences, GIFs and APNGs, labels, resuming.
mod animate;
/// `vstf bench --quick`.
mod bench;
/// `vstf serve` driven in a real browser (skips without chromium).
mod browser;
/// `vstf serve`'s page as a user sees it, in a real browser: captions,
/// images, sliders, a screenshot.
mod browser_page;
/// `vstf check`: its table, JSON and golden images, in and out of a copy
/// of this repository.
mod check;
/// `vstf debug` and `vstf debug-diff`.
mod debug;
/// `vstf approve`, `reject` and `review`: golden images one view at a time.
mod golden;
/// `render --out` EXR (with its layers) and JPEG.
mod outputs;
/// Projects: none, one from `vstf init`, a fixture given as a file.
mod project;
/// `vstf render` and `vstf list --views`.
mod render;
/// A new user's scenes, their views at solved camera times, checked
/// outside any project.
mod scenes;
/// `vstf serve` as a process: the allocator setting it runs with.
#[cfg(target_os = "linux")]
mod serve;
/// Sharded `animate` and `check` runs and `vstf merge`.
mod shards;
/// How a run ends when interrupted or when its reader goes away.
mod signals;
/// The sharded jobs of docs/scaling.md on a one-machine Slurm cluster
/// (skips without Slurm).
mod slurm;
/// `animate --out` videos through ffmpeg.
mod videos;
