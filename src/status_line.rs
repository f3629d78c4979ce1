//! One line of status on stderr, redrawn in place, for a person at a terminal: quiet
//! when stderr is not one, so that logs and tests see only what is printed for good.

use std::io::{IsTerminal, Write};

pub struct StatusLine {
    enabled: bool,
    shown: bool,
}

impl StatusLine {
    /// Drawn when stderr is a terminal and the caller may draw on it (`allowed`).
    pub fn on_terminal(allowed: bool) -> StatusLine {
        StatusLine {
            enabled: allowed && std::io::stderr().is_terminal(),
            shown: false,
        }
    }

    pub fn enabled(&self) -> bool {
        self.enabled
    }

    /// Replaces the line with `text`.
    pub fn draw(&mut self, text: &str) {
        if !self.enabled {
            return;
        }
        let mut err = std::io::stderr().lock();
        let _ = write!(err, "\r\x1b[2K{text}");
        let _ = err.flush();
        self.shown = true;
    }

    /// Takes the line away before other output.
    pub fn clear(&mut self) {
        if self.shown {
            let _ = write!(std::io::stderr().lock(), "\r\x1b[2K");
            self.shown = false;
        }
    }
}
