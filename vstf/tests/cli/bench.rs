//! `vstf bench --quick`: every section of the benchmark, and Embree's side
//! where it is installed.

use crate::support::{vstf, RunExt};

/// At the baseline vector level (`--simd`, which its header names and
/// section 7's child processes inherit), as a smoke test of that path.
#[test]
fn bench_quick_prints_every_figure() {
    let run = vstf()
        .args(["--simd", "baseline", "bench", "--quick"])
        .run();
    run.succeeds();
    let text = run.stdout();
    assert!(
        text.starts_with("vstf bench (quick run")
            && text.contains("node tests at the build's baseline)"),
        "{text}"
    );
    for section in [
        "\n1. primary rays per second",
        "\n2. relativistic render time",
        "\n3. accelerated against brute force",
        "\n4. the same 28 moving boxes",
        "\n5. memory",
        "\n6. one 480x270 teaser frame",
        "\n7. against Embree 3",
    ] {
        assert!(text.contains(section), "{section:?} missing from:\n{text}");
    }
    // Each goal of the figures beside it.
    for goal in [
        "same scene and size (goal <= 1.3)",
        "(goal >= 100x at 10k)",
        "goal <= 0.3 s)",
        "frames in turn (goal <= 1.1x)",
    ] {
        assert!(text.contains(goal), "{goal:?} missing from:\n{text}");
    }
    // The cost of motion twice: across two processes on every thread, and
    // within one process on one bound core.
    let moving: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("moving at 0.9c"))
        .collect();
    assert_eq!(moving.len(), 2, "{text}");
    for line in moving {
        let ratios = line
            .split_whitespace()
            .filter(|w| w.ends_with('x') && w[..1].parse::<u8>().is_ok());
        assert_eq!(ratios.count(), 2, "two ratios: {line}");
        assert!(line.contains("one bound core"), "{line}");
    }
    // Section 7: with Embree installed both sides trace the same rays and
    // hit on the same pixels; without it, it says how to install it. Under
    // the header, the goals of the ratio columns.
    let seven = &text[text.find("\n7. against Embree 3").unwrap()..];
    let words: Vec<Vec<&str>> = seven
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .collect();
    let goals = words.iter().find(|w| w.first() == Some(&"goal"));
    assert_eq!(
        goals.map(|w| w.join(" ")).as_deref(),
        Some("goal <= 1.2x <= 1.3x <= 1.5x <= 2x"),
        "{seven}"
    );
    let table: Vec<&Vec<&str>> = words
        .iter()
        .filter(|w| w.len() == 12 && w[0].parse::<u64>().is_ok())
        .collect();
    assert_eq!(table.len(), 2, "{seven}");
    for row in &table {
        // A delivered frame is its render and then its PNG encoding.
        let secs = |i: usize| row[i].parse::<f64>().unwrap();
        assert!(secs(2) >= secs(1), "frame+png under the render: {seven}");
    }
    if std::path::Path::new("/usr/include/embree3/rtcore.h").is_file() {
        for row in &table {
            assert_eq!(row[10], row[11], "hits differ from Embree's: {seven}");
            for ratio in [5, 7, 8, 9] {
                assert!(row[ratio].ends_with('x'), "{seven}");
            }
        }
        for line in ["peak memory per triangle", "first frame"] {
            let found = seven.lines().find(|l| l.contains(line));
            assert!(
                found.is_some_and(|l| l.ends_with("(goal <= 1.2x)")),
                "{line}: {seven}"
            );
        }
    } else {
        assert!(seven.contains("apt-get install libembree-dev"), "{seven}");
    }
}
