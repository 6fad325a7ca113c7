//! Every vector level the machine runs gives every fixture's image to the
//! bit: the hierarchies' node tests are the only code that differs.

use renderer::{Packing, SimdLevel, Traversal};
use vstf::fixture::Overrides;
use workspace_tests::bits;

/// Each fixture at odd small sizes, several jittered samples over a
/// shutter, one ray at a time and in packets, at each level
/// [`SimdLevel::supported`] lists: the same bits as the baseline's.
#[test]
fn every_vector_level_renders_every_fixture_to_the_bit() {
    let levels = SimdLevel::supported();
    for name in workspace_tests::repo().fixture_names() {
        let f = workspace_tests::fixture(&name);
        let overrides = Overrides {
            width: Some(23),
            height: Some(17),
            camera_t: f
                .spec
                .camera
                .worldline
                .as_ref()
                .map(|_| f.spec.camera.t + 10.0),
            ..Default::default()
        };
        let mut view = vstf::run::view(&f, &overrides).unwrap();
        view.settings.spp = 2;
        view.settings.shutter = 2.0;
        let mut db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        for packing in [Packing::Single, Packing::Packets] {
            db.set_packing(packing);
            let mut images = levels.iter().map(|&level| {
                db.set_simd(level);
                (
                    level,
                    bits(&vstf::run::render_with(&db, &f, &view).unwrap()),
                )
            });
            let (_, baseline) = images.next().unwrap();
            for (level, image) in images {
                assert!(image == baseline, "{name}, {packing:?}: {level:?} differs");
            }
        }
    }
}

/// The control: where the CPU has x86-64-v3 (AVX2, FMA and the rest of
/// the level), the list holds the wider level, so the test above compares
/// two levels rather than one with itself.
#[test]
fn the_machines_wider_level_is_listed() {
    let levels = SimdLevel::supported();
    assert_eq!(levels[0], SimdLevel::Baseline);
    assert_eq!(SimdLevel::best(), levels[levels.len() - 1]);
    #[cfg(target_arch = "x86_64")]
    {
        use std::is_x86_feature_detected as has;
        let v3 = has!("avx")
            && has!("avx2")
            && has!("fma")
            && has!("bmi1")
            && has!("bmi2")
            && has!("lzcnt")
            && has!("popcnt")
            && has!("sse4.2");
        assert_eq!(levels.contains(&SimdLevel::X86V3), v3, "{levels:?}");
    }
}
