//! How the programs end: a failure's kind decides its exit status, in one
//! place for `raytrace`, `psout` and the tools (which print it and end:
//! `cli::exit_code`). The port's (the thesis's
//! program has no exit statuses to speak of).
//!
//! | kind | status | |
//! |---|---|---|
//! | [`Kind::Usage`] | 2 | a bad flag or output name (clap's own usage errors end with 2 too) |
//! | [`Kind::Input`] | 2 | a deck or an input file that cannot be used |
//! | [`Kind::Other`] | 1 | anything else: an output that cannot be written, a missing folder |
//! | [`Kind::Signal`] | 128 + the signal | stopped by SIGINT (130) or SIGTERM (143), as a shell reports it |

use std::fmt;

/// What went wrong, as far as the exit status is concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The command line asks for something that cannot be done.
    Usage,
    /// An input (a deck, a raster) cannot be used.
    Input,
    /// Anything else.
    Other,
    /// Stopped by this signal.
    Signal(i32),
}

impl Kind {
    /// The exit status of a failure of this kind.
    pub fn status(self) -> u8 {
        match self {
            Kind::Usage | Kind::Input => 2,
            Kind::Other => 1,
            Kind::Signal(signal) => u8::try_from(128 + signal.clamp(1, 127)).unwrap_or(u8::MAX),
        }
    }
}

/// Why a program stops: the kind of failure and the message for stderr.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failure {
    pub kind: Kind,
    pub message: String,
}

impl Failure {
    pub fn new(kind: Kind, message: impl fmt::Display) -> Failure {
        Failure {
            kind,
            message: message.to_string(),
        }
    }

    /// A usage error (exit 2).
    pub fn usage(message: impl fmt::Display) -> Failure {
        Failure::new(Kind::Usage, message)
    }

    /// An input that cannot be used (exit 2).
    pub fn input(message: impl fmt::Display) -> Failure {
        Failure::new(Kind::Input, message)
    }

    /// Any other failure (exit 1).
    pub fn other(message: impl fmt::Display) -> Failure {
        Failure::new(Kind::Other, message)
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_has_its_status() {
        assert_eq!(Kind::Usage.status(), 2);
        assert_eq!(Kind::Input.status(), 2);
        assert_eq!(Kind::Other.status(), 1);
        assert_eq!(Kind::Signal(2).status(), 130);
        assert_eq!(Kind::Signal(15).status(), 143);
        assert_eq!(Kind::Signal(127).status(), 255);
    }

    #[test]
    fn the_constructors_keep_the_message_and_set_the_kind() {
        assert_eq!(Failure::usage("u"), Failure::new(Kind::Usage, "u"));
        assert_eq!(Failure::input(4).kind, Kind::Input);
        assert_eq!(Failure::other("o").to_string(), "o");
        assert_eq!(Failure::other("o").kind, Kind::Other);
    }
}
