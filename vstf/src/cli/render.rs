//! `vstf render`: one view of a fixture to a PNG.

use super::args::RenderArgs;
use super::view::prepare;
use renderer::LightSpeed;
use std::path::Path;
use std::time::Instant;

/// Renders the view and reports what was rendered and how long it took.
pub fn run(root: Option<&Path>, args: RenderArgs) -> Result<(), String> {
    let RenderArgs {
        fixture,
        out,
        view,
        brute_force,
    } = args;
    let png = out
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        return Err(format!(
            "--out {}: vstf writes PNG images; name the file .png",
            out.display()
        ));
    }
    let started = Instant::now();
    let (fixture, view, db) = prepare(root, &fixture, &view, brute_force, true)?;
    let image = vstf::run::render_with(&db, &fixture, &view)?;
    vstf::output::write_png(&out, &image.to_rgb8())?;
    for warning in vstf::aim::out_of_view(&fixture, &view) {
        eprintln!("warning: {warning}");
    }
    eprintln!(
        "rendered {} ({} model{}, t_c = {}, {}x{}, {} spp, {} tetrahedra) in {:.2} s -> {}",
        fixture.name,
        view.model,
        if view.model.light_speed == LightSpeed::Infinite {
            ", lab slice"
        } else {
            ""
        },
        view.camera_t,
        view.camera.width,
        view.camera.height,
        view.settings.spp,
        db.tetrahedra().len(),
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(())
}
