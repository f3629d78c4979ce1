//! Plain data exchanged over the HAL.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Where a body's front and its laser scanner lie ahead of the reference point whose
/// pose the robot reports, metres: what the VM needs of a body to place what it sees
/// and what it may hit. The simulator knows them of its bodies; a model alone does not.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyOffsets {
    pub front: f64,
    pub scanner: f64,
}

/// The planar pose every layer shares (ilmr-geometry's): metres and radians, heading
/// counter-clockwise from x.
pub use ilmr_geometry::Pose;

pub use ilmr_geometry::Side;

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
    /// When the latest odometry sample was taken, seconds; `None` when the robot does
    /// not report it (then its odometry is not supervised).
    pub odometry_t: Option<f64>,
    /// When the latest navigation fix was taken, seconds; `None` when the robot has no
    /// separate navigation subsystem or does not report it.
    pub nav_t: Option<f64>,
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

/// A solid of the known map: every point within `radius` of the segment from `a` to
/// `b` (a wall of thickness `2 * radius`; a round obstacle when `a == b`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Solid {
    pub a: (f64, f64),
    pub b: (f64, f64),
    pub radius: f64,
    /// What the site plan calls it (a world file's wall `id`), for messages that
    /// point at it; `None` when the plan gives no name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

impl Solid {
    /// Distance from `p` to the solid's surface; negative inside it.
    pub fn distance(&self, p: (f64, f64)) -> f64 {
        segment_distance(p, self.a, self.b) - self.radius
    }
}

/// Distance from `p` to the segment `a`-`b` (to `a` when the two coincide).
pub fn segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// What the robot knows of its surroundings before it sees them: the area it may
/// drive in and the solids in it, in the frame of [`Snapshot::pose`]. A simulator
/// fills it from its world; a real robot from a site plan.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct KnownMap {
    /// `(min x, min y, max x, max y)`; `None`: unbounded.
    pub bounds: Option<(f64, f64, f64, f64)>,
    pub solids: Vec<Solid>,
}

impl KnownMap {
    /// Whether `p` lies inside the bounds (always, without bounds).
    pub fn contains(&self, p: (f64, f64)) -> bool {
        self.bounds
            .is_none_or(|(x0, y0, x1, y1)| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1)
    }

    /// The solid nearest to `p` and its distance, if there is any solid.
    pub fn nearest(&self, p: (f64, f64)) -> Option<(usize, f64)> {
        self.solids
            .iter()
            .enumerate()
            .map(|(i, s)| (i, s.distance(p)))
            .filter(|(_, d)| !d.is_nan())
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }
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
    /// The robot side did not answer within the call's deadline.
    Timeout(String),
}

impl fmt::Display for HalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HalError::Unsupported(what) => write!(f, "unsupported: {what}"),
            HalError::Refused(why) => write!(f, "refused: {why}"),
            HalError::UnknownOp(id) => write!(f, "unknown operation {}", id.0),
            HalError::Link(why) => write!(f, "robot link: {why}"),
            HalError::Timeout(what) => write!(f, "no answer: {what}"),
        }
    }
}

impl std::error::Error for HalError {}
