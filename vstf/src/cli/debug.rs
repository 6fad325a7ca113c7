//! `vstf debug` and `vstf debug-diff`: the variables along a pixel's rays,
//! and the comparison of two logs of them.

use super::args::{DebugArgs, DebugDiffArgs};
use super::view::prepare;
use std::path::Path;
use vstf::error::Error;

/// Traces the pixel (printing every step) or the region, and writes one JSON
/// line per pixel to the log if one is given.
pub fn run(root: Option<&Path>, args: DebugArgs) -> Result<(), Error> {
    let DebugArgs {
        fixture,
        pixel,
        region,
        log,
        view,
        brute_force,
        candidates,
    } = args;
    let (fixture, view, db) = prepare(root, &fixture, &view, brute_force, false)?;
    let (x0, y0, x1, y1) = match (pixel, region) {
        (Some((x, y)), _) => (x, y, x, y),
        (None, Some(r)) => r,
        (None, None) => unreachable!("clap requires --pixel or --region"),
    };
    let mut lines = String::new();
    for y in y0..=y1 {
        for x in x0..=x1 {
            let mut entry = vstf::debug::trace_pixel(&fixture, &view, &db, x, y)?;
            if !candidates {
                entry.drop_candidates();
            }
            if pixel.is_some() {
                print!("{}", vstf::debug::describe(&entry));
            }
            lines.push_str(&serde_json::to_string(&entry).map_err(|e| e.to_string())?);
            lines.push('\n');
        }
    }
    if let Some(path) = log {
        vstf::write_atomic(&path, lines.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        eprintln!(
            "logged {} pixels to {}",
            lines.lines().count(),
            path.display()
        );
    }
    Ok(())
}

/// Prints the first differing pixels of two logs, each with its differing
/// fields; fails if any differ. Both logs are read a line at a time.
pub fn diff(args: DebugDiffArgs) -> Result<(), Error> {
    let DebugDiffArgs {
        a,
        b,
        tol,
        ignore,
        show,
        first,
    } = args;
    let open = |p: &Path| {
        std::fs::File::open(p)
            .map(std::io::BufReader::new)
            .map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let options = vstf::debug::DiffOptions {
        tol,
        ignore: &ignore,
        first_only: first,
        keep: show,
    };
    let c = vstf::debug::diff_streams(open(&a)?, open(&b)?, &options)?;
    for d in &c.shown {
        println!(
            "line {} pixel {}: {} field(s) differ",
            d.line,
            d.pixel,
            d.fields.len()
        );
        for (path, x, y) in &d.fields {
            println!("  {path}: {x} vs {y}");
        }
    }
    if c.differing == 0 {
        println!("the logs agree ({} pixels, tolerance {tol})", c.lines.0);
        Ok(())
    } else {
        Err(Error::Failed {
            message: format!(
                "{} of {} pixels differ{}",
                c.differing,
                c.lines.0.max(c.lines.1),
                if c.differing > c.shown.len() {
                    format!(" (the first {} shown; --show N for more)", c.shown.len())
                } else {
                    String::new()
                }
            ),
        })
    }
}
