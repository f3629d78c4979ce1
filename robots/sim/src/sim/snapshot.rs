//! What the robot's software sees, in one value: the estimated pose and every
//! sensor's latest reading. The true pose is not in here on purpose.

use super::error::Contact;
use crate::geometry::Pose;
use crate::kinematics::{BodyPose, MovementMode};
use crate::sensors::{
    BatteryReading, CameraFrame, GyroReading, NavFix, OdometryReading, PlateEvent, Scan,
    UltrasonicReading,
};
use serde::Serialize;
use std::sync::Arc;

#[derive(Debug, Clone, PartialEq)]
pub struct SensorSnapshot {
    /// Simulated time, s.
    pub time: f64,
    /// Estimated pose in the user frame (see `Simulator::locate`).
    pub pose: Pose,
    /// Drive speed as the motor controller measures it (wheel speed, so slip
    /// is not seen), m/s.
    pub speed: f64,
    /// Curvature from the steering or articulation angle sensor, 1/m.
    pub curvature: f64,
    /// MoRo's front wheel angle, or Workpartner's articulation angle, rad.
    pub steering_angle: f64,
    /// The latest scan; compare `seq` to tell a new one.
    pub scan: Option<Arc<Scan>>,
    pub odometry: OdometryReading,
    /// When `odometry` was read, s; behind `time` while the counters are silent.
    pub odometry_time: f64,
    pub gyro: Option<GyroReading>,
    /// The latest floor-plate detection.
    pub plate: Option<PlateEvent>,
    /// The latest navigation fix, in the user frame.
    pub nav_fix: Option<NavFix>,
    pub ultrasonic: Option<UltrasonicReading>,
    pub camera: Option<CameraFrame>,
    pub battery: BatteryReading,
    pub movement_mode: MovementMode,
    /// Measured body pose (Workpartner).
    pub body_pose: Option<BodyPose>,
    /// Id of the box held by the manipulator.
    pub carrying: Option<String>,
    /// The robot is pressed against something and its drive is stopped.
    pub blocked: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum EventKind {
    ContactBegan(Contact),
    ContactEnded,
    Plate(PlateEvent),
    BoxTaken(String),
    BoxLeft(String),
    BatteryEmpty,
    /// An injected fault (by its kind's name) came into force.
    FaultBegan(String),
    FaultEnded(String),
}

/// Something that happened during a step, for traces.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SimEvent {
    pub time: f64,
    pub kind: EventKind,
}
