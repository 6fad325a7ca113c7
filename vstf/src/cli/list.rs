//! `vstf list`: the fixtures and what each shows.

use vstf::fixture::Fixture;

/// Prints each fixture's name and description (or why it does not load).
pub fn run() -> Result<(), String> {
    for name in vstf::fixture::all_names() {
        let desc = Fixture::load(&name)
            .map(|f| f.spec.description)
            .unwrap_or_else(|e| format!("(invalid: {e})"));
        println!("{name:24} {desc}");
    }
    Ok(())
}
