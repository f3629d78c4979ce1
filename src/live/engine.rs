//! The thread that owns the VM: it ticks every 10 ms of wall time and, between ticks,
//! answers its front end's jobs at once. Nothing a front end does can block it: answers
//! go back on a channel per request, events on bounded channels with `try_send`.
//!
//! Answers are typed ([`LineAnswer`], [`Status`]); `serve` writes them as JSON and the
//! shell as text.

use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, SyncSender, TrySendError};
use std::time::{Duration, Instant};

use ilmr_compiler::Diagnostic;
use ilmr_compiler::lower::{LineOptions, lower_line_warned};
use ilmr_hal::Pose;
use ilmr_model::RobotModel;
use ilmr_stdlib::VarKind;
use ilmr_vm::bytecode::BlockId;
use ilmr_vm::runtime::trace::fmt_num;
use ilmr_vm::{Activity, LineError, ModuleBuilder, SimClock, VarRecord, Vm};

use super::guard;
use crate::run::backend::{AnyRobot, Robot};

/// What a front end asks of the VM thread.
pub enum Job {
    /// Join ILMR text to the running task.
    Line {
        text: String,
        reply: Sender<LineAnswer>,
    },
    /// Check ILMR text against the running task as a line would be, and join nothing
    /// (`check` ... `checkend`).
    Check {
        text: String,
        reply: Sender<LineAnswer>,
    },
    Status {
        reply: Sender<Status>,
    },
    /// Send every event from now on to `out`, as trace lines. `first`, when given,
    /// makes the line queued before the first event (the subscription's answer) from
    /// the VM's time; then the engine acknowledges on `done`.
    Subscribe {
        conn: u64,
        out: SyncSender<String>,
        first: Option<Box<dyn FnOnce(f64) -> String + Send>>,
        done: Sender<()>,
    },
    /// The front end has gone: stop sending to it.
    Unsubscribe {
        conn: u64,
    },
}

/// What became of ILMR text, at simulated time `t`.
#[derive(Debug)]
pub struct LineAnswer {
    pub t: f64,
    pub outcome: Outcome,
}

#[derive(Debug)]
pub enum Outcome {
    /// Joined (or, for a check, would join), with the warnings the checker gave.
    Accepted { warnings: Vec<Diagnostic> },
    /// Nothing joined; the diagnostics point into the text.
    Rejected { diagnostics: Vec<Diagnostic> },
    /// Nothing joined, for a reason that is not in the text.
    Failed(String),
}

/// A variable of the running task.
#[derive(Debug, Clone)]
pub struct VarState {
    pub name: String,
    pub kind: VarKind,
    pub record: VarRecord,
}

/// A live command: its statement's text and where it came from.
#[derive(Debug, Clone)]
pub struct LiveCommand {
    /// The task file or `<typed N>`, the Nth line typed.
    pub file: String,
    pub line: u32,
    pub text: String,
}

/// The robot and the task at simulated time `t`.
#[derive(Debug, Clone)]
pub struct Status {
    pub t: f64,
    pub ticks: u64,
    /// Ground truth in the world frame for a simulated robot; a ROS 2 robot's own
    /// odometry in the task's frame.
    pub pose: Pose,
    pub speed: f64,
    pub curvature: f64,
    pub activity: Activity,
    pub finished: bool,
    /// One entry per live command, guard, loop or skill call, in program order.
    pub live: Vec<LiveCommand>,
    pub vars: Vec<VarState>,
    /// The skills lines may call.
    pub skills: Vec<String>,
}

pub struct Engine {
    /// The VM's clock is logical; the engine keeps it to the wall clock itself, so that
    /// it can wait for jobs and ticks at once (`RealClock` would sleep in `tick`).
    vm: Vm<AnyRobot, SimClock>,
    model: RobotModel,
    subscribers: Vec<(u64, SyncSender<String>)>,
    /// `"robot":"NAME",`, put first in every event of a robot of a fleet.
    tag: Option<String>,
}

impl Engine {
    pub fn new(vm: Vm<AnyRobot, SimClock>, model: RobotModel) -> Engine {
        Engine {
            vm,
            model,
            subscribers: Vec::new(),
            tag: None,
        }
    }

    /// Names the robot in every event it sends, for subscribers of a fleet.
    pub fn tagged(mut self, name: &str) -> Engine {
        let name = serde_json::to_string(name).unwrap_or_else(|_| "\"\"".into());
        self.tag = Some(format!("\"robot\":{name},"));
        self
    }

    /// Runs until every sender of `jobs` is gone. Tick `n` is due `n` periods after the
    /// start; a late engine catches up without waiting, as `RealClock` does.
    pub fn run(mut self, jobs: Receiver<Job>) {
        let start = Instant::now();
        let period = self.vm.config().period;
        loop {
            let due = start + Duration::from_secs_f64(self.vm.ticks() as f64 * period);
            loop {
                let now = Instant::now();
                if now >= due {
                    break;
                }
                match jobs.recv_timeout(due - now) {
                    Ok(job) => self.handle(job),
                    Err(RecvTimeoutError::Timeout) => break,
                    Err(RecvTimeoutError::Disconnected) => return,
                }
            }
            while let Ok(job) = jobs.try_recv() {
                self.handle(job);
            }
            self.vm.tick();
            let events = self.vm.take_events();
            if !self.subscribers.is_empty() {
                for e in &events {
                    let line = ilmr_vm::render_event(self.vm.module(), e);
                    self.publish(&line);
                }
            }
        }
    }

    fn handle(&mut self, job: Job) {
        match job {
            Job::Line { text, reply } => {
                let t = self.vm.time();
                // `line` catches a panic of the compiler itself, leaving the module as
                // it was; this catches one of the VM's joining, after which the line's
                // blocks may be in the module but are never run.
                let answer = guard::guarded("joining the line", || self.line(&text))
                    .unwrap_or_else(|why| LineAnswer {
                        t,
                        outcome: Outcome::Failed(why),
                    });
                let _ = reply.send(answer);
            }
            Job::Check { text, reply } => {
                let t = self.vm.time();
                let answer = guard::guarded("checking the line", || self.check(&text))
                    .unwrap_or_else(|why| LineAnswer {
                        t,
                        outcome: Outcome::Failed(why),
                    });
                let _ = reply.send(answer);
            }
            Job::Status { reply } => {
                let _ = reply.send(self.status());
            }
            Job::Subscribe {
                conn,
                out,
                first,
                done,
            } => {
                let acknowledged = match first {
                    Some(first) => out.try_send(first(self.vm.time())).is_ok(),
                    None => true,
                };
                if acknowledged && !self.subscribers.iter().any(|(c, _)| *c == conn) {
                    self.subscribers.push((conn, out));
                }
                let _ = done.send(());
            }
            Job::Unsubscribe { conn } => self.subscribers.retain(|(c, _)| *c != conn),
        }
    }

    /// Joins `text` to the running task, or says why not; subscribers see a `line`
    /// event either way, as in `ilmrc run`'s trace.
    fn line(&mut self, text: &str) -> LineAnswer {
        let options = LineOptions { robotless: false };
        self.join(text, |b, model, warnings| {
            lower_line_warned(text, b, model, options, warnings)
        })
    }

    /// Joins what `lower` builds for `text`. A panic inside `lower` is caught there, so
    /// the VM takes the line as rejected and truncates the module to what it was.
    fn join(
        &mut self,
        text: &str,
        lower: impl FnOnce(
            &mut ModuleBuilder,
            &RobotModel,
            &mut Vec<Diagnostic>,
        ) -> Result<Vec<BlockId>, Vec<Diagnostic>>,
    ) -> LineAnswer {
        let t = self.vm.time();
        let mut warnings = Vec::new();
        let model = &self.model;
        let result = self.vm.add_line(|b| {
            match guard::guarded("compiling the line", || lower(b, model, &mut warnings)) {
                Ok(Ok(start)) => Ok(start),
                Ok(Err(diagnostics)) => Err(Refusal::Diagnostics(diagnostics)),
                Err(why) => Err(Refusal::Panicked(why)),
            }
        });
        let outcome = match result {
            Ok(()) => Outcome::Accepted { warnings },
            Err(LineError::Lower(Refusal::Diagnostics(diagnostics))) => {
                Outcome::Rejected { diagnostics }
            }
            Err(LineError::Lower(Refusal::Panicked(why))) => Outcome::Failed(why),
            Err(LineError::Invalid(e)) => Outcome::Failed(format!("the line was not joined: {e}")),
            Err(LineError::Replaced) => Outcome::Failed(
                "the line was not joined: the lowering did not return the program".into(),
            ),
        };
        if !self.subscribers.is_empty() {
            self.publish(&line_event(t, text, &outcome));
        }
        LineAnswer { t, outcome }
    }

    /// Lowers `text` against a copy of the running module and throws the result away:
    /// the diagnostics are a line's, and the VM does not change.
    fn check(&self, text: &str) -> LineAnswer {
        let mut b = ModuleBuilder::extending(self.vm.module());
        let mut warnings = Vec::new();
        let options = LineOptions { robotless: false };
        let outcome = match lower_line_warned(text, &mut b, &self.model, options, &mut warnings) {
            Ok(_) => Outcome::Accepted { warnings },
            Err(diagnostics) => Outcome::Rejected { diagnostics },
        };
        LineAnswer {
            t: self.vm.time(),
            outcome,
        }
    }

    fn status(&self) -> Status {
        let module = self.vm.module();
        let live = self
            .vm
            .live_statements()
            .into_iter()
            .filter_map(|id| module.stmt(id))
            .map(|s| LiveCommand {
                file: module
                    .files
                    .get(s.file.0 as usize)
                    .cloned()
                    .unwrap_or_default(),
                line: s.line,
                text: s.text.clone(),
            })
            .collect();
        let vars = module
            .globals
            .iter()
            .filter_map(|g| {
                self.vm.var(&g.name).map(|record| VarState {
                    name: g.name.clone(),
                    kind: g.kind,
                    record,
                })
            })
            .collect();
        let skills = module
            .units
            .iter()
            .filter(|u| u.skill)
            .map(|u| u.name.clone())
            .collect();
        let motion = self.vm.hal().true_motion().unwrap_or_default();
        Status {
            t: self.vm.time(),
            ticks: self.vm.ticks(),
            pose: self.vm.hal().true_pose().unwrap_or_default(),
            speed: motion.0,
            curvature: motion.1,
            activity: self.vm.activity(),
            finished: self.vm.finished(),
            live,
            vars,
            skills,
        }
    }

    /// Sends a line to every subscriber. One that has gone, or has let its queue fill
    /// (it stopped reading), is dropped: the robot never waits for a front end.
    fn publish(&mut self, line: &str) {
        let tagged;
        let line = match (&self.tag, line.strip_prefix('{')) {
            (Some(tag), Some(rest)) => {
                tagged = format!("{{{tag}{rest}");
                tagged.as_str()
            }
            _ => line,
        };
        self.subscribers
            .retain(|(_, out)| match out.try_send(line.to_string()) {
                Ok(()) => true,
                Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => false,
            });
    }
}

/// Why a line's lowering gave nothing to join.
enum Refusal {
    Diagnostics(Vec<Diagnostic>),
    /// The compiler panicked; the message says so.
    Panicked(String),
}

/// The `line` event of `ilmrc run`'s trace, written as it writes it, plus the codes
/// of a joined line's warnings.
fn line_event(t: f64, text: &str, outcome: &Outcome) -> String {
    let text = serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into());
    let accepted = matches!(outcome, Outcome::Accepted { .. });
    let mut line = format!(
        "{{\"t\":{},\"event\":\"line\",\"text\":{text},\"accepted\":{accepted}",
        fmt_num(t)
    );
    let codes: Vec<&str> = match outcome {
        Outcome::Accepted { warnings: d } | Outcome::Rejected { diagnostics: d } => {
            d.iter().map(|d| d.code.as_str()).collect()
        }
        Outcome::Failed(_) => Vec::new(),
    };
    if !codes.is_empty() {
        line.push_str(",\"codes\":");
        line.push_str(&serde_json::to_string(&codes).unwrap_or_else(|_| "[]".into()));
    }
    line.push('}');
    line
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::Compiled;

    /// MoRo in the empty world with no task, as `serve` starts without `--task`.
    fn engine() -> Engine {
        let args = super::super::RobotArgs {
            robot: "moro".into(),
            model: None,
            world: Some("empty".into()),
            start: None,
            seed: 0,
            skills: None,
            task: None,
            ros2: crate::ros2::Ros2Args::default(),
        };
        let opened = super::super::robot::open(&args).unwrap_or_else(|e| panic!("{e}"));
        let Ok(Compiled::Module(module)) = super::super::no_task(&opened.spec, None) else {
            panic!("the empty task compiles");
        };
        let vm = Vm::new(*module, opened.robot, SimClock, opened.config)
            .unwrap_or_else(|e| panic!("{e}"));
        Engine::new(vm, opened.model)
    }

    fn counts(e: &Engine) -> ilmr_vm::bytecode::Counts {
        e.vm.module().counts()
    }

    #[test]
    fn a_panic_while_a_line_compiles_is_its_error_and_the_task_is_kept() {
        let mut e = engine();
        assert!(matches!(e.line("n = 1").outcome, Outcome::Accepted { .. }));
        let before = counts(&e);
        let options = LineOptions { robotless: false };
        // Half a line is built into the module before the compiler falls over.
        let answer = e.join("m = 2", |b, model, warnings| {
            let built = lower_line_warned("m = 2", b, model, options, warnings);
            assert!(built.is_ok());
            panic!("the compiler fell over")
        });
        match answer.outcome {
            Outcome::Failed(why) => assert!(
                why.starts_with("ilmrc failed while compiling the line (the compiler fell over)"),
                "{why}"
            ),
            other => panic!("{other:?}"),
        }
        assert_eq!(counts(&e), before, "the half-built line was not taken back");
        assert!(e.vm.var("m").is_none());
        // The engine goes on: the next line joins and the robot ticks.
        assert!(matches!(
            e.line("n = n + 1").outcome,
            Outcome::Accepted { .. }
        ));
        for _ in 0..3 {
            e.vm.tick();
        }
        assert_eq!(e.vm.var("n").map(|r| r.value), Some(2.0));
    }
}
