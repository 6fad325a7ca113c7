//! `vstf debug` and `vstf debug-diff`: the variables along a pixel's rays,
//! and the comparison of two logs of them.

use super::args::{DebugArgs, DebugDiffArgs};
use super::view::prepare;
use std::path::Path;

/// Traces the pixel (printing every step) or the region, and writes one JSON
/// line per pixel to the log if one is given.
pub fn run(root: Option<&Path>, args: DebugArgs) -> Result<(), String> {
    let DebugArgs {
        fixture,
        pixel,
        region,
        log,
        view,
        brute_force,
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
            let entry = vstf::debug::trace_pixel(&fixture, &view, &db, x, y)?;
            if pixel.is_some() {
                print!("{}", vstf::debug::describe(&entry));
            }
            lines.push_str(&serde_json::to_string(&entry).map_err(|e| e.to_string())?);
            lines.push('\n');
        }
    }
    if let Some(path) = log {
        vstf::output::write_atomic(&path, lines.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        eprintln!(
            "logged {} pixels to {}",
            lines.lines().count(),
            path.display()
        );
    }
    Ok(())
}

/// Prints the first differing pixels of two logs; fails if any differ.
pub fn diff(args: DebugDiffArgs) -> Result<(), String> {
    let DebugDiffArgs {
        a,
        b,
        tol,
        ignore,
        show,
    } = args;
    let read = |p: &Path| {
        std::fs::read_to_string(p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let diffs = vstf::debug::diff_logs(&read(&a)?, &read(&b)?, tol, &ignore)?;
    for d in diffs.iter().take(show) {
        println!(
            "line {} pixel {}: {}: {} vs {}",
            d.line, d.pixel, d.path, d.a, d.b
        );
    }
    if diffs.is_empty() {
        println!("the logs agree (tolerance {tol})");
        Ok(())
    } else {
        Err(format!("{} pixels differ", diffs.len()))
    }
}
