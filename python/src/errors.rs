//! The harness's typed errors as Python exception classes, one per
//! variant of [`vstf::Error`], all under `vstf.VstfError`, so that a
//! notebook can tell a fixture to fix from a missing file from a check that
//! cannot be measured. Each keeps the message the command line prints, and
//! carries the fields a program wants as attributes (`file`, `path`, ...).

use pyo3::exceptions::{PyException, PyKeyboardInterrupt};
use pyo3::prelude::*;
use pyo3::{create_exception, PyErr};

create_exception!(
    vstf,
    VstfError,
    PyException,
    "Every error the harness raises."
);
create_exception!(
    vstf,
    FixtureError,
    VstfError,
    "A fixture that does not load: `file`, `path` (the JSON path of the field at fault) and `message`."
);
create_exception!(
    vstf,
    NoProjectError,
    VstfError,
    "No vstf project around the folder (run `vstf init`)."
);
create_exception!(
    vstf,
    NoFixtureError,
    VstfError,
    "No fixture of that name in the project: `name`."
);
create_exception!(
    vstf,
    BudgetError,
    VstfError,
    "Work refused before it starts: beyond the memory or time budget (pass force=True)."
);
create_exception!(
    vstf,
    VstfIOError,
    VstfError,
    "A file that cannot be read or written: `filename`."
);
create_exception!(
    vstf,
    CheckError,
    VstfError,
    "A declared check that cannot be measured: `file`, `index`, `check`."
);
create_exception!(
    vstf,
    NonFiniteError,
    VstfError,
    "A render that gave a pixel that is not a finite colour."
);
create_exception!(
    vstf,
    GoldenError,
    VstfError,
    "The golden-image workflow refused: nothing pending, an unknown image."
);
create_exception!(
    vstf,
    UsageError,
    VstfError,
    "An argument that makes no sense (an unknown model or view, a size of zero)."
);

/// The Python exception for `e`, its attributes set from the variant.
pub fn to_py(e: vstf::Error) -> PyErr {
    let message = e.to_string();
    Python::attach(|py| {
        let err = match &e {
            vstf::Error::Fixture(_) => FixtureError::new_err(message),
            vstf::Error::NoProject { .. } => NoProjectError::new_err(message),
            vstf::Error::NoFixture { .. } => NoFixtureError::new_err(message),
            vstf::Error::Budget { .. } => BudgetError::new_err(message),
            vstf::Error::Io { .. } => VstfIOError::new_err(message),
            vstf::Error::Check { .. } => CheckError::new_err(message),
            vstf::Error::NonFinite { .. } => NonFiniteError::new_err(message),
            vstf::Error::Golden { .. } => GoldenError::new_err(message),
            vstf::Error::Usage { .. } => UsageError::new_err(message),
            vstf::Error::Interrupted { .. } => PyKeyboardInterrupt::new_err(message),
            vstf::Error::Failed { .. } | vstf::Error::Other(_) => VstfError::new_err(message),
        };
        let value = err.value(py);
        // Setting an attribute on a fresh exception instance does not fail.
        let _ = match e {
            vstf::Error::Fixture(f) => value
                .setattr("file", f.file.display().to_string())
                .and(value.setattr("path", f.path))
                .and(value.setattr("detail", f.message)),
            vstf::Error::NoFixture { name, .. } => value.setattr("name", name),
            vstf::Error::Io { path, .. } => value.setattr("filename", path.display().to_string()),
            vstf::Error::Check {
                file, index, check, ..
            } => value
                .setattr("file", file.display().to_string())
                .and(value.setattr("index", index))
                .and(value.setattr("check", check)),
            _ => Ok(()),
        };
        err
    })
}

/// A usage error with `message`.
pub fn usage(message: impl Into<String>) -> PyErr {
    UsageError::new_err(message.into())
}

/// Adds the exception classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("VstfError", py.get_type::<VstfError>())?;
    m.add("FixtureError", py.get_type::<FixtureError>())?;
    m.add("NoProjectError", py.get_type::<NoProjectError>())?;
    m.add("NoFixtureError", py.get_type::<NoFixtureError>())?;
    m.add("BudgetError", py.get_type::<BudgetError>())?;
    m.add("VstfIOError", py.get_type::<VstfIOError>())?;
    m.add("CheckError", py.get_type::<CheckError>())?;
    m.add("NonFiniteError", py.get_type::<NonFiniteError>())?;
    m.add("GoldenError", py.get_type::<GoldenError>())?;
    m.add("UsageError", py.get_type::<UsageError>())?;
    Ok(())
}
