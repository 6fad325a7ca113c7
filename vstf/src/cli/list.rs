//! `vstf list`: the fixtures and what each shows.

use std::path::Path;
use vstf::project::Project;

/// Prints each fixture's name and description (or why it does not load).
pub fn run(root: Option<&Path>) -> Result<(), String> {
    let project = Project::locate(root)?;
    for name in project.fixture_names() {
        let desc = project
            .load(&name)
            .map(|f| f.spec.description)
            .unwrap_or_else(|e| format!("(invalid: {e})"));
        println!("{name:24} {desc}");
    }
    Ok(())
}
