//! Presenting check results: the table on the terminal, the JSON rows, and
//! the static HTML report with images and expected-point markers.

mod html;
mod markers;
mod numbers;

pub use html::html;
pub use markers::{marker_groups, with_markers, MarkerGroup, SMALL_GROUP};
use numbers::num;

use crate::check::Row;
use std::fmt::Write as _;

/// The measurement table, one line per row, and below a row that could
/// not be measured, why.
pub fn table(rows: &[Row]) -> String {
    let headers = [
        "fixture",
        "quantity",
        "measured",
        "expected",
        "paper",
        "tolerance",
        "unit",
        "result",
    ];
    let cells: Vec<[String; 8]> = rows
        .iter()
        .map(|r| {
            let num = |x: f64| {
                if r.error.is_some() {
                    "-".into()
                } else {
                    num(x)
                }
            };
            let plus_minus = |x: f64| {
                if r.error.is_some() {
                    "-".into()
                } else {
                    format!("±{}", num(x))
                }
            };
            [
                r.fixture.clone(),
                r.quantity.clone(),
                num(r.measured),
                num(r.expected),
                r.paper.map_or("-".into(), |p| {
                    if r.paper_disagrees() {
                        format!("{}*", num(p))
                    } else {
                        num(p)
                    }
                }),
                plus_minus(r.tolerance),
                r.unit.to_string(),
                if r.pass { "pass".into() } else { "FAIL".into() },
            ]
        })
        .collect();
    let mut width: Vec<usize> = headers.iter().map(|h| h.len()).collect();
    for c in &cells {
        for (i, s) in c.iter().enumerate() {
            width[i] = width[i].max(s.chars().count());
        }
    }
    let mut out = String::new();
    let line = |out: &mut String, c: &[String]| {
        let parts: Vec<String> = c
            .iter()
            .enumerate()
            .map(|(i, s)| format!("{s:w$}", w = width[i]))
            .collect();
        let _ = writeln!(out, "{}", parts.join("  ").trim_end());
    };
    line(&mut out, &headers.map(String::from));
    for (c, r) in cells.iter().zip(rows) {
        line(&mut out, c);
        if let Some(e) = &r.error {
            let _ = writeln!(out, "  error: {e}");
        }
    }
    let (pass, fail) = (
        rows.iter().filter(|r| r.pass).count(),
        rows.iter().filter(|r| !r.pass).count(),
    );
    if rows.iter().any(Row::paper_disagrees) {
        let _ = writeln!(out, "* the paper's figure differs from first principles by more than the tolerance: see docs/physics.md");
    }
    let _ = writeln!(out, "check: {pass} passed, {fail} failed");
    out
}

/// The widest line of [`summary_table`].
pub const SUMMARY_WIDTH: usize = 100;

/// The measurement table in at most [`SUMMARY_WIDTH`] columns: a line per
/// fixture, then its rows indented (quantity, measured, expected,
/// tolerance with unit, result), long quantity names shortened with an
/// ellipsis, and below a row that could not be measured, why (shortened
/// too). The full table ([`table`], with the paper's figures) is what
/// `vstf check --verbose`, the JSON and the report give.
pub fn summary_table(rows: &[Row]) -> String {
    const NUMBER: usize = 10;
    const UNIT: usize = 14;
    let quantity =
        SUMMARY_WIDTH - (2 + 2 + NUMBER + 2 + NUMBER + 2 + (NUMBER + 1) + 1 + UNIT + 1 + 4);
    let mut out = String::new();
    let mut fixture = None;
    let mut solved_t = None;
    for r in rows {
        if fixture != Some(&r.fixture) {
            let _ = writeln!(out, "{}", r.fixture);
            fixture = Some(&r.fixture);
            solved_t = None;
        }
        if let Some(t) = r.camera_t.filter(|t| solved_t != Some(*t)) {
            let _ = writeln!(out, "  at camera t = {t} (solved from the view's t)");
        }
        solved_t = r.camera_t;
        let name = shortened(&r.quantity, quantity);
        let short_num = |x: f64| {
            if r.error.is_some() {
                "-".into()
            } else {
                short_num(x)
            }
        };
        let tolerance = match r.error {
            Some(_) => "-".into(),
            None => format!("±{}", short_num(r.tolerance)),
        };
        let line = format!(
            "  {name:quantity$}  {:>NUMBER$}  {:>NUMBER$}  {tolerance:>w$} {:UNIT$} {}",
            short_num(r.measured),
            short_num(r.expected),
            r.unit.to_string(),
            if r.pass { "pass" } else { "FAIL" },
            w = NUMBER + 1
        );
        let _ = writeln!(out, "{}", line.trim_end());
        if let Some(e) = &r.error {
            let _ = writeln!(out, "    error: {}", shortened(e, SUMMARY_WIDTH - 11));
        }
    }
    let (pass, fail) = (
        rows.iter().filter(|r| r.pass).count(),
        rows.iter().filter(|r| !r.pass).count(),
    );
    let _ = writeln!(out, "check: {pass} passed, {fail} failed");
    out
}

/// A number in at most 10 characters: 7 significant digits in [1e-3, 1e5),
/// else 4 in exponent form.
fn short_num(x: f64) -> String {
    let a = x.abs();
    if !x.is_finite() || (a != 0.0 && !(1e-3..1e5).contains(&a)) {
        return format!("{x:.3e}");
    }
    let digits = if a == 0.0 {
        0
    } else {
        a.log10().floor() as i32
    };
    let decimals = (6 - digits).clamp(0, 6) as usize;
    format!("{x:.decimals$}")
}

/// `s` in at most `width` characters, cut with an ellipsis.
fn shortened(s: &str, width: usize) -> String {
    if s.chars().count() <= width {
        return s.to_string();
    }
    let kept: String = s.chars().take(width.saturating_sub(1)).collect();
    format!("{kept}…")
}

/// The rows as a JSON array of objects with keys fixture, quantity,
/// measured, expected, paper, tolerance, unit, pass, and `error` on a row
/// that could not be measured (its numbers `null`).
pub fn json(rows: &[Row]) -> String {
    serde_json::to_string_pretty(rows).expect("rows serialise")
}

/// What `vstf check --json` writes: `{"rows": [...], "goldens": [...]}`,
/// the rows as [`json`] gives them and one object per golden image
/// (fixture, view, pass, missing, max_diff, differing, allowed_max_diff,
/// allowed_max_pixels, worst_pixel, size, pending).
pub fn check_json(rows: &[Row], goldens: &[&crate::golden::Comparison]) -> String {
    let goldens: Vec<serde_json::Value> = goldens
        .iter()
        .map(|g| {
            serde_json::json!({
                "fixture": g.fixture,
                "view": g.view,
                "pass": g.pass,
                "missing": g.missing,
                "max_diff": g.max_diff,
                "differing": g.differing,
                "allowed_max_diff": g.allowed.max_diff,
                "allowed_max_pixels": g.allowed.max_pixels,
                "worst_pixel": g.worst_at.map(|(x, y)| [x, y]),
                "size": [g.size.0, g.size.1],
                "pending": g.pending.as_ref().map(|p| p.display().to_string()),
            })
        })
        .collect();
    let value = serde_json::json!({ "rows": rows, "goldens": goldens });
    serde_json::to_string_pretty(&value).expect("rows serialise")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::Unit;

    /// A marker on a light pixel is drawn black, on a dark one white, each
    /// outlined in the other, and numbered beside it.
    #[test]
    fn markers_contrast_with_what_is_under_them() {
        let mut img = image::RgbImage::from_pixel(60, 30, image::Rgb([250, 240, 20]));
        for y in 0..30 {
            for x in 30..60 {
                img.put_pixel(x, y, image::Rgb([10, 10, 40]));
            }
        }
        let groups = marker_groups(&[(10.5, 10.5), (45.5, 10.5)], &["a".into(), "b".into()]);
        let marked = with_markers(&img, &groups);
        assert_eq!(marked.get_pixel(12, 10).0, [0, 0, 0], "on yellow: black");
        assert_eq!(
            marked.get_pixel(12, 11).0,
            [255, 255, 255],
            "its outline: white"
        );
        assert_eq!(
            marked.get_pixel(47, 10).0,
            [255, 255, 255],
            "on dark blue: white"
        );
        let numbered =
            (15..25).any(|x| (15..25).any(|y| marked.get_pixel(x, y).0 == [255, 255, 255]));
        assert!(numbered, "no number beside the first marker");
    }

    /// `n` points evenly on a circle of radius `r` about `c`.
    fn circle(n: usize, r: f64, c: f64) -> Vec<(f64, f64)> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                (c + r * a.cos(), c + r * a.sin())
            })
            .collect()
    }

    /// The pixels a label's box darkened on a plain yellow image (a quarter
    /// of the yellow), and the black (ink) pixels.
    fn labels_and_ink(marked: &image::RgbImage) -> (usize, usize) {
        let box_px = marked.pixels().filter(|p| p.0 == [62, 60, 5]).count();
        let ink = marked.pixels().filter(|p| p.0 == [0, 0, 0]).count();
        (box_px, ink)
    }

    /// How many separate marks of ink (black pixels connected through
    /// their sides) an image holds.
    fn ink_marks(img: &image::RgbImage) -> usize {
        let (w, h) = img.dimensions();
        let mut seen = vec![false; (w * h) as usize];
        let mut marks = 0;
        for start in 0..w * h {
            let ink = |i: u32| img.get_pixel(i % w, i / w).0 == [0, 0, 0];
            if seen[start as usize] || !ink(start) {
                continue;
            }
            marks += 1;
            let mut stack = vec![start];
            seen[start as usize] = true;
            while let Some(i) = stack.pop() {
                let (x, y) = (i % w, i / w);
                let next = [
                    (x > 0).then(|| i - 1),
                    (x + 1 < w).then(|| i + 1),
                    (y > 0).then(|| i - w),
                    (y + 1 < h).then(|| i + w),
                ];
                for j in next.into_iter().flatten() {
                    if !seen[j as usize] && ink(j) {
                        seen[j as usize] = true;
                        stack.push(j);
                    }
                }
            }
        }
        marks
    }

    /// 16 points of one row on the outline of a 20-pixel ball are drawn as
    /// 16 separate small marks (crosses shrunk to arms of at most a pixel,
    /// none touching another) and numbered once, beside the ball, and the legend
    /// has that row once; the same 16 points on a 240-pixel ball, 47 pixels
    /// apart (the control), keep full crosses, each numbered.
    #[test]
    fn markers_on_a_small_object_stay_apart_and_are_numbered_once() {
        let yellow = image::Rgb([250, 240, 20]);
        let rows = vec!["ball radius".to_string(); 16];
        let small = marker_groups(&circle(16, 10.0, 50.5), &rows);
        assert_eq!(small.len(), 1, "one legend row");
        assert_eq!((small[0].number, small[0].points.len()), (1, 16));
        let img = image::RgbImage::from_pixel(120, 100, yellow);
        let marked = with_markers(&img, &small);
        let (box_px, ink) = labels_and_ink(&marked);
        // One label "1" is a 10 x 11 box less its glyph's pixels.
        assert!(box_px > 0 && box_px <= 110, "{box_px} label pixels");
        assert!(ink <= 16 * 5, "{ink} ink pixels: crosses of arm at most 1");
        assert_eq!(ink_marks(&marked), 16, "16 marks, none touching another");
        // On a 50-pixel ball the points are 10 pixels apart: still one label.
        let medium = marker_groups(&circle(16, 25.0, 50.5), &rows);
        let marked = with_markers(&img, &medium);
        let (box_px, _) = labels_and_ink(&marked);
        assert!(box_px > 0 && box_px <= 110, "{box_px} label pixels");
        assert_eq!(ink_marks(&marked), 16);
        let large = marker_groups(&circle(16, 120.0, 150.5), &rows);
        let img = image::RgbImage::from_pixel(300, 300, yellow);
        let (box_px, ink) = labels_and_ink(&with_markers(&img, &large));
        assert!(
            box_px > 10 * 110,
            "{box_px} label pixels: a label per cross"
        );
        assert_eq!(ink, 16 * 13, "16 crosses of arm 3");
        assert_eq!(ink_marks(&with_markers(&img, &large)), 16);
    }

    /// Rows are numbered in the order they first appear, each once.
    #[test]
    fn marker_groups_number_each_row_once() {
        let at = [(1.0, 1.0), (2.0, 2.0), (3.0, 3.0), (4.0, 4.0)];
        let rows = ["a", "b", "a", ""].map(String::from);
        let g = marker_groups(&at, &rows);
        let seen: Vec<(usize, &str, usize)> = g
            .iter()
            .map(|g| (g.number, g.row.as_str(), g.points.len()))
            .collect();
        assert_eq!(seen, [(1, "a", 2), (2, "b", 1), (3, "", 1)]);
    }

    /// A view's solved camera time is printed once above the rows measured
    /// in it, the number in full; rows of a view given a number print none.
    #[test]
    fn the_summary_records_solved_camera_times() {
        let row = |quantity: &str, camera_t: Option<f64>| Row {
            fixture: "rod".into(),
            quantity: quantity.into(),
            measured: 1.0,
            expected: 1.0,
            paper: None,
            tolerance: 0.1,
            unit: Unit::Pixels,
            pass: true,
            error: None,
            camera_t,
        };
        let t = 32.234_567_891;
        let text = summary_table(&[
            row("left edge", Some(t)),
            row("right edge", Some(t)),
            row("static", None),
        ]);
        assert_eq!(
            text.matches("at camera t = 32.234567891 (solved").count(),
            1,
            "{text}"
        );
        let text = summary_table(&[row("static", None)]);
        assert!(!text.contains("camera t"), "{text}");
    }

    /// Long names, negative and tiny numbers and the widest unit still fit
    /// in 100 columns; the full table keeps the name whole (the control).
    #[test]
    fn the_summary_fits_in_a_hundred_columns() {
        let name = "emulator, 58 slices, the paper's 6 cm gate: pixels disagreeing away from edges";
        let row = Row {
            fixture: "hornof-2025".into(),
            quantity: name.into(),
            measured: -1.234_567e-7,
            expected: -98_765.432_1,
            paper: Some(53.13),
            tolerance: 1.5e-12,
            unit: Unit::LUnitsPerTUnit,
            pass: false,
            error: None,
            camera_t: None,
        };
        let text = summary_table(std::slice::from_ref(&row));
        for line in text.lines() {
            assert!(
                line.chars().count() <= SUMMARY_WIDTH,
                "{} columns: {line}",
                line.chars().count()
            );
        }
        assert!(text.contains('…') && text.contains("FAIL"), "{text}");
        assert!(table(&[row]).contains(name));
    }
}
