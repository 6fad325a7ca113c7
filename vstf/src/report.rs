//! Presenting check results: the table on the terminal, the JSON rows, and
//! the static HTML report with images and expected-point markers.

use crate::check::{FixtureReport, Row};
use crate::golden::{slug, Comparison};
use std::fmt::Write as _;
use std::path::Path;

fn num(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        format!("{x:.4e}")
    } else {
        format!("{x:.6}")
    }
}

/// The measurement table, one line per row.
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
                format!("±{}", num(r.tolerance)),
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
    for c in &cells {
        line(&mut out, c);
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
/// ellipsis. The full table ([`table`], with the paper's figures) is what
/// `vstf check --verbose`, the JSON and the report give.
pub fn summary_table(rows: &[Row]) -> String {
    const NUMBER: usize = 10;
    const UNIT: usize = 14;
    let quantity =
        SUMMARY_WIDTH - (2 + 2 + NUMBER + 2 + NUMBER + 2 + (NUMBER + 1) + 1 + UNIT + 1 + 4);
    let mut out = String::new();
    let mut fixture = None;
    for r in rows {
        if fixture != Some(&r.fixture) {
            let _ = writeln!(out, "{}", r.fixture);
            fixture = Some(&r.fixture);
        }
        let name = shortened(&r.quantity, quantity);
        let tolerance = format!("±{}", short_num(r.tolerance));
        let line = format!(
            "  {name:quantity$}  {:>NUMBER$}  {:>NUMBER$}  {tolerance:>w$} {:UNIT$} {}",
            short_num(r.measured),
            short_num(r.expected),
            r.unit.to_string(),
            if r.pass { "pass" } else { "FAIL" },
            w = NUMBER + 1
        );
        let _ = writeln!(out, "{}", line.trim_end());
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
/// measured, expected, paper, tolerance, unit, pass.
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

/// Draws small crosses at the markers on a copy of the image.
pub fn with_markers(img: &image::RgbImage, markers: &[(f64, f64)]) -> image::RgbImage {
    let mut out = img.clone();
    for &(x, y) in markers {
        let (cx, cy) = (x.floor() as i64, y.floor() as i64);
        for d in -3i64..=3 {
            for (px, py) in [(cx + d, cy), (cx, cy + d)] {
                if px >= 0 && py >= 0 && (px as u32) < out.width() && (py as u32) < out.height() {
                    out.put_pixel(px as u32, py as u32, image::Rgb([255, 255, 0]));
                }
            }
        }
    }
    out
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Writes `dir/index.html` with each fixture's views (plain and with the
/// expected points marked) and its rows, failing fixtures and rows first.
pub fn html(dir: &Path, reports: &[FixtureReport]) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let mut order: Vec<&FixtureReport> = reports.iter().collect();
    order.sort_by_key(|r| r.passed());
    let mut h = String::from(
        "<!doctype html><meta charset=utf-8><title>VSTF report</title><style>\
         body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{padding:2px 8px;border-bottom:1px solid #ccc;text-align:left}\
         .FAIL{background:#fdd}.pass{background:#dfd}img{margin:4px;image-rendering:pixelated}figure{display:inline-block;margin:0 1em 1em 0}</style>\
         <h1>VSTF report</h1><p>Markers (yellow crosses) are where first-principles physics puts the marked points, computed without the ray tracer. \
         A paper figure marked * differs from first principles by more than the tolerance (see docs/physics.md).</p>",
    );
    for r in order {
        let failed = r.rows.iter().filter(|x| !x.pass).count();
        let _ = write!(
            h,
            "<h2>{} {}</h2><p>{}</p>",
            esc(&r.fixture),
            if failed > 0 {
                format!("— {failed} failing")
            } else {
                String::new()
            },
            esc(&r.description)
        );
        for v in &r.views {
            let base = format!("{}-{}", slug(&r.fixture), slug(&v.name));
            crate::output::write_png(&dir.join(format!("{base}.png")), &v.image)?;
            crate::output::write_png(
                &dir.join(format!("{base}-markers.png")),
                &with_markers(&v.image, &v.markers),
            )?;
            let _ = write!(
                h,
                "<figure><img src=\"{base}.png\" width=480><img src=\"{base}-markers.png\" width=480><figcaption>{}</figcaption></figure>",
                esc(&v.name)
            );
        }
        let _ = write!(h, "<table><tr><th>quantity<th>measured<th>expected<th>paper<th>tolerance<th>unit<th>result</tr>");
        let mut rows: Vec<&Row> = r.rows.iter().collect();
        rows.sort_by_key(|x| x.pass);
        for x in rows {
            let res = if x.pass { "pass" } else { "FAIL" };
            let paper = x.paper.map_or("-".into(), |p| {
                format!("{}{}", num(p), if x.paper_disagrees() { " *" } else { "" })
            });
            let _ = write!(
                h,
                "<tr class={res}><td>{}<td>{}<td>{}<td>{}<td>±{}<td>{}<td>{res}</tr>",
                esc(&x.quantity),
                num(x.measured),
                num(x.expected),
                paper,
                num(x.tolerance),
                esc(x.unit.as_str())
            );
        }
        h.push_str("</table>");
        golden_section(&mut h, dir, &r.goldens)?;
    }
    crate::output::write_atomic(&dir.join("index.html"), h.as_bytes())
        .map_err(|e| format!("cannot write report: {e}"))
}

/// Each failing golden comparison: the actual and expected images side by
/// side (hover or click either to swap them), and the diff; then one line
/// per passing view.
fn golden_section(h: &mut String, dir: &Path, goldens: &[Comparison]) -> Result<(), String> {
    for g in goldens.iter().filter(|g| !g.pass) {
        let _ = write!(h, "<p class=FAIL><code>{}</code></p>", esc(&g.to_string()));
        let Some(pending) = &g.pending else { continue };
        let base = format!("golden-{}-{}", slug(&g.fixture), slug(&g.view));
        let mut figures = Vec::new();
        for (file, caption) in [
            ("actual.png", "actual"),
            ("expected.png", "expected"),
            ("diff.png", "diff"),
        ] {
            let src = pending.join(file);
            if src.is_file() {
                let name = format!("{base}-{file}");
                std::fs::copy(&src, dir.join(&name))
                    .map_err(|e| format!("cannot copy {}: {e}", src.display()))?;
                figures.push((name, caption));
            }
        }
        let other = |c: &str| {
            figures
                .iter()
                .find(|(_, k)| *k == c)
                .map(|(n, _)| n.clone())
        };
        for (name, caption) in &figures {
            let swap = match *caption {
                "actual" => other("expected"),
                "expected" => other("actual"),
                _ => None,
            };
            let js = swap.map_or(String::new(), |o| {
                format!(" onmouseover=\"this.src='{o}'\" onmouseout=\"this.src='{name}'\" onclick=\"this.src=this.src.endsWith('{name}')?'{o}':'{name}'\"")
            });
            let _ = write!(h, "<figure><img src=\"{name}\" width=480{js}><figcaption>{caption}</figcaption></figure>");
        }
    }
    for g in goldens.iter().filter(|g| g.pass) {
        let _ = write!(h, "<p class=pass><code>{}</code></p>", esc(&g.to_string()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::Unit;

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
