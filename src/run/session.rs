//! What a run keeps between ticks besides the VM: which commands live, what has ended
//! how, how far the robot went, and interactive lines joined or rejected.

use ilmr_compiler::lower::{LineOptions, lower_line_into};
use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_hal::Pose;
use ilmr_model::RobotModel;
use ilmr_trace::{Entered, Event as Line, Record};
use ilmr_vm::LineError;
use ilmr_vm::{Clock, Event, EventKind, How, Vm};

use super::backend::AnyRobot;
use super::console::Console;

#[derive(Debug, Default)]
pub struct Tally {
    pub completed: u32,
    pub broken: u32,
    pub refused: u32,
    pub overruns: u32,
    pub errors: u32,
    pub lines_accepted: u32,
    pub lines_rejected: u32,
}

pub struct Session {
    /// Movement statements by their statement index: queued in issue order, and the
    /// one holding the reservation (for the progress line).
    pub queued: Vec<usize>,
    pub moving: Option<usize>,
    pub tally: Tally,
    options: LineOptions,
    /// Metres the robot's reference point travelled (ground truth).
    pub distance: f64,
    last_pose: Option<Pose>,
}

impl Session {
    pub fn new(robotless: bool) -> Session {
        Session {
            queued: Vec::new(),
            moving: None,
            tally: Tally::default(),
            options: LineOptions { robotless },
            distance: 0.0,
            last_pose: None,
        }
    }

    /// Takes the tick's events: follows the movement queue and counts. Returns whether
    /// a block overran the budget (it still has statements to run).
    pub fn absorb(&mut self, events: &[Event], movement: &[bool]) -> bool {
        let mut overran = false;
        for e in events {
            let stmt = e.stmt.map(|s| s.index());
            if let Some(i) = stmt.filter(|i| movement.get(*i).copied().unwrap_or(false)) {
                match e.kind {
                    // A movement issued again and again in one tick is one event
                    // with a count (the trace's coalescing).
                    EventKind::Issue => {
                        self.queued
                            .extend(std::iter::repeat_n(i, e.count.max(1) as usize));
                    }
                    EventKind::Start { .. } => {
                        if let Some(q) = self.queued.iter().position(|&s| s == i) {
                            self.queued.remove(q);
                        }
                        self.moving = Some(i);
                    }
                    EventKind::End { .. } => {
                        if self.moving == Some(i) {
                            self.moving = None;
                        } else if let Some(q) = self.queued.iter().position(|&s| s == i) {
                            self.queued.remove(q);
                        }
                    }
                    _ => {}
                }
            }
            match &e.kind {
                EventKind::End { how, .. } => match how {
                    How::Completed => self.tally.completed += 1,
                    How::Broken => self.tally.broken += 1,
                    How::Refused => self.tally.refused += 1,
                },
                EventKind::Overrun { .. } => {
                    overran = true;
                    self.tally.overruns += 1;
                }
                EventKind::Error { .. } => self.tally.errors += 1,
                _ => {}
            }
        }
        overran
    }

    pub fn travel(&mut self, pose: Option<Pose>) {
        if let (Some(a), Some(b)) = (self.last_pose, pose) {
            self.distance += (b.x - a.x).hypot(b.y - a.y);
        }
        if pose.is_some() {
            self.last_pose = pose;
        }
    }

    pub fn last_pose(&self) -> Option<Pose> {
        self.last_pose
    }

    /// Compiles an interactive line against the running task and joins it; a bad line
    /// is reported and changes nothing. Returns the trace line that records it.
    pub fn line<C: Clock>(
        &mut self,
        vm: &mut Vm<AnyRobot, C>,
        model: &RobotModel,
        text: &str,
        console: &mut Console,
    ) -> Record<'static> {
        let t = ilmr_vm::runtime::trace::fmt_num(vm.time());
        let options = self.options;
        let (accepted, codes) = match vm.add_line(|b| lower_line_into(text, b, model, options)) {
            Ok(()) => {
                self.tally.lines_accepted += 1;
                (true, Vec::new())
            }
            Err(LineError::Invalid(e)) => {
                self.tally.lines_rejected += 1;
                console.err(&format!("line at t={t} not joined: {e}\n"));
                (false, Vec::new())
            }
            Err(LineError::Replaced) => {
                self.tally.lines_rejected += 1;
                console.err(&format!(
                    "line at t={t} not joined: the lowering did not return the program\n"
                ));
                (false, Vec::new())
            }
            Err(LineError::Lower(diagnostics)) => {
                self.tally.lines_rejected += 1;
                let file = [RenderFile {
                    path: "<line>",
                    text,
                }];
                console.err(&format!(
                    "line at t={t} rejected:\n{}",
                    render::human(&diagnostics, &file, Style::PLAIN)
                ));
                let codes = diagnostics.iter().map(|d| d.code.as_str().into()).collect();
                (false, codes)
            }
        };
        Record::new(
            vm.time(),
            Line::Line(Entered {
                text: text.to_string().into(),
                accepted,
                codes,
            }),
        )
    }
}
