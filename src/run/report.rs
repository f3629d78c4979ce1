//! What a run tells its operator as it goes: each refusal, supervisor fault and its
//! clearing, overrun and runtime error as one notice on stderr when it happens (at
//! most one of a kind a second, see [`crate::notice::Gate`]); the holds in force, for
//! the progress line and `--hold-limit`; the first few notices, for the summary.

use ilmr_vm::runtime::safety::{Fault, Reaction};
use ilmr_vm::runtime::trace::{fmt_num, record};
use ilmr_vm::{Event, EventKind, How, Module};

use crate::notice::{self, Detail, Gate};

/// Notices the summary repeats: enough to see the first cause, few enough to read.
pub const FIRST_KEPT: usize = 3;

/// A supervisor fault whose reaction holds the robot, in force since `since`.
#[derive(Debug, Clone)]
pub struct Hold {
    pub fault: Fault,
    pub message: String,
    pub since: f64,
}

#[derive(Default)]
pub struct Report {
    gate: Gate,
    /// Holds in force, oldest first.
    pub holds: Vec<Hold>,
    /// Holds begun over the run.
    pub holds_begun: u32,
    /// The first [`FIRST_KEPT`] notices of the run.
    pub first: Vec<String>,
}

impl Report {
    /// Takes a tick's events; `say` gets each notice that passes the gate.
    pub fn absorb(&mut self, module: &Module, events: &[Event], mut say: impl FnMut(&str)) {
        for e in events {
            let mut after = String::new();
            match &e.kind {
                EventKind::End {
                    how: How::Refused, ..
                }
                | EventKind::Overrun { .. }
                | EventKind::Error { .. } => {}
                EventKind::Fault { fault, message } => {
                    let held = self.holds.iter().any(|h| h.fault == *fault);
                    if fault.reaction() == Reaction::Hold && !held {
                        self.holds_begun += 1;
                        self.holds.push(Hold {
                            fault: *fault,
                            message: message.clone(),
                            since: e.t,
                        });
                    }
                }
                EventKind::Recovered { fault } => {
                    if let Some(i) = self.holds.iter().position(|h| h.fault == *fault) {
                        let hold = self.holds.remove(i);
                        after = format!(", released after {} s", fmt_num(e.t - hold.since));
                    }
                }
                _ => continue,
            }
            let r = record(module, e);
            let Some(text) = notice::for_event(&r, Detail::Trouble) else {
                continue;
            };
            if self.first.len() < FIRST_KEPT {
                self.first.push(format!("{text}{after}"));
            }
            if let Some(text) = self.gate.admit(&r, text) {
                say(&format!("{text}{after}"));
            }
        }
    }

    /// The hold in force longest, and for how long at `now`.
    pub fn longest_hold(&self, now: f64) -> Option<(&Hold, f64)> {
        self.holds.first().map(|h| (h, now - h.since))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn empty_module() -> Module {
        use ilmr_compiler::check::{Source, analyze};
        let model = crate::inputs::load_robot_model("moro").expect("moro loads");
        let sources = [Source::new("<test>", "")];
        let analysis = analyze(&sources, &model);
        ilmr_compiler::lower::lower(&analysis, &model, ilmr_compiler::FileId(0))
            .expect("the empty task lowers")
    }

    fn event(t: f64, kind: EventKind) -> Event {
        Event::new((t * 100.0) as u64, t, None, kind)
    }

    #[test]
    fn a_hold_is_kept_until_it_clears_and_its_length_is_said() {
        let module = empty_module();
        let mut report = Report::default();
        let mut said = Vec::new();
        let near = || EventKind::Fault {
            fault: Fault::ObstacleNear,
            message: "an obstacle 0.25 m ahead".into(),
        };
        report.absorb(&module, &[event(11.84, near())], |s| {
            said.push(s.to_string())
        });
        report.absorb(
            &module,
            &[event(
                12.0,
                EventKind::Fault {
                    fault: Fault::BatteryLow,
                    message: "battery at 10.9 V".into(),
                },
            )],
            |s| said.push(s.to_string()),
        );
        let (hold, length) = report.longest_hold(14.0).unwrap();
        assert_eq!(
            hold.fault,
            Fault::ObstacleNear,
            "a raised fault holds nothing"
        );
        assert!((length - 2.16).abs() < 1e-9);
        report.absorb(
            &module,
            &[event(
                15.0,
                EventKind::Recovered {
                    fault: Fault::ObstacleNear,
                },
            )],
            |s| said.push(s.to_string()),
        );
        assert!(report.longest_hold(16.0).is_none());
        assert_eq!(report.holds_begun, 1);
        assert_eq!(said.len(), 3, "{said:?}");
        assert!(said[0].starts_with("[t=11.84] held (R0206 obstacle_near)"));
        assert_eq!(
            said[2],
            "[t=15] cleared (R0206 obstacle_near), released after 3.16 s"
        );
        assert_eq!(report.first, said);
    }
}
