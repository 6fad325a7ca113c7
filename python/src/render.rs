//! Images as numpy arrays: one view of a scene, or a stack of them at
//! several camera times, rendered by the harness's one render path
//! (`vstf::run`), so that an array holds exactly the pixels of the PNG the
//! command line writes for the same scene and view.

use crate::errors::{to_py, usage};
use crate::scene::Scene;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use renderer::{Database, Image, Model, Traversal};
use std::str::FromStr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;
use vstf::fixture::{Fixture, ModelName, Overrides, View};
use vstf::{Budget, CameraTime};

/// A camera time as Python gives it: a number, `"auto"` or `"auto:OBJECT"`
/// (as `--camera-t`).
#[derive(FromPyObject)]
pub enum TimeArg {
    /// A lab time, t.units.
    At(f64),
    /// `auto` or `auto:OBJECT`.
    Named(String),
}

/// What a caller asks of a view, before it is resolved against the scene.
pub struct Request {
    /// A view of the scene by name (declared, or rendered by a named check).
    pub view: Option<String>,
    /// The camera time.
    pub t: Option<TimeArg>,
    /// `infinite`, `classical` or `relativistic`.
    pub model: Option<String>,
    /// Image size, samples and colour effects.
    pub width: Option<u32>,
    /// Image height.
    pub height: Option<u32>,
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// The Doppler shift on.
    pub doppler: bool,
    /// The searchlight effect on.
    pub searchlight: bool,
}

impl Request {
    /// The fixture (with a named view's effects) and the view to render.
    fn resolve(&self, f: &Fixture) -> Result<(Fixture, View), vstf::Error> {
        if let Some(name) = &self.view {
            let others = self.t.is_some()
                || self.model.is_some()
                || self.width.is_some()
                || self.height.is_some()
                || self.spp.is_some()
                || self.doppler
                || self.searchlight;
            if others {
                return Err(vstf::Error::usage(format!(
                    "view={name:?} renders the view exactly as `vstf check` does for its golden \
                     image; leave t, model, width, height, spp, doppler and searchlight unset"
                )));
            }
            return vstf::check::golden_view(f, name).map_err(vstf::Error::usage);
        }
        let model = self.model.as_deref().map(model_named).transpose()?;
        let camera_t = match &self.t {
            None => None,
            Some(TimeArg::At(t)) => Some(*t),
            Some(TimeArg::Named(s)) => {
                let t = CameraTime::from_str(s)
                    .map_err(|e| vstf::Error::usage(format!("t={s:?}: {e}")))?;
                let solving = model.unwrap_or_else(|| f.model(&Overrides::default()));
                Some(vstf::resolve_camera_time(f, &t, solving).map_err(vstf::Error::usage)?)
            }
        };
        let overrides = Overrides {
            model,
            camera_t,
            width: self.width,
            height: self.height,
            spp: self.spp,
            doppler: self.doppler,
            searchlight: self.searchlight,
        };
        Ok((f.clone(), vstf::run::view(f, &overrides)?))
    }
}

/// The renderer's model named `name`, with the fixture schema's message
/// for an unknown one.
fn model_named(name: &str) -> Result<Model, vstf::Error> {
    serde_json::from_value::<ModelName>(serde_json::Value::String(name.into()))
        .map(ModelName::model)
        .map_err(|e| vstf::Error::usage(format!("model={name:?}: {e}")))
}

/// The fixture, its view and its database, within the budget unless
/// `force` (the work of `frames` frames of the view's size).
pub(crate) fn prepare(
    scene: &Scene,
    request: &Request,
    force: bool,
    frames: usize,
) -> Result<(Fixture, View, Database), vstf::Error> {
    let (fixture, view) = request.resolve(&scene.fixture)?;
    let size = (view.camera.width, view.camera.height);
    Budget::forced(force).check_work(size, view.settings.spp, frames)?;
    let db = vstf::run::database(&fixture, view.model.lorentz, Traversal::Bvh)?;
    Ok((fixture, view, db))
}

/// An image as a numpy array of shape (height, width, 3): the PNG's 8-bit
/// values (`uint8`), or the linear radiance (`float64`) when `linear`.
fn to_array<'py>(py: Python<'py>, image: &Image, linear: bool) -> PyResult<Bound<'py, PyAny>> {
    let shape = [image.height as usize, image.width as usize, 3];
    if linear {
        let flat: Vec<f64> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
        Ok(PyArray1::from_vec(py, flat).reshape(shape)?.into_any())
    } else {
        let bytes = image.to_rgb8_bytes();
        Ok(PyArray1::from_vec(py, bytes).reshape(shape)?.into_any())
    }
}

/// One float output variable of a pixel.
type Read = fn(&vstf::PixelAov) -> f64;

/// The output variables of every pixel ([`vstf::aov`]) as a dict of
/// arrays of shape (height, width), (height, width, 3) for the normal.
fn aov_arrays<'py>(
    py: Python<'py>,
    aovs: &[vstf::PixelAov],
    (width, height): (u32, u32),
) -> PyResult<Bound<'py, PyDict>> {
    let (h, w) = (height as usize, width as usize);
    let out = PyDict::new(py);
    let floats: [(&str, Read); 5] = [
        ("event_t", |a| a.event_t),
        ("proper_time", |a| a.proper_time),
        ("doppler", |a| a.doppler),
        ("searchlight", |a| a.searchlight),
        ("distance", |a| a.distance),
    ];
    for (name, read) in floats {
        let values: Vec<f64> = aovs.iter().map(read).collect();
        out.set_item(name, PyArray1::from_vec(py, values).reshape([h, w])?)?;
    }
    let objects: Vec<i64> = aovs.iter().map(|a| a.object).collect();
    out.set_item("object", PyArray1::from_vec(py, objects).reshape([h, w])?)?;
    let normals: Vec<f64> = aovs.iter().flat_map(|a| a.normal.to_array()).collect();
    out.set_item(
        "normal",
        PyArray1::from_vec(py, normals).reshape([h, w, 3])?,
    )?;
    Ok(out)
}

/// Runs `work` (which watches its stop flag) on a thread of its own while
/// the calling thread, the GIL released, looks for Ctrl-C every 20 ms; on
/// one it sets the flag, waits for the work to stop (within a row of
/// pixels) and raises `KeyboardInterrupt`.
fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&AtomicBool) -> Result<T, vstf::Error> + Send,
) -> PyResult<T> {
    let stop = AtomicBool::new(false);
    let mut interrupt: Option<PyErr> = None;
    let outcome = py.detach(|| {
        std::thread::scope(|s| {
            let worker = s.spawn(|| work(&stop));
            while !worker.is_finished() {
                std::thread::sleep(Duration::from_millis(20));
                if interrupt.is_none() {
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        interrupt = Some(e);
                        stop.store(true, Ordering::Relaxed);
                    }
                }
            }
            worker.join()
        })
    });
    if let Some(e) = interrupt {
        return Err(e);
    }
    match outcome {
        Ok(result) => result.map_err(to_py),
        Err(panic) => std::panic::resume_unwind(panic),
    }
}

/// Renders one view of `scene` into an array (see the package's `render`);
/// with `aovs`, a pair of the array and a dict of per-pixel arrays.
#[pyfunction]
#[pyo3(signature = (scene, *, view=None, t=None, model=None, width=None, height=None,
                    spp=None, doppler=false, searchlight=false, linear=false, force=false,
                    aovs=false))]
#[allow(clippy::too_many_arguments)] // Python's keyword arguments, one per view setting.
pub fn render<'py>(
    py: Python<'py>,
    scene: &Scene,
    view: Option<String>,
    t: Option<TimeArg>,
    model: Option<String>,
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
    doppler: bool,
    searchlight: bool,
    linear: bool,
    force: bool,
    aovs: bool,
) -> PyResult<Bound<'py, PyAny>> {
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
    let (image, per_pixel) = interruptible(py, |stop| {
        let (fixture, view, db) = prepare(scene, &request, force, 1)?;
        let image = vstf::run::render_until(&db, &fixture, &view, stop)?;
        let per_pixel = aovs.then(|| vstf::aovs(&fixture, &view, &db));
        Ok((image, per_pixel))
    })?;
    let array = to_array(py, &image, linear)?;
    match per_pixel {
        None => Ok(array),
        Some(a) => {
            let dict = aov_arrays(py, &a, (image.width, image.height))?;
            Ok((array, dict).into_pyobject(py)?.into_any())
        }
    }
}

/// Renders the view at each camera time in `times`, one database for all,
/// into an array of shape (frames, height, width, 3). `progress`, if given,
/// is called with (frames done, frames) after each frame; Ctrl-C stops the
/// work between frames with `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (scene, times, *, model=None, width=None, height=None, spp=None,
                    doppler=false, searchlight=false, linear=false, force=false, progress=None))]
#[allow(clippy::too_many_arguments)] // Python's keyword arguments, one per view setting.
pub fn animate<'py>(
    py: Python<'py>,
    scene: &Scene,
    times: Vec<f64>,
    model: Option<String>,
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
    doppler: bool,
    searchlight: bool,
    linear: bool,
    force: bool,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    if times.is_empty() {
        return Err(usage("times: give at least one camera time"));
    }
    let mut request = Request {
        view: None,
        t: Some(TimeArg::At(times[0])),
        model,
        width,
        height,
        spp,
        doppler,
        searchlight,
    };
    let (fixture, first, db) = py
        .detach(|| prepare(scene, &request, force, times.len()))
        .map_err(to_py)?;
    let mut frames = Vec::with_capacity(times.len());
    for (i, &t) in times.iter().enumerate() {
        request.t = Some(TimeArg::At(t));
        let image = interruptible(py, |stop| {
            let (_, view) = request.resolve(&fixture)?;
            debug_assert_eq!(view.model, first.model);
            vstf::run::render_until(&db, &fixture, &view, stop)
        })?;
        frames.push(to_array(py, &image, linear)?);
        if let Some(callback) = &progress {
            callback.call1((i + 1, times.len()))?;
        }
    }
    let numpy = py.import("numpy")?;
    numpy.call_method1("stack", (frames,))
}
