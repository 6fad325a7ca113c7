//! `vstf render`: sizes, views, models, colour flags, camera times, where
//! it writes and what it refuses; `vstf list --views`.

use crate::support::{repo_root, rgb, vstf, RunExt, Scratch};
use std::path::Path;

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = Scratch::new("size");
    let out = dir.join("out.png");
    vstf()
        .args(["render", "flange", "--out"])
        .arg(&out)
        .args([
            "--width",
            "64",
            "--height",
            "48",
            "--model",
            "classical",
            "--camera-t",
            "1171",
        ])
        .run()
        .succeeds();
    assert_eq!(rgb(&out).dimensions(), (64, 48));
}

#[test]
fn a_missing_fixture_is_a_clear_error_not_a_panic() {
    let run = vstf()
        .args(["render", "no-such-scene", "--out", "/tmp/x.png"])
        .run();
    run.fails_with("no fixture \"no-such-scene\"")
        .stderr_lacks("panicked");
    assert!(run.stderr().starts_with("error: "), "{run}");
}

#[test]
fn an_absurd_resolution_is_refused() {
    vstf()
        .args(["render", "flange", "--out", "/tmp/x.png", "--width", "0"])
        .run()
        .fails_with("flange.json: image: resolution 0x480 is out of range");
}

/// --doppler and --searchlight change the picture of moving surfaces and
/// leave static ones alone; keyframed scenes render.
#[test]
fn doppler_and_searchlight_flags_change_moving_colours() {
    let dir = Scratch::new("doppler");
    let render = |fixture: &str, flags: &[&str], name: &str| {
        let out = dir.join(name);
        vstf()
            .args(["render", fixture, "--out"])
            .arg(&out)
            .args(["--width", "80", "--height", "60", "--spp", "1"])
            .args(flags)
            .run()
            .succeeds();
        rgb(&out)
    };
    // The accelerated fixture's plates move at up to 0.99c.
    let plain = render("accelerated", &[], "plain.png");
    let shifted = render("accelerated", &["--doppler"], "shifted.png");
    let lit = render("accelerated", &["--searchlight"], "lit.png");
    assert_ne!(plain, shifted);
    assert_ne!(plain, lit);
    // The stage is static and the camera at rest: every factor is 1.
    let a = render("stage", &["--searchlight"], "stage.png");
    let b = render("stage", &[], "stage-plain.png");
    assert_eq!(a, b, "the searchlight of static surfaces is 1");
}

/// `render --view` reproduces a declared view bit for bit as `vstf check`
/// renders it for its golden image (colour effects included); an unknown
/// view is an error naming the declared ones.
#[test]
fn render_view_reproduces_the_golden_image() {
    let dir = Scratch::new("view");
    for (fixture, view, golden) in [
        ("flange", "frame 1151", "flange/frame-1151.png"),
        ("accelerated", "t_c = 22", "accelerated/t-c-22.png"),
        (
            "doppler",
            "doppler and searchlight",
            "doppler/doppler-and-searchlight.png",
        ),
        (
            "sphere-relativistic",
            "view",
            "sphere-relativistic/view.png",
        ),
    ] {
        let out = dir.join("view.png");
        vstf()
            .args(["render", fixture, "--view", view, "--out"])
            .arg(&out)
            .run()
            .succeeds();
        let approved = rgb(&repo_root().join("golden").join(golden));
        assert!(
            rgb(&out) == approved,
            "{fixture} {view} differs from {golden}"
        );
    }
    let no_view = ["--out", "/tmp/vstf-no.png"];
    vstf()
        .args(["render", "flange", "--view", "frame 9"])
        .args(no_view)
        .run()
        .fails_with("declared views: frame 920, frame 1151");
    // A named check's own views are taken too, exactly as checked; an
    // unknown name points at them.
    let png = dir.join("named.png");
    vstf()
        .args(["render", "stage", "--view", "view", "--out"])
        .arg(&png)
        .run()
        .succeeds();
    assert_eq!(
        std::fs::read(&png).unwrap(),
        std::fs::read(repo_root().join("golden/stage/view.png")).unwrap()
    );
    vstf()
        .args(["render", "stage", "--view", "nowhere"])
        .args(no_view)
        .run()
        .fails_with("its named check stage renders views of other names");
}

/// `list --views` names each declared view as `--view` takes it.
#[test]
fn list_views_names_what_view_takes() {
    vstf()
        .args(["list", "--views"])
        .run()
        .succeeds()
        .stdout_has("--view \"frame 1151\"  (camera t = 1171, relativistic model)")
        .stdout_has("--view \"t_c = 26\"");
}

/// A fixture that declares neither views nor checks has the one view
/// `vstf check` gives it, `view`: `list --views` names it and `render
/// --view view` reproduces the check's image bit for bit; a fixture with
/// declared views has no such view (the control).
#[test]
fn a_fixture_without_views_has_its_own_view() {
    let dir = Scratch::new("own-view");
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    let sphere =
        std::fs::read_to_string(repo_root().join("fixtures/sphere-relativistic.json")).unwrap();
    let mut bare: serde_json::Value = serde_json::from_str(&sphere).unwrap();
    let spec = bare.as_object_mut().unwrap();
    spec.remove("views");
    spec.remove("checks");
    std::fs::write(dir.join("fixtures/bare.json"), bare.to_string()).unwrap();
    std::fs::copy(
        repo_root().join("fixtures/flange.json"),
        dir.join("fixtures/flange.json"),
    )
    .unwrap();
    let listed = vstf().current_dir(&dir).args(["list", "--views"]).run();
    listed
        .succeeds()
        .stdout_has("--view \"view\"  (camera t = ");
    assert_eq!(
        listed.stdout().matches("--view \"view\"").count(),
        1,
        "{listed}"
    );
    vstf()
        .current_dir(&dir)
        .args(["check", "bare", "--quick"])
        .run()
        .stderr_has("MISSING");
    let out = dir.join("own.png");
    vstf()
        .current_dir(&dir)
        .args(["render", "bare", "--view", "view", "--out"])
        .arg(&out)
        .run()
        .succeeds();
    let checked = rgb(&dir.join("target/vstf/bare/view/actual.png"));
    assert!(
        rgb(&out) == checked,
        "render --view view differs from the check's image"
    );
    vstf()
        .current_dir(&dir)
        .args(["render", "flange", "--view", "view", "--out"])
        .arg(dir.join("no.png"))
        .run()
        .fails_with("no view named \"view\"");
}

/// `--camera-t auto:OBJECT` picks the time the object is seen crossing
/// the line of sight; a render in which a moving object is nowhere in view
/// says so, with that hint; a word that is neither a time nor `auto` is
/// refused with what is expected.
#[test]
fn camera_time_auto_finds_a_moving_object_and_an_empty_render_is_flagged() {
    let dir = Scratch::new("auto");
    let out_png = dir.join("auto.png");
    let run = |t: &str| {
        vstf()
            .args(["render", "hornof-2025", "--width", "64", "--height", "48"])
            .args(["--spp", "1", "--camera-t", t, "--out"])
            .arg(&out_png)
            .run()
    };
    run("0")
        .fails_with("nothing is in view")
        .stderr_has("warning: \"cube front\" is out of view")
        .stderr_has("try --camera-t \"auto:cube front\"");
    run("auto:cube front")
        .stderr_has("t_c = 5,")
        .stderr_lacks("\"cube front\" is out of view")
        .stderr_lacks("\"cube front\" is not in view");
    run("soon").fails_with("`auto:OBJECT`");
}

/// `render --models all`: the three models side by side, each panel
/// labelled (white text at its top left) and each different.
#[test]
fn render_models_all_puts_three_labelled_panels_side_by_side() {
    let dir = Scratch::new("models");
    let out_png = dir.join("models.png");
    vstf()
        .args([
            "render", "teaser", "--models", "all", "--width", "96", "--height", "54", "--spp", "1",
            "--out",
        ])
        .arg(&out_png)
        .run()
        .succeeds();
    let img = rgb(&out_png);
    assert_eq!(img.dimensions(), (3 * 96 + 8, 54));
    let panel = |k: u32| image::imageops::crop_imm(&img, k * 100, 0, 96, 54).to_image();
    let white = |p: &image::RgbImage| {
        p.enumerate_pixels()
            .filter(|(x, y, c)| *x < 80 && *y < 12 && c.0 == [255, 255, 255])
            .count()
    };
    for k in 0..3 {
        assert!(white(&panel(k)) > 30, "panel {k} has no label");
    }
    assert_ne!(
        panel(0).into_raw(),
        panel(2).into_raw(),
        "infinite and relativistic panels alike"
    );
    let both = vstf()
        .args(["render", "teaser", "--models", "all"])
        .args(["--model", "classical", "--out"])
        .arg(&out_png)
        .run();
    assert!(
        !both.success(),
        "--models all with --model was accepted: {both}"
    );
}

/// `--out` writes through a symbolic link and refuses what is not a
/// regular file, leaving it as it was.
#[test]
fn render_out_follows_links_and_refuses_special_files() {
    let dir = Scratch::new("out");
    let render = |out: &Path| {
        vstf()
            .args(["render", "stage", "--width", "16", "--height", "12"])
            .arg("--out")
            .arg(out)
            .run()
    };
    std::fs::write(dir.join("real.png"), "old").unwrap();
    std::os::unix::fs::symlink("real.png", dir.join("link.png")).unwrap();
    render(&dir.join("link.png")).succeeds();
    assert!(std::fs::symlink_metadata(dir.join("link.png"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(image::open(dir.join("real.png")).unwrap().width(), 16);
    // A link to a device, and a directory, each named like a PNG.
    std::os::unix::fs::symlink("/dev/null", dir.join("null.png")).unwrap();
    std::fs::create_dir(dir.join("folder.png")).unwrap();
    for special in [dir.join("null.png"), dir.join("folder.png")] {
        render(&special).fails_with("not a regular file");
    }
    let null = std::fs::metadata("/dev/null").unwrap().file_type();
    assert!(std::os::unix::fs::FileTypeExt::is_char_device(&null));
}

/// A render far beyond the time budget is refused at once with its
/// estimate and the flag that overrides it.
#[test]
fn a_day_long_render_is_refused_with_its_estimate() {
    let started = std::time::Instant::now();
    vstf()
        .args(["render", "stage", "--out", "/tmp/never.png"])
        .args(["--width", "8192", "--height", "8192", "--spp", "4096"])
        .run()
        .fails_with("days")
        .stderr_has("--force");
    assert!(started.elapsed().as_secs() < 10);
    assert!(!Path::new("/tmp/never.png").exists());
}

/// Small command-line errors: an unknown fixture to approve, an output in
/// a format vstf does not write, and a near miss of a fixture's name.
#[test]
fn small_cli_mistakes_are_clear_errors() {
    vstf()
        .env_remove("CI")
        .args(["approve", "nosuch"])
        .run()
        .fails_with("nothing pending for \"nosuch\"");
    vstf()
        .args(["render", "stage", "--out", "/tmp/vstf-x.tif"])
        .run()
        .fails_with("writes one image as .png, .jpg (or .jpeg) or .exr");
    assert!(!Path::new("/tmp/vstf-x.tif").exists());
    vstf()
        .args(["render", "flang", "--out", "/tmp/vstf-x.png"])
        .run()
        .fails_with("did you mean \"flange\"?");
}

/// `--simd baseline` limits the searches to the build's own vector level:
/// the same image to the bit as the default's (the teaser: shadows, a
/// mirror, moving objects); a level that does not exist is refused with
/// the ones that do.
#[test]
fn every_simd_level_renders_the_same_bytes() {
    let dir = Scratch::new("simd");
    let render = |level: Option<&str>, name: &str| {
        let out = dir.join(name);
        let mut cmd = vstf();
        if let Some(level) = level {
            cmd.args(["--simd", level]);
        }
        cmd.args(["render", "teaser", "--out"])
            .arg(&out)
            .args(["--width", "96", "--height", "54"])
            .run()
            .succeeds();
        std::fs::read(out).unwrap()
    };
    let default = render(None, "default.png");
    assert_eq!(render(Some("baseline"), "baseline.png"), default);
    assert_eq!(render(Some("x86-64-v3"), "v3.png"), default);
    vstf()
        .args(["--simd", "avx512", "list"])
        .run()
        .fails_with("expected baseline or x86-64-v3");
}
