//! The thread that owns the VM: it ticks every 10 ms of wall time and, between ticks,
//! answers its front end's jobs at once. Nothing a front end does can block it: answers
//! go back on a [`Reply`] per request, events to sinks that never wait. Lines are
//! compiled on a thread of their own (`lines.rs`); this one only joins what that
//! thread lowered, and an emergency stop (`stop.rs`) reaches it around both.
//!
//! Answers are typed ([`LineAnswer`], [`Status`]); `serve` writes them as JSON and the
//! shell as text.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, SyncSender, TrySendError};
use std::time::{Duration, Instant};

use ilmr_compiler::Diagnostic;
use ilmr_compiler::lower::{LineOptions, lower_line_warned};
use ilmr_hal::Pose;
use ilmr_model::RobotModel;
use ilmr_stdlib::VarKind;
use ilmr_vm::bytecode::{BlockId, Fragment, ModuleError};
use ilmr_vm::runtime::safety::Fault;
use ilmr_vm::{Activity, LineError, ModuleBuilder, SimClock, VarRecord, Vm, VmError};

use super::guard;
use super::lines::{Lowered, Verdict, Work, added_since};
use super::reply::Reply;
use super::stop::EmergencyStop;
use crate::run::backend::{AnyRobot, Robot};

/// What a front end asks of the VM thread.
pub enum Job {
    /// Join ILMR text to the running task.
    Line {
        text: String,
        reply: Reply<LineAnswer>,
    },
    /// Check ILMR text against the running task as a line would be, and join nothing
    /// (`check` ... `checkend`).
    Check {
        text: String,
        reply: Reply<LineAnswer>,
    },
    Status {
        reply: Reply<Status>,
    },
    /// Send every event from now on to `out`, as trace lines. `first`, when given,
    /// makes the line queued before the first event (the subscription's answer) from
    /// the VM's time; then the engine acknowledges on `done`.
    Subscribe {
        conn: u64,
        out: Box<dyn EventSink>,
        first: Option<Box<dyn FnOnce(f64) -> String + Send>>,
        done: Reply<()>,
    },
    /// The front end has gone: stop sending to it.
    Unsubscribe {
        conn: u64,
    },
    /// A text the line compiler has dealt with (only `live` makes these).
    Lowered(Box<Lowered>),
}

/// Where a subscriber's events go. `offer` must not block the engine: a sink that
/// cannot take an event now drops it (and may count it) or says it is gone.
pub trait EventSink: Send {
    /// `false` when the subscriber has gone (or can no longer be served), so the
    /// engine forgets it.
    fn offer(&self, event: &Arc<str>) -> bool;

    /// Queues the subscription's own answer, which must not be dropped as an event
    /// may be; `false` when the subscriber has gone.
    fn answer(&self, line: String) -> bool {
        self.offer(&Arc::from(line))
    }
}

/// The shell's sink: a subscriber that lets its queue fill has stopped reading, and
/// is dropped.
impl EventSink for SyncSender<String> {
    fn offer(&self, event: &Arc<str>) -> bool {
        match self.try_send(event.to_string()) {
            Ok(()) => true,
            Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => false,
        }
    }
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
    /// The longest wall time between two ticks' starts since the robot started,
    /// seconds (a period, 0.01, when no tick was late).
    pub longest_tick_gap: f64,
    /// The supervisor's faults in force, most urgent first: a hold says why the
    /// robot stands.
    pub faults: Vec<Fault>,
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
    subscribers: Vec<(u64, Box<dyn EventSink>)>,
    /// `"robot":"NAME",`, put first in every event of a robot of a fleet.
    tag: Option<String>,
    /// The line compiler's queue, and where it hears of fragments joined here.
    compiler: Option<(Sender<Work>, Sender<Fragment>)>,
    stop: Arc<EmergencyStop>,
    /// An emergency stop joined: the ticks until the robot has been commanded to
    /// brake, and who waits to hear so.
    braking: Option<Braking>,
    last_tick: Option<Instant>,
    longest_tick_gap: Duration,
    /// The live view in Foxglove (`--foxglove`).
    view: Option<crate::view::live::Live>,
}

struct Braking {
    ticks_left: u8,
    t: f64,
    joined: Result<(), String>,
    waiting: Vec<Reply<LineAnswer>>,
}

/// Ticks from joining `stop` to the first command of the braking ramp: the line's
/// block starts and runs `stop` in the first tick, after that tick's motion step; the
/// second tick's motion step commands the ramp down to zero.
const TICKS_TO_BRAKE: u8 = 2;

impl Engine {
    pub fn new(vm: Vm<AnyRobot, SimClock>, model: RobotModel) -> Engine {
        Engine {
            vm,
            model,
            subscribers: Vec::new(),
            tag: None,
            compiler: None,
            stop: Arc::default(),
            braking: None,
            last_tick: None,
            longest_tick_gap: Duration::ZERO,
            view: None,
        }
    }

    /// Publishes every tick to a live view in Foxglove.
    pub(super) fn with_view(mut self, view: Option<crate::view::live::Live>) -> Engine {
        self.view = view;
        self
    }

    /// Sends lines to the line compiler (`lines.rs`) instead of compiling them here,
    /// and takes emergency stops from `stop`.
    pub(super) fn with_compiler(
        mut self,
        work: Sender<Work>,
        news: Sender<Fragment>,
        stop: Arc<EmergencyStop>,
    ) -> Engine {
        self.compiler = Some((work, news));
        self.stop = stop;
        self
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
            // Jobs that come now wait for the tick: a flood of them (each cheap, now
            // that lines are compiled elsewhere) must not hold the tick back.
            self.emergency_stop();
            self.tick();
        }
    }

    fn tick(&mut self) {
        let now = Instant::now();
        if let Some(last) = self.last_tick.replace(now) {
            self.longest_tick_gap = self.longest_tick_gap.max(now - last);
        }
        self.vm.tick();
        let events = self.vm.take_events();
        if let Some(view) = &mut self.view {
            let scan = self.vm.hal_mut().new_scan();
            view.tick(self.vm.module(), &events, scan.as_ref());
        }
        if !self.subscribers.is_empty() {
            for e in &events {
                let line = ilmr_vm::render_event(self.vm.module(), e);
                self.publish(&line);
            }
        }
        if let Some(b) = &mut self.braking {
            b.ticks_left = b.ticks_left.saturating_sub(1);
            if b.ticks_left == 0
                && let Some(b) = self.braking.take()
            {
                for reply in b.waiting {
                    let outcome = match &b.joined {
                        Ok(()) => Outcome::Accepted {
                            warnings: Vec::new(),
                        },
                        Err(why) => Outcome::Failed(why.clone()),
                    };
                    reply.send(LineAnswer { t: b.t, outcome });
                }
            }
        }
    }

    /// Joins `stop` when a front end raised the emergency stop: compiled here, since it
    /// is four letters, and told to the line compiler so that its copy keeps step.
    /// Raisers while the robot is being told to brake wait for the same answer.
    fn emergency_stop(&mut self) {
        let Some(waiting) = self.stop.take() else {
            return;
        };
        if let Some(b) = &mut self.braking {
            b.waiting.extend(waiting);
            return;
        }
        // The operator's stop is not the task's to hold back.
        self.vm.lift_priority();
        let base = self.vm.module().counts();
        let answer = self.line("stop");
        let joined = match answer.outcome {
            Outcome::Accepted { .. } => {
                if let Some((_, news)) = &self.compiler {
                    let _ = news.send(added_since(self.vm.module(), base));
                }
                Ok(())
            }
            Outcome::Rejected { .. } => Err("the robot refused `stop`".to_string()),
            Outcome::Failed(why) => Err(why),
        };
        self.braking = Some(Braking {
            ticks_left: TICKS_TO_BRAKE,
            t: answer.t,
            joined,
            waiting,
        });
    }

    fn handle(&mut self, job: Job) {
        match job {
            Job::Line { text, reply } => self.take_text(Work::Line { text, reply }),
            Job::Check { text, reply } => self.take_text(Work::Check { text, reply }),
            Job::Status { reply } => reply.send(self.status()),
            Job::Subscribe {
                conn,
                out,
                first,
                done,
            } => {
                let acknowledged = match first {
                    Some(first) => out.answer(first(self.vm.time())),
                    None => true,
                };
                if acknowledged && !self.subscribers.iter().any(|(c, _)| *c == conn) {
                    self.subscribers.push((conn, out));
                }
                done.send(());
            }
            Job::Unsubscribe { conn } => self.subscribers.retain(|(c, _)| *c != conn),
            Job::Lowered(lowered) => self.join_lowered(*lowered),
        }
    }

    /// The line compiler's thread has ended (it panicked outside a line): the text is
    /// answered as failed rather than lost.
    /// Hands a line (or a `check` block) to the line compiler; without one, lowers
    /// it here.
    fn take_text(&mut self, work: Work) {
        if let Some((compiler, _)) = &self.compiler {
            if let Err(e) = compiler.send(work) {
                self.no_compiler(e.0);
            }
            return;
        }
        let t = self.vm.time();
        let (answer, reply) = match work {
            Work::Line { text, reply } => (
                guard::guarded("joining the line", || self.line(&text)),
                reply,
            ),
            Work::Check { text, reply } => (
                guard::guarded("checking the line", || self.check(&text)),
                reply,
            ),
        };
        reply.send(answer.unwrap_or_else(|why| LineAnswer {
            t,
            outcome: Outcome::Failed(why),
        }));
    }

    fn no_compiler(&self, work: Work) {
        let (Work::Line { reply, .. } | Work::Check { reply, .. }) = work;
        reply.send(LineAnswer {
            t: self.vm.time(),
            outcome: Outcome::Failed("the line compiler has stopped".into()),
        });
    }

    /// Joins what the line compiler lowered (its cost is the fragment's size), answers
    /// and publishes it; a fragment lowered against a module that has changed since
    /// goes back to be lowered again.
    fn join_lowered(&mut self, l: Lowered) {
        let t = self.vm.time();
        let Lowered {
            text,
            mut outcome,
            fragment,
            publish,
            reply,
            verdict,
        } = l;
        let mut back = None;
        if let Some(fragment) = fragment {
            match self.vm.add_block(&fragment) {
                Ok(()) => back = Some(Verdict::Joined),
                Err(VmError::Module(ModuleError::StaleFragment)) => {
                    if let Some(v) = verdict {
                        let _ = v.send(Verdict::Stale(reply));
                    }
                    return;
                }
                Err(e) => {
                    outcome = Outcome::Failed(format!("the line was not joined: {e}"));
                    back = Some(Verdict::Refused);
                }
            }
        }
        if publish && !self.subscribers.is_empty() {
            self.publish(&line_event(t, &text, &outcome));
        }
        reply.send(LineAnswer { t, outcome });
        if let (Some(v), Some(back)) = (verdict, back) {
            let _ = v.send(back);
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
        let vars = self
            .vm
            .globals()
            .map(|(g, record)| VarState {
                name: g.name.clone(),
                kind: g.kind,
                record,
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
            longest_tick_gap: self.longest_tick_gap.as_secs_f64(),
            faults: self.vm.faults_in_force(),
            live,
            vars,
            skills,
        }
    }

    /// Offers a line to every subscriber, one shared copy for all; one whose sink says
    /// it has gone is dropped: the robot never waits for a front end.
    fn publish(&mut self, line: &str) {
        let line: Arc<str> = match (&self.tag, line.strip_prefix('{')) {
            (Some(tag), Some(rest)) => Arc::from(format!("{{{tag}{rest}")),
            _ => Arc::from(line),
        };
        self.subscribers.retain(|(_, out)| out.offer(&line));
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
    let codes = match outcome {
        Outcome::Accepted { warnings: d } | Outcome::Rejected { diagnostics: d } => {
            d.iter().map(|d| d.code.as_str().into()).collect()
        }
        Outcome::Failed(_) => Vec::new(),
    };
    ilmr_trace::to_line(&ilmr_trace::Record::new(
        t,
        ilmr_trace::Event::Line(ilmr_trace::Entered {
            text: text.into(),
            accepted: matches!(outcome, Outcome::Accepted { .. }),
            codes,
        }),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::Compiled;

    /// MoRo in the empty world with no task, as `serve` starts without `--task`.
    pub(super) fn engine() -> Engine {
        let args = super::super::RobotArgs {
            robot: "moro".into(),
            model: None,
            world: Some("empty".into()),
            start: None,
            seed: 0,
            skills: None,
            task: None,
            ros2: crate::ros2::Ros2Args::default(),
            view: Default::default(),
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

#[cfg(test)]
mod compiler_tests {
    use std::sync::mpsc;

    use super::tests as tests_support;
    use super::*;
    use crate::live::lines::Compiler;

    /// An engine with its line compiler on a thread, and the queue the compiler hands
    /// its work back on (the engine's, read here one job at a time).
    fn engine_with_compiler() -> (Engine, Receiver<Job>, Arc<EmergencyStop>) {
        engine_with_compiler_limited(u32::MAX, u64::MAX)
    }

    fn engine_with_compiler_limited(
        statements: u32,
        bytes: u64,
    ) -> (Engine, Receiver<Job>, Arc<EmergencyStop>) {
        let mut e = tests_support::engine();
        let (jobs, queue) = mpsc::channel();
        let (work, to_compile) = mpsc::channel();
        let (news, heard) = mpsc::channel();
        let stop = Arc::new(EmergencyStop::default());
        let compiler = Compiler::new(e.vm.module().clone(), e.model.clone(), jobs, heard)
            .limited_to(statements, bytes);
        std::thread::spawn(move || compiler.run(to_compile));
        e = e.with_compiler(work, news, Arc::clone(&stop));
        (e, queue, stop)
    }

    fn next(queue: &Receiver<Job>) -> Job {
        queue
            .recv_timeout(Duration::from_secs(20))
            .unwrap_or_else(|_| panic!("the line compiler answered"))
    }

    #[test]
    fn a_line_lowered_before_an_emergency_stop_is_lowered_again_and_joined() {
        let (mut e, queue, stop) = engine_with_compiler();
        let (reply, answer) = mpsc::channel();
        e.handle(Job::Line {
            text: "n = 1".into(),
            reply: reply.into(),
        });
        let lowered = next(&queue);
        // The stop joins between the lowering and the join: the fragment is stale.
        let (acked, ack) = mpsc::channel();
        stop.raise(acked.into());
        e.emergency_stop();
        e.handle(lowered);
        assert!(
            answer.try_recv().is_err(),
            "a stale line is not answered yet"
        );
        let again = next(&queue);
        e.handle(again);
        let joined = answer
            .recv_timeout(Duration::from_secs(20))
            .expect("an answer");
        assert!(
            matches!(joined.outcome, Outcome::Accepted { .. }),
            "{joined:?}"
        );
        for _ in 0..TICKS_TO_BRAKE {
            assert!(ack.try_recv().is_err(), "acknowledged before the ramp");
            e.tick();
        }
        let acked = ack.try_recv().expect("the stop's acknowledgement");
        assert!(
            matches!(acked.outcome, Outcome::Accepted { .. }),
            "{acked:?}"
        );
        assert_eq!(e.vm.var("n").map(|r| r.value), Some(1.0));
        // The compiler's copy followed both: the next line lowers against it at once.
        let (reply, answer) = mpsc::channel();
        e.handle(Job::Line {
            text: "n = n + 1".into(),
            reply: reply.into(),
        });
        let lowered = next(&queue);
        e.handle(lowered);
        let joined = answer
            .recv_timeout(Duration::from_secs(20))
            .expect("an answer");
        assert!(
            matches!(joined.outcome, Outcome::Accepted { .. }),
            "{joined:?}"
        );
        e.tick();
        assert_eq!(e.vm.var("n").map(|r| r.value), Some(2.0));
    }

    #[test]
    fn lines_past_the_statement_limit_are_refused_and_the_robot_goes_on() {
        let (mut e, queue, _) = engine_with_compiler_limited(3, 30);
        let ask = |e: &mut Engine, text: &str| {
            let (reply, answer) = mpsc::channel();
            e.handle(Job::Line {
                text: text.into(),
                reply: reply.into(),
            });
            e.handle(next(&queue));
            answer
                .recv_timeout(Duration::from_secs(20))
                .expect("an answer")
        };
        assert!(matches!(
            ask(&mut e, "a = 1\nb = 2").outcome,
            Outcome::Accepted { .. }
        ));
        let before = e.vm.module().counts();
        match ask(&mut e, "c = 3\nd = 4").outcome {
            Outcome::Failed(why) => assert!(why.contains("3 statements from lines"), "{why}"),
            other => panic!("{other:?}"),
        }
        assert_eq!(e.vm.module().counts(), before, "nothing of it joined");
        assert!(matches!(
            ask(&mut e, "a = 5").outcome,
            Outcome::Accepted { .. }
        ));
        e.tick();
        assert_eq!(e.vm.var("a").map(|r| r.value), Some(5.0));
    }

    #[test]
    fn a_rejected_line_and_a_check_change_nothing() {
        let (mut e, queue, _) = engine_with_compiler();
        let before = e.vm.module().counts();
        let (reply, answer) = mpsc::channel();
        e.handle(Job::Line {
            text: "goahed(1)".into(),
            reply: reply.into(),
        });
        e.handle(next(&queue));
        let a = answer
            .recv_timeout(Duration::from_secs(20))
            .expect("an answer");
        assert!(matches!(a.outcome, Outcome::Rejected { .. }), "{a:?}");
        let (reply, answer) = mpsc::channel();
        e.handle(Job::Check {
            text: "goahead(1)".into(),
            reply: reply.into(),
        });
        e.handle(next(&queue));
        let a = answer
            .recv_timeout(Duration::from_secs(20))
            .expect("an answer");
        assert!(matches!(a.outcome, Outcome::Accepted { .. }), "{a:?}");
        assert_eq!(e.vm.module().counts(), before);
    }
}
