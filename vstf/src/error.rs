//! The harness's one error type: what went wrong, by kind, with the file,
//! field, fixture or check it concerns, so that a front end can tell a
//! fixture the user must fix from a missing file from a failed check.
//!
//! Each variant keeps the message users have always seen (file, JSON path,
//! line and column for fixtures); [`Error::exit_code`] is the process's
//! status for it.

use crate::fixture::FixtureError;
use std::fmt;
use std::path::PathBuf;

/// An error of the harness.
#[derive(Debug)]
pub enum Error {
    /// A fixture file that does not load: its file, the JSON path of the
    /// field at fault, and where in the file.
    Fixture(FixtureError),
    /// No project around the starting folder, or `--root` is not one.
    NoProject {
        /// Why, and how to make one.
        message: String,
    },
    /// A fixture name that is neither in the project nor a file, or a
    /// project without fixtures.
    NoFixture {
        /// The name asked for (empty: the project has none).
        name: String,
        /// The message, with the nearest known name.
        message: String,
    },
    /// Work refused before it starts: a database or a render beyond the
    /// memory or time budget (`--force` lifts it).
    Budget {
        /// The estimate against the budget.
        message: String,
    },
    /// A file that cannot be read or written.
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What failed.
        message: String,
    },
    /// A check that cannot be measured on its fixture (this is not a check
    /// that measured and failed: see [`Error::Failed`]). The declared checks
    /// give such a check as its failing row instead ([`crate::check::Row`]'s
    /// `error`); the variant stays for front ends that match it.
    Check {
        /// The fixture's file.
        file: PathBuf,
        /// The check's index in the fixture's `checks`.
        index: usize,
        /// The check's name.
        check: String,
        /// Why it cannot be measured.
        message: String,
    },
    /// A render that gave a pixel that is not a finite colour.
    NonFinite {
        /// The pixel, its object and the command that logs its rays.
        message: String,
    },
    /// The golden images: nothing pending to approve, an approval refused
    /// under CI, an unknown image.
    Golden {
        /// What was refused.
        message: String,
    },
    /// A command-line argument or request parameter that makes no sense.
    Usage {
        /// What is wrong with it.
        message: String,
    },
    /// Checks or golden comparisons ran and some failed.
    Failed {
        /// The summary printed.
        message: String,
    },
    /// Work stopped by Ctrl-C, with what was finished.
    Interrupted {
        /// What was finished and where it is.
        message: String,
    },
    /// A failure of a part without a kind of its own (frame sequences,
    /// shards, ray logs, benchmarks, the local viewer).
    Other(String),
}

impl Error {
    /// The process's exit status: 1 for a verdict that failed, 130 (as a
    /// shell reports SIGINT) for work interrupted, 2 for work that could
    /// not be done.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Failed { .. } => 1,
            Error::Interrupted { .. } => 130,
            _ => 2,
        }
    }

    /// An I/O error on `path`, worded as `what`.
    pub fn io(path: impl Into<PathBuf>, message: impl Into<String>) -> Error {
        Error::Io {
            path: path.into(),
            message: message.into(),
        }
    }

    /// A bad argument.
    pub fn usage(message: impl Into<String>) -> Error {
        Error::Usage {
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Fixture(e) => e.fmt(f),
            Error::Check {
                file,
                index,
                check,
                message,
            } => write!(
                f,
                "{}: checks[{index}] {check:?}: {message}",
                file.display()
            ),
            Error::NoProject { message }
            | Error::NoFixture { message, .. }
            | Error::Budget { message }
            | Error::Io { message, .. }
            | Error::NonFinite { message }
            | Error::Golden { message }
            | Error::Usage { message }
            | Error::Failed { message }
            | Error::Interrupted { message }
            | Error::Other(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for Error {}

impl From<FixtureError> for Error {
    fn from(e: FixtureError) -> Error {
        Error::Fixture(e)
    }
}

impl From<String> for Error {
    fn from(message: String) -> Error {
        Error::Other(message)
    }
}

impl From<&str> for Error {
    fn from(message: &str) -> Error {
        Error::Other(message.into())
    }
}

/// The message of an error, for the layers that report plain messages (a
/// check kind's failure becomes its row's [`Error::Check`]).
impl From<Error> for String {
    fn from(e: Error) -> String {
        e.to_string()
    }
}
