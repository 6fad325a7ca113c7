//! `vstf animate`: frames that differ only by the camera's t, from one 4D
//! database, with a progress bar and Ctrl-C keeping the frames finished.

use super::args::AnimateArgs;
use renderer::Traversal;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;
use vstf::error::Error;
use vstf::fixture::Overrides;

/// Renders the frames, assembles the GIF or APNG asked for and reports the
/// timings; an interruption leaves the finished frames and fails.
pub fn run(root: Option<&Path>, args: AnimateArgs) -> Result<(), Error> {
    let AnimateArgs {
        fixture,
        frames,
        step,
        out,
        fps,
        resume,
        label,
        shard,
        view,
    } = args;
    let shard = match shard {
        Some(s) => vstf::shard::Shard::parse(&s, |v| std::env::var(v).ok())?,
        None => vstf::shard::Shard::WHOLE,
    };
    if view.camera_t.is_some() {
        return Err(Error::usage(
            "animate takes its camera times from --frames, not --camera-t",
        ));
    }
    vstf::animate::frame_times(frames.from, frames.to, step)?;
    // What cannot be written (a folder where the file goes, a video
    // without ffmpeg) is refused before anything is rendered or made; a
    // shard's frames need ffmpeg only when merged.
    let output = vstf::animate::Output::from_path(&out)?;
    output.preflight(shard == vstf::shard::Shard::WHOLE)?;
    let budget = vstf::Budget::forced(view.force);
    let fixture = vstf::project::load_fixture(root, &fixture, &budget)?;
    let times = vstf::animate::lab_times(&fixture, frames, step)?;
    // A declared view gives the model, size and samples; the times are the frames'.
    let (fixture, view) = match &view.view {
        Some(declared) => {
            let (fixture, base) = vstf::check::golden_view(&fixture, declared)?;
            let first = vstf::fixture::View {
                camera_t: times[0],
                ..base
            };
            (fixture, first)
        }
        None => {
            let overrides = Overrides {
                camera_t: Some(times[0]),
                ..view.overrides(&fixture)?
            };
            let first = vstf::run::view(&fixture, &overrides)?;
            (fixture, first)
        }
    };
    budget.check_work(
        (view.camera.width, view.camera.height),
        view.settings.spp,
        times.len(),
    )?;
    let stop = stop_on_ctrl_c()?;
    let started = Instant::now();
    let db = vstf::run::database(&fixture, view.model.lorentz, Traversal::Bvh)?;
    let build = started.elapsed().as_secs_f64();
    let owned = (0..times.len()).filter(|&i| shard.owns_frame(i)).count();
    let bar = progress_bar(owned);
    let opts = vstf::animate::FrameOptions {
        resume,
        label,
        shard,
    };
    let done =
        vstf::animate::render_frames((&fixture, &view, &db), &times, &output, &stop, opts, |n| {
            bar.set_position(n as u64)
        })?;
    bar.finish_and_clear();
    let dir = output.frames_dir();
    if done < owned {
        return Err(Error::Interrupted {
            message: format!(
                "interrupted: {done} of {owned} frames finished, in {}",
                dir.display()
            ),
        });
    }
    if shard != vstf::shard::Shard::WHOLE {
        eprintln!(
            "shard {shard}: {done} of {} frames in {} ({:.2} s); once every shard is done: vstf merge --out {} FOLDER...",
            times.len(),
            dir.display(),
            started.elapsed().as_secs_f64(),
            out.display()
        );
        return Ok(());
    }
    vstf::animate::finish(&output, done, fps)?;
    eprintln!(
        "animated {} ({} frames, {} = {}..{} step {step}, {} model, {}x{}): database built once in {build:.2} s, {:.2} s in all -> {}",
        fixture.name,
        done,
        clock_name(frames.clock),
        frames.from,
        frames.to,
        view.model,
        view.camera.width,
        view.camera.height,
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(())
}

/// A flag that Ctrl-C raises, for the renderer to stop between frames; a
/// second Ctrl-C exits at once (the frames finished so far are whole on
/// disk: each is written atomically).
fn stop_on_ctrl_c() -> Result<Arc<AtomicBool>, String> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            eprintln!("\ninterrupted twice: exiting now");
            std::process::exit(130);
        }
        eprintln!("\ninterrupted: finishing the frame being rendered (Ctrl-C again to exit now)");
    })
    .map_err(|e| format!("cannot handle Ctrl-C: {e}"))?;
    Ok(stop)
}

/// A bar of `frames` frames with rate, elapsed time and time left.
fn progress_bar(frames: usize) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(frames as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} frames  {per_sec}  {elapsed} elapsed, {eta} left",
        )
        .expect("a valid template"),
    );
    bar
}

/// The symbol of the clock the frames step.
fn clock_name(clock: vstf::animate::Clock) -> &'static str {
    match clock {
        vstf::animate::Clock::Lab => "t",
        vstf::animate::Clock::Proper => "tau",
    }
}
