//! The progress line on a terminal while tests run long: runs done of all, and the
//! wall time. Quiet when stderr is not a terminal, and for the first second.

use crate::status_line::StatusLine;
use std::time::{Duration, Instant};

/// Shown once the tests have run this long.
const AFTER: Duration = Duration::from_secs(1);
/// Redrawn at most this often.
pub const EVERY: Duration = Duration::from_millis(100);

pub struct Progress {
    line: StatusLine,
    started: Instant,
}

impl Progress {
    pub fn on_terminal() -> Progress {
        Progress {
            line: StatusLine::on_terminal(true),
            started: Instant::now(),
        }
    }

    pub fn show(&mut self, done: usize, total: usize) {
        let elapsed = self.started.elapsed();
        if elapsed >= AFTER {
            self.line.draw(&line(done, total, elapsed));
        }
    }

    /// Takes the line away before other output.
    pub fn clear(&mut self) {
        self.line.clear();
    }
}

/// `[=====>     ] 12/40 runs, 3.4 s`.
pub fn line(done: usize, total: usize, elapsed: Duration) -> String {
    const WIDTH: usize = 30;
    let filled = (done * WIDTH)
        .checked_div(total)
        .unwrap_or(WIDTH)
        .min(WIDTH);
    let bar: String = (0..WIDTH)
        .map(|i| match i.cmp(&filled) {
            std::cmp::Ordering::Less => '=',
            std::cmp::Ordering::Equal => '>',
            std::cmp::Ordering::Greater => ' ',
        })
        .collect();
    format!(
        "[{bar}] {done}/{total} runs, {:.1} s",
        elapsed.as_secs_f64()
    )
}
