//! `ilmrc run`: compiles a task, runs it on a robot backend at 100 Hz of logical time,
//! writes the trace and prints a summary.
//!
//! A run ends when no command is left, or when nothing is left but `if` guards that
//! wait and the robot is at rest, or at `--max-time`; the summary says which.

mod backend;
mod liveness;
mod scenario;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use ilmr_compiler::lower::{LineOptions, lower_line};
use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_model::RobotModel;
use ilmr_vm::{EventKind, How, SimClock, TraceLevel, Vm, render_event};

use crate::build::{Compiled, compile};
pub use backend::Backend;
use backend::{AnyRobot, Robot};
use liveness::Liveness;
use scenario::Scenario;

#[derive(clap::Args)]
pub struct RunArgs {
    /// The robot to run on: `none` (no robot commands allowed) or `scripted`.
    #[arg(long, value_enum)]
    pub robot: Backend,
    /// Robot model the task is checked against and the robot moves within (`moro`,
    /// `workpartner` or a ROBO.INI path); with `--robot none`, only its constants.
    #[arg(long, default_value = "moro")]
    pub model: String,
    /// A directory of skill files (`*.ilms`) the task may call.
    #[arg(long)]
    pub skills: Option<PathBuf>,
    /// What the scripted world does, and interactive lines (JSON; see `src/run/scenario.rs`).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Seed of the robot's noise (simulated robots; the scripted robot has none).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Stop after this many seconds of logical time.
    #[arg(long, default_value_t = 600.0)]
    pub max_time: f64,
    /// Write every event as JSON Lines here.
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Ticks between pose samples in the trace.
    #[arg(long, default_value_t = 10)]
    pub pose_every: u32,
    /// The task file.
    pub task: PathBuf,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// No command is left.
    Finished,
    /// Only waiting guards are left, and the robot is at rest.
    Waiting,
    MaxTime,
}

#[derive(Debug, Default)]
struct Tally {
    completed: u32,
    broken: u32,
    refused: u32,
    overruns: u32,
    errors: u32,
    lines_accepted: u32,
    lines_rejected: u32,
}

pub fn run(args: RunArgs) -> ExitCode {
    match execute(&args) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn execute(args: &RunArgs) -> Result<ExitCode, String> {
    if !(args.max_time.is_finite() && args.max_time >= 0.0) {
        return Err(format!("--max-time {} is not a time", args.max_time));
    }
    let scenario = match &args.scenario {
        Some(p) => Scenario::load(p)?,
        None => Scenario::default(),
    };
    let robotless = args.robot == Backend::None;
    let model = crate::inputs::load_robot(&args.model)?.model;
    let compiled = compile(&args.task, &args.model, args.skills.as_deref(), |m| {
        if robotless {
            ilmr_compiler::lower::robot_uses(m)
        } else {
            Vec::new()
        }
    })?;
    let module = match compiled {
        Compiled::Module(m) => *m,
        Compiled::Rejected => return Ok(ExitCode::from(crate::EXIT_ERRORS)),
    };

    let robot = backend::open(args.robot, &model, &scenario, args.seed)?;
    // Pose samples say nothing when there is no robot.
    let trace_level = if args.trace.is_some() && !robotless {
        TraceLevel::Full
    } else {
        TraceLevel::Commands
    };
    let config = ilmr_vm::Config {
        trace: trace_level,
        pose_every: args.pose_every,
        ..backend::config(&model)
    };
    let mut vm = Vm::new(module, robot, SimClock, config).map_err(|e| e.to_string())?;
    for (name, points) in &scenario.paths {
        vm.add_path(name, points.clone());
    }

    let mut out: Option<std::io::BufWriter<std::fs::File>> = match &args.trace {
        Some(p) => Some(std::io::BufWriter::new(
            std::fs::File::create(p)
                .map_err(|e| format!("cannot write trace `{}`: {e}", p.display()))?,
        )),
        None => None,
    };
    let mut session = Session {
        live: Liveness::default(),
        tally: Tally::default(),
        options: LineOptions { robotless },
    };
    session.live.learn(vm.module());
    let mut next_line = 0;
    let max_ticks = (args.max_time / vm.config().period).round() as u64;
    let outcome = loop {
        while let Some(line) = scenario
            .lines
            .get(next_line)
            .filter(|l| l.t <= vm.time() + 1e-9)
        {
            next_line += 1;
            let note = session.line(&mut vm, &model, &line.text);
            if let Some(w) = out.as_mut() {
                writeln!(w, "{note}").map_err(|e| e.to_string())?;
            }
        }
        if vm.ticks() >= max_ticks {
            break Outcome::MaxTime;
        }
        vm.tick();
        let overran = session.absorb(&mut vm, out.as_mut())?;
        let more_lines = next_line < scenario.lines.len();
        if more_lines || overran || !vm.hal().at_rest() {
            continue;
        }
        if vm.finished() {
            break Outcome::Finished;
        }
        if session.live.only_guards_wait() {
            break Outcome::Waiting;
        }
    };
    if let Some(mut w) = out {
        w.flush().map_err(|e| e.to_string())?;
    }
    print!("{}", session.summary(&vm, outcome, args));
    Ok(ExitCode::SUCCESS)
}

struct Session {
    live: Liveness,
    tally: Tally,
    options: LineOptions,
}

impl Session {
    /// Takes the tick's events: follows liveness, counts, writes the trace. Returns
    /// whether a block overran the budget (it still has statements to run).
    fn absorb(
        &mut self,
        vm: &mut Vm<AnyRobot, SimClock>,
        out: Option<&mut std::io::BufWriter<std::fs::File>>,
    ) -> Result<bool, String> {
        let events = vm.take_events();
        let mut overran = false;
        for e in &events {
            self.live.observe(e);
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
        if let Some(w) = out {
            for e in &events {
                writeln!(w, "{}", render_event(vm.module(), e)).map_err(|e| e.to_string())?;
            }
        }
        Ok(overran)
    }

    /// Compiles an interactive line against the running task and joins it; a bad line
    /// is reported and changes nothing. Returns the trace line that records it.
    fn line(&mut self, vm: &mut Vm<AnyRobot, SimClock>, model: &RobotModel, text: &str) -> String {
        let t = ilmr_vm::runtime::trace::fmt_num(vm.time());
        let quoted = serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into());
        match lower_line(text, vm.module(), model, self.options) {
            Ok(fragment) => match vm.add_block(&fragment) {
                Ok(()) => {
                    self.live.learn(vm.module());
                    self.tally.lines_accepted += 1;
                    format!("{{\"t\":{t},\"event\":\"line\",\"text\":{quoted},\"accepted\":true}}")
                }
                Err(e) => {
                    self.tally.lines_rejected += 1;
                    eprintln!("line at t={t} not joined: {e}");
                    format!("{{\"t\":{t},\"event\":\"line\",\"text\":{quoted},\"accepted\":false}}")
                }
            },
            Err(diagnostics) => {
                self.tally.lines_rejected += 1;
                let file = [RenderFile {
                    path: "<line>",
                    text,
                }];
                eprint!(
                    "line at t={t} rejected:\n{}",
                    render::human(&diagnostics, &file, Style::PLAIN)
                );
                let codes: Vec<&str> = diagnostics.iter().map(|d| d.code.as_str()).collect();
                format!(
                    "{{\"t\":{t},\"event\":\"line\",\"text\":{quoted},\"accepted\":false,\"codes\":{}}}",
                    serde_json::to_string(&codes).unwrap_or_default()
                )
            }
        }
    }

    fn summary(&self, vm: &Vm<AnyRobot, SimClock>, outcome: Outcome, args: &RunArgs) -> String {
        let t = ilmr_vm::runtime::trace::fmt_num(vm.time());
        let how = match outcome {
            Outcome::Finished => "finished: no command left".to_string(),
            Outcome::Waiting => "finished: only waiting guards left, robot at rest".to_string(),
            Outcome::MaxTime => format!("max-time: stopped at --max-time {}", args.max_time),
        };
        let k = &self.tally;
        let mut s = format!(
            "{}: {how}\n  simulated time  {t} s ({} ticks)\n  commands ended  {} completed, {} broken, {} refused\n  guards waiting  {}\n  overruns        {}\n  runtime errors  {}\n",
            args.task.display(),
            vm.ticks(),
            k.completed,
            k.broken,
            k.refused,
            self.live.guards_waiting(),
            k.overruns,
            k.errors,
        );
        if k.lines_accepted + k.lines_rejected > 0 {
            s.push_str(&format!(
                "  lines           {} joined, {} rejected\n",
                k.lines_accepted, k.lines_rejected
            ));
        }
        s
    }
}
