//! Rendering a fixture's view: the one path shared by `vstf render`, the
//! checks and the tests.

use crate::error::Error;
use crate::fixture::{Fixture, Overrides, View};
use renderer::{Database, Image, Traversal};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

mod lazy;
mod memo;
pub use lazy::LazyImage;
use memo::Key;
pub use memo::Renders;

/// A fixture's database for one Lorentz setting.
pub fn database(fixture: &Fixture, lorentz: bool, traversal: Traversal) -> Result<Database, Error> {
    let mut db = fixture.database(lorentz)?;
    db.set_traversal(traversal);
    Ok(db)
}

/// [`database`], or the one this fixture (or a copy of it) built already
/// for the same scene, Lorentz setting and traversal ([`Renders`]).
pub fn database_shared(
    fixture: &Fixture,
    lorentz: bool,
    traversal: Traversal,
) -> Result<Arc<Database>, Error> {
    shared_database(
        fixture,
        fixture.renders.scene_key(fixture),
        lorentz,
        traversal,
    )
}

/// [`database_shared`], the scene's key found already.
fn shared_database(
    fixture: &Fixture,
    scene: Key,
    lorentz: bool,
    traversal: Traversal,
) -> Result<Arc<Database>, Error> {
    let key = fixture.renders.database_key(scene, lorentz, traversal);
    if let Some(db) = fixture.renders.get_database(key) {
        return Ok(db);
    }
    let db = Arc::new(database(fixture, lorentz, traversal)?);
    let bytes = crate::budget::kept_database_bytes(&fixture.scene);
    fixture.renders.keep_database(key, &db, bytes);
    Ok(db)
}

/// The fixture's view after `overrides`, or an error naming the file and field.
pub fn view(fixture: &Fixture, overrides: &Overrides) -> Result<View, Error> {
    fixture
        .view(overrides)
        .map_err(|e| Error::Fixture(e.in_file(&fixture.file)))
}

/// Renders `view` of `fixture` with a database built for it, or gives the
/// image this fixture (or a copy of it) rendered already for the same
/// scene, spec, view and traversal ([`Renders`]).
pub fn render(fixture: &Fixture, view: &View, traversal: Traversal) -> Result<Image, Error> {
    render_shared(fixture, view, traversal).map(Arc::unwrap_or_clone)
}

/// [`render`], the image shared with the store of kept renders rather
/// than copied out of it: what the checks read, most of their images
/// never asked for again.
pub fn render_shared(
    fixture: &Fixture,
    view: &View,
    traversal: Traversal,
) -> Result<Arc<Image>, Error> {
    let scene = fixture.renders.scene_key(fixture);
    let key = fixture.renders.key(scene, fixture, view, traversal);
    if let Some(image) = fixture.renders.get(key) {
        return Ok(image);
    }
    let db = shared_database(fixture, scene, view.model.lorentz, traversal)?;
    let image = Arc::new(render_with(&db, fixture, view)?);
    fixture.renders.keep(key, &image);
    Ok(image)
}

/// `view` of `fixture` rendered as it is read ([`LazyImage`]), or the one
/// this fixture (or a copy of it) made already for the same scene, spec
/// and view, with what of it was read so far.
pub fn render_lazy(fixture: &Fixture, view: &View) -> Result<Arc<LazyImage>, Error> {
    let scene = fixture.renders.scene_key(fixture);
    let key = fixture.renders.key(scene, fixture, view, Traversal::Bvh);
    if let Some(image) = fixture.renders.get_lazy(key) {
        return Ok(image);
    }
    let db = shared_database(fixture, scene, view.model.lorentz, Traversal::Bvh)?;
    let image = Arc::new(LazyImage::new(fixture.clone(), *view, db));
    fixture.renders.keep_lazy(key, &image);
    Ok(image)
}

/// Renders `view` with an existing database (built with the view's Lorentz
/// setting). A pixel that is not a finite colour fails the render: a NaN or
/// an infinity would be written as black without a word.
pub fn render_with(db: &Database, fixture: &Fixture, view: &View) -> Result<Image, Error> {
    render_until(db, fixture, view, &AtomicBool::new(false))
}

/// [`render_with`] into the memory of `spent`, an earlier frame's image
/// ([`renderer::render_reusing`]): how a run of frames renders.
pub fn render_reusing(
    db: &Database,
    fixture: &Fixture,
    view: &View,
    spent: Image,
) -> Result<Image, Error> {
    render_into(db, fixture, view, &AtomicBool::new(false), spent)
}

/// [`render_with`], stopped with [`Error::Interrupted`] once `stop` is set
/// (a front end's Ctrl-C), within a row's time.
pub fn render_until(
    db: &Database,
    fixture: &Fixture,
    view: &View,
    stop: &AtomicBool,
) -> Result<Image, Error> {
    render_into(db, fixture, view, stop, Image::default())
}

/// [`render_until`] into the memory of `spent`.
fn render_into(
    db: &Database,
    fixture: &Fixture,
    view: &View,
    stop: &AtomicBool,
    spent: Image,
) -> Result<Image, Error> {
    let view = &fixture
        .spec
        .retimed(view)
        .map_err(|e| Error::Fixture(e.in_file(&fixture.file)))?;
    let frame = renderer::Frame {
        camera: &view.camera,
        camera_t: view.camera_t,
        model: view.model,
        settings: &view.settings,
    };
    let window = view.window.unwrap_or(renderer::Window::whole(
        view.camera.width,
        view.camera.height,
    ));
    let image = renderer::render_window(db, &fixture.scene, &frame, window, stop, spent)
        .ok_or_else(|| Error::Interrupted {
            message: format!("{}: the render was interrupted", fixture.file.display()),
        })?;
    match image.pixels.iter().position(|p| !p.is_finite()) {
        None => Ok(image),
        Some(i) => Err(Error::NonFinite {
            message: non_finite(db, fixture, view, &image, i),
        }),
    }
}

/// The error for a render whose pixel `i` is not finite: the pixel, its
/// value, how many more there are, the object its primary ray hits and the
/// command that shows every variable along its rays.
fn non_finite(db: &Database, fixture: &Fixture, view: &View, image: &Image, i: usize) -> String {
    // (A window's pixel i is the frame's pixel at the window's corner plus i's place.)
    let (x0, y0) = view.window.map_or((0, 0), |w| (w.x, w.y));
    let (x, y) = (x0 + i as u32 % image.width, y0 + i as u32 / image.width);
    let count = image.pixels.iter().filter(|p| !p.is_finite()).count();
    let log = crate::debug::trace_pixel(fixture, view, db, x, y).ok();
    let steps = log.as_ref().map_or(&[][..], |l| &l.steps[..]);
    let object = steps
        .iter()
        .find_map(|s| match s {
            renderer::Step::Hit { object, .. } => Some(format!("object {object:?}")),
            _ => None,
        })
        .unwrap_or_else(|| "no object".to_string());
    // The first step along the pixel's rays that records a value that is not
    // finite: where in the shading it went wrong.
    let first = steps
        .iter()
        .map(|s| format!("{s:?}"))
        .find(|d| d.contains("NaN") || d.contains("inf"))
        .map(|d| {
            let kind: String = d.chars().take_while(|c| c.is_alphanumeric()).collect();
            format!(", first not finite at its {kind} step")
        })
        .unwrap_or_default();
    format!(
        "{}: pixel ({x}, {y}) is {} (not a finite colour; {count} such pixels), where the ray meets {object}{first}; \
         `vstf debug {} --pixel {x},{y} {}` shows how",
        fixture.file.display(),
        image.pixels[i],
        fixture.file.display(),
        debug_flags(view)
    )
}

/// The view flags that make `vstf debug` trace `view` (of a fixture's own
/// camera; a probe's turned camera has none).
fn debug_flags(view: &View) -> String {
    let model = match (view.model.light_speed, view.model.lorentz) {
        (renderer::LightSpeed::Infinite, false) => "--model infinite",
        (renderer::LightSpeed::Infinite, true) => "--model infinite --lorentz",
        (renderer::LightSpeed::Finite, false) => "--model classical",
        (renderer::LightSpeed::Finite, true) => "--model relativistic",
    };
    let effects = view.settings.effects;
    format!(
        "--width {} --height {} --camera-t {} --spp {} {model}{}{}",
        view.camera.width,
        view.camera.height,
        view.camera_t,
        view.settings.spp,
        if effects.doppler { " --doppler" } else { "" },
        if effects.searchlight {
            " --searchlight"
        } else {
            ""
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderer::Traversal;
    use std::path::Path;

    /// `fixtures/lit-plate.json` (a matte plate under a lamp, black
    /// background), small and without its views and checks, with `edit`
    /// applied to its JSON.
    fn lit_plate(edit: impl FnOnce(&mut serde_json::Value)) -> Fixture {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/lit-plate.json");
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        v["image"]["width"] = 48.into();
        v["image"]["height"] = 36.into();
        let o = v.as_object_mut().unwrap();
        o.remove("views");
        o.remove("checks");
        edit(&mut v);
        Fixture::parse(&v.to_string(), &file).unwrap()
    }

    fn pixels(f: &Fixture) -> Vec<glam::DVec3> {
        let view = view(f, &Overrides::default()).unwrap();
        render(f, &view, Traversal::Bvh).unwrap().pixels
    }

    /// A render repeated, of the fixture or of a copy, is the first's
    /// image, reused; a copy whose lamp is dimmer (as checks recolour
    /// their copies), a later camera time or the other traversal is
    /// rendered anew (negative controls), the traversal giving the same
    /// image.
    #[test]
    fn a_render_repeated_is_reused_and_any_change_renders_anew() {
        let f = lit_plate(|_| {});
        let v = view(&f, &Overrides::default()).unwrap();
        let first = render(&f, &v, Traversal::Bvh).unwrap();
        assert_eq!(f.renders.counts(), (1, 0));
        assert_eq!(render(&f.clone(), &v, Traversal::Bvh).unwrap(), first);
        assert_eq!(f.renders.counts(), (1, 1));
        let mut dimmer = f.clone();
        dimmer.scene.light.color *= 0.5;
        assert_ne!(render(&dimmer, &v, Traversal::Bvh).unwrap(), first);
        assert_eq!(f.renders.counts(), (2, 1));
        let later = View {
            camera_t: v.camera_t + 0.25,
            ..v
        };
        render(&f, &later, Traversal::Bvh).unwrap();
        assert_eq!(f.renders.counts(), (3, 1));
        assert_eq!(render(&f, &v, Traversal::BruteForce).unwrap(), first);
        assert_eq!(f.renders.counts(), (4, 1));
    }

    /// Images beyond the budget are not kept.
    #[test]
    fn renders_beyond_the_budget_are_not_kept() {
        let f = lit_plate(|_| {});
        let v = view(&f, &Overrides::default()).unwrap();
        let image = render(&f, &v, Traversal::Bvh).unwrap();
        let bytes = std::mem::size_of_val(image.pixels.as_slice());
        for (budget, kept) in [(bytes - 1, None), (bytes, Some(&image))] {
            let renders = Renders::within(budget);
            let key = renders.key(renders.scene_key(&f), &f, &v, Traversal::Bvh);
            renders.keep(key, &Arc::new(image.clone()));
            assert_eq!(renders.get(key).as_deref(), kept);
        }
    }

    /// A scene's database is built once for its fixture and the copies of
    /// it, whatever the view; the other Lorentz setting, the other
    /// traversal or a moved object builds another (negative controls).
    #[test]
    fn a_database_is_built_once_for_its_scene() {
        let f = lit_plate(|_| {});
        let shared =
            |f: &Fixture, lorentz, traversal| database_shared(f, lorentz, traversal).unwrap();
        let first = shared(&f, true, Traversal::Bvh);
        let mut wider = f.clone();
        wider.spec.image.width *= 2;
        assert!(Arc::ptr_eq(&first, &shared(&wider, true, Traversal::Bvh)));
        let galilean = shared(&f, false, Traversal::Bvh);
        assert!(!Arc::ptr_eq(&first, &galilean));
        let brute = shared(&f, true, Traversal::BruteForce);
        assert!(!Arc::ptr_eq(&first, &brute));
        assert_eq!(brute.traversal(), Traversal::BruteForce);
        let mut moved = f.clone();
        let renderer::Shape::Mesh(mesh) = &mut moved.scene.objects[0].shape else {
            panic!("the plate is a mesh");
        };
        mesh.vertices.iter_mut().for_each(|v| v.x += 0.5);
        let elsewhere = shared(&moved, true, Traversal::Bvh);
        assert!(!Arc::ptr_eq(&first, &elsewhere));
        assert_ne!(elsewhere.spatial_bounds(), first.spatial_bounds());
    }

    /// A database beyond the budget is not kept.
    #[test]
    fn a_database_beyond_the_budget_is_not_kept() {
        let f = lit_plate(|_| {});
        let db = Arc::new(database(&f, true, Traversal::Bvh).unwrap());
        let bytes = crate::budget::kept_database_bytes(&f.scene);
        for (budget, kept) in [(bytes - 1, false), (bytes, true)] {
            let renders = Renders::within(usize::try_from(budget).unwrap());
            let key = renders.database_key(renders.scene_key(&f), true, Traversal::Bvh);
            renders.keep_database(key, &db, bytes);
            assert_eq!(renders.get_database(key).is_some(), kept);
        }
    }

    /// Without `light` a fixture renders as with a black lamp and ambient 1:
    /// each surface shows its own colour, so the plate is not black.
    #[test]
    fn a_fixture_without_light_renders_its_colours_flat() {
        let unlit = lit_plate(|v| {
            v.as_object_mut().unwrap().remove("light");
        });
        let black_lamp = lit_plate(|v| {
            v["light"] =
                serde_json::json!({ "position": [0, 0, 0], "color": [0, 0, 0], "ambient": 1 });
        });
        let lit = lit_plate(|_| {});
        let seen = pixels(&unlit);
        assert_eq!(seen, pixels(&black_lamp));
        assert_ne!(seen, pixels(&lit));
        assert!(seen.iter().any(|p| p.max_element() > 0.0));
        assert!(seen.iter().all(|p| p.is_finite()));
    }

    /// `unlit` is its long form exactly, lit or not, in RGB and with the
    /// Doppler shift: the same pixels, bit for bit.
    #[test]
    fn an_unlit_material_renders_as_its_long_form() {
        let with = |material: serde_json::Value, doppler: bool| {
            lit_plate(|v| {
                v["objects"][0]["material"] = material;
                v["image"]["doppler"] = doppler.into();
            })
        };
        for doppler in [false, true] {
            let short = pixels(&with(
                serde_json::json!({ "unlit": [0.9, 0.5, 0.1] }),
                doppler,
            ));
            let long = serde_json::json!({
                "color": [0, 0, 0], "diffuse": 0, "emission": { "rgb": [0.9, 0.5, 0.1] }
            });
            assert_eq!(short, pixels(&with(long, doppler)));
            let lit = serde_json::json!({ "color": [0.9, 0.5, 0.1] });
            assert_ne!(short, pixels(&with(lit, doppler)));
            assert!(short.iter().any(|p| p.max_element() > 0.0));
        }
    }
}
