//! `vstf bench --quick`: every section of the benchmark, and Embree's side
//! where it is installed.

use crate::support::{vstf, RunExt};

#[test]
fn bench_quick_prints_every_figure() {
    let run = vstf().args(["bench", "--quick"]).run();
    run.succeeds();
    let text = run.stdout();
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
    // Section 7: with Embree installed both sides trace the same rays and
    // hit on the same pixels; without it, it says how to install it.
    let seven = &text[text.find("\n7. against Embree 3").unwrap()..];
    let table: Vec<Vec<&str>> = seven
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|w| w.len() == 9 && w[0].parse::<u64>().is_ok())
        .collect();
    assert_eq!(table.len(), 2, "{seven}");
    if std::path::Path::new("/usr/include/embree3/rtcore.h").is_file() {
        for row in &table {
            assert_eq!(row[7], row[8], "hits differ from Embree's: {seven}");
            assert!(row[4].ends_with('x'), "{seven}");
        }
        assert!(seven.contains("peak memory per triangle"), "{seven}");
    } else {
        assert!(seven.contains("apt-get install libembree-dev"), "{seven}");
    }
}
