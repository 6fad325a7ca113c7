//! The cost of motion in section 7 of `vstf bench`, measured in one
//! process on one core: the tori moving at 0.9c and the same tori at rest,
//! both loaded and built, their primary rays traced in alternate frames by
//! one thread bound to one core. On a shared machine a frame's time moves
//! by up to a third from one process to the next, and on two threads from
//! one frame to the next, while one bound thread's frames agree to a
//! percent (docs/performance.md, "Stop 61"). The ratio across two
//! processes on every thread is printed beside it.

use super::primary::{self, cpu_seconds, trace};
use crate::fixture::{Fixture, Overrides};
use renderer::Traversal;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The best frame's CPU seconds tracing each scene's primary rays, the
/// two traced in turn in one process, and how many of each scene's rays
/// hit.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
pub struct Paired {
    /// The moving tori.
    pub moving: f64,
    /// The same tori at rest.
    pub still: f64,
    /// The moving tori's rays that hit.
    pub moving_hits: u64,
    /// The still tori's rays that hit.
    pub still_hits: u64,
}

impl Paired {
    /// The moving tori's tracing over the still ones'.
    pub fn ratio(&self) -> f64 {
        self.moving / self.still
    }
}

/// Loads `moving` and `still` (fixtures of the same image size), builds
/// both databases and traces `frames` frames of each, in turn.
pub fn measure(moving: &Path, still: &Path, frames: usize) -> Result<Paired, String> {
    let load = |path: &Path| -> Result<_, String> {
        let f = Fixture::load(path).map_err(|e| e.to_string())?;
        let view = crate::run::view(&f, &Overrides::default())?;
        let db = crate::run::database(&f, false, Traversal::Bvh)?;
        Ok((view, db))
    };
    let (moving_view, moving_db) = load(moving)?;
    let (still_view, still_db) = load(still)?;
    let mut best = Paired {
        moving: f64::INFINITY,
        still: f64::INFINITY,
        ..Paired::default()
    };
    for _ in 0..frames.max(1) {
        let c = cpu_seconds();
        best.still_hits = trace(&still_db, &still_view);
        best.still = best.still.min(cpu_seconds() - c);
        let c = cpu_seconds();
        best.moving_hits = trace(&moving_db, &moving_view);
        best.moving = best.moving.min(cpu_seconds() - c);
    }
    Ok(best)
}

/// Runs `work` on a thread of its own bound to one core (the last this
/// process may use, on Linux), whose rayon pool is that one thread: what
/// `work` measures then runs where nothing else of this process does. Gives
/// the core, or `None` where threads cannot be bound here.
pub fn on_one_core<R: Send>(work: impl FnOnce() -> R + Send) -> Result<(R, Option<usize>), String> {
    std::thread::scope(|scope| {
        scope
            .spawn(|| {
                // Threads inherit their creator's binding: bound first,
                // then the pool is made.
                let core = bind_to_one_core()?;
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(1)
                    .build()
                    .map_err(|e| format!("cannot start a thread pool: {e}"))?;
                Ok((pool.install(work), core))
            })
            .join()
            .map_err(|_| "the measuring thread panicked".to_string())?
    })
}

/// Binds the calling thread to the last core it may run on.
#[cfg(target_os = "linux")]
fn bind_to_one_core() -> Result<Option<usize>, String> {
    use nix::sched::{sched_getaffinity, sched_setaffinity, CpuSet};
    use nix::unistd::Pid;
    let this = Pid::from_raw(0);
    let allowed = sched_getaffinity(this)
        .map_err(|e| format!("cannot read the cores this thread may use: {e}"))?;
    let Some(core) = (0..CpuSet::count())
        .rev()
        .find(|&c| allowed.is_set(c).unwrap_or(false))
    else {
        return Ok(None);
    };
    let mut one = CpuSet::new();
    one.set(core)
        .map_err(|e| format!("cannot name core {core}: {e}"))?;
    sched_setaffinity(this, &one).map_err(|e| format!("cannot bind to core {core}: {e}"))?;
    Ok(Some(core))
}

/// Threads are not bound off Linux: the measure runs on one thread alone.
#[cfg(not(target_os = "linux"))]
fn bind_to_one_core() -> Result<Option<usize>, String> {
    Ok(None)
}

/// [`measure`] in a fresh `vstf` process, at this process's vector level
/// (on one core: `vstf bench --measure --against` binds itself).
pub(super) fn measure_in_child(
    moving: &Path,
    still: &Path,
    frames: usize,
) -> Result<Paired, String> {
    let frames = frames.to_string();
    let args = [moving.as_ref(), "--against".as_ref(), still.as_ref()];
    primary::measure_in_child(&[&args[..], &["--frames".as_ref(), frames.as_ref()]].concat())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::tori::{self, Motion};

    /// Both scenes are loaded, built and traced in one process: each
    /// frame's CPU time is finite and positive and each scene's rays hit
    /// (the moving tori fewer, lit on one side of their light-time
    /// cut). A fixture that is not there is an error naming it.
    #[test]
    fn the_moving_and_the_still_tori_are_traced_in_turn() {
        let dir = std::env::temp_dir().join(format!("vstf-paired-{}", std::process::id()));
        let size = (48, 27);
        let (_, still, _) = tori::write(&dir, 2_000, size, Motion::Static).expect("written");
        let (_, moving, _) = tori::write(&dir, 2_000, size, Motion::Moving).expect("written");
        let p = measure(&moving, &still, 2).expect("measured");
        for t in [p.moving, p.still] {
            assert!(t.is_finite() && t > 0.0, "{p:?}");
        }
        assert!(p.still_hits > 0 && p.moving_hits > 0, "{p:?}");
        let absent = dir.join("absent.json");
        let err = measure(&absent, &still, 1).expect_err("no such fixture");
        assert!(err.contains("absent.json"), "{err}");
        std::fs::remove_dir_all(&dir).ok();
    }

    /// The cores the calling thread may run on (none read off Linux).
    fn cores() -> Vec<usize> {
        #[cfg(target_os = "linux")]
        {
            use nix::sched::{sched_getaffinity, CpuSet};
            let set = sched_getaffinity(nix::unistd::Pid::from_raw(0)).expect("read");
            (0..CpuSet::count())
                .filter(|&c| set.is_set(c).unwrap_or(false))
                .collect()
        }
        #[cfg(not(target_os = "linux"))]
        Vec::new()
    }

    /// The work runs on a thread of its own, the only one of its pool,
    /// bound to one core where threads can be bound; the calling thread's
    /// cores are as they were.
    #[test]
    fn the_work_runs_on_one_bound_thread() {
        let (caller, before) = (std::thread::current().id(), cores());
        let ((threads, elsewhere, bound), core) = on_one_core(|| {
            let elsewhere = std::thread::current().id() != caller;
            (rayon::current_num_threads(), elsewhere, cores())
        })
        .expect("ran");
        assert_eq!(threads, 1);
        assert!(elsewhere, "the work ran on the caller's thread");
        assert_eq!(cores(), before, "the caller was bound too");
        if cfg!(target_os = "linux") {
            let core = core.expect("bound on Linux");
            assert_eq!(bound, vec![core]);
            assert_eq!(before.last(), Some(&core), "the last core allowed");
        }
    }
}
