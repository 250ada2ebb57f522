//! Where commands print: stdout and stderr, with a closed pipe (`knotlab ... | head`) ending the output
//! quietly instead of panicking.

use std::io::Write;

/// Line-oriented output of one command.
pub struct Output {
    closed: bool,
}

/// `outln!(out, "format", args...)`: one formatted line to the command's output.
macro_rules! outln {
    ($out:expr) => { $out.line(String::new()) };
    ($out:expr, $($arg:tt)*) => { $out.line(format!($($arg)*)) };
}
pub(crate) use outln;

impl Output {
    /// Output to the process's stdout.
    pub fn stdout() -> Self {
        Self { closed: false }
    }

    /// Writes one line to stdout; after the reader has gone, writes nothing.
    pub fn line(&mut self, text: impl AsRef<str>) {
        if self.closed {
            return;
        }
        let mut stdout = std::io::stdout().lock();
        if writeln!(stdout, "{}", text.as_ref()).is_err() {
            self.closed = true;
        }
    }

    /// Writes one line to stderr (diagnostics a script should not parse).
    pub fn error(&mut self, text: impl AsRef<str>) {
        let _ignored = writeln!(std::io::stderr().lock(), "{}", text.as_ref());
    }
}
