//! `vstf approve`: pending images become golden images, or are listed.

use super::args::ApproveArgs;
use std::path::Path;
use vstf::golden::Store;
use vstf::project::Project;

/// Lists the pending images, or approves those of the named fixtures (or
/// all); approving is refused when CI is set.
pub fn run(root: Option<&Path>, args: ApproveArgs) -> Result<(), String> {
    let ApproveArgs {
        fixtures,
        all,
        list,
    } = args;
    let store = Project::locate(root)?.store();
    if list {
        list_pending(&store);
        return Ok(());
    }
    if fixtures.is_empty() && !all {
        return Err("name the fixtures to approve, or give --all (see --list)".into());
    }
    let ci = std::env::var_os("CI").is_some();
    let chosen = if all { None } else { Some(fixtures.as_slice()) };
    let done = store.approve(chosen, ci)?;
    if done.is_empty() {
        println!("nothing to approve");
    }
    for p in done {
        let what = if p.replaces { "updated" } else { "created" };
        println!(
            "{what} {}",
            store.golden_path(&p.fixture, &p.view).display()
        );
    }
    Ok(())
}

/// Prints each pending image: new, or changed from its golden image.
fn list_pending(store: &Store) {
    let pending = store.list_pending();
    if pending.is_empty() {
        println!("nothing pending");
    }
    for p in pending {
        let what = if p.replaces { "changed" } else { "new" };
        println!(
            "{what:8} {} / {}  {}",
            p.fixture,
            p.view,
            p.actual.display()
        );
    }
}
