//! Recorded inputs: everything the VM received from the robot, tick by tick, so that
//! `ilmrc replay --inputs` can run the task again against exactly those inputs, with no
//! robot and no simulator.
//!
//! `ilmrc run --record-inputs` adds two kinds of lines to the trace: one [`Tape`] line
//! after the header (what the run was configured with), then one [`Input`] line at the
//! end of each tick: every call the VM made to the robot's HAL since the last one, in
//! order, each with its arguments and the robot's answer, and what the run itself read
//! of the robot (at rest, true pose, the new scan).
//!
//! Unlike the rest of the trace, whose numbers have four decimals, these lines carry
//! every number exactly (the shortest decimal that reads back as the same `f64`), since
//! a replay that fed the VM rounded inputs would not reproduce the run. The strings
//! `"inf"`, `"-inf"` and `"nan"` stand for the values JSON has no number for, as
//! elsewhere in the trace.
//!
//! The types mirror the HAL's (`ilmr-hal`), which this crate does not depend on: the
//! conversion is the recorder's (`src/tape` of `ilmrc`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{At, Num, Points};

/// The version of the recorded inputs' form, in every [`Tape`] line. Changed when an
/// older replay would misread the lines.
pub const INPUT_FORMAT: u32 = 1;

fn is_false(b: &bool) -> bool {
    !*b
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}

/// How the recorded run was set up, as far as a replay needs it beside the task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Tape {
    /// [`INPUT_FORMAT`] of the writer.
    pub format: u32,
    /// The version of `ilmrc` that recorded the run: a replay by another version may
    /// run the task differently.
    pub ilmrc: String,
    /// `none`, `scripted`, `sim` or `ros2`.
    pub backend: String,
    /// The robot model the task was checked against (`moro`, `workpartner` or a
    /// ROBO.INI path).
    pub model: String,
    /// The simulated body (`moro`, `workpartner`), for a simulated robot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// The VM's `scanner_offset`, when the robot said where its scanner is (ROS 2's
    /// `tf`) rather than its model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scanner_offset: Option<Num>,
    pub pose_every: u32,
    pub scan_every: Num,
    pub max_time: Num,
    pub hold_limit: Num,
    /// Paths given to the task before it started (a scenario's taught paths).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub paths: Vec<TaughtPath>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TaughtPath {
    pub name: String,
    pub points: Points<'static>,
}

/// One tick's inputs: the HAL calls in the order the VM made them, then what the run
/// read of the robot after the tick.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Input {
    pub calls: Vec<Exchange>,
    pub robot: Seen,
}

/// A HAL call and the robot's answer. `error` is there when the call failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "call", rename_all = "snake_case")]
pub enum Exchange {
    Update {
        t: Num,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    /// The snapshot as the robot left it, failed or not.
    Snapshot {
        snapshot: Box<Snapshot>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    SetMotion {
        speed: Num,
        curvature: Num,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    Actuator {
        id: String,
        value: Num,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    Locmode {
        mode: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    Bodypose {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        roll: Option<Num>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pitch: Option<Num>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        clearance: Option<Num>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    Locate {
        pose: At,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    /// An operation that takes time; `id` is what the robot answered.
    Start {
        op: Operation,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        id: Option<u32>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    Poll {
        id: u32,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        status: Option<OpState>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    Cancel {
        id: u32,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<Failure>,
    },
    KnownMap {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        map: Option<Map>,
    },
    ActuatorRange {
        id: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        range: Option<(Num, Num)>,
    },
}

impl Exchange {
    /// The call's name, as its `call` key says it.
    pub fn name(&self) -> &'static str {
        match self {
            Exchange::Update { .. } => "update",
            Exchange::Snapshot { .. } => "snapshot",
            Exchange::SetMotion { .. } => "set_motion",
            Exchange::Actuator { .. } => "actuator",
            Exchange::Locmode { .. } => "locmode",
            Exchange::Bodypose { .. } => "bodypose",
            Exchange::Locate { .. } => "locate",
            Exchange::Start { .. } => "start",
            Exchange::Poll { .. } => "poll",
            Exchange::Cancel { .. } => "cancel",
            Exchange::KnownMap { .. } => "known_map",
            Exchange::ActuatorRange { .. } => "actuator_range",
        }
    }
}

/// A failed call (the HAL's `HalError`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Failure {
    Unsupported { message: String },
    Refused { message: String },
    UnknownOp { id: u32 },
    Link { message: String },
    Timeout { message: String },
}

/// An operation that takes time (the HAL's `AsyncOp`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Operation {
    /// `init(addresses)`; empty means everything.
    Init(Vec<String>),
    /// `take`, `leave`, `getball` or `giveball`.
    Manipulate(String),
    MoveMode(String),
}

/// An operation's state (the HAL's `OpStatus`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OpState {
    Pending,
    Done,
    Failed(String),
}

/// Everything the VM read from the robot in one tick (the HAL's `Snapshot`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Snapshot {
    pub t: Num,
    /// The robot's own estimate.
    pub pose: At,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub true_pose: Option<At>,
    pub speed: Num,
    pub curvature: Num,
    /// A scan that differs from the last one recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scan: Option<Ranges>,
    /// The snapshot holds the same scan as the last one recorded (it is not repeated).
    #[serde(default, skip_serializing_if = "is_false")]
    pub scan_kept: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub battery: Option<Num>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub devices: Vec<Reading>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub detections: Vec<Sighting>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub odometry_t: Option<Num>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nav_t: Option<Num>,
}

/// A laser scan in the robot's frame: `ranges[i]` at `angle_min + i * angle_step`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Ranges {
    pub device: String,
    pub t: Num,
    pub angle_min: Num,
    pub angle_step: Num,
    pub ranges: Vec<Num>,
}

/// A named device's latest value; none when it gives no data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Reading {
    pub name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Num>,
}

/// An object a sensor sees, in world coordinates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Sighting {
    pub sensor: String,
    pub object: String,
    pub x: Num,
    pub y: Num,
    pub h: Num,
    /// `left` or `right`.
    pub side: String,
}

/// The robot's static map (the HAL's `KnownMap`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Map {
    /// `[min x, min y, max x, max y]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bounds: Option<(Num, Num, Num, Num)>,
    pub solids: Vec<Solid>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Solid {
    pub a: (Num, Num),
    pub b: (Num, Num),
    pub radius: Num,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

/// What the run read of the robot after the tick, besides the HAL: whether it is at
/// rest (a run does not end while it moves), its true pose and motion, how often it
/// touched something, and the scan that came in, placed in the world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Seen {
    pub at_rest: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub true_pose: Option<At>,
    /// Speed and curvature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<(Num, Num)>,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub contacts: u64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scan: Option<PlacedScan>,
}

/// A scan with the scanner's pose in the world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PlacedScan {
    pub t: Num,
    pub origin: At,
    pub angle_min: Num,
    pub angle_step: Num,
    pub max_range: Num,
    /// Absent when they are the ranges of the last scan in a snapshot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ranges: Option<Vec<Num>>,
}
