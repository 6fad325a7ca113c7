//! `vstf serve`: the local page of [`vstf::serve`], until Ctrl-C.

use std::io::Write;
use std::path::Path;
use vstf::error::Error;
use vstf::project::Project;

/// Serves the project found from `root` on 127.0.0.1:`port`.
pub fn run(root: Option<&Path>, port: u16) -> Result<(), Error> {
    let project = Project::locate(root)?;
    vstf::serve::serve(project, port, |addr| {
        println!("serving {addr} (127.0.0.1 only; Ctrl-C stops)");
        std::io::stdout().flush().ok();
    })
}
