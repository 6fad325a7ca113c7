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

/// Limits every search of this process to the vector level `level`
/// names (`"baseline"` or `"x86-64-v3"`) at the widest, as
/// `vstf --simd` does; the images are the same to the bit at every level.
#[pyfunction]
fn limit_simd(level: &str) -> PyResult<()> {
    let level = renderer::SimdLevel::from_name(level).ok_or_else(|| {
        let names = renderer::SimdLevel::ALL.map(|l| format!("{:?}", l.name()));
        errors::usage(format!(
            "simd level {level:?}: expected {}",
            names.join(" or ")
        ))
    })?;
    renderer::SimdLevel::limit_process(level);
    Ok(())
}

/// The vector level searches run at here: the machine's widest, within
/// [`limit_simd`]'s limit.
#[pyfunction]
fn simd_level() -> &'static str {
    renderer::SimdLevel::best().name()
}

/// The module `vstf._vstf`.
#[pymodule]
fn _vstf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::animate, m)?)?;
    m.add_function(wrap_pyfunction!(check::check, m)?)?;
    m.add_function(wrap_pyfunction!(check::debug, m)?)?;
    m.add_function(wrap_pyfunction!(limit_simd, m)?)?;
    m.add_function(wrap_pyfunction!(simd_level, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)
}
