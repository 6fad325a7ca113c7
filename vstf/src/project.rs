//! The project `vstf` works on: a folder holding `fixtures/` (scene files),
//! `golden/` (their approved images) and `target/vstf/` (pending images).
//!
//! A project is found at run time, never at compile time: it is the nearest
//! ancestor of the current directory (the directory itself included) that
//! holds a `vstf.toml` file or a `fixtures/` folder, or the folder given with
//! `--root`. A binary installed with `cargo install` therefore checks the
//! project it is run in, and a copy of a project is checked against its own
//! goldens. `vstf.toml` only marks the root; its content is not read.
//! Outside any project, `vstf check FILE` takes the file's folder as one
//! that is only read ([`Project::beside`]): goldens from its `golden/`, no
//! pending images.

use crate::budget::Budget;
use crate::error::Error;
use crate::fixture::Fixture;
use crate::golden::Store;
use crate::spelling::closest;
use std::path::{Path, PathBuf};

/// The file that marks a project's root.
pub const MARKER: &str = "vstf.toml";

/// A project folder (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Project {
    root: PathBuf,
    /// A fixture file's folder outside any project: goldens are read from
    /// its `golden/`, and nothing is written there.
    beside_file: bool,
}

impl Project {
    /// The project at `root`, which must be a folder.
    pub fn at(root: &Path) -> Result<Project, Error> {
        if !root.is_dir() {
            return Err(Error::NoProject {
                message: format!("--root {}: not a folder", root.display()),
            });
        }
        let root = root
            .canonicalize()
            .map_err(|e| Error::io(root, format!("--root {}: {e}", root.display())))?;
        Ok(Project {
            root,
            beside_file: false,
        })
    }

    /// The nearest ancestor of `start` (itself included) that holds
    /// `vstf.toml` or `fixtures/`.
    pub fn discover(start: &Path) -> Result<Project, Error> {
        let start = start
            .canonicalize()
            .map_err(|e| Error::io(start, format!("{}: {e}", start.display())))?;
        start
            .ancestors()
            .find(|dir| is_root(dir))
            .map(|root| Project {
                root: root.to_path_buf(),
                beside_file: false,
            })
            .ok_or_else(|| Error::NoProject {
                message: format!(
                    "no vstf project in {} or above it: no {MARKER} or fixtures/ folder \
                     (create one with `vstf init`, or name it with --root DIR)",
                    start.display()
                ),
            })
    }

    /// The project named by `--root`, or else the one the current directory lies in.
    pub fn locate(root: Option<&Path>) -> Result<Project, Error> {
        match root {
            Some(r) => Project::at(r),
            None => {
                let cwd = std::env::current_dir().map_err(|e| {
                    Error::io(".", format!("cannot read the current directory: {e}"))
                })?;
                Project::discover(&cwd)
            }
        }
    }

    /// The project's root folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The project's scene files.
    pub fn fixtures_dir(&self) -> PathBuf {
        self.root.join("fixtures")
    }

    /// The project's approved and pending images.
    pub fn store(&self) -> Store {
        Store {
            root: self.root.clone(),
            golden: self.root.join("golden"),
            pending: self.root.join("target").join("vstf"),
            writes_pending: !self.beside_file,
        }
    }

    /// The folder of the fixture files `files` outside any project, as a
    /// project that only reads: goldens from its `golden/` (as `vstf init`
    /// there would keep them), no pending images written. The files must
    /// share one folder.
    pub fn beside(files: &[String]) -> Result<Project, Error> {
        let mut folder: Option<PathBuf> = None;
        for f in files {
            let p = Path::new(f);
            if !p.is_file() {
                return Err(Error::NoProject {
                    message: format!(
                        "no vstf project here, and {f:?} is not a fixture file: outside a project `vstf check` takes fixture files (vstf check FILE.json), or make one with `vstf init`"
                    ),
                });
            }
            let dir = p
                .canonicalize()
                .map_err(|e| Error::io(p, format!("{f}: {e}")))?
                .parent()
                .map(Path::to_path_buf)
                .unwrap_or_default();
            match &folder {
                Some(d) if *d != dir => {
                    return Err(Error::usage(format!(
                        "outside a project the fixture files must share one folder (its golden/ holds their images): {} and {}",
                        d.display(),
                        dir.display()
                    )))
                }
                _ => folder = Some(dir),
            }
        }
        let root = folder.ok_or_else(|| Error::NoProject {
            message: "no vstf project here: name fixture files (vstf check FILE.json), or make a project with `vstf init`"
                .into(),
        })?;
        Ok(Project {
            root,
            beside_file: true,
        })
    }

    /// Whether this is a fixture file's folder outside any project
    /// ([`Project::beside`]).
    pub fn is_beside_file(&self) -> bool {
        self.beside_file
    }

    /// A fixture file: `name_or_path` if it is a file, else
    /// `fixtures/<name>.json` of this project.
    pub fn resolve(&self, name_or_path: &str) -> Result<PathBuf, Error> {
        let p = Path::new(name_or_path);
        if p.is_file() {
            return Ok(p.to_path_buf());
        }
        let candidate = self.fixtures_dir().join(format!("{name_or_path}.json"));
        if candidate.is_file() {
            return Ok(candidate);
        }
        let known = self.fixture_names();
        let hint = closest(name_or_path, &known)
            .map(|k| format!("did you mean {k:?}? "))
            .unwrap_or_default();
        Err(Error::NoFixture {
            name: name_or_path.into(),
            message: format!(
                "no fixture {name_or_path:?}: not a file, and no {}; {hint}fixtures here: {}",
                candidate.display(),
                if known.is_empty() {
                    "none".into()
                } else {
                    known.join(", ")
                }
            ),
        })
    }

    /// Loads a fixture by path, or by name from this project's `fixtures/`.
    pub fn load(&self, name_or_path: &str) -> Result<Fixture, Error> {
        self.load_within(name_or_path, &Budget::DEFAULT)
    }

    /// [`Project::load`] within a memory budget.
    pub fn load_within(&self, name_or_path: &str, budget: &Budget) -> Result<Fixture, Error> {
        let file = self.resolve(name_or_path)?;
        Ok(Fixture::load_within(&file, budget)?)
    }

    /// Names of the fixtures in `fixtures/`, sorted.
    pub fn fixture_names(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(self.fixtures_dir())
            .into_iter()
            .flatten()
            .flatten()
            .filter_map(|e| {
                let p = e.path();
                (p.extension()? == "json").then(|| p.file_stem()?.to_str().map(String::from))?
            })
            .collect();
        names.sort();
        names
    }

    /// The fixtures a command given `names` works on: those names, or all
    /// of the project's when there are none.
    pub fn fixtures_or_all(&self, names: &[String]) -> Vec<String> {
        if names.is_empty() {
            self.fixture_names()
        } else {
            names.to_vec()
        }
    }
}

/// Whether `dir` is a project's root.
fn is_root(dir: &Path) -> bool {
    dir.join(MARKER).is_file() || dir.join("fixtures").is_dir()
}

/// Loads a fixture for a command that needs no project when given a file:
/// a path loads directly, a name is looked up in the project found by
/// [`Project::locate`].
pub fn load_fixture(
    root: Option<&Path>,
    name_or_path: &str,
    budget: &Budget,
) -> Result<Fixture, Error> {
    let p = Path::new(name_or_path);
    if p.is_file() && root.is_none() {
        return Ok(Fixture::load_within(p, budget)?);
    }
    Project::locate(root)?.load_within(name_or_path, budget)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("vstf-project-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn the_nearest_marked_ancestor_is_the_project() {
        let dir = scratch("nearest");
        std::fs::create_dir_all(dir.join("outer/fixtures")).unwrap();
        std::fs::create_dir_all(dir.join("outer/inner/deep")).unwrap();
        std::fs::write(dir.join("outer/inner/vstf.toml"), "").unwrap();
        let found = Project::discover(&dir.join("outer/inner/deep")).unwrap();
        assert_eq!(
            found.root(),
            dir.join("outer/inner").canonicalize().unwrap()
        );
        let outer = Project::discover(&dir.join("outer")).unwrap();
        assert_eq!(outer.root(), dir.join("outer").canonicalize().unwrap());
        assert_eq!(outer.store().golden, outer.root().join("golden"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn no_project_is_an_error_naming_the_way_out() {
        let dir = scratch("none");
        // The temporary folder itself may lie inside a project on some
        // machines; only a folder without one above it can be tested.
        if dir.ancestors().skip(1).any(is_root) {
            return;
        }
        let e = Project::discover(&dir).unwrap_err();
        assert!(
            matches!(&e, Error::NoProject { message }
                if message.contains("vstf init") && message.contains("--root")),
            "{e}"
        );
        assert!(matches!(
            Project::at(&dir.join("missing")),
            Err(Error::NoProject { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
