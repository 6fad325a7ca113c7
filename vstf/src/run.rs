//! Rendering a fixture's view: the one path shared by `vstf render`, the
//! checks and the tests.

use crate::fixture::{Fixture, Overrides, View};
use renderer::{Database, Image, Traversal};

/// A fixture's database for one Lorentz setting.
pub fn database(
    fixture: &Fixture,
    lorentz: bool,
    traversal: Traversal,
) -> Result<Database, String> {
    let mut db = fixture.database(lorentz).map_err(|e| e.to_string())?;
    db.set_traversal(traversal);
    Ok(db)
}

/// The fixture's view after `overrides`, or an error naming the file and field.
pub fn view(fixture: &Fixture, overrides: &Overrides) -> Result<View, String> {
    fixture
        .view(overrides)
        .map_err(|e| e.in_file(&fixture.file).to_string())
}

/// Renders `view` of `fixture` with a database built for it.
pub fn render(fixture: &Fixture, view: &View, traversal: Traversal) -> Result<Image, String> {
    let db = database(fixture, view.model.lorentz, traversal)?;
    Ok(render_with(&db, fixture, view))
}

/// Renders `view` with an existing database (built with the view's Lorentz setting).
pub fn render_with(db: &Database, fixture: &Fixture, view: &View) -> Image {
    renderer::render(
        db,
        &fixture.scene,
        &view.camera,
        view.camera_t,
        view.model,
        &view.settings,
    )
}
