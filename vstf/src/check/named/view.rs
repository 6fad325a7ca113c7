//! The view a named kind renders for its golden image.

use crate::fixture::Fixture;
use renderer::Model;

/// A view a named kind renders for its golden image: its name, the fixture
/// it renders (possibly a derived copy: the cube moving instead of the
/// camera, a season's speed), the model and the camera time.
pub struct NamedView {
    /// The view's name (also its golden image's).
    pub name: String,
    /// The fixture rendered.
    pub fixture: Fixture,
    /// The model rendered with.
    pub model: Model,
    /// The camera's lab time.
    pub camera_t: f64,
}
