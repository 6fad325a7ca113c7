//! The native half of the Python package `vstf`: scenes, renders into numpy
//! arrays, checks and ray logs, each a thin call into the harness (`vstf`)
//! and the renderer, never a second implementation. The Python half
//! (`vstf/__init__.py`) gives them their documented signatures and turns
//! the JSON the harness writes into Python objects.
//!
//! The GIL is released while the harness works, and renders use every
//! thread of the renderer's pool.

mod check;
mod errors;
mod render;
mod scene;

use pyo3::prelude::*;

/// The module `vstf._vstf`.
#[pymodule]
fn _vstf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::animate, m)?)?;
    m.add_function(wrap_pyfunction!(check::check, m)?)?;
    m.add_function(wrap_pyfunction!(check::debug, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)
}
