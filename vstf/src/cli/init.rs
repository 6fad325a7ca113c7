//! `vstf init [DIR]`: a small project that `vstf check` passes after one
//! `vstf approve`: `vstf.toml`, a fixture with declared checks, a
//! `.gitignore` for `target/` and a README paragraph. Nothing that exists
//! is overwritten.

use super::args::InitArgs;
use std::path::{Path, PathBuf};
use vstf::error::Error;

/// The example fixture: a cube at 0.8c whose trailing face shows, with a
/// check of every general kind (docs/checks.md walks through it).
const FIXTURE: &str = include_str!("init-moving-cube.json");

const MARKER: &str =
    "# This file marks a vstf project: fixtures/ holds its scenes, golden/ their\n\
# approved images, target/vstf/ the images waiting for approval.\n";

const GITIGNORE: &str = "# Pending images and reports of vstf check.\ntarget/\n\
# Temporary files of an interrupted vstf write (removed by its next run).\n.*.vstf-tmp-*\n";

const README: &str = "# Checked spacetime scenes\n\n\
Each file in `fixtures/` is a scene with the checks it declares\n\
(docs/checks.md of vstf). `vstf check` renders every view, measures the\n\
images, compares them with first principles and with the approved images\n\
in `golden/`; `vstf approve FIXTURE` accepts pending images after review.\n";

/// Writes the project into `dir` (the current directory by default).
pub fn run(args: InitArgs) -> Result<(), Error> {
    let dir = args.dir.unwrap_or_else(|| PathBuf::from("."));
    if dir.exists() && !dir.is_dir() {
        return Err(Error::usage(format!(
            "{}: exists and is not a folder",
            dir.display()
        )));
    }
    let fixture = dir.join("fixtures").join("moving-cube.json");
    for link in [
        dir.join("fixtures"),
        dir.join(".gitignore"),
        dir.join("README.md"),
    ]
    .iter()
    .chain([dir.join(vstf::project::MARKER), fixture.clone()].iter())
    {
        if is_link(link) {
            return Err(Error::usage(format!(
                "{} is a symbolic link: init writes only new files of its own (nothing was written)",
                link.display()
            )));
        }
    }
    for owned in [dir.join(vstf::project::MARKER), fixture.clone()] {
        if owned.exists() {
            return Err(Error::usage(format!(
                "{} already exists: {} is a vstf project already (nothing was written)",
                owned.display(),
                dir.display()
            )));
        }
    }
    write(&dir.join(vstf::project::MARKER), MARKER)?;
    write(&fixture, FIXTURE)?;
    for (name, text) in [(".gitignore", GITIGNORE), ("README.md", README)] {
        let path = dir.join(name);
        if path.exists() {
            eprintln!("left {} as it is", path.display());
        } else {
            write(&path, text)?;
        }
    }
    println!("created a vstf project in {}", dir.display());
    println!("next, in {}:", dir.display());
    println!("  vstf check                 # passes its rows; its golden images are MISSING");
    println!("  (look at target/vstf/moving-cube/*/actual.png)");
    println!("  vstf approve moving-cube   # then vstf check passes");
    println!("docs/checks.md of vstf explains the checks in fixtures/moving-cube.json");
    Ok(())
}

/// Whether `path` is a symbolic link, dangling or not.
fn is_link(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink())
}

/// Writes a new file atomically, creating its folder.
fn write(path: &Path, text: &str) -> Result<(), String> {
    vstf::write_atomic(path, text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}
