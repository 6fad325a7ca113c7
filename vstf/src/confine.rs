//! The project's own folders (`golden/`, `target/vstf/`) written and
//! cleared without following a symbolic link out of them, and without
//! deleting anything vstf did not write there.
//!
//! A cloned repository may hold a link such as `target/vstf -> ../victim`:
//! every folder from the project's root down to the one written is
//! checked to be a real folder (or not yet there, to be made as one), and
//! a pending folder is cleared file by file, by the names vstf gives its
//! files, never by a recursive delete.

use crate::error::Error;
use crate::output::TEMP_MARK;
use std::path::{Path, PathBuf};

/// The files vstf writes into a view's pending folder.
pub(crate) const PENDING_FILES: [&str; 4] = ["actual.png", "expected.png", "diff.png", "names"];

/// Whether every folder from `root` down to `dir` is a real folder of the
/// project or does not exist yet; an error naming the first link (or file)
/// on the way, or `dir` outside `root`.
pub(crate) fn real_folder(root: &Path, dir: &Path) -> Result<(), Error> {
    let below = dir.strip_prefix(root).map_err(|_| {
        Error::io(
            dir,
            format!(
                "{} is outside the project {}",
                dir.display(),
                root.display()
            ),
        )
    })?;
    let mut at = root.to_path_buf();
    for part in below.components() {
        at.push(part);
        let Ok(meta) = std::fs::symlink_metadata(&at) else {
            return Ok(());
        };
        if meta.file_type().is_symlink() {
            return Err(Error::io(
                &at,
                format!(
                    "{} is a symbolic link: vstf writes and deletes in the project's own \
                     folders only, never through a link (remove it, or make it a folder)",
                    at.display()
                ),
            ));
        }
        if !meta.is_dir() {
            return Err(Error::io(&at, format!("{} is not a folder", at.display())));
        }
    }
    Ok(())
}

/// An error if `file` is a symbolic link: a golden image read outside a
/// project is read only from the fixture's own folder, never through a
/// link out of it.
pub(crate) fn no_link(file: &Path) -> Result<(), Error> {
    match std::fs::symlink_metadata(file) {
        Ok(meta) if meta.file_type().is_symlink() => Err(Error::io(
            file,
            format!(
                "{} is a symbolic link: vstf reads golden images from the fixture's folder \
                 only, never through a link",
                file.display()
            ),
        )),
        _ => Ok(()),
    }
}

/// Removes the files vstf wrote into the pending folder `dir` (and their
/// temporary files), then the folder if nothing else is left in it.
pub(crate) fn clear_pending(root: &Path, dir: &Path) -> Result<(), Error> {
    real_folder(root, dir)?;
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let name = name.to_string_lossy();
        let ours = PENDING_FILES.iter().any(|f| {
            name == *f || (name.starts_with(&format!(".{f}")) && name.contains(TEMP_MARK))
        });
        let file = e.file_type().is_ok_and(|t| t.is_file());
        if ours && file {
            std::fs::remove_file(e.path()).map_err(|err| {
                Error::io(
                    e.path(),
                    format!("cannot remove {}: {err}", e.path().display()),
                )
            })?;
        }
    }
    let _ = std::fs::remove_dir(dir);
    Ok(())
}

/// The folder a fixture's own files (meshes) must lie in: the project the
/// fixture lies in (the nearest folder above it with `vstf.toml` or
/// `fixtures/`), or else the fixture's own folder.
pub(crate) fn fixture_root(fixture: &Path) -> Result<PathBuf, String> {
    let folder = fixture.parent().filter(|p| !p.as_os_str().is_empty());
    let folder = folder.unwrap_or(Path::new("."));
    let folder = folder.canonicalize().map_err(|e| {
        format!(
            "cannot resolve the fixture's folder {}: {e}",
            folder.display()
        )
    })?;
    Ok(crate::project::Project::discover(&folder)
        .map(|p| p.root().to_path_buf())
        .unwrap_or(folder))
}

/// `file` resolved through every link, if it lies inside `root`; a file
/// outside it (by `..`, an absolute path or a link) is refused, naming both.
pub(crate) fn inside(root: &Path, file: &Path) -> Result<PathBuf, String> {
    let resolved = file
        .canonicalize()
        .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    if resolved.starts_with(root) {
        Ok(resolved)
    } else {
        Err(format!(
            "{} (resolved to {}) is outside {}: a fixture reads files only inside its project \
             (or its own folder when it has none)",
            file.display(),
            resolved.display(),
            root.display()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("vstf-confine-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir.canonicalize().unwrap()
    }

    #[test]
    fn a_link_on_the_way_is_refused_and_a_real_folder_is_not() {
        let dir = scratch("link");
        let (project, victim) = (dir.join("project"), dir.join("victim"));
        std::fs::create_dir_all(project.join("target")).unwrap();
        std::fs::create_dir_all(&victim).unwrap();
        std::os::unix::fs::symlink(&victim, project.join("target/vstf")).unwrap();
        let e = real_folder(&project, &project.join("target/vstf/rod/t-34")).unwrap_err();
        assert!(
            matches!(&e, Error::Io { path, .. } if path.ends_with("target/vstf")),
            "{e}"
        );
        // Control: the same path in real folders, and one not made yet.
        std::fs::remove_file(project.join("target/vstf")).unwrap();
        std::fs::create_dir_all(project.join("target/vstf/rod")).unwrap();
        real_folder(&project, &project.join("target/vstf/rod/t-34")).unwrap();
        assert!(
            real_folder(&project, &victim).is_err(),
            "outside the project"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn clearing_removes_only_what_vstf_wrote() {
        let dir = scratch("clear");
        let pending = dir.join("target/vstf/rod/t-34");
        std::fs::create_dir_all(&pending).unwrap();
        for f in PENDING_FILES {
            std::fs::write(pending.join(f), "x").unwrap();
        }
        std::fs::write(pending.join("important.txt"), "keep").unwrap();
        clear_pending(&dir, &pending).unwrap();
        let left: Vec<_> = std::fs::read_dir(&pending)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(left, ["important.txt"]);
        // Control: with only vstf's files, the folder goes too.
        std::fs::remove_file(pending.join("important.txt")).unwrap();
        std::fs::write(pending.join("actual.png"), "x").unwrap();
        clear_pending(&dir, &pending).unwrap();
        assert!(!pending.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
