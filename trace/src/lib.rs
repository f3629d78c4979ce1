//! The trace schema: every line of an ILMR trace (`ilmrc run --trace`, serve's event
//! stream) as a Rust type, so that the writers (the VM, the run) and the readers
//! (plot, replay, serve) cannot drift apart.
//!
//! A trace is JSON Lines. Each line is a [`Record`]: `t` (seconds of logical time),
//! `event` (the tag naming the [`Event`]), then the event's keys in the order of its
//! type's fields. The first line of a trace file is the [`Event::Trace`] line with the
//! schema version, `{"t":0,"event":"trace","version":1}`; a [`Reader`] refuses a trace
//! without it or of another version, with a [`TraceError`] and its code.
//!
//! Numbers are [`Num`]s: at most four decimals (exact in the recorded inputs, [`input`]), and the strings `"inf"`, `"-inf"`,
//! `"nan"` for the values JSON has no number for. Strings are `Cow`s, so the VM writes
//! its events without copying their texts (a reader gets owned ones: the tagged,
//! flattened shape goes through serde's buffer).
//!
//! The JSON Schema of a line is `docs/trace-schema.json`, generated from these types
//! ([`json_schema`]) and kept in step by `tests/schema.rs`.
//!
//! This crate sits below the VM: it knows the events' shapes, not what they mean
//! (fault names and codes are the VM's, carried here as text).

mod input;
mod num;
mod points;
mod read;
mod write;

use std::borrow::Cow;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use input::{
    Exchange, Failure, INPUT_FORMAT, Input, Map, OpState, Operation, PlacedScan, Ranges, Reading,
    Seen, Sighting, Snapshot, Solid, Tape, TaughtPath,
};
pub use num::{INFINITY, NAN, NEG_INFINITY, Num, Short, fmt_num, write_short};
pub use points::Points;
pub use read::{Code, Reader, TraceError, records};
pub use write::{to_line, write_line};

/// The version of the schema the writers write and the readers read. Changed when a
/// line's meaning or keys change in a way an older reader would misread.
pub const SCHEMA_VERSION: u32 = 1;

type Text<'a> = Cow<'a, str>;

/// One line of a trace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "ILMR trace line")]
pub struct Record<'a> {
    /// Seconds of logical time.
    pub t: Num,
    #[serde(flatten, borrow)]
    pub event: Event<'a>,
}

impl<'a> Record<'a> {
    pub fn new(t: f64, event: Event<'a>) -> Record<'a> {
        Record { t: Num(t), event }
    }

    /// The first line of every trace file.
    pub fn header() -> Record<'static> {
        Record::new(
            0.0,
            Event::Trace(Version {
                version: SCHEMA_VERSION,
            }),
        )
    }
}

impl Event<'_> {
    /// Whether the line's numbers are written exactly rather than to four decimals:
    /// the recorded inputs, which a replay feeds back to the VM.
    pub fn is_exact(&self) -> bool {
        matches!(self, Event::Tape(_) | Event::Input(_))
    }
}

/// What happened, by its `event` tag.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum Event<'a> {
    /// The first line of a trace file: the schema version.
    Trace(Version),
    /// A simulated run's header: what ran where (the run's own line, after `trace`).
    Run(#[serde(borrow)] Run<'a>),
    /// The run failed before the VM started; the whole trace is then its `run` line
    /// (when robot and world were known) and this.
    Failed(#[serde(borrow)] Failed<'a>),
    /// The trace reached its size limit; nothing after this line was written.
    Truncated(#[serde(borrow)] Truncated<'a>),
    /// An interactive line was offered to the running task.
    Line(#[serde(borrow)] Entered<'a>),
    /// A block executed the statement.
    Issue(#[serde(borrow)] Issue<'a>),
    /// A queued movement got the reservation, an `if` body started, a `while`
    /// iteration started.
    Start(#[serde(borrow)] Start<'a>),
    /// A live command ended, or an instant one was refused.
    End(#[serde(borrow)] End<'a>),
    /// A variable changed.
    Var(#[serde(borrow)] Var<'a>),
    /// A pose sample, every `pose_every` ticks.
    Pose(Pose),
    /// A movement got its reference path.
    Path(#[serde(borrow)] Path<'a>),
    /// Obstacle avoidance changed state.
    Avoid(#[serde(borrow)] Avoid<'a>),
    /// The supervisor raised a fault.
    Fault(#[serde(borrow)] Fault<'a>),
    /// A fault's condition cleared.
    Recovered(#[serde(borrow)] Recovered<'a>),
    /// A block ran out of the tick's budget and was suspended.
    Overrun(#[serde(borrow)] Overrun<'a>),
    /// A runtime error that ended no command.
    Error(#[serde(borrow)] Error<'a>),
    /// A movement command started or ended: the true pose there.
    Mark(#[serde(borrow)] Mark<'a>),
    /// Scanner hits in the world frame.
    Scan(#[serde(borrow)] Scan<'a>),
    /// How a run that records its inputs was set up (`ilmrc run --record-inputs`).
    Tape(Tape),
    /// One tick's inputs from the robot, written exactly (see [`input`]).
    Input(Box<Input>),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Version {
    /// [`SCHEMA_VERSION`] of the writer.
    pub version: u32,
}

/// The statement an event belongs to: its source line and text, and its file when
/// that is not the task's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Stmt<'a> {
    pub line: u32,
    #[serde(borrow)]
    pub text: Text<'a>,
    /// The file of a statement outside the task: a skill file
    /// (`examples/skills/gestures.ilms`, `<stdlib>/charging.ilms`) or an interactive
    /// line (`<typed 3>`); absent for the task's own statements, so that `line` alone
    /// names a line of the task.
    #[serde(borrow, default, skip_serializing_if = "Option::is_none")]
    pub file: Option<Text<'a>>,
}

/// A pose in the world frame; `h` is the heading in radians.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct At {
    pub x: Num,
    pub y: Num,
    pub h: Num,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Run<'a> {
    /// The task file as given.
    #[serde(borrow)]
    pub task: Text<'a>,
    #[serde(borrow)]
    pub robot: Text<'a>,
    /// A shipped world's name or a world file's path.
    #[serde(borrow)]
    pub world: Text<'a>,
    pub seed: u64,
    /// The simulated robot's error profile (`--sim-profile`) when it is not `basic`.
    #[serde(borrow, default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<Text<'a>>,
    pub start: At,
    /// A world file's text (a shipped world is known by its name).
    #[serde(borrow, default, skip_serializing_if = "Option::is_none")]
    pub world_toml: Option<Text<'a>>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Failed<'a> {
    #[serde(borrow)]
    pub reason: Text<'a>,
    /// The exit code, 1 (the task has errors) or 2 (usage, input or output).
    pub exit: u8,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Truncated<'a> {
    /// The limit reached, bytes.
    pub limit: u64,
    #[serde(borrow)]
    pub message: Text<'a>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Entered<'a> {
    /// The line as typed.
    #[serde(borrow)]
    pub text: Text<'a>,
    /// Whether it joined the task.
    pub accepted: bool,
    /// The codes of its diagnostics (a rejected line's errors, a joined line's
    /// warnings).
    #[serde(borrow, default, skip_serializing_if = "Vec::is_empty")]
    pub codes: Vec<Text<'a>>,
}

fn one() -> u32 {
    1
}

fn is_one(n: &u32) -> bool {
    *n == 1
}

fn is_false(b: &bool) -> bool {
    !*b
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Issue<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    /// How many events of this tick this one stands for (repeats joined into the
    /// first); written when more than one.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub count: u32,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Start<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    /// A `while`'s iteration (the last, when `count` joins several).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iteration: Option<u32>,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub count: u32,
}

/// How a command ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum How {
    Completed,
    Broken,
    Refused,
}

impl How {
    pub fn name(self) -> &'static str {
        match self {
            How::Completed => "completed",
            How::Broken => "broken",
            How::Refused => "refused",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct End<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    pub how: How,
    /// A movement ended early because the next one was joined to it.
    #[serde(default, skip_serializing_if = "is_false")]
    pub linked: bool,
    /// The stable code of a safety refusal or of the fault that ended it (`R0101`...).
    #[serde(borrow, default, skip_serializing_if = "Option::is_none")]
    pub code: Option<Text<'a>>,
    #[serde(borrow, default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<Text<'a>>,
    /// What to do about the code's cause.
    #[serde(borrow, default, skip_serializing_if = "Option::is_none")]
    pub help: Option<Text<'a>>,
}

/// A variable's fields that changed (Table 8), in the VM's `FIELDS` order, and how its
/// command ended when its status changed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Var<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    #[serde(borrow)]
    pub var: Text<'a>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub h: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dist: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub how: Option<How>,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub count: u32,
}

/// Where a pose sample comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Source {
    /// Ground truth (a simulated robot).
    #[serde(rename = "true")]
    Truth,
    /// The robot's own estimate.
    #[serde(rename = "estimated")]
    Estimated,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Pose {
    pub x: Num,
    pub y: Num,
    /// Heading, radians.
    pub h: Num,
    /// Speed, m/s.
    pub v: Num,
    /// Curvature, 1/m.
    pub c: Num,
    pub source: Source,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Path<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    /// The path's points in the robot's frame, metres, thinned to 1 cm.
    #[serde(borrow)]
    pub points: Points<'a>,
}

/// Obstacle avoidance's state (section 4.5.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum AvoidState {
    Normal,
    Avoiding,
    Returning,
    Blocked,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Avoid<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    pub state: AvoidState,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Fault<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    /// The fault's name (`obstacle_near`...; docs/reliability.md).
    #[serde(borrow)]
    pub fault: Text<'a>,
    #[serde(borrow)]
    pub code: Text<'a>,
    /// What the supervisor does while it lasts (`hold`, `stop`...).
    #[serde(borrow)]
    pub reaction: Text<'a>,
    #[serde(borrow)]
    pub message: Text<'a>,
    #[serde(borrow)]
    pub help: Text<'a>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Recovered<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    #[serde(borrow)]
    pub fault: Text<'a>,
    #[serde(borrow)]
    pub code: Text<'a>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Overrun<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    pub pending: u32,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Error<'a> {
    #[serde(flatten, borrow)]
    pub stmt: Option<Stmt<'a>>,
    #[serde(borrow)]
    pub message: Text<'a>,
}

/// Where a movement command was when it started or ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Moment {
    Start,
    End,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Mark<'a> {
    pub line: u32,
    #[serde(borrow)]
    pub text: Text<'a>,
    pub at: Moment,
    pub x: Num,
    pub y: Num,
    pub h: Num,
    /// How an ended command ended.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub how: Option<How>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Scan<'a> {
    /// The scanner's pose.
    pub x: Num,
    pub y: Num,
    pub h: Num,
    /// Hits in the world frame, to the centimetre.
    #[serde(borrow)]
    pub hits: Points<'a>,
}

/// The JSON Schema of one trace line, as published in `docs/trace-schema.json`.
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(Record<'static>);
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}

#[cfg(test)]
mod tests;
