//! `vstf list`: the fixtures and what each shows, and with `--views` the
//! views each declares.

use std::path::Path;
use vstf::check::ViewEntry;
use vstf::error::Error;
use vstf::project::Project;

/// Prints each fixture's name and description (or why it does not load);
/// with `views`, each declared view's name, camera time and model under it.
pub fn run(root: Option<&Path>, views: bool) -> Result<(), Error> {
    let project = Project::locate(root)?;
    for name in project.fixture_names() {
        match project.load(&name) {
            Ok(f) => {
                println!("{name:24} {}", f.spec.description);
                if views {
                    for v in vstf::check::views_of(&f) {
                        print_view(&v);
                    }
                }
            }
            Err(e) => println!("{name:24} (invalid: {e})"),
        }
    }
    Ok(())
}

/// One `--view` line: the view's name, camera time and model, and the named
/// check that renders it, if any.
fn print_view(v: &ViewEntry) {
    let (name, t, model) = (&v.name, v.camera_t, v.model);
    match v.rendered_by {
        None => println!("    --view {name:?}  (camera t = {t}, {model} model)"),
        Some(kind) => println!(
            "    --view {name:?}  (camera t = {t}, {model} model; rendered by the named check {kind})"
        ),
    }
}
