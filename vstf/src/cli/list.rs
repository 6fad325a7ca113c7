//! `vstf list`: the fixtures and what each shows, and with `--views` the
//! views each declares.

use std::path::Path;
use vstf::project::Project;

/// Prints each fixture's name and description (or why it does not load);
/// with `views`, each declared view's name, camera time and model under it.
pub fn run(root: Option<&Path>, views: bool) -> Result<(), String> {
    let project = Project::locate(root)?;
    for name in project.fixture_names() {
        match project.load(&name) {
            Ok(f) => {
                println!("{name:24} {}", f.spec.description);
                if views {
                    for v in &f.spec.views {
                        let mut model = match v.model {
                            Some(m) => m.model(),
                            None => f.model(&vstf::Overrides::default()),
                        };
                        if let Some(l) = v.lorentz {
                            model.lorentz = l;
                        }
                        let t = v.t.unwrap_or(f.spec.camera.t);
                        println!("    --view {:?}  (camera t = {t}, {model} model)", v.name);
                    }
                    for c in &f.spec.checks {
                        let vstf::fixture::checks::MeasureSpec::Named(n) = &c.measure else {
                            continue;
                        };
                        for v in vstf::check::named::views(&f, n).unwrap_or_default() {
                            println!(
                                "    --view {:?}  (camera t = {}, {} model; rendered by the named check {})",
                                v.name,
                                v.camera_t,
                                v.model,
                                n.kind()
                            );
                        }
                    }
                }
            }
            Err(e) => println!("{name:24} (invalid: {e})"),
        }
    }
    Ok(())
}
