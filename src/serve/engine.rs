//! The thread that owns the VM: it ticks every 10 ms of wall time and, between ticks,
//! answers the connections' jobs at once. Nothing a client does can block it: answers
//! go back on a channel per request, events on bounded channels with `try_send`.

use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, SyncSender, TrySendError};
use std::time::{Duration, Instant};

use ilmr_compiler::lower::{LineOptions, lower_line_into};
use ilmr_compiler::render::{self, RenderFile};
use ilmr_model::RobotModel;
use ilmr_sim::SimRobot;
use ilmr_vm::runtime::trace::fmt_num;
use ilmr_vm::{LineError, SimClock, Vm};
use serde_json::{Map, Value, json};

use super::protocol::{answer, error};

/// What a connection asks of the VM thread.
pub enum Job {
    /// Join ILMR text; the answer (an object without `id`) goes to `reply`.
    Line {
        text: String,
        reply: Sender<Map<String, Value>>,
    },
    Status {
        reply: Sender<Map<String, Value>>,
    },
    /// Send every event from now on to `out`, as trace lines. The engine queues the
    /// answer (with `id`) on `out` itself, so that it comes before the first event,
    /// and then acknowledges on `done`.
    Subscribe {
        conn: u64,
        out: SyncSender<String>,
        id: Option<Value>,
        done: Sender<()>,
    },
    /// The connection has gone: stop sending to it.
    Unsubscribe {
        conn: u64,
    },
}

pub struct Engine {
    /// The VM's clock is logical; the engine keeps it to the wall clock itself, so that
    /// it can wait for jobs and ticks at once (`RealClock` would sleep in `tick`).
    vm: Vm<SimRobot, SimClock>,
    model: RobotModel,
    subscribers: Vec<(u64, SyncSender<String>)>,
}

impl Engine {
    pub fn new(vm: Vm<SimRobot, SimClock>, model: RobotModel) -> Engine {
        Engine {
            vm,
            model,
            subscribers: Vec::new(),
        }
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
                let answer = self.line(&text);
                let _ = reply.send(answer);
            }
            Job::Status { reply } => {
                let _ = reply.send(self.status());
            }
            Job::Subscribe {
                conn,
                out,
                id,
                done,
            } => {
                let answer = answer(ok(self.vm.time()), id.as_ref());
                if out.try_send(answer).is_ok() && !self.subscribers.iter().any(|(c, _)| *c == conn)
                {
                    self.subscribers.push((conn, out));
                }
                let _ = done.send(());
            }
            Job::Unsubscribe { conn } => self.subscribers.retain(|(c, _)| *c != conn),
        }
    }

    /// Joins `text` to the running task, or says why not; subscribers see a `line`
    /// event either way, as in `ilmrc run`'s trace.
    fn line(&mut self, text: &str) -> Map<String, Value> {
        let model = &self.model;
        let options = LineOptions { robotless: false };
        let t = self.vm.time();
        let result = self
            .vm
            .add_line(|b| lower_line_into(text, b, model, options));
        let mut codes = None;
        let answer = match result {
            Ok(()) => ok(t),
            Err(LineError::Lower(diagnostics)) => {
                let files = [RenderFile {
                    path: "<line>",
                    text,
                }];
                let rendered = render::json(&diagnostics, &files);
                codes = Some(
                    diagnostics
                        .iter()
                        .map(|d| d.code.as_str().to_string())
                        .collect::<Vec<_>>(),
                );
                let mut m = Map::new();
                m.insert("ok".into(), json!(false));
                m.insert("t".into(), time(t));
                m.insert("diagnostics".into(), json!(rendered));
                m
            }
            Err(LineError::Invalid(e)) => error(&format!("the line was not joined: {e}")),
            Err(LineError::Replaced) => {
                error("the line was not joined: the lowering did not return the program")
            }
        };
        if !self.subscribers.is_empty() {
            let accepted = answer.get("ok") == Some(&json!(true));
            self.publish(&line_event(t, text, accepted, codes.as_deref()));
        }
        answer
    }

    /// Simulated time, the robot's pose and speed, and what is live.
    fn status(&self) -> Map<String, Value> {
        let pose = self.vm.hal().true_pose();
        let sim = self.vm.hal().sim();
        let a = self.vm.activity();
        let mut m = ok(self.vm.time());
        m.insert("ticks".into(), json!(self.vm.ticks()));
        m.insert(
            "pose".into(),
            json!({"x": pose.x, "y": pose.y, "h": pose.h}),
        );
        m.insert("speed".into(), json!(sim.true_speed()));
        m.insert("curvature".into(), json!(sim.true_curvature()));
        m.insert(
            "activity".into(),
            json!({
                "running_commands": a.running_commands,
                "queued_movements": a.queued_movements,
                "waiting_guards": a.waiting_guards,
                "sleeping": a.sleeping,
                "issuing_blocks": a.issuing_blocks,
                "ready": a.ready,
                "robot_at_rest": a.robot_at_rest,
                "finished": self.vm.finished(),
            }),
        );
        m
    }

    /// Sends a line to every subscriber. One that has gone, or has let its queue fill
    /// (it stopped reading), is dropped: the robot never waits for a client.
    fn publish(&mut self, line: &str) {
        self.subscribers
            .retain(|(_, out)| match out.try_send(line.to_string()) {
                Ok(()) => true,
                Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => false,
            });
    }
}

/// The `line` event of `ilmrc run`'s trace, written as it writes it.
fn line_event(t: f64, text: &str, accepted: bool, codes: Option<&[String]>) -> String {
    let text = serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into());
    let mut line = format!(
        "{{\"t\":{},\"event\":\"line\",\"text\":{text},\"accepted\":{accepted}",
        fmt_num(t)
    );
    if let Some(codes) = codes {
        line.push_str(",\"codes\":");
        line.push_str(&serde_json::to_string(codes).unwrap_or_else(|_| "[]".into()));
    }
    line.push('}');
    line
}

/// Times as the trace writes them (`fmt_num`), so answers and events agree.
fn time(t: f64) -> Value {
    serde_json::from_str(&fmt_num(t)).unwrap_or(json!(t))
}

fn ok(t: f64) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("ok".into(), json!(true));
    m.insert("t".into(), time(t));
    m
}
