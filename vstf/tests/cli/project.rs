//! Projects: outside any, `vstf` says how to make one; one made by `vstf
//! init` is checked, approved and tampered with on its own.

use crate::support::{repo_root, tamper, vstf, RunExt, Scratch};
use std::path::{Path, PathBuf};

/// Outside any project, commands that need one say how to get one; a
/// fixture given as a file still renders.
#[test]
fn outside_a_project_check_says_how_to_make_one() {
    let dir = Scratch::new("noproject");
    let run = vstf().current_dir(&dir).args(["check", "--quick"]).run();
    // Only meaningful where no folder above the temporary one is a project.
    if !dir
        .ancestors()
        .skip(1)
        .any(|d| d.join("fixtures").is_dir() || d.join("vstf.toml").is_file())
    {
        run.fails_with("no vstf project").stderr_has("vstf init");
    }
    std::fs::copy(
        repo_root().join("fixtures/stage.json"),
        dir.join("scene.json"),
    )
    .unwrap();
    vstf()
        .current_dir(&dir)
        .args(["render", "scene.json", "--out", "scene.png"])
        .args(["--width", "32", "--height", "24"])
        .run()
        .succeeds();
    assert!(dir.join("scene.png").is_file());
}

/// A user's project from `vstf init`, with a second fixture of its own: the
/// first check fails on MISSING goldens only, approve writes into that
/// project's golden/, the second check passes, a tampered golden there is
/// caught, and this repository's golden/ is untouched throughout.
#[test]
fn a_project_from_init_checks_approves_and_catches_a_tamper() {
    let dir = Scratch::new("init");
    let project = dir.join("my-scenes");
    let repo_goldens = golden_listing(&repo_root().join("golden"));
    let run = |args: &[&str]| {
        vstf()
            .current_dir(&project)
            .env_remove("CI")
            .args(args)
            .run()
    };
    vstf()
        .current_dir(&dir)
        .args(["init", "my-scenes"])
        .run()
        .succeeds();
    std::fs::write(project.join("fixtures/fast-ball.json"), FAST_BALL).unwrap();
    let first = run(&["check", "--quick"]);
    first.fails().stdout_has("check: 25 passed, 0 failed");
    assert_eq!(
        first.stdout().matches("golden MISSING").count(),
        3,
        "{first}"
    );
    run(&["approve", "--all"]).succeeds();
    assert!(project.join("golden/moving-cube/t-10.png").is_file());
    assert!(project.join("golden/fast-ball/now.png").is_file());
    run(&["check", "--quick"])
        .succeeds()
        .stdout_has("golden: 3 passed, 0 failed");
    tamper(&project.join("golden/moving-cube/t-11.png"));
    run(&["check", "moving-cube", "--quick"])
        .fails()
        .stdout_has("golden FAIL fixture=moving-cube view=t-11");
    assert_eq!(golden_listing(&repo_root().join("golden")), repo_goldens);
    let again = vstf().current_dir(&dir).args(["init", "my-scenes"]).run();
    assert!(!again.success(), "init overwrote a project: {again}");
}

/// Every golden image under `dir` with its bytes.
fn golden_listing(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
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

/// `init` never writes through a link a cloned repository holds, dangling
/// or not; a real folder beside it still works.
#[test]
fn init_refuses_a_dangling_link() {
    let dir = Scratch::new("init-link");
    let outside = dir.join("outside");
    std::fs::create_dir_all(dir.join("proj")).unwrap();
    std::os::unix::fs::symlink(outside.join("created.toml"), dir.join("proj/vstf.toml")).unwrap();
    vstf()
        .current_dir(&dir)
        .args(["init", "proj"])
        .run()
        .fails_with("is a symbolic link");
    assert!(!outside.exists(), "init wrote outside the project");
    // Control: a real folder is made into a project.
    vstf()
        .current_dir(&dir)
        .args(["init", "real"])
        .run()
        .succeeds();
    assert!(dir.join("real/fixtures/moving-cube.json").is_file());
}

/// A cloned repository with a committed link `target/vstf -> ../victim`:
/// a passing `vstf check` used to clear the victim's "stale pending"
/// folders. It now refuses, naming the link, and deletes nothing; with a
/// real `target/vstf` the same check passes.
#[test]
fn check_never_deletes_through_a_linked_pending_folder() {
    let dir = Scratch::new("linked-target");
    let project = dir.join("cloned");
    vstf()
        .current_dir(&dir)
        .args(["init", "cloned"])
        .run()
        .succeeds();
    let run = |args: &[&str]| {
        vstf()
            .current_dir(&project)
            .env_remove("CI")
            .args(args)
            .run()
    };
    run(&["check", "moving-cube", "--quick"]).fails();
    run(&["approve", "--all"]).succeeds();
    let victim = dir.join("victim");
    std::fs::create_dir_all(victim.join("moving-cube/t-10")).unwrap();
    std::fs::write(victim.join("moving-cube/t-10/important.txt"), "keep").unwrap();
    std::fs::write(victim.join("moving-cube/t-10/actual.png"), "not ours").unwrap();
    std::fs::remove_dir_all(project.join("target/vstf")).ok();
    std::fs::create_dir_all(project.join("target")).unwrap();
    std::os::unix::fs::symlink(&victim, project.join("target/vstf")).unwrap();
    run(&["check", "moving-cube", "--quick"]).fails_with("is a symbolic link");
    assert_eq!(
        std::fs::read_to_string(victim.join("moving-cube/t-10/important.txt")).unwrap(),
        "keep"
    );
    assert!(victim.join("moving-cube/t-10/actual.png").exists());
    // Control: a real target/vstf, and the check passes.
    std::fs::remove_file(project.join("target/vstf")).unwrap();
    run(&["check", "moving-cube", "--quick"]).succeeds();
}

/// Every file under `dir`, sorted, with its bytes.
fn listing(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let bytes = std::fs::read(&p).unwrap_or_default();
                out.push((p, bytes));
            }
        }
    }
    out.sort();
    out
}

/// Whether a folder above `dir` is a project (then nothing outside one can
/// be tested there).
fn inside_a_project(dir: &Path) -> bool {
    dir.ancestors()
        .skip(1)
        .any(|d| d.join("fixtures").is_dir() || d.join("vstf.toml").is_file())
}

/// `vstf check FILE` outside any project checks the file against the
/// golden images in a `golden/` beside it and writes nothing there: first
/// MISSING with the commands that approve them (which work as said), then,
/// with the folder no project again, passing; a changed golden fails, and a
/// golden that is a link out of the folder is refused, not read.
#[test]
fn a_fixture_file_outside_a_project_checks_against_the_golden_beside_it() {
    let dir = Scratch::new("beside");
    if inside_a_project(&dir) {
        return;
    }
    std::fs::write(dir.join("ball.json"), FAST_BALL).unwrap();
    let check = || {
        vstf()
            .current_dir(&dir)
            .env_remove("CI")
            .args(["check", "ball.json", "--quick"])
            .run()
    };
    let before = listing(&dir);
    check()
        .fails()
        .stdout_has("golden MISSING fixture=ball view=now")
        .stderr_has("vstf init")
        .stderr_has("vstf approve --root");
    assert_eq!(listing(&dir), before, "check wrote beside the file");
    let root = dir.to_str().unwrap();
    let run = |args: &[&str]| vstf().current_dir(&dir).env_remove("CI").args(args).run();
    run(&["init", root]).succeeds();
    // Inside a project the commands name the fixture (the control).
    run(&["check", "--root", root, "ball.json", "--quick"])
        .fails()
        .stderr_has("vstf render ball --view \"now\"");
    run(&["approve", "--root", root, "ball"]).succeeds();
    assert!(dir.join("golden/ball/now.png").is_file());
    for made in ["vstf.toml", "README.md", ".gitignore"] {
        std::fs::remove_file(dir.join(made)).unwrap();
    }
    std::fs::remove_dir_all(dir.join("fixtures")).unwrap();
    std::fs::remove_dir_all(dir.join("target")).unwrap();
    let approved = listing(&dir);
    check().succeeds().stdout_has("golden: 1 passed, 0 failed");
    tamper(&dir.join("golden/ball/now.png"));
    let tampered = listing(&dir);
    // The commands after the failure name the file, which they take
    // outside a project (the fixture's name alone they would not find).
    check()
        .fails()
        .stdout_has("golden FAIL fixture=ball view=now")
        .stderr_has("vstf render ball.json --view \"now\"")
        .stderr_has("vstf debug ball.json --view \"now\"");
    assert_eq!(listing(&dir), tampered, "check wrote beside the file");
    assert_ne!(tampered, approved);
    let outside = Scratch::new("beside-outside");
    std::fs::copy(dir.join("golden/ball/now.png"), outside.join("now.png")).unwrap();
    std::fs::remove_file(dir.join("golden/ball/now.png")).unwrap();
    std::os::unix::fs::symlink(outside.join("now.png"), dir.join("golden/ball/now.png")).unwrap();
    check().fails_with("symbolic link");
}
