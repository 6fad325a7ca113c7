//! `vstf approve` and `vstf reject`: pending images become golden images
//! (one view or all of a fixture's), are dropped, or are listed with where
//! they differ.

use super::args::{ApproveArgs, RejectArgs};
use std::path::Path;
use vstf::error::Error;
use vstf::golden::ci_is_set;
use vstf::golden::Store;
use vstf::project::Project;

/// Lists the pending images, or approves those of the named fixtures (or
/// all); approving is refused when CI is set.
pub fn run(root: Option<&Path>, args: ApproveArgs) -> Result<(), Error> {
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
        return Err(Error::usage(
            "name the fixtures to approve, or give --all (see --list)",
        ));
    }
    for p in store.remove_stale_temps() {
        eprintln!("removed {} (left by an interrupted write)", p.display());
    }
    let ci = ci_is_set(std::env::var("CI").ok().as_deref());
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

/// Drops the pending images asked for.
pub fn reject(root: Option<&Path>, args: RejectArgs) -> Result<(), Error> {
    let store = Project::locate(root)?.store();
    let chosen = if args.all {
        None
    } else {
        Some(args.fixtures.as_slice())
    };
    let dropped = store.reject(chosen)?;
    if dropped.is_empty() {
        println!("nothing pending");
    }
    for p in dropped {
        println!("rejected {} / {} (golden unchanged)", p.fixture, p.view);
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
        let change = p.change().map(|c| format!(": {c}")).unwrap_or_default();
        println!(
            "{what:8} {}/{}  {}{change}",
            p.fixture,
            vstf::golden::slug(&p.view),
            p.actual.display()
        );
    }
    for p in store.stale_temps() {
        println!(
            "stale    {}  (left by an interrupted write; vstf approve or vstf check removes it)",
            p.display()
        );
    }
}

#[cfg(test)]
mod tests {
    use vstf::golden::ci_is_set;

    #[test]
    fn ci_counts_only_when_set_to_something_true() {
        for yes in ["true", "1", "yes", "github"] {
            assert!(ci_is_set(Some(yes)), "{yes}");
        }
        for no in [
            None,
            Some(""),
            Some("0"),
            Some("false"),
            Some("FALSE"),
            Some(" "),
        ] {
            assert!(!ci_is_set(no), "{no:?}");
        }
    }
}
