//! The VSTF's checks, run at test resolution: every measured quantity must
//! agree with first principles within its stated tolerance, and the table
//! is snapshotted so that any change to a measured value shows in review.

use std::sync::OnceLock;
use vstf::check::{Effort, FixtureReport, Row};
use vstf::golden::Store;

/// The quick run of every check, shared by the tests of this file.
fn reports() -> &'static Vec<FixtureReport> {
    static R: OnceLock<Vec<FixtureReport>> = OnceLock::new();
    R.get_or_init(|| {
        vstf::check::run(&workspace_tests::repo(), &[], &Effort::QUICK)
            .unwrap_or_else(|e| panic!("{e}"))
    })
}

fn rows() -> Vec<Row> {
    reports().iter().flat_map(|r| r.rows.clone()).collect()
}

/// Six significant digits: enough to see any real change, stable against
/// last-bit differences of libm.
fn sig(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(5 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

#[test]
fn every_checked_quantity_agrees_with_first_principles() {
    let rows = rows();
    let fixtures: Vec<&str> = reports().iter().map(|r| r.fixture.as_str()).collect();
    for f in [
        "stage",
        "flange",
        "terrell-decoupled",
        "terrell-contracted",
        "aberration",
        "teaser",
    ] {
        assert!(fixtures.contains(&f), "no check ran for {f}");
    }
    assert!(rows.len() >= 90, "only {} rows", rows.len());
    let failing: Vec<&Row> = rows.iter().filter(|r| !r.pass).collect();
    assert!(
        failing.is_empty(),
        "failing rows:\n{}",
        vstf::report::table(&rows)
    );
}

/// Positions on the stage within 0.01 l.units, velocities within 0.1%,
/// angles within 0.05 degrees.
fn assert_targets(rows: &[Row]) {
    for r in rows {
        match r.unit.as_str() {
            "l.units" => assert!(r.tolerance < 0.01, "{}: {}", r.quantity, r.tolerance),
            "deg" => assert!(r.tolerance < 0.05, "{}: {}", r.quantity, r.tolerance),
            "l.units/t.unit" => assert!(
                r.tolerance < 1e-3 * r.expected.abs(),
                "{}: {}",
                r.quantity,
                r.tolerance
            ),
            // An exact count (pixels disagreeing away from every edge) has
            // no tolerance; every other row a positive, finite one.
            "px" if r.expected == 0.0 && r.quantity.contains("away from edges") => {
                assert_eq!(r.tolerance, 0.0, "{}", r.quantity)
            }
            _ => assert!(
                r.tolerance > 0.0 && r.tolerance.is_finite(),
                "{}: {}",
                r.quantity,
                r.tolerance
            ),
        }
    }
}

#[test]
fn tolerances_meet_the_targets_at_the_default_check_resolution() {
    let full = vstf::check::run(&workspace_tests::repo(), &[], &Effort::FULL).unwrap();
    let rows: Vec<Row> = full.iter().flat_map(|r| r.rows.clone()).collect();
    assert!(
        rows.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&rows)
    );
    assert_targets(&rows);
}

#[test]
fn measurement_table_snapshot() {
    let rounded: Vec<serde_json::Value> = rows()
        .iter()
        .map(|r| {
            serde_json::json!({
                "fixture": r.fixture, "quantity": r.quantity, "measured": sig(r.measured),
                "expected": sig(r.expected), "paper": r.paper, "tolerance": sig(r.tolerance),
                "unit": r.unit, "pass": r.pass,
            })
        })
        .collect();
    insta::assert_json_snapshot!("check_rows", rounded);
}

#[test]
fn json_rows_have_exactly_the_documented_keys() {
    let v: serde_json::Value = serde_json::from_str(&vstf::report::json(&rows())).unwrap();
    let arr = v.as_array().unwrap();
    assert!(!arr.is_empty());
    for o in arr {
        let mut keys: Vec<&str> = o.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort();
        // The camera time of a row measured in a view whose time was solved
        // on loading: only the views of the rocket fixtures, given by
        // proper time.
        if keys.contains(&"camera_t") {
            let fixture = o["fixture"].as_str();
            assert!(
                matches!(
                    fixture,
                    Some("rocket" | "rocket-doppler" | "rocket-keyframes")
                ),
                "{o}"
            );
            keys.retain(|k| *k != "camera_t");
        }
        assert_eq!(
            keys,
            [
                "expected",
                "fixture",
                "measured",
                "paper",
                "pass",
                "quantity",
                "tolerance",
                "unit"
            ]
        );
        assert!(o["paper"].is_null() || o["paper"].is_number());
    }
}

#[test]
fn the_report_shows_images_markers_and_rows() {
    let dir = std::env::temp_dir().join(format!("vstf-report-{}", std::process::id()));
    vstf::report::html(&dir, reports()).unwrap();
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    // A passing run says so in its title, with the counts and contents.
    assert!(
        html.contains("<title>VSTF report: pass</title>"),
        "{}",
        &html[..300]
    );
    assert!(html.contains("<nav><h2>Contents</h2>"));
    for r in reports() {
        let anchor = vstf::golden::slug(&r.fixture);
        assert!(
            html.contains(&format!("<section id=\"{anchor}\">"))
                && html.contains(&format!("href=\"#{anchor}\"")),
            "{} missing or not in the contents",
            r.fixture
        );
        for v in &r.views {
            assert!(
                html.contains(&format!("<h3>view {}</h3>", v.name)),
                "{} {}",
                r.fixture,
                v.name
            );
        }
        // Every view a row is measured in marks where first principles put
        // it (the rocket's horizon views have no rows: tests/tests/harness/rocket.rs).
        for v in r.views.iter().filter(|v| !v.measured.is_empty()) {
            assert!(
                !v.markers.is_empty(),
                "{} {} has no expected points",
                r.fixture,
                v.name
            );
            let (w, h) = (f64::from(v.image.width()), f64::from(v.image.height()));
            let inside = v
                .markers
                .iter()
                .filter(|(x, y)| (0.0..w).contains(x) && (0.0..h).contains(y))
                .count();
            let groups = vstf::report::marker_groups(&v.markers, &v.rows);
            let marked = vstf::report::with_markers(&v.image, &groups);
            assert!(
                inside == 0 || marked != v.image,
                "{} {}: markers not drawn",
                r.fixture,
                v.name
            );
        }
    }
    let pngs = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "png")
        })
        .count();
    assert!(pngs >= 2 * reports().iter().map(|r| r.views.len()).sum::<usize>());
    assert!(html.contains("golden image"), "no golden images shown");
    // Numbered markers of declared checks link to their rows.
    let flange = reports().iter().find(|r| r.fixture == "flange").unwrap();
    let row = &flange.views[0].rows[0];
    assert!(!row.is_empty(), "the flange's marker names no row");
    let anchor = format!("flange-row-{}", vstf::golden::slug(row));
    assert!(
        html.contains(&format!("<a href=\"#{anchor}\">"))
            && html.contains(&format!("id=\"{anchor}\"")),
        "the marker of {row:?} is not linked to its row"
    );
    std::fs::remove_dir_all(&dir).ok();
    // A failing run says FAIL in its title and lists the failing fixture first.
    let mut failing: Vec<FixtureReport> = reports().iter().take(2).map(copy_of).collect();
    failing[1].rows[0].pass = false;
    let dir = std::env::temp_dir().join(format!("vstf-report-fail-{}", std::process::id()));
    vstf::report::html(&dir, &failing).unwrap();
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let name = &failing[1].fixture;
    assert!(
        html.contains("<title>VSTF report: FAIL (1 of 2 fixtures)</title>"),
        "{}",
        &html[..300]
    );
    assert!(html.contains(&format!(
        "<p class=FAIL>Failing: <a href=\"#{}\">{name}</a></p>",
        vstf::golden::slug(name)
    )));
    assert!(
        html.contains(&format!(">{name} — FAIL (1 row)</h2>")),
        "the failing fixture's heading"
    );
    let first = html.find("<section id=").unwrap();
    assert!(html[first..].starts_with(&format!("<section id=\"{}\">", vstf::golden::slug(name))));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn each_view_shows_the_rows_measured_in_it() {
    // Every row of the suite is measured in some view, and the report
    // shows it once, beside that view.
    for r in reports() {
        for row in &r.rows {
            assert!(
                r.views.iter().any(|v| v.measured.contains(&row.quantity)),
                "{}: row {:?} is attributed to no view",
                r.fixture,
                row.quantity
            );
        }
    }
    let dir = std::env::temp_dir().join(format!("vstf-report-views-{}", std::process::id()));
    let chosen: Vec<FixtureReport> = reports()
        .iter()
        .filter(|r| r.fixture == "aberration" || r.fixture == "flange")
        .map(copy_of)
        .collect();
    vstf::report::html(&dir, &chosen).unwrap();
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    for r in &chosen {
        for row in &r.rows {
            let id = format!(
                "id=\"{}-row-{}\"",
                vstf::golden::slug(&r.fixture),
                vstf::golden::slug(&row.quantity)
            );
            assert_eq!(
                html.matches(&id).count(),
                1,
                "{id} is not shown exactly once"
            );
        }
    }
    let view = "approaching 0.5c classical";
    let at = html.find(&format!("<h3>view {view}</h3>")).unwrap();
    let next = at + 4 + html[at + 4..].find("<h3>view ").unwrap();
    let row = format!(
        "aberration-row-{}",
        vstf::golden::slug(&format!("{view}: left edge azimuth"))
    );
    let shown = html.find(&format!("id=\"{row}\"")).unwrap();
    assert!(at < shown && shown < next, "the row is not beside its view");
    assert!(!html.contains("rows of no single view"));
    // Control: rows no view measured are not lost, they follow the views.
    let mut orphans = copy_of(chosen.iter().find(|r| r.fixture == "aberration").unwrap());
    for v in &mut orphans.views {
        v.measured.clear();
    }
    vstf::report::html(&dir, &[orphans]).unwrap();
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let rest = html
        .find("rows of no single view")
        .expect("orphan rows not shown");
    assert!(html.find(&format!("id=\"{row}\"")).unwrap() > rest);
    std::fs::remove_dir_all(&dir).ok();
}

/// A report's copy (reports hold images and cannot be cloned wholesale).
fn copy_of(r: &FixtureReport) -> FixtureReport {
    FixtureReport {
        fixture: r.fixture.clone(),
        description: r.description.clone(),
        views: r
            .views
            .iter()
            .map(|v| vstf::check::ViewReport {
                name: v.name.clone(),
                image: v.image.clone(),
                markers: v.markers.clone(),
                rows: v.rows.clone(),
                measured: v.measured.clone(),
            })
            .collect(),
        rows: r.rows.clone(),
        goldens: r.goldens.clone(),
        declared_views: r.declared_views.clone(),
    }
}

/// Mutation: the flange rendered 0.01 l.units to the right of where its
/// declaration puts it. The declared edge rows of both frames fail (the
/// velocity, a difference, does not move); the honest render passes them.
#[test]
fn a_flange_rendered_a_hundredth_elsewhere_fails_its_edge_rows() {
    let f = workspace_tests::fixture("flange");
    let mut shifted = f.clone();
    let obj = shifted
        .scene
        .objects
        .iter_mut()
        .find(|o| o.name == "flange")
        .unwrap();
    let renderer::Motion::Extrusion { start, .. } = &mut obj.motion else {
        panic!("the flange moves by extrusion");
    };
    start.x.x += 0.01;
    let judged = |rendered: &vstf::Fixture| -> Vec<Row> {
        vstf::check::evaluate(rendered, &f, &Effort::QUICK)
            .unwrap()
            .quantities
            .into_iter()
            .map(|q| q.judge("flange"))
            .collect()
    };
    let (honest, moved) = (judged(&f), judged(&shifted));
    let edges = |rows: &[Row]| -> Vec<Row> {
        rows.iter()
            .filter(|r| r.quantity.starts_with("right edge"))
            .cloned()
            .collect()
    };
    assert_eq!(edges(&honest).len(), 2);
    assert!(
        honest.iter().all(|r| r.pass),
        "{}",
        vstf::report::table(&honest)
    );
    for r in edges(&moved) {
        assert!(!r.pass, "a 0.01 shift went unnoticed: {r:?}");
        assert_abs_diff_eq!(r.measured - r.expected, 0.01, epsilon = 2.0 * r.tolerance);
    }
}

#[test]
fn every_view_matches_its_golden_image() {
    let goldens: Vec<_> = reports().iter().flat_map(|r| r.goldens.iter()).collect();
    let views: usize = reports().iter().map(|r| r.views.len()).sum();
    assert_eq!(goldens.len(), views);
    let failing: Vec<String> = goldens
        .iter()
        .filter(|g| !g.pass)
        .map(|g| g.to_string())
        .collect();
    assert!(failing.is_empty(), "{}", failing.join("\n"));
}

#[test]
fn a_one_pixel_change_in_a_real_render_is_caught_without_touching_golden() {
    let r = reports().iter().find(|r| r.fixture == "flange").unwrap();
    let view = &r.views[0];
    let real = workspace_tests::repo().store();
    let golden_path = real.golden_path(&r.fixture, &view.name);
    let before = std::fs::read(&golden_path).unwrap();
    let scratch = std::env::temp_dir().join(format!("vstf-pending-{}", std::process::id()));
    // The repository's goldens and a scratch pending folder share only `/`.
    let store = Store {
        root: std::path::PathBuf::from("/"),
        golden: real.golden.clone(),
        pending: scratch.clone(),
        writes_pending: true,
    };
    let mut changed = view.image.clone();
    let p = changed.get_pixel(10, 10).0;
    changed.put_pixel(10, 10, image::Rgb([p[0] ^ 0x80, p[1], p[2]]));
    let c = store
        .check(&r.fixture, &view.name, &changed, Default::default())
        .unwrap();
    assert!(!c.pass);
    assert_eq!((c.max_diff, c.differing), (Some(0x80), 1));
    let line = c.to_string();
    assert!(
        line.starts_with(
            "golden FAIL fixture=flange view=frame-920 max_diff=128 differing=1 worst_pixel=10,10 size=240x180 allowed=fuzzy(0,0)"
        ),
        "{line}"
    );
    let dir = store.pending_dir(&r.fixture, &view.name);
    for f in ["actual.png", "expected.png", "diff.png"] {
        assert!(dir.join(f).is_file(), "{f} not written");
    }
    assert_eq!(
        std::fs::read(&golden_path).unwrap(),
        before,
        "the golden was modified"
    );
    std::fs::remove_dir_all(&scratch).ok();
}

/// Every view a named kind renders for its golden image is reproduced bit
/// for bit through `--view` (`check::golden_view`), and `list --views`
/// has them all.
#[test]
fn named_kinds_views_reproduce_their_goldens() {
    let repo = workspace_tests::repo();
    let store = repo.store();
    let mut checked = 0;
    for name in repo.fixture_names() {
        let f = repo.load(&name).unwrap();
        for v in vstf::check::views_of(&f) {
            if v.rendered_by.is_none() {
                continue;
            }
            let (fixture, view) = vstf::check::golden_view(&f, &v.name).unwrap();
            let img =
                vstf::rgb8(&vstf::run::render(&fixture, &view, renderer::Traversal::Bvh).unwrap());
            let golden = image::open(store.golden_path(&name, &v.name))
                .unwrap()
                .to_rgb8();
            assert!(img == golden, "{name} / {}: not its golden image", v.name);
            checked += 1;
        }
    }
    assert!(checked >= 25, "only {checked} named views");
}
