//! A fixture's views by name, as `vstf check` renders them for their golden
//! images: the declared views and the views the named kinds render. The one
//! way `render --view`, `animate`, `list` and `serve` find a view, so that
//! each reproduces its golden image bit for bit.

use crate::check::named;
use crate::check::probe::VIEW_WIDTH;
use crate::fixture::checks::{MeasureSpec, ViewSpec};
use crate::fixture::{Fixture, View};
use crate::observer::{fixture_model, Observer};
use renderer::Model;

/// The name of the one view of a fixture that declares neither views nor
/// checks.
pub(crate) const OWN_VIEW: &str = "view";

/// The observer of a fixture that declares neither views nor checks: its
/// own camera event in its own model, the view [`OWN_VIEW`] that `vstf
/// check` compares with its golden image. `None` for any other fixture.
pub(crate) fn own_observer(f: &Fixture) -> Option<Observer<'_>> {
    (f.spec.views.is_empty() && f.spec.checks.is_empty()).then(|| Observer {
        fixture: f,
        model: fixture_model(f),
        camera_t: f.spec.camera.t,
    })
}

/// A view of a fixture as `vstf list --views` shows it.
pub struct ViewEntry {
    /// The view's name (also its golden image's).
    pub name: String,
    /// The model it is rendered with.
    pub model: Model,
    /// The camera's lab time.
    pub camera_t: f64,
    /// The named kind that renders it; `None` for a declared view.
    pub rendered_by: Option<&'static str>,
}

/// Every view of `f`: the declared ones in order, then those of each named
/// check in order; the own view `"view"` for a fixture that declares neither. A
/// named kind whose views cannot be made (its derived fixture is invalid)
/// lists none; `vstf check` reports why.
pub fn views_of(f: &Fixture) -> Vec<ViewEntry> {
    let declared = f.spec.views.iter().map(|v| {
        let o = Observer::declared(f, v);
        ViewEntry {
            name: v.name.clone(),
            model: o.model,
            camera_t: o.camera_t,
            rendered_by: None,
        }
    });
    let named = f.spec.checks.iter().filter_map(|c| match &c.measure {
        MeasureSpec::Named(n) => Some(n),
        _ => None,
    });
    let named = named.flat_map(|n| {
        named::views(f, n)
            .unwrap_or_default()
            .into_iter()
            .map(|v| ViewEntry {
                name: v.name,
                model: v.model,
                camera_t: v.camera_t,
                rendered_by: Some(n.kind()),
            })
    });
    let own = own_observer(f).map(|o| ViewEntry {
        name: OWN_VIEW.to_string(),
        model: o.model,
        camera_t: o.camera_t,
        rendered_by: None,
    });
    declared.chain(named).chain(own).collect()
}

/// The fixture with a view's colour effects, where the view sets any.
pub(crate) fn with_view_effects(f: &Fixture, v: &ViewSpec) -> Option<Fixture> {
    if v.doppler.is_none() && v.searchlight.is_none() {
        return None;
    }
    let mut f = f.clone();
    f.spec.image.doppler = v.doppler.unwrap_or(f.spec.image.doppler);
    f.spec.image.searchlight = v.searchlight.unwrap_or(f.spec.image.searchlight);
    Some(f)
}

/// The declared view `name` of `f` exactly as `vstf check` renders it for
/// its golden image: the fixture (with the view's colour effects) and the
/// view (its camera time and model, the report's size, the fixture's
/// samples), so that `vstf render --view` reproduces the golden bit for bit.
pub fn golden_view(f: &Fixture, name: &str) -> Result<(Fixture, View), String> {
    if let Some(own) = own_observer(f).filter(|_| name == OWN_VIEW) {
        return Ok((f.clone(), own.report_view(VIEW_WIDTH)?));
    }
    if !f.spec.views.iter().any(|v| v.name == name) {
        if let Some(found) = named_view(f, name)? {
            return Ok(found);
        }
    }
    let v = f
        .spec
        .views
        .iter()
        .find(|v| v.name == name)
        .ok_or_else(|| {
            let known: Vec<&str> = f.spec.views.iter().map(|v| v.name.as_str()).collect();
            let named: Vec<&str> = f
                .spec
                .checks
                .iter()
                .filter_map(|c| match &c.measure {
                    MeasureSpec::Named(n) => Some(n.kind()),
                    _ => None,
                })
                .collect();
            let also = if named.is_empty() {
                String::new()
            } else {
                format!(
                    "; its named check{} {} render{} views of other names (vstf list --views)",
                    if named.len() > 1 { "s" } else { "" },
                    named.join(", "),
                    if named.len() > 1 { "" } else { "s" }
                )
            };
            format!(
                "{}: no view named {name:?} (declared views: {}){also}",
                f.file.display(),
                if known.is_empty() {
                    "none".into()
                } else {
                    known.join(", ")
                }
            )
        })?;
    let fixture = with_view_effects(f, v).unwrap_or_else(|| f.clone());
    let view = Observer::declared(&fixture, v).report_view(VIEW_WIDTH)?;
    Ok((fixture, view))
}

/// The view `name` one of `f`'s named kinds renders for its golden image,
/// as `vstf check` renders it: the kind's fixture, model and camera time at
/// the report's size.
fn named_view(f: &Fixture, name: &str) -> Result<Option<(Fixture, View)>, String> {
    for c in &f.spec.checks {
        let MeasureSpec::Named(n) = &c.measure else {
            continue;
        };
        let Some(v) = named::views(f, n)?.into_iter().find(|v| v.name == name) else {
            continue;
        };
        let observer = Observer {
            fixture: &v.fixture,
            model: v.model,
            camera_t: v.camera_t,
        };
        let view = observer.report_view(VIEW_WIDTH)?;
        return Ok(Some((v.fixture, view)));
    }
    Ok(None)
}
