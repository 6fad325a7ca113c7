//! What both sides of section 7 of `vstf bench` time: the process's CPU
//! clock, and a frame's primary rays traced as Embree's side traces them.

/// CPU seconds this process has used, every thread's, user and system:
/// the clock Embree's side reads (`CLOCK_PROCESS_CPUTIME_ID`), to the
/// nanosecond. (/proc gives the same time in 10 ms ticks, 2% of a frame.)
/// NaN where the clock cannot be read.
#[cfg(unix)]
pub(super) fn cpu_seconds() -> f64 {
    use nix::time::{clock_gettime, ClockId};
    clock_gettime(ClockId::CLOCK_PROCESS_CPUTIME_ID)
        .map_or(f64::NAN, |t| t.tv_sec() as f64 + t.tv_nsec() as f64 * 1e-9)
}

/// No process CPU clock is read off Unix (Embree's side, section 7, runs
/// on Linux alone).
#[cfg(not(unix))]
pub(super) fn cpu_seconds() -> f64 {
    f64::NAN
}

/// How many of the view's primary rays (one at each pixel's centre) hit
/// something: the work of Embree's side, on every thread of the pool it
/// runs in, in packets of 2 x 2 pixels
/// ([`renderer::Database::closest_hits`]).
pub(super) fn trace(db: &renderer::Database, view: &crate::fixture::View) -> u64 {
    use rayon::prelude::*;
    let (w, h) = (view.camera.width, view.camera.height);
    let light = view.model.light_speed;
    let ray = |x: u32, y: u32| {
        let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        view.camera.ray(px, py, view.camera_t, light)
    };
    (0..h.div_ceil(2))
        .into_par_iter()
        .map(|pair| {
            let rows = 2 * pair..(2 * pair + 2).min(h);
            let mut rays = Vec::with_capacity(4);
            let mut hits = [None; 4];
            let mut count = 0;
            for x0 in (0..w).step_by(2) {
                rays.clear();
                for y in rows.clone() {
                    rays.extend((x0..(x0 + 2).min(w)).map(|x| ray(x, y)));
                }
                let hits = &mut hits[..rays.len()];
                db.closest_hits(&rays, (0.0, f64::INFINITY), hits);
                count += hits.iter().filter(|h| h.is_some()).count() as u64;
            }
            count
        })
        .sum()
}

/// `vstf bench --measure` with `args` in a fresh `vstf` process at this
/// process's vector level, the JSON it prints read as `T`.
pub(super) fn measure_in_child<T: serde::de::DeserializeOwned>(
    args: &[&std::ffi::OsStr],
) -> Result<T, String> {
    let shown: Vec<_> = args.iter().map(|a| a.to_string_lossy()).collect();
    let command = format!("vstf bench --measure {}", shown.join(" "));
    let exe = std::env::current_exe().map_err(|e| format!("cannot find vstf itself: {e}"))?;
    let out = std::process::Command::new(exe)
        .args(["--simd", renderer::SimdLevel::best().name()])
        .args(["bench", "--measure"])
        .args(args)
        .output()
        .map_err(|e| format!("cannot run {command}: {e}"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(format!("{command} failed: {err}"));
    }
    serde_json::from_slice(&out.stdout).map_err(|e| format!("{command}: {e}"))
}

#[cfg(all(test, unix))]
mod tests {
    use super::cpu_seconds;

    /// The process clock reads work far finer than /proc's 10 ms ticks,
    /// and never runs backwards: of consecutive readings that differ, some
    /// differ by under a millisecond (a tick-counting clock moves only by
    /// whole ticks). Other tests' threads, which this process clock counts
    /// too, may make any one step longer, not all of them.
    #[test]
    fn the_cpu_clock_reads_finer_than_a_tick() {
        let mut last = cpu_seconds();
        let mut smallest = f64::INFINITY;
        for _ in 0..100_000 {
            let now = cpu_seconds();
            assert!(now >= last, "{now} after {last}");
            if now > last {
                smallest = smallest.min(now - last);
            }
            last = now;
        }
        assert!(smallest < 0.001, "the smallest step was {smallest} s");
    }
}
