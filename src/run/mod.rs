//! `ilmrc run`: compiles a task, runs it on a robot at 100 Hz of logical time, writes
//! the trace (and an MCAP file, a plot), shows progress and prints a summary.
//!
//! A run ends when no command is left, or when nothing is left but `if` guards that
//! wait and endless readings and the robot is at rest, or when a supervisor hold has
//! lasted `--hold-limit`, or at `--max-time`; the summary and the exit code say which.

pub(crate) mod backend;
pub(crate) mod console;
pub(crate) mod mcap;
mod progress;
pub(crate) mod record;
mod report;
pub(crate) mod scenario;
mod session;
pub(crate) mod setup;
mod summary;

use std::path::PathBuf;
use std::process::ExitCode;

use foxglove::schemas::log::Level;
use ilmr_vm::runtime::trace;
use ilmr_vm::{Clock, RealClock, SimClock, TraceLevel, Vm};

use crate::build::{Compiled, compile_given};
use backend::{AnyRobot, Robot};
use console::Console;
use progress::Progress;
use record::{Extra, Sink};
use report::Report;
use scenario::Scenario;
use session::Session;
use setup::{Backend, Choice, Setup};
use summary::Outcome;

#[derive(clap::Args)]
pub struct RunArgs {
    /// The robot: `moro` or `workpartner` (simulated), a ROBO.INI path (simulated on
    /// the body it describes), `ros2` (a ROS 2 robot over DDS, checked against
    /// `--model`), `scripted` (replays `--scenario`) or `none`.
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// With `--robot ros2|none|scripted`: the model the task is checked against and
    /// whose limits bound the robot (`moro`, `workpartner` or a ROBO.INI path; default
    /// moro).
    #[arg(long)]
    pub model: Option<String>,
    /// The simulated robot's world: `office`, `yard`, `empty` or a world file
    /// (default: office for MoRo, yard for Workpartner).
    #[arg(long)]
    pub world: Option<String>,
    /// Where the simulated robot starts, `X,Y,HEADING` in metres and degrees (default:
    /// the world's start).
    #[arg(long, allow_hyphen_values = true)]
    pub start: Option<String>,
    /// A skill file, or a directory of skill files (`*.ilms`), the task may call.
    #[arg(long)]
    pub skills: Option<PathBuf>,
    /// Taught paths and timed interactive lines; for `--robot scripted` also what its
    /// world does (JSON; see docs/run.md).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Seed of the simulated robot's noise.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// The simulated robot's errors: `ideal` (exact kinematics, noise-free sensors),
    /// `basic` (light noise) or `calibrated` (the default: the errors of the
    /// dissertation's robots, fitted to its Table 10; docs/robot-model.md).
    #[arg(long, value_name = "PROFILE", value_parser = parse_profile)]
    pub sim_profile: Option<ilmr_sim::SimProfile>,
    /// Injects a fault into the simulated robot, besides the world's `[[fault]]`
    /// entries: `KIND[@START[+DURATION]][:PARAM]`, such as `scanner_dropout@5+3` or
    /// `obstacle_appears@6:1.2`. Repeatable. Kinds and parameters: robots/worlds/README.md.
    #[arg(long = "fault", value_name = "KIND[@T[+D]][:PARAM]", value_parser = ilmr_sim::faults::flag::parse)]
    pub faults: Vec<ilmr_sim::FaultSpec>,
    /// Stop after this many seconds of logical time.
    #[arg(long, default_value_t = 600.0)]
    pub max_time: f64,
    /// End the run when a supervisor hold (an obstacle too near, no scans, no answer
    /// from the robot) has lasted this many seconds (`inf`: wait for it to clear).
    #[arg(long, default_value_t = 30.0)]
    pub hold_limit: f64,
    /// Keep to the wall clock: one tick every 10 ms (always, with `--robot ros2`).
    #[arg(long)]
    pub realtime: bool,
    #[command(flatten)]
    pub ros2: crate::ros2::Ros2Args,
    /// Write every event as JSON Lines here.
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Record in the trace everything the VM receives from the robot, tick by tick,
    /// so that `ilmrc replay --inputs TRACE TASK` can run the task again without it.
    #[arg(long)]
    pub record_inputs: bool,
    /// Write the run as an MCAP file (pose, scans, reference paths, command events).
    #[arg(long)]
    pub mcap: Option<PathBuf>,
    #[command(flatten)]
    pub view: crate::view::live::FoxgloveArgs,
    /// Draw the run as an SVG: world, trajectory, scanner hits, command positions,
    /// speed and curvature over time.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Ticks between pose samples in the trace.
    #[arg(long, default_value_t = 10)]
    pub pose_every: u32,
    /// Seconds between the scans kept in the trace and the plot (a simulated robot
    /// scans at 4 Hz; the MCAP file keeps every scan).
    #[arg(long, default_value_t = 1.0)]
    pub scan_every: f64,
    /// Interactive lines besides the scenario's (`ilmrc test` gives them; no flag).
    #[arg(skip)]
    pub lines: Vec<scenario::Line>,
    /// The task file.
    pub task: PathBuf,
}

pub(crate) fn parse_profile(name: &str) -> Result<ilmr_sim::SimProfile, String> {
    ilmr_sim::SimProfile::parse(name).ok_or_else(|| {
        let names: Vec<&str> = ilmr_sim::SimProfile::ALL.iter().map(|p| p.name()).collect();
        format!("no profile `{name}`: use {}", names.join(", "))
    })
}

pub fn run(args: RunArgs) -> ExitCode {
    let mut reached = Reached::default();
    let (code, failure) = match execute(&args, &mut reached, &mut Console::Terminal) {
        Ok(Ran::Ended(code)) => return ExitCode::from(code),
        Ok(Ran::Rejected) => (
            crate::EXIT_ERRORS,
            "the task has errors; they were printed with the checker's diagnostics".to_string(),
        ),
        Err(message) => {
            eprintln!("error: {message}");
            (crate::EXIT_USAGE, message)
        }
    };
    // A run that failed before it started still leaves a trace, an MCAP file and a plot
    // that say why, rather than an empty file, half a recording or the last run's
    // output; one that failed while it ran keeps what it wrote.
    if !reached.running {
        write_failures(&args, &reached, &failure, code);
    }
    ExitCode::from(code)
}

/// Writes each output asked for as the file of a run that did not start. An output
/// that cannot be written gets a warning, unless its failing is why the run failed.
fn write_failures(args: &RunArgs, reached: &Reached, failure: &str, code: u8) {
    let written = [
        args.trace.as_deref().map(|p| {
            let r = record::write_failure(p, reached.header.as_ref(), failure, code);
            (r, "cannot write trace")
        }),
        args.mcap.as_deref().map(|p| {
            let r = mcap::write_failure(p, &args.task, failure, code);
            (r, "cannot write MCAP")
        }),
        args.plot.as_deref().map(|p| {
            let r = ilmr_plot::write_failure(failure, code, p);
            (r, "cannot write plot")
        }),
    ];
    for (result, cause) in written.into_iter().flatten() {
        if let Err(e) = result
            && !failure.starts_with(cause)
        {
            eprintln!("warning: {e}");
        }
    }
}

/// How far a run got, for the outputs of one that fails.
#[derive(Default)]
pub(crate) struct Reached {
    /// The trace's `run` line, once the robot and world are known.
    header: Option<ilmr_trace::Record<'static>>,
    /// The VM has started: the trace holds the run so far.
    running: bool,
}

pub(crate) enum Ran {
    /// The task ran; the exit code says how it ended.
    Ended(u8),
    /// The checker rejected the task.
    Rejected,
}

/// Runs the task of `args`; what the run says goes to `console`.
pub(crate) fn execute(
    args: &RunArgs,
    reached: &mut Reached,
    console: &mut Console,
) -> Result<Ran, String> {
    check_times(args)?;
    if args.record_inputs && args.trace.is_none() && args.mcap.is_none() {
        return Err("--record-inputs records into the trace or the MCAP file: give --trace OUT.jsonl or --mcap OUT.mcap".into());
    }
    let mut setup = setup::choose(&Choice {
        robot: &args.robot,
        profile: args.sim_profile,
        model: args.model.as_deref(),
        world: args.world.as_deref(),
        start: args.start.as_deref(),
        ros2: &args.ros2,
    })?;
    if !args.faults.is_empty() {
        let Some(loaded) = setup.world.as_mut() else {
            return Err(
                "--fault needs a simulated robot (--robot moro|workpartner|ROBO.INI)".into(),
            );
        };
        loaded.world.faults.extend(args.faults.iter().cloned());
    }
    reached.header = record::header(&setup, args);
    if let (Backend::Sim(kind), Some(loaded)) = (setup.backend, setup.world.as_ref()) {
        let end = Some(args.max_time);
        setup::check_faults(loaded, &setup.model, kind, end, args.faults.len())?;
    }
    let mut scenario = match &args.scenario {
        Some(p) => Scenario::load(p)?,
        None => Scenario::default(),
    };
    scenario.lines.extend(args.lines.iter().cloned());
    scenario.lines.sort_by(|a, b| a.t.total_cmp(&b.t));
    // Outputs are opened before the run, so that a path that cannot be written fails
    // at once rather than after minutes of simulation.
    let sink = Sink::open(args.trace.as_deref(), args.plot.as_deref())?;
    let prelude = reached.header.clone().into_iter().collect();
    launch(
        args,
        Start {
            setup: &setup,
            scenario: &scenario,
            sink,
            robot: Source::Open,
            prelude,
        },
        reached,
        console,
    )
}

/// The run's times are times: `--max-time`, `--hold-limit`, `--scan-every` (a replay
/// reads them from its recording).
pub(crate) fn check_times(args: &RunArgs) -> Result<(), String> {
    if !(args.max_time.is_finite() && args.max_time >= 0.0) {
        return Err(format!("--max-time {} is not a time", args.max_time));
    }
    if args.hold_limit.is_nan() || args.hold_limit < 0.0 {
        return Err(format!("--hold-limit {} is not a time", args.hold_limit));
    }
    if !(args.scan_every.is_finite() && args.scan_every > 0.0) {
        return Err(format!("--scan-every {} is not a period", args.scan_every));
    }
    Ok(())
}

/// Where the run's robot comes from.
pub(crate) enum Source {
    /// Opened from the setup (`setup::open`).
    Open,
    /// A recording's inputs, played back (`ilmrc replay --inputs`); the recording
    /// says where the scanner is.
    Played {
        player: crate::tape::Player,
        scanner_offset: Option<f64>,
    },
}

/// What a run starts with once its options are read.
pub(crate) struct Start<'a> {
    pub setup: &'a Setup,
    pub scenario: &'a Scenario,
    pub sink: Sink,
    pub robot: Source,
    /// The trace's lines after its version line and before the run's events: the
    /// `run` header (and a replay's recorded `tape` line).
    pub prelude: Vec<ilmr_trace::Record<'a>>,
}

/// Compiles the task, opens the robot and the outputs and runs the task.
pub(crate) fn launch(
    args: &RunArgs,
    start: Start<'_>,
    reached: &mut Reached,
    console: &mut Console,
) -> Result<Ran, String> {
    let Start {
        setup,
        scenario,
        mut sink,
        robot: source,
        mut prelude,
    } = start;
    let mut mcap = match &args.mcap {
        Some(p) => Some(mcap::McapOut::create(
            p,
            setup.world.as_ref(),
            &args.task,
            setup.backend == Backend::Ros2,
        )?),
        None => None,
    };
    let live = args.view.open(
        &args.task.display().to_string(),
        setup.world.as_ref().map(|w| &w.world),
    )?;
    let robotless = setup.backend == Backend::None;
    let given = ilmr_compiler::check::Given {
        paths: scenario.paths.keys().cloned().collect(),
    };
    let compiled = compile_given(
        &args.task,
        &setup.model_spec,
        args.skills.as_deref(),
        &given,
        console,
        |m| {
            if robotless {
                ilmr_compiler::lower::robot_uses(m)
            } else {
                Vec::new()
            }
        },
    )?;
    let module = match compiled {
        Compiled::Module(m) => *m,
        Compiled::Rejected => return Ok(Ran::Rejected),
    };
    let played = matches!(source, Source::Played { .. });
    let (mut robot, scanner_offset) = match source {
        Source::Open => {
            let mut robot = setup::open(setup, scenario, args.seed)?;
            if mcap.is_some() {
                robot.record_ros2_messages();
            }
            let offset =
                (setup.backend == Backend::Ros2).then(|| setup::ros2_scanner_offset(&robot));
            (robot, offset)
        }
        Source::Played {
            player,
            scanner_offset,
        } => (AnyRobot::new(player), scanner_offset),
    };
    if args.record_inputs {
        // A replay's prelude is the recording's, its `tape` line included.
        if !played {
            prelude.push(crate::tape::header(setup, scenario, args, scanner_offset));
        }
        robot = AnyRobot::new(crate::tape::Taping::new(robot));
    }
    let body = match setup.backend {
        Backend::Sim(kind) => Some(ilmr_sim::config_from_model(&setup.model, kind)),
        _ => None,
    };
    // Pose samples say nothing when there is no robot.
    let trace_level = if sink.wants_poses() || mcap.is_some() || live.is_some() {
        if robotless {
            TraceLevel::Commands
        } else {
            TraceLevel::Full
        }
    } else {
        TraceLevel::Commands
    };
    let mut config = ilmr_vm::Config {
        trace: trace_level,
        pose_every: args.pose_every,
        ..setup::vm_config(&setup.model, body.as_ref())
    };
    if let Some(offset) = scanner_offset {
        config.scanner_offset = offset;
    }
    for line in &prelude {
        sink.put(line)?;
        if let (true, Some(m)) = (args.record_inputs, mcap.as_mut()) {
            m.input(line)?;
        }
    }
    let parts = Parts {
        setup,
        scenario,
        sink,
        mcap,
        live,
    };
    // A real robot lives on the wall clock; its recording does not.
    if (args.realtime || setup.backend == Backend::Ros2) && !played {
        let vm = Vm::new(module, robot, RealClock::new(), config).map_err(|e| e.to_string())?;
        reached.running = true;
        drive(vm, parts, args, console)
    } else {
        let vm = Vm::new(module, robot, SimClock, config).map_err(|e| e.to_string())?;
        reached.running = true;
        drive(vm, parts, args, console)
    }
}

/// What the run loop writes to and reads from, besides the VM.
struct Parts<'a> {
    setup: &'a Setup,
    scenario: &'a Scenario,
    sink: Sink,
    mcap: Option<mcap::McapOut>,
    live: Option<crate::view::live::Live>,
}

fn drive<C: Clock>(
    mut vm: Vm<AnyRobot, C>,
    mut parts: Parts<'_>,
    args: &RunArgs,
    console: &mut Console,
) -> Result<Ran, String> {
    let scenario = parts.scenario;
    for (name, points) in &scenario.paths {
        vm.add_path(name, points.clone());
    }
    let mut session = Session::new(parts.setup.backend == Backend::None);
    let mut extra = Extra::new(vm.module(), args.scan_every);
    let mut progress = Progress::on_terminal(console.is_terminal());
    let mut report = Report::default();
    let mut next_line = 0;
    let max_ticks = (args.max_time / vm.config().period).round() as u64;
    let outcome = loop {
        while let Some(line) = scenario
            .lines
            .get(next_line)
            .filter(|l| l.t <= vm.time() + 1e-9)
        {
            next_line += 1;
            let note = session.line(&mut vm, &parts.setup.model, &line.text, console);
            extra.learn(vm.module());
            parts.sink.put(&note)?;
            if let (true, Some(m)) = (args.record_inputs, parts.mcap.as_mut()) {
                m.input(&note)?;
            }
        }
        if vm.ticks() >= max_ticks {
            break Outcome::MaxTime;
        }
        if vm.hal().inputs_exhausted() {
            break Outcome::RecordingEnded;
        }
        vm.tick();
        let events = vm.take_events();
        let overran = session.absorb(&events, extra.movement());
        report.absorb(vm.module(), &events, |notice| {
            progress.clear();
            console.err(&format!("{notice}\n"));
        });
        let pose = vm.hal().true_pose();
        session.travel(pose);
        let scan = vm.hal_mut().new_scan();
        // Lines no trace or plot takes are not rendered: among walls, formatting
        // every scan's hits cost a tenth of a run.
        if parts.sink.wants_poses() {
            for e in &events {
                parts.sink.put(&trace::record(vm.module(), e))?;
            }
            for line in extra.lines(vm.module(), &events, pose, scan.as_ref()) {
                parts.sink.put(&line)?;
            }
        }
        if let Some(m) = parts.mcap.as_mut() {
            m.tick(vm.module(), &events, scan.as_ref())?;
            m.ros2(vm.hal_mut().take_ros2_messages())?;
        }
        if let Some(l) = parts.live.as_mut() {
            l.tick(vm.module(), &events, scan.as_ref());
        }
        if let Some(input) = vm.hal_mut().end_tick() {
            // At the time of the tick whose inputs they are, as its events are.
            let t = vm.ticks().saturating_sub(1) as f64 * vm.config().period;
            let line = ilmr_trace::Record::new(t, ilmr_trace::Event::Input(Box::new(input)));
            parts.sink.put(&line)?;
            if let Some(m) = parts.mcap.as_mut() {
                m.input(&line)?;
            }
        }
        progress.show(&vm, &session, &report);
        if report
            .longest_hold(vm.time())
            .is_some_and(|(_, held)| held >= args.hold_limit)
        {
            break Outcome::Held;
        }
        let more_lines = next_line < scenario.lines.len();
        if more_lines || overran || !vm.hal().at_rest() {
            continue;
        }
        if vm.finished() {
            break Outcome::Finished;
        }
        if vm.activity().only_waiting() {
            break Outcome::Waiting;
        }
    };
    progress.clear();
    vm.trace_last_pose();
    let last = vm.take_events();
    if parts.sink.wants_poses() {
        for e in &last {
            parts.sink.put(&trace::record(vm.module(), e))?;
        }
    }
    if let Some(m) = parts.mcap.as_mut() {
        m.tick(vm.module(), &last, None)?;
    }
    if let Some(l) = parts.live.as_mut() {
        l.tick(vm.module(), &last, None);
    }
    let plot = parts.sink.finish()?;
    if let Some(m) = parts.mcap {
        m.finish()?;
    }
    if let (Some(path), Some(record)) = (&args.plot, plot) {
        ilmr_plot::write_svg(&record, path)?;
    }
    let ended = summary::Ended {
        outcome,
        session: &session,
        report: &report,
    };
    if let Some(mut l) = parts.live.take() {
        l.note(vm.time(), Level::Info, ended.how(&vm, args));
        crate::view::live::close(l);
    }
    console.out(&summary::render(&ended, &vm, args, parts.setup));
    Ok(Ran::Ended(ended.exit_code()))
}
