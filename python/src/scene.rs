//! A scene as Python holds it: a loaded, validated fixture. It is made from
//! a fixture file, a project's fixture name, or the JSON text of a dict
//! written in the fixture schema; every path goes through the harness's own
//! loader, so the validation and its messages (file, JSON path) are the
//! command line's.

use crate::errors::{to_py, usage};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use vstf::fixture::{Fixture, MeshSpec};
use vstf::Budget;

/// A loaded scene: its objects, camera, views and checks, validated.
#[pyclass(module = "vstf", frozen)]
pub struct Scene {
    pub(crate) fixture: Fixture,
}

#[pymethods]
impl Scene {
    /// Loads a fixture file, or a fixture of the project around the current
    /// folder (or `root`) by name. `force` lifts the memory budget.
    #[staticmethod]
    #[pyo3(signature = (name_or_path, root=None, force=false))]
    fn load(
        py: Python<'_>,
        name_or_path: PathBuf,
        root: Option<PathBuf>,
        force: bool,
    ) -> PyResult<Scene> {
        let name = name_or_path.to_string_lossy().into_owned();
        let budget = Budget::forced(force);
        py.detach(|| vstf::project::load_fixture(root.as_deref(), &name, &budget))
            .map(|fixture| Scene { fixture })
            .map_err(to_py)
    }

    /// A scene from fixture JSON text (what `json.dumps` of a dict in the
    /// fixture schema gives). `file` names it in errors and anchors the
    /// relative paths of its meshes; it is not read.
    #[staticmethod]
    #[pyo3(signature = (text, file, force=false))]
    fn parse(py: Python<'_>, text: &str, file: PathBuf, force: bool) -> PyResult<Scene> {
        let budget = Budget::forced(force);
        py.detach(|| Fixture::parse_within(text, &file, &budget))
            .map(|fixture| Scene { fixture })
            .map_err(|e| to_py(e.into()))
    }

    /// A scene from a dict written in the fixture schema (docs/fixtures.md),
    /// with the file's validation and messages; `file` names it in errors
    /// (its stem is the scene's name) and anchors relative mesh paths.
    #[staticmethod]
    #[pyo3(signature = (spec, file=None, force=false))]
    fn from_dict(
        py: Python<'_>,
        spec: &Bound<'_, PyAny>,
        file: Option<PathBuf>,
        force: bool,
    ) -> PyResult<Scene> {
        if !spec.is_instance_of::<pyo3::types::PyDict>() {
            return Err(usage(format!(
                "from_dict takes a dict in the fixture schema, not {}",
                spec.get_type().name()?
            )));
        }
        let text: String = py
            .import("json")?
            .call_method1("dumps", (spec,))
            .map_err(|e| usage(format!("the scene dict is not JSON: {e}")))?
            .extract()?;
        let file = file.unwrap_or_else(|| PathBuf::from("scene.json"));
        Scene::parse(py, &text, file, force)
    }

    /// Writes the scene as a fixture file that `vstf check` reads unchanged
    /// (atomically; an existing file only with `overwrite`). Relative OBJ
    /// paths are made absolute when the file goes to another folder, so that
    /// the same meshes are found from there.
    #[pyo3(signature = (path, overwrite=false))]
    fn save(&self, path: PathBuf, overwrite: bool) -> PyResult<()> {
        if path.exists() && !overwrite {
            return Err(to_py(vstf::Error::io(
                &path,
                format!(
                    "{} exists; pass overwrite=True to replace it",
                    path.display()
                ),
            )));
        }
        let mut spec = self.fixture.spec.clone();
        let from = self.fixture.file.parent().unwrap_or(Path::new(""));
        let to = path.parent().unwrap_or(Path::new(""));
        let here = |d: &Path| {
            std::fs::canonicalize(if d.as_os_str().is_empty() {
                Path::new(".")
            } else {
                d
            })
            .ok()
        };
        if here(from).is_none() || here(from) != here(to) {
            for object in &mut spec.objects {
                anchor_meshes(&mut object.mesh, from);
            }
        }
        let text = serde_json::to_string_pretty(&spec)
            .map_err(|e| usage(format!("cannot write the scene as JSON: {e}")))?;
        vstf::write_atomic(&path, format!("{text}\n").as_bytes()).map_err(|e| {
            to_py(vstf::Error::io(
                &path,
                format!("cannot write {}: {e}", path.display()),
            ))
        })
    }

    /// The camera's lab time as the fixture gives it.
    #[getter]
    fn camera_t(&self) -> f64 {
        self.fixture.spec.camera.t
    }

    /// The distance from the camera to the point it looks at (the light
    /// time across the scene), or `None` when it gives no `look_at`.
    #[getter]
    fn look_distance(&self) -> Option<f64> {
        let c = &self.fixture.spec.camera;
        c.look_at.map(|p| p.distance(c.position))
    }

    /// The speed (fraction of c) of the scene's one uniformly moving object,
    /// or `None` when it has none or several.
    #[getter]
    fn mover_speed(&self) -> Option<f64> {
        let i = vstf::fixture::single_mover(&self.fixture)?;
        Some(self.fixture.scene.objects[i].motion.velocity()?.length())
    }

    /// The scene with its one moving object at `speed` (a fraction of c,
    /// below 1), its start event kept: what the viewers' speed sliders
    /// render.
    fn with_speed(&self, speed: f64) -> PyResult<Scene> {
        let now = self.mover_speed().ok_or_else(|| {
            usage("with_speed needs a scene with exactly one uniformly moving object")
        })?;
        if !(0.0..1.0).contains(&speed) {
            return Err(usage(format!(
                "speed={speed}: give a fraction of c, at least 0 and below 1"
            )));
        }
        if now == 0.0 {
            return Err(usage(
                "the moving object is at rest; its speed cannot be scaled",
            ));
        }
        vstf::fixture::with_speed(&self.fixture, speed / now)
            .map(|fixture| Scene { fixture })
            .map_err(usage)
    }

    /// The fixture's name (its file's stem).
    #[getter]
    fn name(&self) -> String {
        self.fixture.name.clone()
    }

    /// The file the scene was read from (or the name it was given).
    #[getter]
    fn file(&self) -> PathBuf {
        self.fixture.file.clone()
    }

    /// The fixture's description.
    #[getter]
    fn description(&self) -> String {
        self.fixture.spec.description.clone()
    }

    /// The names of its objects, in order (an object's index in the
    /// `object` AOV is its place here).
    #[getter]
    fn objects(&self) -> Vec<String> {
        self.fixture
            .scene
            .objects
            .iter()
            .map(|o| o.name.clone())
            .collect()
    }

    /// Every view by name, as `vstf list --views` lists them: declared
    /// views, then those the named checks render; `view` for a fixture
    /// that declares neither views nor checks.
    #[getter]
    fn views(&self) -> Vec<String> {
        vstf::check::views_of(&self.fixture)
            .into_iter()
            .map(|v| v.name)
            .collect()
    }

    /// The scene with its fixture's checks and views as JSON text, as it
    /// was read (defaults filled in).
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.fixture.spec).map_err(|e| {
            usage(format!(
                "{}: cannot write as JSON: {e}",
                self.fixture.file.display()
            ))
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "<vstf.Scene {:?} from {} ({} objects)>",
            self.fixture.name,
            self.fixture.file.display(),
            self.fixture.scene.objects.len()
        )
    }
}

/// Makes every relative OBJ path in `mesh` absolute from `dir`, the folder
/// of the file it was read from, so that the mesh is found from anywhere.
fn anchor_meshes(mesh: &mut MeshSpec, dir: &Path) {
    match mesh {
        MeshSpec::Obj { path } if path.is_relative() => {
            let joined = dir.join(&*path);
            *path = joined.canonicalize().unwrap_or(joined);
        }
        MeshSpec::Group(parts) => parts.iter_mut().for_each(|m| anchor_meshes(m, dir)),
        _ => {}
    }
}
