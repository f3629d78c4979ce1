//! The progress line on a terminal: simulated time, pose, speed, the commands running
//! and the movements queued, redrawn at most ten times a second of wall time. Quiet
//! when stderr is not a terminal, so logs and tests see only the summary.

use std::time::{Duration, Instant};

use ilmr_vm::{Clock, Vm};

use super::backend::{AnyRobot, Robot};
use super::report::Report;
use super::session::Session;
use crate::status_line::StatusLine;

const EVERY: Duration = Duration::from_millis(100);
/// Characters kept of the line, so that it does not wrap on a common terminal.
const WIDTH: usize = 118;

pub struct Progress {
    line: StatusLine,
    last: Option<Instant>,
}

impl Progress {
    /// Shown when stderr is a terminal and the run may draw on it (`allowed`).
    pub fn on_terminal(allowed: bool) -> Progress {
        Progress {
            line: StatusLine::on_terminal(allowed),
            last: None,
        }
    }

    pub fn show<C: Clock>(&mut self, vm: &Vm<AnyRobot, C>, session: &Session, report: &Report) {
        if !self.line.enabled() || self.last.is_some_and(|l| l.elapsed() < EVERY) {
            return;
        }
        self.last = Some(Instant::now());
        self.line.draw(&render(vm, session, report));
    }

    pub fn clear(&mut self) {
        self.line.clear();
    }
}

fn render<C: Clock>(vm: &Vm<AnyRobot, C>, session: &Session, report: &Report) -> String {
    let mut s = format!("t {:7.2} s", vm.time());
    if let Some(p) = vm.hal().true_pose() {
        s.push_str(&format!(
            "  ({:.2}, {:.2}, {:.0}°)",
            p.x,
            p.y,
            p.h.to_degrees()
        ));
    }
    if let Some((v, _)) = vm.hal().true_motion() {
        s.push_str(&format!("  {v:5.2} m/s"));
    }
    // A hold comes first: the robot stands, and the commands after it say why not.
    if let Some((h, held)) = report.longest_hold(vm.time()) {
        s.push_str(&format!(
            "  held {:.0} s ({}): {}",
            held,
            h.fault.name(),
            h.message
        ));
    }
    let text = |i: usize| {
        vm.module()
            .stmts
            .get(i)
            .map(|st| format!("{} [{}]", st.text, st.line))
            .unwrap_or_default()
    };
    let a = vm.activity();
    if let Some(i) = session.moving {
        s.push_str(&format!("  moving: {}", text(i)));
    }
    let others = a.running_commands - usize::from(session.moving.is_some());
    if others > 0 {
        s.push_str(&format!("  +{others} running"));
    }
    if !session.queued.is_empty() {
        let q: Vec<String> = session.queued.iter().map(|&i| text(i)).collect();
        s.push_str(&format!("  queued: {}", q.join(", ")));
    }
    if a.waiting_guards > 0 {
        s.push_str(&format!("  {} guards waiting", a.waiting_guards));
    }
    if s.chars().count() > WIDTH {
        s = s.chars().take(WIDTH - 1).collect::<String>() + "…";
    }
    s
}
