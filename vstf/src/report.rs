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

/// Draws each marker on a copy of the image as a cross in the colour that
/// contrasts with the pixels under it (black on light, white on dark),
/// outlined in the other, and numbered from 1 beside it.
pub fn with_markers(img: &image::RgbImage, markers: &[(f64, f64)]) -> image::RgbImage {
    let mut out = img.clone();
    let (w, h) = (i64::from(out.width()), i64::from(out.height()));
    let inside = |x: i64, y: i64| x >= 0 && y >= 0 && x < w && y < h;
    for (k, &(x, y)) in markers.iter().enumerate() {
        let (cx, cy) = (x.floor() as i64, y.floor() as i64);
        if !inside(cx, cy) {
            continue;
        }
        let under = img.get_pixel(cx as u32, cy as u32).0;
        let luma = 0.2126 * f64::from(under[0])
            + 0.7152 * f64::from(under[1])
            + 0.0722 * f64::from(under[2]);
        let (ink, rim) = if luma > 110.0 {
            (image::Rgb([0, 0, 0]), image::Rgb([255, 255, 255]))
        } else {
            (image::Rgb([255, 255, 255]), image::Rgb([0, 0, 0]))
        };
        let arm = |d: i64| [(cx + d, cy), (cx, cy + d)];
        for d in -4i64..=4 {
            for (px, py) in arm(d) {
                for (ox, oy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    if inside(px + ox, py + oy) {
                        out.put_pixel((px + ox) as u32, (py + oy) as u32, rim);
                    }
                }
            }
        }
        for d in -3i64..=3 {
            for (px, py) in arm(d) {
                if inside(px, py) {
                    out.put_pixel(px as u32, py as u32, ink);
                }
            }
        }
        let at = (
            (cx + 5).clamp(0, w - 1) as u32,
            (cy + 5).clamp(0, h - 1) as u32,
        );
        crate::label::draw_at(&mut out, &(k + 1).to_string(), at, 1);
    }
    out
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

const STYLE: &str = "body{font-family:sans-serif;margin:2em;max-width:110em}\
table{border-collapse:collapse}td,th{padding:2px 8px;border-bottom:1px solid #ccc;text-align:left}\
.FAIL{background:#fdd}.pass{background:#dfd}img{image-rendering:pixelated;max-width:100%}\
figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}figcaption{font-size:90%}\
.fixture{display:flex;flex-wrap:wrap;gap:1.5em;align-items:flex-start}.views{flex:1 1 60em}.rows{flex:1 1 30em}\
nav li{margin:2px 0}h1.FAIL,h1.pass{padding:4px 8px}ol.marks{font-size:85%;columns:2}";

/// Writes `index.html` and its images into `dir`: a static page that opens
/// from disk. Its title says pass or FAIL; a summary (counts, the failing
/// fixtures first, linked) and a table of contents come first; each
/// fixture then shows its views, each with labelled images (the render, the
/// render with the expected points numbered, the golden image and, where
/// they differ, the diff), beside its rows.
pub fn html(dir: &Path, reports: &[FixtureReport]) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let mut order: Vec<&FixtureReport> = reports.iter().collect();
    order.sort_by_key(|r| r.passed());
    let mut h = String::new();
    summary(&mut h, &order);
    for r in order {
        fixture_section(&mut h, dir, r)?;
    }
    crate::output::write_atomic(&dir.join("index.html"), h.as_bytes())
        .map_err(|e| format!("cannot write report: {e}"))
}

/// The page's head: the verdict in the title, the counts, the failing
/// fixtures linked, and the table of contents.
fn summary(h: &mut String, order: &[&FixtureReport]) {
    let failing: Vec<&&FixtureReport> = order.iter().filter(|r| !r.passed()).collect();
    let rows: Vec<&Row> = order.iter().flat_map(|r| &r.rows).collect();
    let goldens: Vec<&Comparison> = order.iter().flat_map(|r| &r.goldens).collect();
    let verdict = if failing.is_empty() {
        "pass".to_string()
    } else {
        format!("FAIL ({} of {} fixtures)", failing.len(), order.len())
    };
    let class = if failing.is_empty() { "pass" } else { "FAIL" };
    let _ = write!(
        h,
        "<!doctype html><meta charset=utf-8><title>VSTF report: {verdict}</title><style>{STYLE}</style>\
         <h1 class={class}>VSTF report: {verdict}</h1><p>{} fixtures; rows {} passed, {} failed; golden images {} passed, {} failed.</p>",
        order.len(),
        rows.iter().filter(|r| r.pass).count(),
        rows.iter().filter(|r| !r.pass).count(),
        goldens.iter().filter(|g| g.pass).count(),
        goldens.iter().filter(|g| !g.pass).count(),
    );
    if !failing.is_empty() {
        let links: Vec<String> = failing
            .iter()
            .map(|r| format!("<a href=\"#{}\">{}</a>", slug(&r.fixture), esc(&r.fixture)))
            .collect();
        let _ = write!(h, "<p class=FAIL>Failing: {}</p>", links.join(", "));
    }
    h.push_str("<nav><h2>Contents</h2><ol>");
    for r in order {
        let ok = |n: usize, of: usize| format!("{n}/{of}");
        let _ = write!(
            h,
            "<li class={}><a href=\"#{}\">{}</a>: rows {}, golden images {}</li>",
            if r.passed() { "pass" } else { "FAIL" },
            slug(&r.fixture),
            esc(&r.fixture),
            ok(r.rows.iter().filter(|x| x.pass).count(), r.rows.len()),
            ok(r.goldens.iter().filter(|g| g.pass).count(), r.goldens.len()),
        );
    }
    h.push_str("</ol></nav><p>The numbered crosses are where first-principles physics puts the points the checks read, computed without the ray tracer, drawn black on light pixels and white on dark ones. \
        A paper figure marked * differs from first principles by more than the tolerance (see docs/physics.md).</p>");
}

/// One fixture: its views with their images, each beside the rows
/// measured in it (views measuring the same rows share one table); rows of
/// no single view after them; then the failing golden comparisons with
/// actual and expected to swap.
fn fixture_section(h: &mut String, dir: &Path, r: &FixtureReport) -> Result<(), String> {
    let failed = r.rows.iter().filter(|x| !x.pass).count();
    let _ = write!(
        h,
        "<section id=\"{}\"><h2 class={}>{} {}</h2><p>{}</p>",
        slug(&r.fixture),
        if r.passed() { "pass" } else { "FAIL" },
        esc(&r.fixture),
        if r.passed() {
            "— pass".to_string()
        } else {
            format!("— FAIL ({failed} rows)")
        },
        esc(&r.description)
    );
    let mut shown = std::collections::HashSet::new();
    for group in r.views.chunk_by(|a, b| a.measured == b.measured) {
        h.push_str("<div class=fixture><div class=views>");
        for v in group {
            view_figures(h, dir, r, v)?;
        }
        h.push_str("</div><div class=rows>");
        let rows: Vec<&Row> = r
            .rows
            .iter()
            .filter(|x| group[0].measured.contains(&x.quantity) && shown.insert(&x.quantity))
            .collect();
        rows_table(h, &r.fixture, &rows);
        h.push_str("</div></div>");
    }
    let rest: Vec<&Row> = r
        .rows
        .iter()
        .filter(|x| !shown.contains(&x.quantity))
        .collect();
    if !rest.is_empty() {
        h.push_str("<h3>rows of no single view</h3>");
        rows_table(h, &r.fixture, &rest);
    }
    golden_section(h, dir, &r.goldens)?;
    h.push_str("</section>");
    Ok(())
}

/// A view's images, each captioned: the render, the expected points, the
/// golden image it was compared with, and the diff where they differ.
fn view_figures(
    h: &mut String,
    dir: &Path,
    r: &FixtureReport,
    v: &crate::check::ViewReport,
) -> Result<(), String> {
    let base = format!("{}-{}", slug(&r.fixture), slug(&v.name));
    crate::output::write_png(&dir.join(format!("{base}.png")), &v.image)?;
    crate::output::write_png(
        &dir.join(format!("{base}-markers.png")),
        &with_markers(&v.image, &v.markers),
    )?;
    let _ = write!(h, "<h3>view {}</h3>", esc(&v.name));
    let mut figure = |src: &str, caption: &str| {
        let _ = write!(
            h,
            "<figure><img src=\"{src}\" width=360><figcaption>{caption}</figcaption></figure>"
        );
    };
    figure(&format!("{base}.png"), "render");
    figure(
        &format!("{base}-markers.png"),
        &format!("render, {} expected points numbered", v.markers.len()),
    );
    let comparison = r.goldens.iter().find(|g| g.view == v.name);
    if let Some(golden) = comparison.and_then(|g| g.golden.as_ref()) {
        let name = format!("{base}-golden.png");
        std::fs::copy(golden, dir.join(&name))
            .map_err(|e| format!("cannot copy {}: {e}", golden.display()))?;
        figure(&name, "golden image");
    }
    if let Some(diff) = comparison
        .filter(|g| !g.pass)
        .and_then(|g| g.pending.as_ref())
        .map(|p| p.join("diff.png"))
    {
        if diff.is_file() {
            let name = format!("{base}-diff.png");
            std::fs::copy(&diff, dir.join(&name))
                .map_err(|e| format!("cannot copy {}: {e}", diff.display()))?;
            figure(&name, "diff from the golden (red: differing pixels)");
        }
    }
    marker_list(h, r, v);
    Ok(())
}

/// Which row each numbered marker belongs to, each linked to its row.
fn marker_list(h: &mut String, r: &FixtureReport, v: &crate::check::ViewReport) {
    if v.rows.iter().all(String::is_empty) {
        return;
    }
    h.push_str("<ol class=marks>");
    for row in &v.rows {
        if row.is_empty() {
            h.push_str("<li>-</li>");
        } else {
            let _ = write!(
                h,
                "<li><a href=\"#{}\">{}</a></li>",
                row_anchor(&r.fixture, row),
                esc(row)
            );
        }
    }
    h.push_str("</ol>");
}

/// The anchor of a fixture's row.
fn row_anchor(fixture: &str, quantity: &str) -> String {
    format!("{}-row-{}", slug(fixture), slug(quantity))
}

/// A table of `fixture`'s `rows`, failing first, each row anchored.
fn rows_table(h: &mut String, fixture: &str, rows: &[&Row]) {
    if rows.is_empty() {
        return;
    }
    h.push_str("<table><tr><th>quantity<th>measured<th>expected<th>paper<th>tolerance<th>unit<th>result</tr>");
    let mut rows = rows.to_vec();
    rows.sort_by_key(|x| x.pass);
    for x in rows {
        let res = if x.pass { "pass" } else { "FAIL" };
        let paper = x.paper.map_or("-".into(), |p| {
            format!("{}{}", num(p), if x.paper_disagrees() { " *" } else { "" })
        });
        let _ = write!(
            h,
            "<tr class={res} id=\"{}\"><td>{}<td>{}<td>{}<td>{}<td>±{}<td>{}<td>{res}</tr>",
            row_anchor(fixture, &x.quantity),
            esc(&x.quantity),
            num(x.measured),
            num(x.expected),
            paper,
            num(x.tolerance),
            esc(x.unit.as_str())
        );
    }
    h.push_str("</table>");
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
        let marked = with_markers(&img, &[(10.5, 10.5), (45.5, 10.5)]);
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
