//! `vstf render`: one view of a fixture to a PNG, a JPEG or an OpenEXR
//! file (with the per-pixel output variables as further channels).

use super::args::{ModelArg, RenderArgs, ViewArgs};
use super::view::prepare;
use renderer::LightSpeed;
use std::path::Path;
use std::time::Instant;
use vstf::error::Error;
use vstf::StillFormat;

/// Renders the view and reports what was rendered and how long it took.
pub fn run(root: Option<&Path>, args: RenderArgs) -> Result<(), Error> {
    let RenderArgs {
        fixture,
        out,
        models,
        view,
        brute_force,
        aovs,
    } = args;
    let format = StillFormat::of(&out)?;
    if aovs && format != StillFormat::Exr {
        return Err(Error::usage(format!(
            "--aovs: the output variables are layers of an OpenEXR file; name --out {} .exr",
            out.display()
        )));
    }
    vstf::writable_file(&out)?;
    if models.is_some() {
        if format == StillFormat::Exr {
            return Err(Error::usage(format!(
                "--out {}: --models all writes a labelled sheet of three 8-bit images \
                 (.png or .jpg); an EXR holds one view (render each --model into its own)",
                out.display()
            )));
        }
        return all_models(root, &fixture, &view, brute_force, (&out, format));
    }
    let started = Instant::now();
    let (fixture, view, db) = prepare(root, &fixture, &view, brute_force, true)?;
    let image = vstf::run::render_with(&db, &fixture, &view)?;
    write(
        &out,
        format,
        &image,
        aovs.then(|| vstf::aovs(&fixture, &view, &db)).as_deref(),
        (&fixture, &view),
    )?;
    for warning in vstf::out_of_view(&fixture, &view) {
        eprintln!("warning: {warning}");
    }
    let empty = vstf::nothing_in_view_at_all(&fixture, &view);
    eprintln!(
        "rendered {} ({} model{}, t_c = {}, {}x{}, {} spp, {} prisms) in {:.2} s -> {}",
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
        db.prism_count(),
        started.elapsed().as_secs_f64(),
        out.display()
    );
    if empty {
        return Err(Error::Failed {
            message: format!(
                "nothing is in view: {} shows no object (written to look at; see the warning above)",
                out.display()
            ),
        });
    }
    Ok(())
}

/// Writes the image in `format`; an EXR with the output variables `aovs`
/// when given, and the view's camera time and model in its header.
fn write(
    out: &Path,
    format: StillFormat,
    image: &renderer::Image,
    aovs: Option<&[vstf::PixelAov]>,
    (fixture, view): (&vstf::Fixture, &vstf::View),
) -> Result<(), Error> {
    if format != StillFormat::Exr {
        return vstf::write_8bit(out, format, &vstf::rgb8(image));
    }
    let meta = vstf::ExrMeta {
        fixture: fixture.name.clone(),
        model: view.model.to_string(),
        camera_t: view.camera_t,
    };
    vstf::write_exr(out, image, aovs, &meta)
}

/// The three models side by side, each panel labelled with its model and
/// camera time: classical and relativistic at the camera time asked for
/// (or the fixture's), infinite at that time less the light time from the
/// looked-at point, so that all three show the scene as it was when the
/// light the finite models see left the middle of the picture.
fn all_models(
    root: Option<&Path>,
    name: &str,
    args: &ViewArgs,
    brute_force: bool,
    (out, format): (&Path, StillFormat),
) -> Result<(), Error> {
    let started = Instant::now();
    let (fixture, base, _) = prepare(root, name, args, brute_force, false)?;
    let camera = &fixture.spec.camera;
    let light_time = camera.look_at.map_or(0.0, |p| p.distance(camera.position));
    let mut panels = Vec::new();
    for (model, t) in [
        (ModelArg::Infinite, base.camera_t - light_time),
        (ModelArg::Classical, base.camera_t),
        (ModelArg::Relativistic, base.camera_t),
    ] {
        let one = ViewArgs {
            model: Some(model),
            camera_t: Some(vstf::CameraTime::At(t)),
            ..args.clone()
        };
        let (fixture, view, db) = prepare(root, name, &one, brute_force, true)?;
        let mut img = vstf::rgb8(&vstf::run::render_with(&db, &fixture, &view)?);
        let label = format!(
            "{}, t = {}",
            view.model,
            vstf::animate::time_label(view.camera_t)
        );
        let scale = vstf::label_scale(img.width());
        vstf::draw_label(&mut img, &label, scale);
        panels.push(img);
    }
    let gap = 4;
    let (w, h) = (panels[0].width(), panels[0].height());
    let mut sheet = image::RgbImage::new(3 * w + 2 * gap, h);
    for (k, p) in panels.iter().enumerate() {
        image::imageops::replace(&mut sheet, p, i64::from(k as u32 * (w + gap)), 0);
    }
    vstf::write_8bit(out, format, &sheet)?;
    eprintln!(
        "rendered {} in the three models ({}x{} each) in {:.2} s -> {}",
        fixture.name,
        w,
        h,
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(())
}
