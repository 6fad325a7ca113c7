//! The `vstf` command line: [`args`] is its grammar, [`view`] turns the view
//! flags into a fixture's view and database, and each subcommand has its
//! module: [`render`], [`check`], [`approve`], [`debug`] (with
//! `debug-diff`), [`animate`], [`merge`] (of sharded runs), [`bench`],
//! [`list`], [`init`] and [`fuzz`].

pub mod animate;
pub mod approve;
pub mod args;
pub mod bench;
pub mod check;
pub mod debug;
pub mod fuzz;
pub mod init;
pub mod list;
pub mod merge;
pub mod render;
pub mod review;
pub mod serve;
pub mod view;

/// Ends the process quietly when its output pipe is closed (`vstf list |
/// head`), as command-line tools do, instead of a panic message and exit
/// code 101: printing to a closed stdout panics, and this hook turns that
/// one panic into the exit status of a process ended by SIGPIPE (141), so
/// that a pipeline still sees that the command did not finish. Every other
/// panic is reported as before.
pub fn quiet_on_closed_pipe() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(141);
        }
        previous(info);
    }));
}
