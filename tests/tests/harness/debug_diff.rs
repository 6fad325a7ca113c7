//! debug-diff tells two debug logs apart: field by field, within a
//! tolerance, ignoring the step kinds asked for, a line at a time.

use renderer::Traversal;
use vstf::debug::{diff_logs, trace_pixel};
use vstf::fixture::Overrides;

/// A 16x9 teaser log at one sample per pixel (a brute-force log holds every
/// tetrahedron of the scene for every ray, so it is kept small).
fn region_log(traversal: Traversal) -> String {
    let f = workspace_tests::fixture("teaser");
    let view = vstf::run::view(
        &f,
        &Overrides {
            width: Some(16),
            height: Some(9),
            spp: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    let db = vstf::run::database(&f, view.model.lorentz, traversal).unwrap();
    let mut out = String::new();
    for y in 0..9 {
        for x in 0..16 {
            out.push_str(
                &serde_json::to_string(&trace_pixel(&f, &view, &db, x, y).unwrap()).unwrap(),
            );
            out.push('\n');
        }
    }
    out
}

#[test]
fn a_log_taken_after_changing_the_traversal_matches_except_for_candidates() {
    let (bvh, brute) = (
        region_log(Traversal::Bvh),
        region_log(Traversal::BruteForce),
    );
    assert!(diff_logs(&bvh, &bvh, 0.0, &[]).unwrap().is_empty());
    let same = diff_logs(&bvh, &brute, 0.0, &["candidate".to_string()]).unwrap();
    assert!(same.is_empty(), "{same:?}");
    // The candidates tested do differ: the BVH culls.
    assert!(!diff_logs(&bvh, &brute, 0.0, &[]).unwrap().is_empty());
}

#[test]
fn debug_diff_reports_the_first_differing_field() {
    let log = region_log(Traversal::Bvh);
    let mut lines: Vec<serde_json::Value> = log
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let k = lines
        .iter()
        .position(|l| {
            l["steps"]
                .as_array()
                .unwrap()
                .iter()
                .any(|s| s["step"] == "hit")
        })
        .unwrap()
        + 3;
    let hit = lines[k]["steps"]
        .as_array()
        .unwrap()
        .iter()
        .position(|s| s["step"] == "hit")
        .expect("a pixel with a hit");
    let t = lines[k]["steps"][hit]["event"]["t"].as_f64().unwrap();
    lines[k]["steps"][hit]["event"]["t"] = (t + 1e-6).into();
    let edited: String = lines.iter().map(|l| format!("{l}\n")).collect();
    let d = diff_logs(&log, &edited, 1e-12, &[]).unwrap();
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].line, k + 1);
    assert_eq!(d[0].path, format!("steps[{hit}] (hit).event.t"));
    assert!(
        diff_logs(&log, &edited, 1e-3, &[]).unwrap().is_empty(),
        "within tolerance"
    );
    let shorter: String = log.lines().take(10).map(|l| format!("{l}\n")).collect();
    assert!(diff_logs(&log, &shorter, 0.0, &[])
        .unwrap()
        .iter()
        .any(|d| d.path == "(number of pixels)"));
}

/// The comparison reads both logs a line at a time, lists every field that
/// differs (or the first, with `first_only`), names the step kind, keeps
/// only the pixels asked for while counting all, and refuses an unknown
/// step kind to ignore.
#[test]
fn debug_diff_streams_and_lists_every_differing_field() {
    use vstf::debug::{diff_streams, DiffOptions};
    let log = region_log(Traversal::Bvh);
    let mut lines: Vec<serde_json::Value> = log
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    for l in lines.iter_mut() {
        l["color"][0] = (l["color"][0].as_f64().unwrap() + 0.5).into();
        l["rgb8"][0] = 7.into();
    }
    let edited: String = lines.iter().map(|l| format!("{l}\n")).collect();
    let all = DiffOptions {
        tol: 0.0,
        ignore: &[],
        first_only: false,
        keep: 2,
    };
    let c = diff_streams(log.as_bytes(), edited.as_bytes(), &all).unwrap();
    assert_eq!(c.differing, lines.len());
    assert_eq!(c.shown.len(), 2);
    let paths: Vec<&str> = c.shown[0].fields.iter().map(|f| f.0.as_str()).collect();
    assert!(
        paths.contains(&"color[0]") && paths.contains(&"rgb8[0]"),
        "{paths:?}"
    );
    let first = DiffOptions {
        first_only: true,
        ..all
    };
    let c = diff_streams(log.as_bytes(), edited.as_bytes(), &first).unwrap();
    assert_eq!(c.shown[0].fields.len(), 1);
    let bad = vec!["candidat".to_string()];
    let wrong = DiffOptions {
        ignore: &bad,
        ..first
    };
    let e = diff_streams(log.as_bytes(), log.as_bytes(), &wrong).unwrap_err();
    assert!(
        e.contains("no such step kind") && e.contains("candidate"),
        "{e}"
    );
    // One log longer than the other: a difference, not a silent pass.
    let short: String = log.lines().take(3).map(|l| format!("{l}\n")).collect();
    let c = diff_streams(log.as_bytes(), short.as_bytes(), &all).unwrap();
    assert!(c.differing >= 1 && c.lines == (lines.len(), 3), "{c:?}");
}
