//! The golden store's tests: approve, reject and the links they refuse.
use super::*;
use image::Rgb;

fn temp_store(name: &str) -> Store {
    let root = std::env::temp_dir().join(format!("vstf-golden-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    Store {
        golden: root.join("golden"),
        pending: root.join("pending"),
        root,
        writes_pending: true,
    }
}

fn picture() -> RgbImage {
    RgbImage::from_fn(32, 24, |x, y| Rgb([(x * 7) as u8, (y * 9) as u8, 100]))
}

#[test]
fn a_missing_golden_fails_and_leaves_a_pending_image() {
    let s = temp_store("missing");
    let c = s
        .check("flange", "frame 920", &picture(), Fuzzy::default())
        .unwrap();
    assert!(!c.pass && c.missing);
    assert!(
        c.to_string()
            .starts_with("golden MISSING fixture=flange view=frame-920"),
        "{c}"
    );
    assert!(s
        .pending_dir("flange", "frame 920")
        .join("actual.png")
        .is_file());
    assert!(!s.golden.exists(), "a check wrote into golden/");
}

#[test]
fn a_one_pixel_change_is_caught_with_a_diff() {
    let s = temp_store("onepixel");
    s.check("stage", "view", &picture(), Fuzzy::default())
        .unwrap();
    s.approve(None, false).unwrap();
    assert!(
        s.check("stage", "view", &picture(), Fuzzy::default())
            .unwrap()
            .pass
    );
    let mut changed = picture();
    changed.put_pixel(5, 6, Rgb([255, 255, 255]));
    let c = s
        .check("stage", "view", &changed, Fuzzy::default())
        .unwrap();
    assert!(!c.pass && !c.missing);
    assert_eq!((c.max_diff, c.differing), (Some(255 - 35), 1));
    assert!(
        c.to_string().starts_with(
            "golden FAIL fixture=stage view=view max_diff=220 differing=1 worst_pixel=5,6 size=32x24 allowed=fuzzy(0,0)"
        ),
        "{c}"
    );
    let dir = s.pending_dir("stage", "view");
    let diff = image::open(dir.join("diff.png")).unwrap().to_rgb8();
    assert_eq!(diff.get_pixel(5, 6).0, [255, 0, 0]);
    assert_ne!(diff.get_pixel(0, 0).0, [255, 0, 0]);
    assert!(dir.join("expected.png").is_file() && dir.join("actual.png").is_file());
    // A fuzzy allowance that covers the change lets it pass, and clears the pending images.
    assert!(
        s.check(
            "stage",
            "view",
            &changed,
            Fuzzy {
                max_diff: 255,
                max_pixels: 1
            }
        )
        .unwrap()
        .pass
    );
    assert!(!dir.exists());
    assert!(
        !s.check(
            "stage",
            "view",
            &changed,
            Fuzzy {
                max_diff: 219,
                max_pixels: 1
            }
        )
        .unwrap()
        .pass
    );
}

#[test]
fn approve_copies_only_pending_views_atomically_and_never_under_ci() {
    let s = temp_store("approve");
    s.check("a", "one", &picture(), Fuzzy::default()).unwrap();
    s.check("b", "two", &picture(), Fuzzy::default()).unwrap();
    assert_eq!(s.list_pending().len(), 2);
    let e = s.approve(None, true).unwrap_err();
    assert!(
        matches!(&e, Error::Golden { message } if message.contains("CI")),
        "{e}"
    );
    assert!(!s.golden.exists(), "approve under CI wrote a golden");
    let done = s.approve(Some(&["a".to_string()]), false).unwrap();
    assert_eq!(done.len(), 1);
    assert_eq!(done[0].fixture, "a");
    assert!(s.golden_path("a", "one").is_file() && !s.golden_path("b", "two").exists());
    assert_eq!(s.list_pending().len(), 1);
    // The golden is the pending image, and no temporary file is left beside it.
    assert_eq!(
        image::open(s.golden_path("a", "one")).unwrap().to_rgb8(),
        picture()
    );
    let names: Vec<String> = std::fs::read_dir(s.golden.join("a"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into())
        .collect();
    assert_eq!(names, ["one.png"]);
    // A passing view has nothing pending, so approving it is an error
    // that names what is pending, and its golden is left alone.
    assert!(
        s.check("a", "one", &picture(), Fuzzy::default())
            .unwrap()
            .pass
    );
    let before = std::fs::read(s.golden_path("a", "one")).unwrap();
    let e = s.approve(Some(&["a".to_string()]), false).unwrap_err();
    assert!(
        matches!(&e, Error::Golden { message }
            if message.contains("nothing pending for \"a\"; pending: b/two")),
        "{e}"
    );
    assert_eq!(std::fs::read(s.golden_path("a", "one")).unwrap(), before);
}

#[test]
fn approve_does_not_write_through_a_golden_that_is_a_link() {
    let s = temp_store("link");
    // A pending image (no golden yet), then a link where the golden goes.
    assert!(
        s.check("a", "one", &picture(), Fuzzy::default())
            .unwrap()
            .missing
    );
    std::fs::create_dir_all(s.golden.join("a")).unwrap();
    let elsewhere = s.golden.parent().unwrap().join("elsewhere.txt");
    std::fs::write(&elsewhere, "not an image").unwrap();
    std::os::unix::fs::symlink(&elsewhere, s.golden_path("a", "one")).unwrap();
    let e = s.approve(None, false).unwrap_err();
    assert!(
        matches!(&e, Error::Golden { message } if message.contains("is a symbolic link")),
        "{e}"
    );
    assert_eq!(std::fs::read_to_string(&elsewhere).unwrap(), "not an image");
}

/// A cloned repository's `target/vstf -> ../victim`: a passing check
/// that clears stale pending images deletes nothing in the victim, and
/// a failing one writes nothing there.
#[test]
fn a_linked_pending_folder_is_neither_cleared_nor_written() {
    let s = temp_store("linked-pending");
    let victim = s.root.join("victim");
    std::fs::create_dir_all(victim.join("a/one")).unwrap();
    std::fs::write(victim.join("a/one/important.txt"), "keep").unwrap();
    std::os::unix::fs::symlink(&victim, &s.pending).unwrap();
    crate::output::write_png(&s.golden_path("a", "one"), &picture()).unwrap();
    let e = s
        .check("a", "one", &picture(), Fuzzy::default())
        .unwrap_err();
    assert!(
        matches!(&e, Error::Io { path, .. } if *path == s.pending),
        "{e}"
    );
    let mut other = picture();
    other.put_pixel(0, 0, Rgb([0, 0, 0]));
    assert!(s.check("a", "one", &other, Fuzzy::default()).is_err());
    assert_eq!(
        std::fs::read_to_string(victim.join("a/one/important.txt")).unwrap(),
        "keep"
    );
    assert!(!victim.join("a/one/actual.png").exists());
    // Control: a real pending folder takes the mismatch.
    std::fs::remove_file(&s.pending).unwrap();
    assert!(s
        .check("a", "one", &other, Fuzzy::default())
        .unwrap()
        .pending
        .is_some());
}

/// With `golden/` linked outside the project, approve writes nothing.
#[test]
fn approve_does_not_write_through_a_linked_golden_folder() {
    let s = temp_store("linked-golden");
    assert!(
        s.check("a", "one", &picture(), Fuzzy::default())
            .unwrap()
            .missing
    );
    let elsewhere = s.root.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::os::unix::fs::symlink(&elsewhere, &s.golden).unwrap();
    let e = s.approve(None, false).unwrap_err();
    assert!(
        matches!(&e, Error::Io { path, .. } if *path == s.golden),
        "{e}"
    );
    assert!(std::fs::read_dir(&elsewhere).unwrap().next().is_none());
    // Control: a real golden folder takes the approval.
    std::fs::remove_file(&s.golden).unwrap();
    assert_eq!(s.approve(None, false).unwrap().len(), 1);
    assert!(s.golden_path("a", "one").is_file());
}
