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

/// The rows as a JSON array of objects with keys fixture, quantity,
/// measured, expected, paper, tolerance, unit, pass.
pub fn json(rows: &[Row]) -> String {
    serde_json::to_string_pretty(rows).expect("rows serialise")
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
