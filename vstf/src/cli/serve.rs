//! `vstf serve`: the local page of [`vstf::serve`], until Ctrl-C.

use std::io::Write;
use std::path::Path;
use vstf::error::Error;
use vstf::project::Project;
use vstf::serve::Limits;

/// Serves the project found from `root` on 127.0.0.1:`port`, keeping at
/// most `cache_mb` MB of built scenes.
pub fn run(root: Option<&Path>, port: u16, cache_mb: u64) -> Result<(), Error> {
    let project = Project::locate(root)?;
    let limits = Limits {
        cache_bytes: cache_mb.saturating_mul(1024 * 1024),
        ..Limits::default()
    };
    vstf::serve::serve_with(project, port, limits, |addr| {
        println!("serving {addr} (127.0.0.1 only, to its own page; Ctrl-C stops)");
        std::io::stdout().flush().ok();
    })
}
