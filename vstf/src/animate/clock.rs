//! Which clock an animation's frames step: the lab's, or the proper time
//! of a camera on a worldline (`--frames tau:A..B`), each frame then
//! rendered at the lab time where the camera's clock reads its value.

use super::{frame_times, parse_range};
use crate::fixture::{CameraClock, Fixture};

/// The clock `--frames` counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// Lab time (`A..B` or `t:A..B`).
    Lab,
    /// The camera's proper time since its worldline's start (`tau:A..B`).
    Proper,
}

/// `--frames`: a range of times on a clock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRange {
    /// Which clock.
    pub clock: Clock,
    /// The first frame's time.
    pub from: f64,
    /// The last frame's time (inclusive).
    pub to: f64,
}

/// Parses `A..B` or `t:A..B` (lab time) and `tau:A..B` (the camera's
/// proper time).
pub fn parse_frames(s: &str) -> Result<FrameRange, String> {
    let (clock, range) = match (s.strip_prefix("tau:"), s.strip_prefix("t:")) {
        (Some(r), _) => (Clock::Proper, r),
        (None, Some(r)) => (Clock::Lab, r),
        (None, None) => (Clock::Lab, s),
    };
    let (from, to) = parse_range(range)
        .map_err(|e| format!("{e}, optionally after t: (lab time) or tau: (proper time)"))?;
    Ok(FrameRange { clock, from, to })
}

/// The frames' lab times: `range` stepped by `step` on its clock; proper
/// times are read on the fixture's camera worldline (refused for a camera
/// without one, or beyond its duration).
pub fn lab_times(f: &Fixture, range: FrameRange, step: f64) -> Result<Vec<f64>, String> {
    let times = frame_times(range.from, range.to, step)?;
    let clock = crate::fixture::camera_clock(&f.spec.camera)
        .map_err(|e| format!("{}: {e}", f.file.display()))?;
    if range.clock == Clock::Lab {
        // A camera on a worldline is asked only for times on it.
        for &t in &times {
            let on = match &clock {
                Some(CameraClock::Hyperbolic(w)) => crate::fixture::camera_frame_within(w, t, 0.0),
                Some(CameraClock::Keyframes(k)) => k.event_at(t).map(|_| ()),
                None => Ok(()),
            };
            on.map_err(|e| format!("--frames {}..{}: {e}", range.from, range.to))?;
        }
        return Ok(times);
    }
    let clock = clock.ok_or_else(|| {
        format!(
            "--frames tau:{}..{}: proper time is for a camera with camera.worldline; {} has none (give lab times, A..B)",
            range.from,
            range.to,
            f.file.display()
        )
    })?;
    times
        .iter()
        .map(|&tau| clock.lab_time(tau, "--frames").map_err(|e| e.to_string()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_name_their_clock_and_plain_ranges_stay_lab_time() {
        let lab = |from, to| FrameRange {
            clock: Clock::Lab,
            from,
            to,
        };
        assert_eq!(parse_frames("940..1171").unwrap(), lab(940.0, 1171.0));
        assert_eq!(parse_frames("t:-5..5").unwrap(), lab(-5.0, 5.0));
        assert_eq!(
            parse_frames("tau:0..2.5").unwrap(),
            FrameRange {
                clock: Clock::Proper,
                from: 0.0,
                to: 2.5
            }
        );
        let e = parse_frames("tau:0-2").unwrap_err();
        assert!(e.contains("tau: (proper time)"), "{e}");
        assert!(parse_frames("s:0..2").is_err());
    }
}
