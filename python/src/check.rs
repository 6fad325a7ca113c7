//! The harness from Python: a scene's declared checks, its golden images,
//! and the variables along one pixel's rays, each as the JSON the command
//! line writes (`vstf check --json`, `vstf debug --log`), which the
//! package's Python half turns into objects.

use crate::errors::to_py;
use crate::render::{Request, TimeArg};
use crate::scene::Scene;
use pyo3::prelude::*;
use std::path::Path;
use vstf::check::Effort;
use vstf::Project;

/// Runs `scene`'s declared checks (at the tests' effort when `quick`) and,
/// when its file lies in a project's `fixtures/` and `goldens`, compares
/// its views with their golden images there (writing pending images as
/// `vstf check` does). Returns `vstf check --json`'s text.
#[pyfunction]
#[pyo3(signature = (scene, *, quick=false, goldens=true))]
pub fn check(py: Python<'_>, scene: &Scene, quick: bool, goldens: bool) -> PyResult<String> {
    let effort = if quick { Effort::QUICK } else { Effort::FULL };
    let fixture = &scene.fixture;
    py.detach(|| {
        let project = goldens.then(|| project_of(&fixture.file)).flatten();
        let store = project.as_ref().map(Project::store);
        let report = vstf::check::check_loaded(fixture, &effort, store.as_ref())?;
        let compared: Vec<_> = report.goldens.iter().collect();
        Ok(vstf::report::check_json(&report.rows, &compared))
    })
    .map_err(to_py)
}

/// The project whose `fixtures/` holds `file`, if any.
fn project_of(file: &Path) -> Option<Project> {
    let dir = file.parent()?.canonicalize().ok()?;
    let project = Project::discover(&dir).ok()?;
    (project.fixtures_dir().canonicalize().ok()? == dir).then_some(project)
}

/// The variables along pixel (x, y)'s rays in a view of `scene`, as the
/// JSON of one `vstf debug --log` line (`candidates` keeps the prisms
/// tested but not hit).
#[pyfunction]
#[pyo3(signature = (scene, x, y, *, view=None, t=None, model=None, width=None, height=None,
                    spp=None, doppler=false, searchlight=false, candidates=false))]
#[allow(clippy::too_many_arguments)] // Python's keyword arguments, one per view setting.
pub fn debug(
    py: Python<'_>,
    scene: &Scene,
    x: u32,
    y: u32,
    view: Option<String>,
    t: Option<TimeArg>,
    model: Option<String>,
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
    doppler: bool,
    searchlight: bool,
    candidates: bool,
) -> PyResult<String> {
    let request = Request {
        view,
        t,
        model,
        width,
        height,
        spp,
        doppler,
        searchlight,
    };
    py.detach(|| {
        let (fixture, view, db) = crate::render::prepare(scene, &request, false, 1)?;
        let mut log =
            vstf::debug::trace_pixel(&fixture, &view, &db, x, y).map_err(vstf::Error::usage)?;
        if !candidates {
            log.drop_candidates();
        }
        serde_json::to_string(&log).map_err(|e| vstf::Error::Other(e.to_string()))
    })
    .map_err(to_py)
}
