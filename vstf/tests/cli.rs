//! The `vstf` binary as a user runs it.

use std::process::Command;

/// The built binary, run from this repository's root (the project of the
/// paper's fixtures).
fn vstf() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_vstf"));
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    c
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let out = std::env::temp_dir().join(format!("vstf-cli-{}.png", std::process::id()));
    let status = vstf()
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
        .status()
        .unwrap();
    assert!(status.success());
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (64, 48));
    std::fs::remove_file(&out).ok();
}

#[test]
fn a_missing_fixture_is_a_clear_error_not_a_panic() {
    let out = vstf()
        .args(["render", "no-such-scene", "--out", "/tmp/x.png"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: ") && err.contains("no fixture \"no-such-scene\""),
        "{err}"
    );
    assert!(!err.contains("panicked"));
}

#[test]
fn an_absurd_resolution_is_refused() {
    let out = vstf()
        .args(["render", "flange", "--out", "/tmp/x.png", "--width", "0"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("flange.json: image: resolution 0x480 is out of range"),
        "{err}"
    );
}

#[test]
fn check_prints_the_table_and_writes_json_rows() {
    let json = std::env::temp_dir().join(format!("vstf-rows-{}.json", std::process::id()));
    let out = vstf()
        .args(["check", "stage", "--quick", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The default table: the fixture, then its rows, every line within 100
    // columns; passing golden images only counted.
    assert_eq!(stdout.lines().next(), Some("stage"), "{stdout}");
    for line in stdout.lines() {
        assert!(
            line.chars().count() <= 100,
            "{} columns: {line}",
            line.chars().count()
        );
    }
    assert!(!stdout.contains("golden pass"), "{stdout}");
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("check: ") && l.ends_with(" passed, 0 failed")),
        "{stdout}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = report["rows"].as_array().unwrap();
    assert!(!rows.is_empty() && rows.iter().all(|r| r["fixture"] == "stage"));
    let goldens = report["goldens"].as_array().unwrap();
    assert_eq!(goldens.len(), 1, "{report}");
    assert_eq!(goldens[0]["pass"], true);
    assert_eq!(goldens[0]["size"], serde_json::json!([240, 180]));
    std::fs::remove_file(&json).ok();
    // --verbose: the full table with every column, and every image's line.
    let out = vstf()
        .args(["check", "stage", "--quick", "--verbose"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let header = stdout.lines().next().unwrap();
    for col in [
        "fixture",
        "quantity",
        "measured",
        "expected",
        "paper",
        "tolerance",
        "unit",
        "result",
    ] {
        assert!(header.contains(col), "{header}");
    }
    assert!(stdout.contains("golden pass fixture=stage"), "{stdout}");
}

#[test]
fn check_of_an_unknown_fixture_fails_clearly() {
    let out = vstf()
        .args(["check", "nosuch", "--quick"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no fixture \"nosuch\"") && err.contains("fixtures here: aberration,"),
        "{err}"
    );
}

#[test]
fn approve_is_refused_under_ci_and_list_works() {
    let out = vstf()
        .args(["approve", "--all"])
        .env("CI", "true")
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("refusing to approve golden images with CI set"));
    let out = vstf().args(["approve", "--list"]).output().unwrap();
    assert!(out.status.success());
    let out = vstf().args(["approve"]).output().unwrap();
    assert!(
        !out.status.success(),
        "approve with neither fixtures nor --all must not approve everything"
    );
}

#[test]
fn debug_prints_a_pixel_and_logs_a_region_that_debug_diff_compares() {
    let out = vstf()
        .args(["debug", "flange", "--pixel", "300,200"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with("pixel (300, 200) of flange, relativistic model")
            && text.contains("Primary ray"),
        "{text}"
    );
    // Compact by default: the candidates tested only with --candidates.
    assert!(!text.contains("rejected:"), "{text}");
    let long = vstf()
        .args(["debug", "flange", "--pixel", "300,200", "--candidates"])
        .output()
        .unwrap();
    let long = String::from_utf8_lossy(&long.stdout);
    assert!(long.contains("rejected:") && long.lines().count() > text.lines().count() + 10);
    let dir = std::env::temp_dir().join(format!("vstf-debug-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b) = (dir.join("a.jsonl"), dir.join("b.jsonl"));
    for (path, extra) in [(&a, None), (&b, Some("--brute-force"))] {
        let mut cmd = vstf();
        cmd.args([
            "debug",
            "flange",
            "--width",
            "64",
            "--height",
            "48",
            "--region",
            "10,10,13,12",
            "--candidates",
            "--log",
        ])
        .arg(path);
        if let Some(e) = extra {
            cmd.arg(e);
        }
        assert!(cmd.status().unwrap().success());
    }
    assert_eq!(std::fs::read_to_string(&a).unwrap().lines().count(), 12);
    let same = vstf()
        .args(["debug-diff", "--ignore", "candidate"])
        .arg(&a)
        .arg(&b)
        .output()
        .unwrap();
    assert!(
        same.status.success(),
        "{}",
        String::from_utf8_lossy(&same.stdout)
    );
    let differ = vstf().arg("debug-diff").arg(&a).arg(&b).output().unwrap();
    assert!(!differ.status.success());
    assert!(String::from_utf8_lossy(&differ.stdout).contains("(kind of step): miss vs candidate"));
    let misspelt = vstf()
        .args(["debug-diff", "--ignore", "candidat"])
        .arg(&a)
        .arg(&b)
        .output()
        .unwrap();
    assert!(!misspelt.status.success());
    let err = String::from_utf8_lossy(&misspelt.stderr);
    assert!(
        err.contains("candidat") && err.contains("candidate"),
        "{err}"
    );
    let outside = vstf()
        .args(["debug", "flange", "--pixel", "5000,1"])
        .output()
        .unwrap();
    assert!(
        !outside.status.success()
            && String::from_utf8_lossy(&outside.stderr).contains("outside the 640x480 image")
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn animate_writes_a_sequence_a_gif_and_an_apng() {
    let dir = std::env::temp_dir().join(format!("vstf-anim-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let run = |out: &std::path::Path| {
        let o = vstf()
            .args([
                "animate", "teaser", "--frames", "10..20", "--step", "5", "--width", "48",
                "--height", "27", "--out",
            ])
            .arg(out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).to_string()
    };
    let msg = run(&dir.join("seq"));
    assert!(
        msg.contains("3 frames") && msg.contains("database built once"),
        "{msg}"
    );
    let frames: Vec<_> = (0..3)
        .map(|i| {
            image::open(dir.join("seq").join(format!("frame-{i:05}.png")))
                .unwrap()
                .to_rgb8()
        })
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
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn animate_refuses_bad_ranges() {
    let o = vstf()
        .args(["animate", "teaser", "--frames", "20..10", "--out", "/tmp/x"])
        .output()
        .unwrap();
    assert!(
        !o.status.success()
            && String::from_utf8_lossy(&o.stderr).contains("the end is before the start")
    );
    let o = vstf()
        .args([
            "animate", "teaser", "--frames", "0..1", "--step", "0", "--out", "/tmp/x",
        ])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("must be positive"));
}

#[test]
fn ctrl_c_leaves_every_finished_frame() {
    let dir = std::env::temp_dir().join(format!("vstf-int-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let gif = dir.join("long.gif");
    let child = vstf()
        .args([
            "animate", "flange", "--frames", "0..50000", "--step", "1", "--width", "64",
            "--height", "48", "--out",
        ])
        .arg(&gif)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let frames = dir.join("long.gif.frames");
    let started = std::time::Instant::now();
    let finished = |dir: &std::path::Path| {
        std::fs::read_dir(dir).map_or(0, |d| {
            d.filter(|e| {
                e.as_ref()
                    .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "png"))
            })
            .count()
        })
    };
    while finished(&frames) < 3 {
        assert!(started.elapsed().as_secs() < 60, "no frames appeared");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("interrupted:"), "{err}");
    let names: Vec<_> = std::fs::read_dir(&frames)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !p.ends_with("animation.txt"))
        .collect();
    assert!(names.len() >= 3);
    for p in &names {
        assert!(
            p.extension().is_some_and(|e| e == "png"),
            "a partial file was left: {}",
            p.display()
        );
        image::open(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_quick_prints_every_figure() {
    let out = vstf().args(["bench", "--quick"]).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
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

/// --doppler and --searchlight change the picture of moving surfaces and
/// leave static ones alone; keyframed scenes render.
#[test]
fn doppler_and_searchlight_flags_change_moving_colours() {
    let dir = std::env::temp_dir().join(format!("vstf-cli-doppler-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render = |fixture: &str, flags: &[&str], name: &str| {
        let out = dir.join(name);
        let status = vstf()
            .args(["render", fixture, "--out"])
            .arg(&out)
            .args(["--width", "80", "--height", "60", "--spp", "1"])
            .args(flags)
            .status()
            .unwrap();
        assert!(status.success(), "{fixture} {flags:?}");
        image::open(&out).unwrap().to_rgb8()
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
    std::fs::remove_dir_all(&dir).ok();
}

/// The repository's root, where the paper's fixtures and goldens live.
fn repo_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap()
}

/// A fresh, empty scratch folder for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("vstf-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Copies the files of `from` into `to`, recursively.
fn copy_tree(from: &std::path::Path, to: &std::path::Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).unwrap();
        }
    }
}

/// Flips one bit of one pixel of a PNG in place.
fn tamper(png: &std::path::Path) {
    let mut img = image::open(png).unwrap().to_rgb8();
    let p = img.get_pixel(10, 10).0;
    img.put_pixel(10, 10, image::Rgb([p[0] ^ 0x01, p[1], p[2]]));
    img.save(png).unwrap();
}

/// The binary built from this repository, run in a copy of it with one
/// golden tampered, compares against the copy's goldens (and so catches the
/// tamper), writes its pending images into the copy, and leaves the
/// repository's own golden/ and target/vstf/ alone.
#[test]
fn a_tampered_golden_in_a_copy_of_the_repository_is_caught() {
    let copy = scratch("copy");
    for dir in ["fixtures", "golden"] {
        copy_tree(&repo_root().join(dir), &copy.join(dir));
    }
    tamper(&copy.join("golden/flange/frame-920.png"));
    let ours = repo_root().join("golden/flange/frame-920.png");
    let before = std::fs::read(&ours).unwrap();
    let out = vstf()
        .current_dir(copy.join("fixtures"))
        .args(["check", "flange", "--quick"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success(), "the tamper passed:\n{text}");
    assert!(
        text.contains("golden FAIL fixture=flange view=frame-920 max_diff=1 differing=1"),
        "{text}"
    );
    assert!(
        !text.contains("golden pass fixture=flange view=frame-1151"),
        "passing images are listed only with --verbose:\n{text}"
    );
    // Each fixture's line as it finishes, the failure again with the command
    // that renders the view, and the closing summary.
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("FAIL flange") && err.contains("rows 3/3, golden images 1/2"),
        "{err}"
    );
    assert!(
        err.contains("vstf render flange --view \"frame 920\" --out"),
        "{err}"
    );
    // The command that debugs the pixel where the image changed most, at
    // the golden's resolution.
    let worst = text
        .split("worst_pixel=")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .expect("the failing line names its worst pixel");
    assert!(
        err.contains(&format!(
            "vstf debug flange --view \"frame 920\" --pixel {worst}"
        )),
        "{err}"
    );
    assert!(
        err.contains("check: 1 fixtures, 3 rows (0 failed), 2 golden images (1 failed)"),
        "{err}"
    );
    assert!(copy
        .join("target/vstf/flange/frame-920/actual.png")
        .is_file());
    assert_eq!(std::fs::read(&ours).unwrap(), before);
    // The untampered repository, checked through --root from elsewhere, passes.
    let out = vstf()
        .current_dir(&copy)
        .arg("--root")
        .arg(repo_root())
        .args(["check", "flange", "--quick"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    std::fs::remove_dir_all(&copy).ok();
}

/// Outside any project, commands that need one say how to get one; a
/// fixture given as a file still renders.
#[test]
fn outside_a_project_check_says_how_to_make_one() {
    let dir = scratch("noproject");
    let out = vstf()
        .current_dir(&dir)
        .args(["check", "--quick"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    // Only meaningful where no folder above the temporary one is a project.
    if !dir
        .ancestors()
        .skip(1)
        .any(|d| d.join("fixtures").is_dir() || d.join("vstf.toml").is_file())
    {
        assert!(!out.status.success());
        assert!(
            err.contains("no vstf project") && err.contains("vstf init"),
            "{err}"
        );
    }
    std::fs::copy(
        repo_root().join("fixtures/stage.json"),
        dir.join("scene.json"),
    )
    .unwrap();
    let status = vstf()
        .current_dir(&dir)
        .args([
            "render",
            "scene.json",
            "--out",
            "scene.png",
            "--width",
            "32",
            "--height",
            "24",
        ])
        .status()
        .unwrap();
    assert!(status.success());
    assert!(dir.join("scene.png").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

/// A user's project from `vstf init`, with a second fixture of its own: the
/// first check fails on MISSING goldens only, approve writes into that
/// project's golden/, the second check passes, a tampered golden there is
/// caught, and this repository's golden/ is untouched throughout.
#[test]
fn a_project_from_init_checks_approves_and_catches_a_tamper() {
    let dir = scratch("init");
    let project = dir.join("my-scenes");
    let repo_goldens = golden_listing(&repo_root().join("golden"));
    let run = |args: &[&str]| {
        vstf()
            .current_dir(&project)
            .env_remove("CI")
            .args(args)
            .output()
            .unwrap()
    };
    let out = vstf()
        .current_dir(&dir)
        .args(["init", "my-scenes"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::write(project.join("fixtures/fast-ball.json"), FAST_BALL).unwrap();
    let first = run(&["check", "--quick"]);
    let text = String::from_utf8_lossy(&first.stdout);
    assert!(!first.status.success());
    assert!(text.contains("check: 25 passed, 0 failed"), "{text}");
    assert_eq!(text.matches("golden MISSING").count(), 3, "{text}");
    let approved = run(&["approve", "--all"]);
    assert!(
        approved.status.success(),
        "{}",
        String::from_utf8_lossy(&approved.stderr)
    );
    assert!(project.join("golden/moving-cube/t-10.png").is_file());
    assert!(project.join("golden/fast-ball/now.png").is_file());
    let second = run(&["check", "--quick"]);
    let text = String::from_utf8_lossy(&second.stdout);
    assert!(second.status.success(), "{text}");
    assert!(text.contains("golden: 3 passed, 0 failed"), "{text}");
    tamper(&project.join("golden/moving-cube/t-11.png"));
    let third = run(&["check", "moving-cube", "--quick"]);
    let text = String::from_utf8_lossy(&third.stdout);
    assert!(!third.status.success());
    assert!(
        text.contains("golden FAIL fixture=moving-cube view=t-11"),
        "{text}"
    );
    assert_eq!(golden_listing(&repo_root().join("golden")), repo_goldens);
    let again = vstf()
        .current_dir(&dir)
        .args(["init", "my-scenes"])
        .output()
        .unwrap();
    assert!(!again.status.success(), "init overwrote a project");
    std::fs::remove_dir_all(&dir).ok();
}

/// Every golden image under `dir` with its bytes.
fn golden_listing(dir: &std::path::Path) -> Vec<(std::path::PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(golden_listing(&p));
        } else {
            out.push((p.clone(), std::fs::read(&p).unwrap()));
        }
    }
    out.sort();
    out
}

/// A user's second fixture: a ball at 0.6c whose outline is fitted, a plate
/// approaching at 0.4c whose blink period is measured, and a glowing lamp
/// at 0.3c whose Doppler factor is read three ways; with the cube of `vstf
/// init`, every general kind is declared.
const FAST_BALL: &str = r#"{
  "description": "A ball of radius 0.5 crossing the view at 0.6c, 8 l.units away; above it a plate approaching at 0.4c, blinking every 0.5 t.units of its proper time; below it a lamp glowing as a 5000 K blackbody at 0.3c.",
  "camera": {"position": [0.0, 0.0, 0.0], "t": 0.0, "look_at": [0.0, 0.0, -1.0], "vfov_deg": 30.0},
  "light": {"position": [0.0, 20.0, 20.0], "color": [0.0, 0.0, 0.0], "ambient": 1.0},
  "background": [0.0, 0.0, 0.0],
  "image": {"width": 160, "height": 120},
  "objects": [
    {"name": "ball", "kind": "V_obj", "mesh": {"analytic_sphere": {"radius": 0.5}},
     "worldline": {"start": [-100.0, -55.2, 0.0, -8.0], "extrusion": [200.0, 120.0, 0.0, 0.0]},
     "material": {"color": [0.9, 0.3, 0.3]}},
    {"name": "blinker", "kind": "V_obj", "mesh": {"quad": {"corner": [-0.3, -0.3, 0.0], "u": [0.6, 0.0, 0.0], "v": [0.0, 0.6, 0.0]}},
     "worldline": {"start": [-20.0, 0.0, 1.2, -16.0], "velocity": [0.0, 0.0, 0.4], "proper_lifetime": 40.0},
     "material": {"color": [0.1, 0.1, 0.6], "blink": {"period": 0.5, "color": [1.0, 1.0, 1.0]}}},
    {"name": "lamp", "kind": "V_obj", "mesh": {"quad": {"corner": [-0.5, -0.5, 0.0], "u": [1.0, 0.0, 0.0], "v": [0.0, 1.0, 0.0]}},
     "worldline": {"start": [-100.0, -26.34, -2.0, -12.0], "extrusion": [200.0, 60.0, 0.0, 0.0]},
     "material": {"color": [0.0, 0.0, 0.0], "emission": {"blackbody": {"kelvin": 5000.0, "scale": 0.35}}}}
  ],
  "views": [{"name": "now"}],
  "checks": [
    {"name": "ball: width", "measure": {"outline": {"view": "now", "object": "ball", "read": "width"}}},
    {"name": "ball: height", "measure": {"outline": {"view": "now", "object": "ball", "read": "height"}}},
    {"name": "ball: axis ratio", "measure": {"outline": {"view": "now", "object": "ball", "read": "axis_ratio"}}},
    {"name": "ball: radius", "measure": {"outline": {"view": "now", "object": "ball", "read": "radius"}}},
    {"name": "ball: RMS from a circle", "measure": {"outline": {"view": "now", "object": "ball", "read": "rms"}}},
    {"name": "ball: centre azimuth", "measure": {"outline": {"view": "now", "object": "ball", "read": "centre_azimuth"}}},
    {"name": "ball: centre elevation", "measure": {"outline": {"view": "now", "object": "ball", "read": "centre_elevation"}}},
    {"name": "blinker: blink period seen", "measure": {"period": {"view": "now", "object": "blinker", "from": -2.0, "to": 2.0, "step": 0.02}}},
    {"name": "lamp: D from the colour", "measure": {"doppler": {"view": "now", "object": "lamp", "from": "colour"}}},
    {"name": "lamp: D from the searchlight, shifted", "measure": {"doppler": {"view": "now", "object": "lamp", "from": "searchlight_shifted"}}},
    {"name": "lamp: D from the searchlight, RGB", "measure": {"doppler": {"view": "now", "object": "lamp", "from": "searchlight_rgb"}}}
  ]
}"#;

/// A write that was killed leaves a recognisable temporary file: `approve
/// --list` reports it, `approve` removes it, and a live writer's is kept.
#[test]
fn stale_temporary_files_are_reported_and_removed() {
    let dir = scratch("stale");
    let out = vstf()
        .current_dir(&dir)
        .args(["init", "p"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let project = dir.join("p");
    std::fs::create_dir_all(project.join("golden/moving-cube")).unwrap();
    // No process has this id.
    let stale = project.join(format!(
        "golden/moving-cube/.t-10.png.vstf-tmp-{}",
        u32::MAX - 1
    ));
    std::fs::write(&stale, "half a png").unwrap();
    let listed = vstf()
        .current_dir(&project)
        .args(["approve", "--list"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&listed.stdout);
    assert!(
        text.contains("stale") && text.contains(".t-10.png.vstf-tmp-"),
        "{text}"
    );
    assert!(stale.exists(), "--list removed it");
    let out = vstf()
        .current_dir(&project)
        .env_remove("CI")
        .args(["approve", "--all"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!stale.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// `--out` writes through a symbolic link and refuses what is not a
/// regular file, leaving it as it was.
#[test]
fn render_out_follows_links_and_refuses_special_files() {
    let dir = scratch("out");
    let render = |out: &std::path::Path| {
        vstf()
            .args([
                "render", "stage", "--width", "16", "--height", "12", "--out",
            ])
            .arg(out)
            .output()
            .unwrap()
    };
    std::fs::write(dir.join("real.png"), "old").unwrap();
    std::os::unix::fs::symlink("real.png", dir.join("link.png")).unwrap();
    assert!(render(&dir.join("link.png")).status.success());
    assert!(std::fs::symlink_metadata(dir.join("link.png"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(image::open(dir.join("real.png")).unwrap().width(), 16);
    // A link to a device, and a directory, each named like a PNG.
    std::os::unix::fs::symlink("/dev/null", dir.join("null.png")).unwrap();
    std::fs::create_dir(dir.join("folder.png")).unwrap();
    for special in [dir.join("null.png"), dir.join("folder.png")] {
        let out = render(&special);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.contains("not a regular file"),
            "{err}"
        );
    }
    let null = std::fs::metadata("/dev/null").unwrap().file_type();
    assert!(std::os::unix::fs::FileTypeExt::is_char_device(&null));
    std::fs::remove_dir_all(&dir).ok();
}

/// `debug-diff --tol` takes only a finite tolerance of 0 or more.
#[test]
fn debug_diff_refuses_a_tolerance_that_is_not_a_number() {
    for bad in ["nan", "-1", "inf"] {
        let out = vstf()
            .args(["debug-diff", "a.jsonl", "b.jsonl", "--tol", bad])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.contains("expected a finite tolerance"),
            "{bad}: {err}"
        );
    }
}

/// `animate --resume` keeps the frames a run of the same animation wrote
/// whole and renders the missing and broken ones; frames of another
/// animation are not resumed.
#[test]
fn animate_resume_renders_only_missing_and_broken_frames() {
    let dir = scratch("resume");
    let frames = dir.join("frames");
    let animate = |extra: &[&str]| {
        vstf()
            .args([
                "animate", "stage", "--frames", "0..9", "--width", "32", "--height", "24", "--out",
            ])
            .arg(&frames)
            .args(extra)
            .output()
            .unwrap()
    };
    assert!(animate(&[]).status.success());
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
    let out = animate(&["--resume"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
        let other = animate(changed);
        let err = String::from_utf8_lossy(&other.stderr);
        assert!(
            !other.status.success() && err.contains("belong to another animation"),
            "{changed:?}: {err}"
        );
    }
    // A new animation into the same folder (not resumed) removes the old
    // frames, so that no later --resume can keep them.
    assert!(animate(&["--step", "2"]).status.success());
    assert!(
        frame(4).exists() && !frame(5).exists(),
        "an old frame was left"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A second Ctrl-C ends `animate` at once.
#[test]
fn a_second_ctrl_c_exits_at_once() {
    let dir = scratch("twice");
    let mut child = vstf()
        .args([
            "animate", "teaser", "--frames", "0..50000", "--width", "320", "--height", "180",
            "--force", "--out",
        ])
        .arg(dir.join("frames"))
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while std::fs::read_dir(dir.join("frames")).map_or(0, |d| d.count()) < 2 {
        assert!(started.elapsed().as_secs() < 60, "no frames appeared");
        assert!(child.try_wait().unwrap().is_none(), "animate ended early");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    for _ in 0..2 {
        Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let asked = std::time::Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(
            asked.elapsed().as_secs() < 5,
            "still running after two Ctrl-C"
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    };
    assert_eq!(status.code(), Some(130));
    std::fs::remove_dir_all(&dir).ok();
}

/// A render far beyond the time budget is refused at once with its
/// estimate and the flag that overrides it.
#[test]
fn a_day_long_render_is_refused_with_its_estimate() {
    let started = std::time::Instant::now();
    let out = vstf()
        .args([
            "render",
            "stage",
            "--out",
            "/tmp/never.png",
            "--width",
            "8192",
            "--height",
            "8192",
            "--spp",
            "4096",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("days") && err.contains("--force"),
        "{err}"
    );
    assert!(started.elapsed().as_secs() < 10);
    assert!(!std::path::Path::new("/tmp/never.png").exists());
}

/// Output into a pipe that is closed ends quietly with the status of a
/// SIGPIPE death (141), not in a panic (exit code 101).
#[test]
fn a_closed_pipe_ends_list_quietly() {
    let mut child = vstf()
        .args(["list"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Close the pipe before `list` has loaded its fixtures and printed.
    drop(child.stdout.take());
    let done = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&done.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(done.status.code(), Some(141), "{err}");
}

/// `--json -` writes the JSON rows, and only them, to stdout.
#[test]
fn check_json_dash_writes_only_json_to_stdout() {
    let out = vstf()
        .args(["check", "stage", "--quick", "--json", "-"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "stdout is not JSON ({e}): {}",
            String::from_utf8_lossy(&out.stdout)
        )
    });
    assert_eq!(rows["rows"].as_array().unwrap().len(), 5);
    assert_eq!(rows["goldens"][0]["view"], "view");
    assert!(String::from_utf8_lossy(&out.stderr).contains("golden: 1 passed, 0 failed"));
    assert!(
        !repo_root().join("-").exists(),
        "a file named - was written"
    );
    // Not a terminal: plain lines, no colour codes and no progress bar.
    assert!(!out.stderr.contains(&0x1b), "escape codes off a terminal");
    assert!(String::from_utf8_lossy(&out.stderr).contains("pass stage "));
}

/// Small command-line errors: an unknown fixture to approve, an output that
/// is not a PNG, and a near miss of a fixture's name.
#[test]
fn small_cli_mistakes_are_clear_errors() {
    let out = vstf()
        .env_remove("CI")
        .args(["approve", "nosuch"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("nothing pending for \"nosuch\""),
        "{err}"
    );
    let out = vstf()
        .args(["render", "stage", "--out", "/tmp/vstf-x.jpg"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("writes PNG images"),
        "{err}"
    );
    assert!(!std::path::Path::new("/tmp/vstf-x.jpg").exists());
    let out = vstf()
        .args(["render", "flang", "--out", "/tmp/vstf-x.png"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("did you mean \"flange\"?"),
        "{err}"
    );
}

/// `render --view` reproduces a declared view bit for bit as `vstf check`
/// renders it for its golden image (colour effects included); an unknown
/// view is an error naming the declared ones.
#[test]
fn render_view_reproduces_the_golden_image() {
    let dir = scratch("view");
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
        let run = vstf()
            .args(["render", fixture, "--view", view, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let rendered = image::open(&out).unwrap().to_rgb8();
        let approved = image::open(repo_root().join("golden").join(golden))
            .unwrap()
            .to_rgb8();
        assert!(
            rendered == approved,
            "{fixture} {view} differs from {golden}"
        );
    }
    let out = vstf()
        .args([
            "render",
            "flange",
            "--view",
            "frame 9",
            "--out",
            "/tmp/vstf-no.png",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("declared views: frame 920, frame 1151"),
        "{err}"
    );
    // A named check's own views are taken too, exactly as checked; an
    // unknown name points at them.
    let png = std::env::temp_dir().join(format!("vstf-named-{}.png", std::process::id()));
    let out = vstf()
        .args(["render", "stage", "--view", "view", "--out"])
        .arg(&png)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(&png).unwrap(),
        std::fs::read(repo_root().join("golden/stage/view.png")).unwrap()
    );
    std::fs::remove_file(&png).ok();
    let out = vstf()
        .args([
            "render",
            "stage",
            "--view",
            "nowhere",
            "--out",
            "/tmp/vstf-no.png",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("its named check stage renders views of other names"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// One view at a time: `approve FIXTURE/VIEW` approves that view only,
/// `reject` drops a pending change and leaves its golden, and `approve
/// --list` says where each change is.
#[test]
fn approve_and_reject_one_view_at_a_time() {
    let copy = scratch("perview");
    for dir in ["fixtures", "golden"] {
        copy_tree(&repo_root().join(dir), &copy.join(dir));
    }
    tamper(&copy.join("golden/flange/frame-920.png"));
    tamper(&copy.join("golden/flange/frame-1151.png"));
    let run = |args: &[&str]| {
        vstf()
            .current_dir(&copy)
            .env_remove("CI")
            .args(args)
            .output()
            .unwrap()
    };
    assert!(!run(&["check", "flange", "--quick"]).status.success());
    let listed = run(&["approve", "--list"]);
    let text = String::from_utf8_lossy(&listed.stdout);
    assert!(
        text.contains("flange/frame-920")
            && text.contains("1 pixels differ (worst by 1) within x 10..=10, y 10..=10 of 240x180"),
        "{text}"
    );
    let before_1151 = std::fs::read(copy.join("golden/flange/frame-1151.png")).unwrap();
    let approved = run(&["approve", "flange/frame-920"]);
    assert!(
        approved.status.success(),
        "{}",
        String::from_utf8_lossy(&approved.stderr)
    );
    assert_eq!(
        std::fs::read(copy.join("golden/flange/frame-1151.png")).unwrap(),
        before_1151
    );
    let rejected = run(&["reject", "flange/frame-1151"]);
    assert!(
        rejected.status.success(),
        "{}",
        String::from_utf8_lossy(&rejected.stderr)
    );
    assert_eq!(
        std::fs::read(copy.join("golden/flange/frame-1151.png")).unwrap(),
        before_1151
    );
    let empty = run(&["approve", "--list"]);
    assert!(String::from_utf8_lossy(&empty.stdout).contains("nothing pending"));
    // frame 920 now passes against its approved (rendered) image; 1151 still
    // fails against the tampered golden that was kept.
    let again = run(&["check", "flange", "--quick", "--verbose"]);
    let text = String::from_utf8_lossy(&again.stdout);
    assert!(
        text.contains("golden pass fixture=flange view=frame-920"),
        "{text}"
    );
    assert!(
        text.contains("golden FAIL fixture=flange view=frame-1151"),
        "{text}"
    );
    std::fs::remove_dir_all(&copy).ok();
}

/// `list --views` names each declared view as `--view` takes it.
#[test]
fn list_views_names_what_view_takes() {
    let out = vstf().args(["list", "--views"]).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(
        text.contains("--view \"frame 1151\"  (camera t = 1171, relativistic model)"),
        "{text}"
    );
    assert!(text.contains("--view \"t_c = 26\""), "{text}");
}

/// `--camera-t auto:OBJECT` picks the time the object is seen crossing
/// the line of sight; a render in which a moving object is nowhere in view
/// says so, with that hint; a word that is neither a time nor `auto` is
/// refused with what is expected.
#[test]
fn camera_time_auto_finds_a_moving_object_and_an_empty_render_is_flagged() {
    let out_png = std::env::temp_dir().join(format!("vstf-auto-{}.png", std::process::id()));
    let run = |t: &str| {
        vstf()
            .args([
                "render",
                "hornof-2025",
                "--width",
                "64",
                "--height",
                "48",
                "--spp",
                "1",
                "--camera-t",
                t,
                "--out",
            ])
            .arg(&out_png)
            .output()
            .unwrap()
    };
    let early = run("0");
    let err = String::from_utf8_lossy(&early.stderr);
    assert!(early.status.success(), "{err}");
    assert!(
        err.contains("warning: \"cube front\" is out of view")
            && err.contains("try --camera-t \"auto:cube front\""),
        "{err}"
    );
    let auto = run("auto:cube front");
    let err = String::from_utf8_lossy(&auto.stderr);
    assert!(err.contains("t_c = 5,"), "{err}");
    assert!(
        !err.contains("\"cube front\" is out of view")
            && !err.contains("\"cube front\" is not in view"),
        "{err}"
    );
    let bad = run("soon");
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("`auto:OBJECT`"));
    std::fs::remove_file(&out_png).ok();
}

/// `render --models all`: the three models side by side, each panel
/// labelled (white text at its top left) and each different.
#[test]
fn render_models_all_puts_three_labelled_panels_side_by_side() {
    let out_png = std::env::temp_dir().join(format!("vstf-models-{}.png", std::process::id()));
    let out = vstf()
        .args([
            "render", "teaser", "--models", "all", "--width", "96", "--height", "54", "--spp", "1",
            "--out",
        ])
        .arg(&out_png)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&out_png).unwrap().to_rgb8();
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
    let err = vstf()
        .args([
            "render",
            "teaser",
            "--models",
            "all",
            "--model",
            "classical",
            "--out",
        ])
        .arg(&out_png)
        .output()
        .unwrap();
    assert!(
        !err.status.success(),
        "--models all with --model was accepted"
    );
    std::fs::remove_file(&out_png).ok();
}

/// `animate --label` writes each frame's camera time on it; the frames
/// differ from unlabelled ones only in the label's corner.
#[test]
fn animate_label_marks_each_frame_with_its_time() {
    let dir = std::env::temp_dir().join(format!("vstf-label-{}", std::process::id()));
    let frames = |d: &std::path::Path, label: bool| {
        let mut cmd = vstf();
        cmd.args([
            "animate", "flange", "--frames", "940..941", "--width", "64", "--height", "48",
            "--spp", "1", "--out",
        ])
        .arg(d);
        if label {
            cmd.arg("--label");
        }
        assert!(cmd.status().unwrap().success());
        image::open(d.join("frame-00001.png")).unwrap().to_rgb8()
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
    std::fs::remove_dir_all(&dir).ok();
}

/// `vstf review`: each pending image shown with its change and files, and
/// accepted, rejected or skipped by the answer read from stdin (nonsense
/// is asked again); CI refuses it.
#[test]
fn review_accepts_and_rejects_one_image_at_a_time() {
    use std::io::Write;
    let copy = scratch("review");
    for dir in ["fixtures", "golden"] {
        copy_tree(&repo_root().join(dir), &copy.join(dir));
    }
    for view in ["frame-920", "frame-1151"] {
        tamper(&copy.join(format!("golden/flange/{view}.png")));
    }
    let check = vstf()
        .current_dir(&copy)
        .args(["check", "flange", "--quick"])
        .output()
        .unwrap();
    assert!(!check.status.success());
    let review = |answers: &str, ci: Option<&str>| {
        let mut cmd = vstf();
        cmd.current_dir(&copy).arg("review").env_remove("CI");
        if let Some(v) = ci {
            cmd.env("CI", v);
        }
        let mut child = cmd
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        child
            .stdin
            .take()
            .unwrap()
            .write_all(answers.as_bytes())
            .ok(); // a refusal exits before reading: the pipe may be closed
        child.wait_with_output().unwrap()
    };
    let refused = review("a\na\n", Some("true"));
    assert!(
        !refused.status.success() && String::from_utf8_lossy(&refused.stderr).contains("CI set")
    );
    let out = review("maybe\na\nr\n", None);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("[1/2] changed: flange / frame 1151"),
        "{text}"
    );
    assert!(
        text.contains("1 pixels differ (worst by 1)") && text.contains("diff.png"),
        "{text}"
    );
    assert!(text.contains("\"maybe\": answer a, r, s or q"), "{text}");
    assert!(
        text.contains("review: 1 accepted, 1 rejected, 0 left pending"),
        "{text}"
    );
    let golden = |v: &str| std::fs::read(copy.join(format!("golden/flange/{v}.png"))).unwrap();
    let ours = |v: &str| std::fs::read(repo_root().join(format!("golden/flange/{v}.png"))).unwrap();
    assert_eq!(
        golden("frame-1151"),
        ours("frame-1151"),
        "the accepted render is the golden"
    );
    assert_ne!(
        golden("frame-920"),
        ours("frame-920"),
        "the rejected change left the golden alone"
    );
    let again = review("", None);
    assert!(String::from_utf8_lossy(&again.stdout).contains("nothing pending"));
    std::fs::remove_dir_all(&copy).ok();
}
