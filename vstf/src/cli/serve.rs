//! `vstf serve`: the local page of [`vstf::serve`], until Ctrl-C.

use std::io::Write;
use std::path::Path;
use vstf::error::Error;
use vstf::project::Project;

/// Serves the project found from `root` on 127.0.0.1:`port`, keeping at
/// most `cache_mb` MiB of databases.
pub fn run(root: Option<&Path>, port: u16, cache_mb: u64) -> Result<(), Error> {
    let project = Project::locate(root)?;
    vstf::serve::serve(
        project,
        (port, cache_mb.saturating_mul(1 << 20)),
        |addr, _| {
            println!("serving {addr} (127.0.0.1 only; Ctrl-C stops)");
            std::io::stdout().flush().ok();
        },
    )
}
