//! Which statements have live commands, followed from the trace alone (the VM exposes
//! its trace but not its command tree). A run may end when nothing is left but `if`
//! guards that wait: every live command is then a waiting guard, or a container (a
//! fired `if`, a `while`, a skill call) of nothing but waiting guards.
//!
//! Per statement the events are: `issue` when its block executes it, `start` when a
//! queued movement gets the reservation or an `if` fires, `end` when a live command
//! ends or an issued one is refused. Instant commands (`speed`, `actuator` ...) leave
//! no live command behind, and their `end` only ever reports a refusal.

use ilmr_stdlib::Command;
use ilmr_vm::bytecode::{Arg, Op};
use ilmr_vm::{Event, EventKind, Module};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    /// Control statements with no life of their own (assign, break, stop ...).
    Instant,
    Guard,
    /// `while` and skill calls: they live while what they started lives.
    Container,
    /// Waits and issued commands that stay live until they end.
    Live {
        movement: bool,
    },
    /// `speed(v,w)`: live only while a movement runs when it is issued.
    SpeedAfter,
}

#[derive(Debug, Clone, Copy, Default)]
struct Count {
    live: u32,
    /// Guards: not yet fired. Movements: queued.
    waiting: u32,
    /// Guards: fired. Movements: holding the reservation.
    started: u32,
}

#[derive(Debug, Default)]
pub struct Liveness {
    class: Vec<Class>,
    count: Vec<Count>,
}

fn classify(module: &Module, op: &Op) -> Class {
    match *op {
        Op::If { .. } => Class::Guard,
        Op::While { .. } | Op::Call { .. } => Class::Container,
        Op::WaitTime { .. } | Op::WaitVar { .. } => Class::Live { movement: false },
        Op::Issue { command, args, .. } => {
            let words = || {
                module.arg_list(args).iter().filter_map(|a| match a {
                    Arg::Word(n) => Some(module.name(*n)),
                    _ => None,
                })
            };
            match command {
                c if c.spec().movement => Class::Live { movement: true },
                Command::Sensor
                | Command::FindTarget
                | Command::Manipulate
                | Command::Init
                | Command::MoveMode => Class::Live { movement: false },
                // `locate(x)` reads; `locate(x,y,h)` sets the pose at once.
                Command::Locate if words().next().is_some() => Class::Live { movement: false },
                Command::Speed if words().any(|w| w.eq_ignore_ascii_case("w")) => Class::SpeedAfter,
                _ => Class::Instant,
            }
        }
        _ => Class::Instant,
    }
}

impl Liveness {
    /// Learns the statements of `module` not seen yet (a joined line adds some).
    pub fn learn(&mut self, module: &Module) {
        let n = module.stmts.len();
        if self.class.len() >= n {
            return;
        }
        self.class.resize(n, Class::Instant);
        self.count.resize(n, Count::default());
        for instr in &module.code {
            if let Some(c) = self.class.get_mut(instr.stmt.index()) {
                *c = classify(module, &instr.op);
            }
        }
    }

    fn moving(&self) -> bool {
        self.class
            .iter()
            .zip(&self.count)
            .any(|(c, n)| *c == Class::Live { movement: true } && n.started > 0)
    }

    pub fn observe(&mut self, e: &Event) {
        let Some(i) = e.stmt.map(|s| s.index()) else {
            return;
        };
        let Some(&class) = self.class.get(i) else {
            return;
        };
        let moving = self.moving();
        let Some(n) = self.count.get_mut(i) else {
            return;
        };
        match (&e.kind, class) {
            (EventKind::Issue, Class::Guard) => {
                n.live += 1;
                n.waiting += 1;
            }
            (EventKind::Issue, Class::Container) => n.live += 1,
            (EventKind::Issue, Class::Live { movement }) => {
                n.live += 1;
                if movement {
                    n.waiting += 1;
                }
            }
            (EventKind::Issue, Class::SpeedAfter) if moving => n.live += 1,
            (EventKind::Start { .. }, Class::Guard | Class::Live { movement: true }) => {
                n.waiting = n.waiting.saturating_sub(1);
                n.started += 1;
            }
            (EventKind::End { .. }, Class::Guard | Class::Live { movement: true }) => {
                n.live = n.live.saturating_sub(1);
                if n.started > 0 {
                    n.started -= 1;
                } else {
                    n.waiting = n.waiting.saturating_sub(1);
                }
            }
            (EventKind::End { .. }, Class::Container | Class::Live { .. } | Class::SpeedAfter) => {
                n.live = n.live.saturating_sub(1);
            }
            _ => {}
        }
    }

    /// Every live command is a waiting guard or a container of waiting guards.
    pub fn only_guards_wait(&self) -> bool {
        self.class.iter().zip(&self.count).all(|(c, n)| match c {
            Class::Live { .. } | Class::SpeedAfter => n.live == 0,
            _ => true,
        })
    }

    pub fn guards_waiting(&self) -> u32 {
        self.class
            .iter()
            .zip(&self.count)
            .filter(|(c, _)| **c == Class::Guard)
            .map(|(_, n)| n.waiting)
            .sum()
    }
}
