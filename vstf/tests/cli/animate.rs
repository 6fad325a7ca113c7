//! `vstf animate`: frame sequences, GIFs and APNGs, labels, bad ranges and
//! `--resume`.

use crate::support::{rgb, vstf, RunExt, Scratch};
use std::path::Path;

#[test]
fn animate_writes_a_sequence_a_gif_and_an_apng() {
    let scratch = Scratch::new("anim");
    // A folder not made yet: animate makes the folders it writes into.
    let dir = scratch.join("new");
    let run = |out: &Path| {
        vstf()
            .args([
                "animate", "teaser", "--frames", "10..20", "--step", "5", "--width", "48",
                "--height", "27", "--out",
            ])
            .arg(out)
            .run()
            .succeeds()
            .stderr()
            .to_string()
    };
    let msg = run(&dir.join("seq"));
    assert!(
        msg.contains("3 frames") && msg.contains("database built once"),
        "{msg}"
    );
    let frames: Vec<_> = (0..3)
        .map(|i| rgb(&dir.join("seq").join(format!("frame-{i:05}.png"))))
        .collect();
    assert_ne!(
        frames[0].as_raw(),
        frames[2].as_raw(),
        "the flanges should move between frames"
    );
    run(&dir.join("a.gif"));
    let gif = std::fs::File::open(dir.join("a.gif")).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif)).unwrap();
    use image::AnimationDecoder;
    assert_eq!(decoder.into_frames().count(), 3);
    assert!(
        !dir.join("a.gif.frames").exists(),
        "the frames folder is removed once the GIF is written"
    );
    run(&dir.join("a.png"));
    let apng = std::fs::read(dir.join("a.png")).unwrap();
    assert!(apng.windows(4).any(|w| w == b"acTL"));
    assert_eq!(apng.windows(4).filter(|w| *w == b"fcTL").count(), 3);
}

#[test]
fn animate_refuses_bad_ranges() {
    vstf()
        .args(["animate", "teaser", "--frames", "20..10", "--out", "/tmp/x"])
        .run()
        .fails_with("the end is before the start");
    vstf()
        .args(["animate", "teaser", "--frames", "0..1", "--step", "0"])
        .args(["--out", "/tmp/x"])
        .run()
        .fails_with("must be positive");
}

/// `animate --label` writes each frame's camera time on it; the frames
/// differ from unlabelled ones only in the label's corner.
#[test]
fn animate_label_marks_each_frame_with_its_time() {
    let scratch = Scratch::new("label");
    let dir = scratch.join("new");
    let frames = |d: &Path, label: bool| {
        vstf()
            .args(["animate", "flange", "--frames", "940..941"])
            .args(["--width", "64", "--height", "48", "--spp", "1", "--out"])
            .arg(d)
            .args(label.then_some("--label"))
            .run()
            .succeeds();
        rgb(&d.join("frame-00001.png"))
    };
    let (plain, labelled) = (
        frames(&dir.join("plain"), false),
        frames(&dir.join("labelled"), true),
    );
    let changed: Vec<(u32, u32)> = plain
        .enumerate_pixels()
        .filter(|(x, y, p)| labelled.get_pixel(*x, *y) != *p)
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(changed.len() > 20, "no label drawn");
    assert!(
        changed.iter().all(|&(x, y)| x < 64 && y < 12),
        "{changed:?}"
    );
}

/// `animate --resume` keeps the frames a run of the same animation wrote
/// whole and renders the missing and broken ones; frames of another
/// animation are not resumed.
#[test]
fn animate_resume_renders_only_missing_and_broken_frames() {
    let dir = Scratch::new("resume");
    let frames = dir.join("frames");
    let animate = |extra: &[&str]| {
        vstf()
            .args([
                "animate", "stage", "--frames", "0..9", "--width", "32", "--height", "24", "--out",
            ])
            .arg(&frames)
            .args(extra)
            .run()
    };
    animate(&[]).succeeds();
    let frame = |i: usize| frames.join(format!("frame-{i:05}.png"));
    let kept: Vec<(Vec<u8>, std::time::SystemTime)> = (0..10)
        .map(|i| {
            (
                std::fs::read(frame(i)).unwrap(),
                std::fs::metadata(frame(i)).unwrap().modified().unwrap(),
            )
        })
        .collect();
    std::fs::remove_file(frame(3)).unwrap();
    std::fs::write(frame(5), "not a png").unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    animate(&["--resume"]).succeeds();
    for (i, (bytes, when)) in kept.iter().enumerate() {
        assert_eq!(
            &std::fs::read(frame(i)).unwrap(),
            bytes,
            "frame {i} differs"
        );
        if i != 3 && i != 5 {
            let now = std::fs::metadata(frame(i)).unwrap().modified().unwrap();
            assert_eq!(&now, when, "frame {i} was rendered again");
        }
    }
    for changed in [
        &["--resume", "--step", "2"][..],
        &["--resume", "--doppler"][..],
    ] {
        animate(changed).fails_with("belong to another animation");
    }
    // A new animation into the same folder (not resumed) removes the old
    // frames, so that no later --resume can keep them.
    animate(&["--step", "2"]).succeeds();
    assert!(
        frame(4).exists() && !frame(5).exists(),
        "an old frame was left"
    );
}

/// `--frames tau:A..B` steps an accelerating camera's proper time: its
/// frames are the views declared at those proper times, bit for bit;
/// plain `A..B` steps lab time, which the camera's clock lags.
#[test]
fn animate_steps_an_accelerating_cameras_proper_time_or_lab_time() {
    let scratch = Scratch::new("rocket");
    let animate = |frames: &str, out: &str| {
        vstf()
            .args(["animate", "rocket", "--view", "start", "--frames", frames])
            .args(["--step", "4", "--out"])
            .arg(scratch.join(out))
            .run()
            .succeeds();
        (0..3)
            .map(|i| rgb(&scratch.join(out).join(format!("frame-{i:05}.png"))))
            .collect::<Vec<_>>()
    };
    let proper = animate("tau:0..8", "proper");
    for (i, view) in [(1, "cruise"), (2, "fast")] {
        let still = scratch.join(format!("{view}.png"));
        vstf()
            .args(["render", "rocket", "--view", view, "--out"])
            .arg(&still)
            .run()
            .succeeds();
        assert_eq!(proper[i].as_raw(), rgb(&still).as_raw(), "{view}");
    }
    let lab = animate("0..8", "lab");
    assert_eq!(
        lab[0].as_raw(),
        proper[0].as_raw(),
        "both start at the start"
    );
    assert_ne!(
        lab[2].as_raw(),
        proper[2].as_raw(),
        "lab time 8 is not proper time 8"
    );
    vstf()
        .args(["animate", "rocket", "--frames", "tau:0..100", "--out"])
        .arg(scratch.join("x"))
        .run()
        .fails_with("--frames: proper time 25");
    vstf()
        .args(["animate", "teaser", "--frames", "tau:0..1", "--out"])
        .arg(scratch.join("y"))
        .run()
        .fails_with("camera.worldline");
}
