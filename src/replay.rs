//! `ilmrc replay`: a finished run again, from its trace.
//!
//! - `ilmrc replay TRACE.jsonl --plot OUT.svg` draws the run from the trace `ilmrc run
//!   --trace` wrote, without running anything: the figure `run --plot` drew, byte for
//!   byte.
//! - `ilmrc replay --inputs RUN.jsonl TASK` runs TASK again on the VM against the inputs
//!   `ilmrc run --record-inputs` recorded in RUN.jsonl (`src/tape`), with no robot and
//!   no simulator. The same task gives the recorded trace byte for byte (exit 0); a
//!   changed one is shown where it parts from the recording: the first HAL call that
//!   differs and the first event, then what changed (exit 1).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use ilmr_plot::{self as plot, RunRecord};
use ilmr_trace::{Event, Input, Record, Tape, fmt_num};

use crate::run::console::Console;
use crate::run::mcap::INPUTS_TOPIC;
use crate::run::record::{Kept, Sink};
use crate::run::scenario::{Line, Scenario};
use crate::run::setup::{Backend, Setup};
use crate::run::{Ran, Reached, RunArgs, Source, Start, launch};
use crate::tape::{BODIES, Player};

#[derive(clap::Args)]
pub struct ReplayArgs {
    /// A trace written by `ilmrc run --trace`; with `--inputs`, the task to run.
    pub file: PathBuf,
    /// Run the task against the inputs recorded in this trace (`ilmrc run
    /// --record-inputs --trace RUN.jsonl`).
    #[arg(long, value_name = "RUN.jsonl")]
    pub inputs: Option<PathBuf>,
    /// With `--inputs`: a skill file, or a directory of skill files, the task may call.
    #[arg(long, requires = "inputs")]
    pub skills: Option<PathBuf>,
    /// With `--inputs`: the robot model to check the task against, in place of the
    /// recorded one (`moro`, `workpartner` or a ROBO.INI path).
    #[arg(long, requires = "inputs")]
    pub model: Option<String>,
    /// With `--inputs`: write the replayed trace here.
    #[arg(long, requires = "inputs")]
    pub trace: Option<PathBuf>,
    /// Draw the run (SVG). Without `--inputs` this is what the command does.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

pub fn run(args: ReplayArgs) -> ExitCode {
    let done = match &args.inputs {
        Some(inputs) => replay_inputs(&args, inputs),
        None => draw(&args).map(|()| 0),
    };
    match done {
        Ok(code) => ExitCode::from(code),
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn draw(args: &ReplayArgs) -> Result<(), String> {
    let Some(out) = &args.plot else {
        return Err("give --plot OUT.svg to draw the run, or --inputs RUN.jsonl to run a task against a run's recorded inputs".into());
    };
    let text = read(&args.file)?;
    let record = RunRecord::from_jsonl(&text)
        .map_err(|e| format!("`{}` is not a trace of ilmrc run: {e}", args.file.display()))?;
    if record.poses.is_empty() {
        return Err(format!(
            "`{}` has no pose samples to draw (a run with --robot none has none)",
            args.file.display()
        ));
    }
    plot::write_svg(&record, out)?;
    println!("{}: drew {}", args.file.display(), out.display());
    Ok(())
}

fn read(path: &Path) -> Result<String, String> {
    ilmr_files::read_text(path, ilmr_files::Kind::Trace)
        .map_err(|e| format!("cannot read trace `{}`: {e}", path.display()))
}

/// What a recording holds for a replay.
struct Recording<'a> {
    /// The lines between the version line and the first event, `tape` included.
    prelude: Vec<Record<'a>>,
    tape: Tape,
    /// The `run` line's seed, for the summary.
    seed: u64,
    ticks: Vec<Input>,
    lines: Vec<Line>,
    /// Where the recording was cut at its size limit.
    truncated: Option<f64>,
}

/// What `records` hold for a replay. Their `input` lines are moved into the recording
/// (the events left are what a changed task's replay is compared with).
fn recording<'a>(path: &Path, records: &mut Vec<Record<'a>>) -> Result<Recording<'a>, String> {
    let (tape_at, tape) = records
        .iter()
        .enumerate()
        .find_map(|(i, r)| match &r.event {
            Event::Tape(tape) => Some((i, tape)),
            _ => None,
        })
        .ok_or_else(|| {
            format!(
                "`{}` has no recorded inputs: record them with `ilmrc run --record-inputs --trace {}`",
                path.display(),
                path.display()
            )
        })?;
    if tape.format != ilmr_trace::INPUT_FORMAT {
        return Err(format!(
            "`{}` records its inputs in form {}; this ilmrc replays form {}",
            path.display(),
            tape.format,
            ilmr_trace::INPUT_FORMAT
        ));
    }
    let mut rec = Recording {
        prelude: records[1..=tape_at].to_vec(),
        tape: tape.clone(),
        seed: 0,
        ticks: Vec::new(),
        lines: Vec::new(),
        truncated: None,
    };
    let mut events = Vec::with_capacity(records.len());
    for r in records.drain(..) {
        match r.event {
            Event::Input(i) => {
                rec.ticks.push(*i);
                continue;
            }
            Event::Run(ref run) => rec.seed = run.seed,
            Event::Line(ref l) => rec.lines.push(Line {
                t: r.t.0,
                text: l.text.to_string(),
            }),
            Event::Truncated(_) => rec.truncated = Some(r.t.0),
            _ => {}
        }
        events.push(r);
    }
    *records = events;
    Ok(rec)
}

#[derive(Parser)]
#[command(no_binary_name = true)]
struct Argv {
    #[command(flatten)]
    run: RunArgs,
}

/// The options of the recorded run, as `ilmrc run` would have been given them.
fn run_args(args: &ReplayArgs, rec: &Recording) -> Result<RunArgs, String> {
    let t = &rec.tape;
    let mut argv = vec![
        args.file.display().to_string(),
        "--seed".into(),
        rec.seed.to_string(),
        "--max-time".into(),
        t.max_time.0.to_string(),
        "--hold-limit".into(),
        t.hold_limit.0.to_string(),
        "--pose-every".into(),
        t.pose_every.to_string(),
        "--scan-every".into(),
        t.scan_every.0.to_string(),
    ];
    if let Some(skills) = &args.skills {
        argv.extend(["--skills".into(), skills.display().to_string()]);
    }
    if let Some(plot) = &args.plot {
        argv.extend(["--plot".into(), plot.display().to_string()]);
    }
    let mut run = Argv::try_parse_from(&argv)
        .map_err(|e| format!("the recording's options: {e}"))?
        .run;
    run.record_inputs = true;
    crate::run::check_times(&run).map_err(|e| format!("the recording's `tape` line: {e}"))?;
    Ok(run)
}

fn setup(args: &ReplayArgs, tape: &Tape) -> Result<Setup, String> {
    let spec = args.model.clone().unwrap_or_else(|| tape.model.clone());
    let model = crate::inputs::load_robot_model(&spec).map_err(|e| {
        format!("{e} (the recorded run's model; give the replay `--model` where it is now)")
    })?;
    let backend = match (tape.backend.as_str(), tape.body.as_deref()) {
        ("none", _) => Backend::None,
        ("scripted", _) => Backend::Scripted,
        ("ros2", _) => Backend::Ros2,
        ("sim", Some(body)) => Backend::Sim(
            BODIES
                .iter()
                .find(|(n, _)| *n == body)
                .map(|(_, k)| *k)
                .ok_or_else(|| format!("the recording's simulated body `{body}` is unknown"))?,
        ),
        (other, _) => return Err(format!("the recording's robot `{other}` is unknown")),
    };
    Ok(Setup {
        backend,
        // The recorded inputs are what the robot sensed, whatever its errors.
        profile: ilmr_sim::SimProfile::Basic,
        model_spec: spec,
        model,
        world: None,
        ros2: None,
    })
}

/// A recording as trace lines: a trace file's own, or the lines an MCAP file holds on
/// its inputs topic (which has no events to compare the replay's with).
enum Lines {
    Trace(String),
    Mcap(String),
}

impl Lines {
    fn read(path: &Path) -> Result<Lines, String> {
        let is_mcap = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("mcap"));
        if !is_mcap {
            return read(path).map(Lines::Trace);
        }
        let bytes = ilmr_files::read(path, ilmr_files::Kind::Recording)
            .map_err(|e| format!("cannot read MCAP recording `{}`: {e}", path.display()))?;
        let bad = |e: &dyn std::fmt::Display| {
            format!("`{}` is not an MCAP recording: {e}", path.display())
        };
        let mut text = ilmr_trace::to_line(&Record::header());
        text.push('\n');
        for message in mcap::MessageStream::new(&bytes).map_err(|e| bad(&e))? {
            let message = message.map_err(|e| bad(&e))?;
            if message.channel.topic != INPUTS_TOPIC {
                continue;
            }
            let line = std::str::from_utf8(&message.data).map_err(|e| bad(&e))?;
            if line.contains('\n') {
                return Err(bad(&"a message on /ilmr/inputs holds more than one line"));
            }
            text.push_str(line);
            text.push('\n');
        }
        Ok(Lines::Mcap(text))
    }

    fn text(&self) -> &str {
        match self {
            Lines::Trace(t) | Lines::Mcap(t) => t,
        }
    }
}

fn replay_inputs(args: &ReplayArgs, inputs: &Path) -> Result<u8, String> {
    let lines = Lines::read(inputs)?;
    let text = lines.text();
    let mut records: Vec<Record<'_>> = ilmr_trace::records(text)
        .collect::<Result<_, _>>()
        .map_err(|e| format!("`{}` is not a trace of ilmrc run: {e}", inputs.display()))?;
    let rec = recording(inputs, &mut records)?;
    if rec.tape.ilmrc != env!("CARGO_PKG_VERSION") {
        eprintln!(
            "warning: `{}` was recorded by ilmrc {}; this is {}: the VM may run the task differently",
            inputs.display(),
            rec.tape.ilmrc,
            env!("CARGO_PKG_VERSION")
        );
    }
    if let Some(t) = rec.truncated {
        eprintln!(
            "warning: `{}` was cut at its size limit at t={}: the replay ends there",
            inputs.display(),
            fmt_num(t)
        );
    }
    let run = run_args(args, &rec)?;
    let setup = setup(args, &rec.tape)?;
    let scenario = Scenario {
        paths: rec
            .tape
            .paths
            .iter()
            .map(|p| (p.name.clone(), p.points.0.to_vec()))
            .collect(),
        lines: rec.lines.clone(),
        ..Scenario::default()
    };
    let kept = Kept::default();
    let sink = Sink::in_memory(kept.clone(), args.plot.as_deref())?;
    let ticks = rec.ticks.len();
    let (player, played) = Player::new(rec.ticks);
    let start = Start {
        setup: &setup,
        scenario: &scenario,
        sink,
        robot: Source::Played {
            player,
            scanner_offset: rec.tape.scanner_offset.map(|o| o.0),
        },
        prelude: rec.prelude,
    };
    match launch(&run, start, &mut Reached::default(), &mut Console::Terminal)? {
        Ran::Ended(_) => {}
        Ran::Rejected => return Ok(crate::EXIT_ERRORS),
    }
    let replayed = kept.take();
    if let Some(out) = &args.trace {
        std::fs::write(out, &replayed)
            .map_err(|e| format!("cannot write trace `{}`: {e}", out.display()))?;
    }
    let replayed = String::from_utf8(replayed).unwrap_or_default();
    let task = args.file.display();
    let same_calls = played.divergence().is_none() && played.ticks() == ticks && !played.ran_out();
    let same = match &lines {
        Lines::Trace(recorded) => replayed == *recorded,
        Lines::Mcap(_) => same_calls,
    };
    if same {
        let what = match lines {
            Lines::Trace(_) => "the trace is the recording's, byte for byte",
            Lines::Mcap(_) => {
                "every call to the robot was the recording's (an MCAP recording holds no trace to compare events with)"
            }
        };
        println!("{task}: replayed {ticks} ticks of recorded inputs; {what}");
        return Ok(0);
    }
    println!(
        "{task}: the replay parts from the recording `{}`",
        inputs.display()
    );
    match played.divergence() {
        Some(d) => println!("first call to the robot that differs: {}", d.describe()),
        None if played.ran_out() => println!(
            "every call to the robot was the recording's, but the task had not ended when the recording did (after {ticks} ticks)"
        ),
        None if played.ticks() < ticks => println!(
            "every call to the robot was the recording's, but the task ended after {} of the recording's {ticks} ticks",
            played.ticks()
        ),
        None => println!("every call to the robot was the recording's"),
    }
    if let Lines::Trace(_) = lines {
        let again: Vec<Record<'_>> = ilmr_trace::records(&replayed)
            .collect::<Result<_, _>>()
            .map_err(|e| format!("the replayed trace: {e}"))?;
        let name = args
            .trace
            .clone()
            .unwrap_or_else(|| PathBuf::from("the replay"));
        print!(
            "{}",
            crate::diff::compare(&records, &again).render(inputs, &name)
        );
    }
    println!(
        "(the replay drives no robot: its poses are the recorded robot's, so the task's \
         decisions differ on the same inputs, not where it would have taken the robot)"
    );
    Ok(crate::EXIT_ERRORS)
}
