//! Plain data exchanged over the HAL.

use serde::{Deserialize, Serialize};
use std::fmt;

/// A planar pose: metres and radians (heading counter-clockwise from x).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose {
    pub x: f64,
    pub y: f64,
    pub h: f64,
}

impl Pose {
    pub const fn new(x: f64, y: f64, h: f64) -> Pose {
        Pose { x, y, h }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    Left,
    Right,
}

/// One laser scan: `ranges[i]` is the distance at `angle_min + i * angle_step` radians
/// in the robot frame.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Scan {
    /// The model's name for the scanner (`scanner`).
    pub device: String,
    /// When the scan was taken, seconds.
    pub t: f64,
    pub angle_min: f64,
    pub angle_step: f64,
    pub ranges: Vec<f64>,
}

/// The latest value of a named device; `None` when the device gives no data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DeviceReading {
    pub name: String,
    pub value: Option<f64>,
}

/// An object of the model that a sensor currently sees, in world coordinates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Detection {
    pub sensor: String,
    pub object: String,
    pub x: f64,
    pub y: f64,
    pub h: f64,
    pub side: Side,
}

/// Everything the VM reads from the robot in one tick.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Snapshot {
    pub t: f64,
    /// The robot's own estimate (dead reckoning and navigation).
    pub pose: Pose,
    /// Ground truth, when the robot is simulated.
    pub true_pose: Option<Pose>,
    pub speed: f64,
    pub curvature: f64,
    pub scan: Option<Scan>,
    pub battery: Option<f64>,
    pub devices: Vec<DeviceReading>,
    /// Objects in view now.
    pub detections: Vec<Detection>,
}

impl Snapshot {
    /// The value of a named device (any letter case); `None` when it is unknown or gives
    /// no data. `battery` falls back to the dedicated field.
    pub fn device(&self, name: &str) -> Option<f64> {
        match self
            .devices
            .iter()
            .find(|d| d.name.eq_ignore_ascii_case(name))
        {
            Some(d) => d.value,
            None if name.eq_ignore_ascii_case("battery") => self.battery,
            None => None,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct BodyPose {
    /// Degrees.
    pub roll: Option<f64>,
    /// Degrees.
    pub pitch: Option<f64>,
    /// Road clearance, metres.
    pub clearance: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ManipTask {
    Take,
    Leave,
    GetBall,
    GiveBall,
}

impl ManipTask {
    pub fn from_name(word: &str) -> Option<ManipTask> {
        [
            ("take", ManipTask::Take),
            ("leave", ManipTask::Leave),
            ("getball", ManipTask::GetBall),
            ("giveball", ManipTask::GiveBall),
        ]
        .into_iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(word))
        .map(|(_, t)| t)
    }
}

/// Operations that take time on the robot side.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum AsyncOp {
    /// `init(addresses)`; empty means everything.
    Init(Vec<String>),
    Manipulate(ManipTask),
    MoveMode(String),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct OpId(pub u32);

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum OpStatus {
    Pending,
    Done,
    Failed(String),
}

/// A failed HAL call.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum HalError {
    /// The robot does not have this device, mode or operation.
    Unsupported(String),
    /// The robot has it but refuses the request now (out of range, busy, locked).
    Refused(String),
    /// An operation id that was never started.
    UnknownOp(OpId),
    /// Communication with the robot side failed.
    Link(String),
}

impl fmt::Display for HalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HalError::Unsupported(what) => write!(f, "unsupported: {what}"),
            HalError::Refused(why) => write!(f, "refused: {why}"),
            HalError::UnknownOp(id) => write!(f, "unknown operation {}", id.0),
            HalError::Link(why) => write!(f, "robot link: {why}"),
        }
    }
}

impl std::error::Error for HalError {}
