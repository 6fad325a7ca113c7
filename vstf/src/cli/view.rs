//! From the view flags to what rendering needs: the fixture, its view with
//! the flags applied, and its 4D database.

use super::args::{ModelArg, ViewArgs};
use renderer::{Database, Model, Traversal};
use std::path::Path;
use vstf::fixture::{Fixture, Overrides, View};
use vstf::project::load_fixture;
use vstf::Budget;

impl ViewArgs {
    /// The fixture overrides these flags ask for.
    pub fn overrides(&self, fixture: &Fixture) -> Result<Overrides, String> {
        let model = model_of(self.model, self.lorentz, fixture);
        let solving = model.unwrap_or_else(|| fixture.model(&Overrides::default()));
        Ok(Overrides {
            model,
            camera_t: self
                .camera_t
                .as_ref()
                .map(|t| vstf::resolve_camera_time(fixture, t, solving))
                .transpose()?,
            width: self.width,
            height: self.height,
            spp: self.spp,
            doppler: self.doppler,
            searchlight: self.searchlight,
        })
    }
}

/// The model `--model` and `--lorentz` ask for; `--lorentz` alone turns on
/// the Lorentz transform in the fixture's own model.
fn model_of(arg: Option<ModelArg>, lorentz: bool, fixture: &Fixture) -> Option<Model> {
    let base = match arg {
        Some(ModelArg::Infinite) => Some(Model::INFINITE),
        Some(ModelArg::Classical) => Some(Model::CLASSICAL),
        Some(ModelArg::Relativistic) => Some(Model::RELATIVISTIC),
        None if lorentz => Some(fixture.model(&Overrides::default())),
        None => None,
    };
    base.map(|m| Model {
        lorentz: m.lorentz || lorentz,
        ..m
    })
}

/// Loads a fixture, applies the view flags and builds the database, within
/// the budget unless `--force` (the time of a whole frame when `frame`).
pub fn prepare(
    root: Option<&Path>,
    name: &str,
    args: &ViewArgs,
    brute_force: bool,
    frame: bool,
) -> Result<(Fixture, View, Database), String> {
    let budget = Budget::forced(args.force);
    let fixture = load_fixture(root, name, &budget)?;
    let (fixture, view) = match &args.view {
        Some(declared) => vstf::check::golden_view(&fixture, declared)?,
        None => {
            let view = vstf::run::view(&fixture, &args.overrides(&fixture)?)?;
            (fixture, view)
        }
    };
    if frame {
        let size = (view.camera.width, view.camera.height);
        budget.check_work(size, view.settings.spp, 1)?;
    }
    let traversal = if brute_force {
        Traversal::BruteForce
    } else {
        Traversal::Bvh
    };
    let db = vstf::run::database(&fixture, view.model.lorentz, traversal)?;
    Ok((fixture, view, db))
}
