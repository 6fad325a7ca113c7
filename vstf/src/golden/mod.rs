//! Approved images ("goldens") and the approve workflow.
//!
//! Like insta's snapshots, a check never writes an approved image: a
//! mismatch or a missing golden leaves a *pending* actual image (with the
//! expected image and a diff beside it) under `target/vstf/<fixture>/<view>/`,
//! and only `vstf approve` copies pending images into `golden/`, atomically.
//! Like WebRender's reftests, each fixture states its tolerance as
//! `fuzzy(max_diff, max_pixels)`, comparing decoded pixels, never PNG bytes.

mod compare;
mod names;

pub use compare::{change, compare, diff_image, Change, Comparison, Difference, Fuzzy};
pub use names::slug;

use crate::error::Error;
use image::RgbImage;
use std::path::{Path, PathBuf};

/// Whether the `CI` variable says this runs under CI: set, non-empty and
/// not `0` or `false`.
pub fn ci_is_set(value: Option<&str>) -> bool {
    value.is_some_and(|v| {
        let v = v.trim();
        !(v.is_empty() || v == "0" || v.eq_ignore_ascii_case("false"))
    })
}

/// A pending image waiting for approval.
#[derive(Clone, Debug, PartialEq)]
pub struct Pending {
    /// Fixture name.
    pub fixture: String,
    /// View name within the fixture.
    pub view: String,
    /// The pending actual image.
    pub actual: PathBuf,
    /// Whether a golden exists (then this is a change, else a new image).
    pub replaces: bool,
}

impl Pending {
    /// Where it differs from the golden it would replace (from the pending
    /// `actual.png` and `expected.png`); `None` for a new image.
    pub fn change(&self) -> Option<Change> {
        let dir = self.actual.parent()?;
        let actual = image::open(&self.actual).ok()?.to_rgb8();
        let expected = image::open(dir.join("expected.png")).ok()?.to_rgb8();
        change(&actual, &expected)
    }
}

/// Where goldens and pending images live.
#[derive(Clone, Debug)]
pub struct Store {
    /// The project's root: nothing between it and the images may be a link.
    pub root: PathBuf,
    /// Approved images, `<fixture>/<view>.png`.
    pub golden: PathBuf,
    /// Pending images, `<fixture>/<view>/{actual,expected,diff}.png`.
    pub pending: PathBuf,
    /// Whether [`Store::check`] writes (and clears) pending images: not
    /// for a fixture file checked outside any project, beside which
    /// nothing is written.
    pub writes_pending: bool,
}

impl Store {
    /// Temporary files in `golden/` and the pending folder left by writes
    /// that were interrupted (their process is gone).
    pub fn stale_temps(&self) -> Vec<PathBuf> {
        let mut all = crate::output::stale_temps(&self.golden);
        all.extend(crate::output::stale_temps(&self.pending));
        all
    }

    /// Removes those stale temporary files; returns them.
    pub fn remove_stale_temps(&self) -> Vec<PathBuf> {
        let mut all = crate::output::remove_stale(&self.golden);
        all.extend(crate::output::remove_stale(&self.pending));
        all
    }

    /// The approved image of a view.
    pub fn golden_path(&self, fixture: &str, view: &str) -> PathBuf {
        self.golden
            .join(slug(fixture))
            .join(format!("{}.png", slug(view)))
    }

    /// The folder of a view's pending images.
    pub fn pending_dir(&self, fixture: &str, view: &str) -> PathBuf {
        self.pending.join(slug(fixture)).join(slug(view))
    }

    /// Compares `actual` with the golden of (`fixture`, `view`). On a
    /// mismatch or a missing golden, writes `actual.png`, `expected.png` (if
    /// any) and `diff.png` into the view's pending folder; on a match,
    /// removes any stale pending images of the view.
    pub fn check(
        &self,
        fixture: &str,
        view: &str,
        actual: &RgbImage,
        allowed: Fuzzy,
    ) -> Result<Comparison, Error> {
        let path = self.golden_path(fixture, view);
        if !self.writes_pending {
            crate::confine::real_folder(&self.root, path.parent().unwrap_or(&self.golden))?;
            crate::confine::no_link(&path)?;
        }
        let expected = if path.exists() {
            Some(
                image::open(&path)
                    .map_err(|e| {
                        Error::io(&path, format!("cannot read golden {}: {e}", path.display()))
                    })?
                    .to_rgb8(),
            )
        } else {
            None
        };
        let measured = expected.as_ref().and_then(|e| compare(actual, e));
        let pass =
            measured.is_some_and(|m| m.max <= allowed.max_diff && m.pixels <= allowed.max_pixels);
        let dir = self.pending_dir(fixture, view);
        let pending = if !self.writes_pending {
            None
        } else if pass {
            crate::confine::clear_pending(&self.root, &dir)?;
            None
        } else {
            crate::confine::real_folder(&self.root, &dir)?;
            crate::output::write_png(&dir.join("actual.png"), actual)?;
            if let Some(e) = &expected {
                crate::output::write_png(&dir.join("expected.png"), e)?;
                crate::output::write_png(&dir.join("diff.png"), &diff_image(actual, e))?;
            } else {
                let _ = std::fs::remove_file(dir.join("expected.png"));
                let _ = std::fs::remove_file(dir.join("diff.png"));
            }
            std::fs::write(dir.join("names"), format!("{fixture}\n{view}\n"))
                .map_err(|e| Error::io(&dir, format!("cannot write {}: {e}", dir.display())))?;
            Some(dir)
        };
        Ok(Comparison {
            fixture: fixture.into(),
            view: view.into(),
            allowed,
            max_diff: measured.map(|m| m.max),
            differing: measured.map_or(0, |m| m.pixels),
            missing: expected.is_none(),
            pass,
            pending,
            worst_at: measured.and_then(|m| m.worst_at),
            size: actual.dimensions(),
            golden: expected.is_some().then_some(path),
        })
    }

    /// Every pending image, sorted.
    pub fn list_pending(&self) -> Vec<Pending> {
        let mut out = Vec::new();
        for fixture_dir in read_dirs(&self.pending) {
            for view_dir in read_dirs(&fixture_dir) {
                let actual = view_dir.join("actual.png");
                let Ok(names) = std::fs::read_to_string(view_dir.join("names")) else {
                    continue;
                };
                let mut lines = names.lines();
                let (Some(fixture), Some(view)) = (lines.next(), lines.next()) else {
                    continue;
                };
                if actual.is_file() {
                    let replaces = self.golden_path(fixture, view).exists();
                    out.push(Pending {
                        fixture: fixture.into(),
                        view: view.into(),
                        actual,
                        replaces,
                    });
                }
            }
        }
        out.sort_by(|a, b| (&a.fixture, &a.view).cmp(&(&b.fixture, &b.view)));
        out
    }

    /// The pending images `names` ask for (all when `None`): a name is a
    /// fixture (all its pending views) or `FIXTURE/VIEW`; a name with
    /// nothing pending is an error that lists what is.
    pub fn select(&self, names: Option<&[String]>) -> Result<Vec<Pending>, Error> {
        let pending = self.list_pending();
        let Some(names) = names else {
            return Ok(pending);
        };
        let matches = |n: &str, p: &Pending| match n.split_once('/') {
            Some((f, v)) => slug(f) == slug(&p.fixture) && slug(v) == slug(&p.view),
            None => slug(n) == slug(&p.fixture),
        };
        if let Some(missing) = names
            .iter()
            .find(|n| !pending.iter().any(|p| matches(n, p)))
        {
            let what: Vec<String> = pending
                .iter()
                .map(|p| format!("{}/{}", p.fixture, slug(&p.view)))
                .collect();
            return Err(Error::Golden {
                message: format!(
                    "nothing pending for {missing:?}; pending: {}",
                    if what.is_empty() {
                        "nothing".into()
                    } else {
                        what.join(", ")
                    }
                ),
            });
        }
        Ok(pending
            .into_iter()
            .filter(|p| names.iter().any(|n| matches(n, p)))
            .collect())
    }

    /// Drops the pending images `names` ask for ([`Store::select`]): the
    /// change is not wanted; the golden images stay as they are.
    pub fn reject(&self, names: Option<&[String]>) -> Result<Vec<Pending>, Error> {
        let chosen = self.select(names)?;
        for p in &chosen {
            let dir = p.actual.parent().expect("pending images live in a folder");
            crate::confine::clear_pending(&self.root, dir)?;
        }
        Ok(chosen)
    }

    /// Copies the pending images `names` ask for ([`Store::select`]) into
    /// the golden folder, each write atomic, and clears them from pending.
    /// Refused when `ci` is set: CI never approves or creates goldens.
    pub fn approve(&self, names: Option<&[String]>, ci: bool) -> Result<Vec<Pending>, Error> {
        if ci {
            return Err(Error::Golden {
                message: "refusing to approve golden images with CI set: approve locally and commit the images".into(),
            });
        }
        let chosen = self.select(names)?;
        for p in &chosen {
            let bytes = std::fs::read(&p.actual).map_err(|e| {
                Error::io(
                    &p.actual,
                    format!("cannot read {}: {e}", p.actual.display()),
                )
            })?;
            image::load_from_memory(&bytes).map_err(|e| {
                Error::io(
                    &p.actual,
                    format!("{} is not a valid PNG: {e}", p.actual.display()),
                )
            })?;
            let dest = self.golden_path(&p.fixture, &p.view);
            crate::confine::real_folder(&self.root, dest.parent().unwrap_or(&self.golden))?;
            if std::fs::symlink_metadata(&dest).is_ok_and(|m| m.file_type().is_symlink()) {
                return Err(Error::Golden {
                    message: format!(
                        "{} is a symbolic link: approve writes golden images only as files of their own",
                        dest.display()
                    ),
                });
            }
            crate::output::write_atomic(&dest, &bytes)
                .map_err(|e| Error::io(&dest, format!("cannot write {}: {e}", dest.display())))?;
            let dir = p.actual.parent().expect("pending images live in a folder");
            crate::confine::clear_pending(&self.root, dir)?;
        }
        Ok(chosen)
    }
}

fn read_dirs(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    v.sort();
    v
}

#[cfg(test)]
mod tests;
