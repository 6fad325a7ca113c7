//! `vstf serve`: the local page of [`vstf::serve`], until Ctrl-C.

use std::io::Write;
use std::path::Path;
use vstf::error::Error;
use vstf::project::Project;
use vstf::serve::Limits;

/// Serves the project found from `root` on 127.0.0.1:`port`, keeping at
/// most `cache_mb` MB of built scenes.
pub fn run(root: Option<&Path>, port: u16, cache_mb: u64) -> Result<(), Error> {
    restart_with_fixed_mmap_threshold();
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

/// Runs this process again with glibc's mmap threshold fixed, unless the
/// user set it: by default glibc raises the threshold each time a large
/// block is freed, after which the arrays of the databases the cache evicts
/// are carved from its heaps and their memory is kept (docs/security.md,
/// 'Limits'). The setting is read when a process starts, and calling
/// `mallopt` would need unsafe code; other C libraries ignore it. If the
/// restart fails the server runs as it is, and says so.
fn restart_with_fixed_mmap_threshold() {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        // Every block of at least 128 KiB in a mapping of its own, returned
        // to the system when freed.
        let (name, value) = ("MALLOC_MMAP_THRESHOLD_", "131072");
        if std::env::var_os(name).is_some() {
            return;
        }
        let error = match std::env::current_exe() {
            Ok(exe) => std::process::Command::new(exe)
                .args(std::env::args_os().skip(1))
                .env(name, value)
                .exec(),
            Err(e) => e,
        };
        eprintln!("warning: cannot restart vstf serve with {name}={value} ({error}); evicted scenes' memory may be kept");
    }
}
