//! The static HTML report: a summary, each fixture's views with their
//! expected-point markers and rows, and the golden comparisons.

use super::markers::{marker_groups, with_markers, MarkerGroup};
use super::numbers::num;
use crate::check::{FixtureReport, Row};
use crate::golden::{slug, Comparison};
use std::fmt::Write as _;
use std::path::Path;

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
        format!(
            "FAIL ({} of {})",
            failing.len(),
            counted(order.len(), "fixture", "fixtures")
        )
    };
    let class = if failing.is_empty() { "pass" } else { "FAIL" };
    let _ = write!(
        h,
        "<!doctype html><meta charset=utf-8><title>VSTF report: {verdict}</title><style>{STYLE}</style>\
         <h1 class={class}>VSTF report: {verdict}</h1><p>{}; rows {} passed, {} failed; golden images {} passed, {} failed.</p>",
        counted(order.len(), "fixture", "fixtures"),
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
    h.push_str("</ol></nav><p>The crosses are where first-principles physics puts the points the checks read, computed without the ray tracer, drawn black on light pixels and white on dark ones, \
        numbered by the row they belong to (the legend under each view lists each row once); where points crowd their crosses shrink, down to dots, and a row's points within 40 pixels of each other carry its number once, beside them. \
        A paper figure marked * differs from first principles by more than the tolerance (see docs/physics.md).</p>");
}

/// One fixture: its views with their images, each beside the rows
/// measured in it (views measuring the same rows share one table); rows of
/// no single view after them; then the failing golden comparisons with
/// actual and expected to swap.
fn fixture_section(h: &mut String, dir: &Path, r: &FixtureReport) -> Result<(), String> {
    let _ = write!(
        h,
        "<section id=\"{}\"><h2 class={}>{} {}</h2><p>{}</p>",
        slug(&r.fixture),
        if r.passed() { "pass" } else { "FAIL" },
        esc(&r.fixture),
        verdict(r),
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
    let groups = marker_groups(&v.markers, &v.rows);
    crate::output::write_png(
        &dir.join(format!("{base}-markers.png")),
        &with_markers(&v.image, &groups),
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
        &format!(
            "render, {} numbered by row",
            counted(v.markers.len(), "expected point", "expected points")
        ),
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
    marker_list(h, &r.fixture, &groups);
    Ok(())
}

/// The legend: each row with markers once, under its number, linked to
/// the row, with how many points it marks.
fn marker_list(h: &mut String, fixture: &str, groups: &[MarkerGroup]) {
    if groups.iter().all(|g| g.row.is_empty()) {
        return;
    }
    h.push_str("<ol class=marks>");
    for g in groups {
        let points = counted(g.points.len(), "point", "points");
        if g.row.is_empty() {
            let _ = write!(h, "<li value={}>no row ({points})</li>", g.number);
        } else {
            let _ = write!(
                h,
                "<li value={}><a href=\"#{}\">{}</a> ({points})</li>",
                g.number,
                row_anchor(fixture, &g.row),
                esc(&g.row)
            );
        }
    }
    h.push_str("</ol>");
}

/// `n` and the noun in the number it takes: "1 row", "2 rows", "0 rows".
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// What a fixture's heading says after its name: "— pass", or "— FAIL"
/// with how many rows failed.
fn verdict(r: &FixtureReport) -> String {
    if r.passed() {
        return "— pass".to_string();
    }
    let failed = r.rows.iter().filter(|x| !x.pass).count();
    format!("— FAIL ({})", counted(failed, "row", "rows"))
}

/// The anchor of a fixture's row.
fn row_anchor(fixture: &str, quantity: &str) -> String {
    format!("{}-row-{}", slug(fixture), slug(quantity))
}

/// A table of `fixture`'s `rows`, failing first, each row anchored, a row
/// that could not be measured followed by why.
fn rows_table(h: &mut String, fixture: &str, rows: &[&Row]) {
    if rows.is_empty() {
        return;
    }
    h.push_str("<table><tr><th>quantity<th>measured<th>expected<th>paper<th>tolerance<th>unit<th>result</tr>");
    let mut rows = rows.to_vec();
    rows.sort_by_key(|x| x.pass);
    for x in rows {
        let res = if x.pass { "pass" } else { "FAIL" };
        let num = |v: f64| {
            if x.error.is_some() {
                "-".into()
            } else {
                num(v)
            }
        };
        let paper = x.paper.map_or("-".into(), |p| {
            format!("{}{}", num(p), if x.paper_disagrees() { " *" } else { "" })
        });
        let _ = write!(
            h,
            "<tr class={res} id=\"{}\"><td>{}<td>{}<td>{}<td>{}<td>{}<td>{}<td>{res}</tr>",
            row_anchor(fixture, &x.quantity),
            esc(&x.quantity),
            num(x.measured),
            num(x.expected),
            paper,
            if x.error.is_some() {
                "-".into()
            } else {
                format!("±{}", num(x.tolerance))
            },
            esc(x.unit.as_str())
        );
        if let Some(e) = &x.error {
            let _ = write!(h, "<tr class=FAIL><td colspan=7>{}</tr>", esc(e));
        }
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

    fn row(quantity: &str, pass: bool) -> Row {
        Row {
            fixture: "ball".into(),
            quantity: quantity.into(),
            measured: 1.0,
            expected: 1.0,
            paper: None,
            tolerance: 0.1,
            unit: Unit::LUnitsPerTUnit,
            pass,
            error: None,
            camera_t: None,
        }
    }

    fn report(rows: Vec<Row>) -> FixtureReport {
        FixtureReport {
            fixture: "ball".into(),
            description: String::new(),
            views: Vec::new(),
            rows,
            goldens: Vec::new(),
            declared_views: Vec::new(),
        }
    }

    /// One failing row is "1 row", two are "2 rows"; all passing is "pass".
    #[test]
    fn the_heading_counts_failed_rows_in_the_right_number() {
        let one = report(vec![row("radius", false), row("centre", true)]);
        assert_eq!(verdict(&one), "— FAIL (1 row)");
        let two = report(vec![row("radius", false), row("centre", false)]);
        assert_eq!(verdict(&two), "— FAIL (2 rows)");
        assert_eq!(verdict(&report(vec![row("radius", true)])), "— pass");
        assert_eq!(counted(0, "row", "rows"), "0 rows");
        let mut h = String::new();
        summary(&mut h, &[&one]);
        assert!(
            h.contains("<title>VSTF report: FAIL (1 of 1 fixture)</title>"),
            "{h}"
        );
        let mut h = String::new();
        summary(&mut h, &[&one, &two]);
        assert!(h.contains("FAIL (2 of 2 fixtures)"), "{h}");
    }

    /// The legend lists a row once however many points it marks, with
    /// their count; two rows are listed under their own numbers.
    #[test]
    fn the_legend_lists_each_row_once() {
        let at: Vec<(f64, f64)> = (0..16).map(|k| (f64::from(k), 5.0)).collect();
        let mut rows = vec!["ball radius".to_string(); 16];
        let mut h = String::new();
        marker_list(&mut h, "ball", &marker_groups(&at, &rows));
        assert_eq!(h.matches(">ball radius<").count(), 1, "{h}");
        assert_eq!(h.matches("<li").count(), 1, "{h}");
        assert!(h.contains("(16 points)"), "{h}");
        rows[3] = "ball centre".into();
        let mut h = String::new();
        marker_list(&mut h, "ball", &marker_groups(&at, &rows));
        assert_eq!(h.matches("<li").count(), 2, "{h}");
        assert!(
            h.contains("<li value=2><a href=\"#ball-row-ball-centre\">ball centre</a> (1 point)"),
            "{h}"
        );
    }
}
