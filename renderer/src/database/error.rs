//! Why a scene cannot be inserted into the database.

use std::fmt;

/// A scene that cannot be inserted, with the field at fault.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// Location of the offending field, e.g. `objects[2].worldline.velocity`.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.message)
    }
}

impl std::error::Error for SceneError {}

pub(super) fn err(path: String, message: String) -> SceneError {
    SceneError { path, message }
}
