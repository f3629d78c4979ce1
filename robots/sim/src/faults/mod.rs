//! Fault injection: what can go wrong with a robot (issue 7), when it goes
//! wrong, and what that does to the simulated sensors and actuators.
//!
//! A fault is a [`FaultSpec`]: a [`FaultKind`] with its parameters, a start
//! time and an optional duration. Specs come from a world file's `[[fault]]`
//! entries ([`world`]), from `ilmrc run --fault KIND[@START[+DURATION]][:PARAM]`
//! ([`flag`]), or from [`random_plan`] for soak tests. A [`FaultPlan`] turns
//! them into the simulator's active [`Faults`] at each step; the simulator's
//! hooks read those. [`check_fits`] refuses a fault for a part the robot lacks
//! or one that starts after the run ends.
//!
//! A fault is active on `[start, start + duration)`, and a reading taken, or a
//! step ending, at time `t` is affected exactly when the fault is active at `t`.

mod active;
pub mod fit;
pub mod flag;
mod plan;
mod random;
pub mod world;

pub use active::Faults;
pub use fit::check_fits;
pub use plan::{FaultPlan, ObstacleChange};
pub use random::random_plan;

use serde::{Deserialize, Serialize};
use std::fmt;

/// Default extra slip: the ground moves 70 % of what the wheels count.
pub const DEFAULT_SLIP: f64 = 0.3;
/// Default odometry scale error, relative.
pub const DEFAULT_BIAS: f64 = 0.05;
/// Default gap between the robot's front and an appearing obstacle, m.
pub const DEFAULT_OBSTACLE_DISTANCE: f64 = 1.5;
/// Default radius of an appearing obstacle (a person, a dropped box), m.
pub const DEFAULT_OBSTACLE_RADIUS: f64 = 0.25;
/// The actuator `actuator_dead` silences when none is named.
pub const DRIVE: &str = "drive";

/// The largest slip a fault may add; beyond it the wheels barely grip, which
/// is a stuck robot rather than slip.
pub const MAX_SLIP: f64 = 0.9;
/// The largest relative odometry scale error a fault may set.
pub const MAX_BIAS: f64 = 0.5;

/// What goes wrong.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum FaultKind {
    /// No new scans arrive; the last one stays in the snapshot.
    ScannerDropout,
    /// The wheels slip: the ground moves only `1 - slip` (on average; the
    /// slip varies from step to step, seeded) of what the wheels count.
    OdometrySlip { slip: f64 },
    /// Every pulse counter counts `1 + bias` times the travel.
    OdometryBias { bias: f64 },
    /// The pulse counters stop reporting: the odometry reading and its stamp
    /// freeze and the robot's own estimate stops integrating. The counters
    /// keep counting, so the estimate catches up in one step when they return.
    OdometryDropout,
    /// The navigation receiver freezes: no new fix (the last keeps its stamp),
    /// and the pilot dead-reckons alone. Robots with a navigation fix only.
    NavFrozen,
    /// The battery reads empty and the drive has no power: it comes to rest
    /// within its deceleration limit and takes no setpoints.
    DeadBattery,
    /// An actuator does not answer. `drive`: `set_motion` fails with a
    /// timeout, and the drive's watchdog brings it to rest within its
    /// deceleration limit, curvature held. A model actuator (`brake` ...):
    /// `actuator(name, v)` fails with a timeout and the value is not applied.
    ActuatorDead { actuator: String },
    /// The manipulator never answers: an operation that would complete while
    /// this is active stays pending until it is cancelled.
    ManipulatorSilent,
    /// A round obstacle of `radius` appears `distance` ahead of the robot's
    /// front, on its heading, when the fault starts, and goes when it ends.
    ObstacleAppears { distance: f64, radius: f64 },
}

/// The kinds' names, as world files and the flag write them.
pub const KIND_NAMES: [&str; 9] = [
    "scanner_dropout",
    "odometry_slip",
    "odometry_bias",
    "odometry_dropout",
    "nav_frozen",
    "dead_battery",
    "actuator_dead",
    "manipulator_silent",
    "obstacle_appears",
];

impl FaultKind {
    pub fn name(&self) -> &'static str {
        match self {
            FaultKind::ScannerDropout => "scanner_dropout",
            FaultKind::OdometrySlip { .. } => "odometry_slip",
            FaultKind::OdometryBias { .. } => "odometry_bias",
            FaultKind::OdometryDropout => "odometry_dropout",
            FaultKind::NavFrozen => "nav_frozen",
            FaultKind::DeadBattery => "dead_battery",
            FaultKind::ActuatorDead { .. } => "actuator_dead",
            FaultKind::ManipulatorSilent => "manipulator_silent",
            FaultKind::ObstacleAppears { .. } => "obstacle_appears",
        }
    }

    /// The kind with its defaults, from its name.
    pub fn named(name: &str) -> Option<FaultKind> {
        Some(match name {
            "scanner_dropout" => FaultKind::ScannerDropout,
            "odometry_slip" => FaultKind::OdometrySlip { slip: DEFAULT_SLIP },
            "odometry_bias" => FaultKind::OdometryBias { bias: DEFAULT_BIAS },
            "odometry_dropout" => FaultKind::OdometryDropout,
            "nav_frozen" => FaultKind::NavFrozen,
            "dead_battery" => FaultKind::DeadBattery,
            "actuator_dead" => FaultKind::ActuatorDead {
                actuator: DRIVE.into(),
            },
            "manipulator_silent" => FaultKind::ManipulatorSilent,
            "obstacle_appears" => FaultKind::ObstacleAppears {
                distance: DEFAULT_OBSTACLE_DISTANCE,
                radius: DEFAULT_OBSTACLE_RADIUS,
            },
            _ => return None,
        })
    }

    /// Checks the parameters; the message names the parameter and its range.
    pub fn check(&self) -> Result<(), String> {
        match self {
            FaultKind::OdometrySlip { slip }
                if !(slip.is_finite() && *slip > 0.0 && *slip <= MAX_SLIP) =>
            {
                Err(format!(
                    "slip must be above 0 and at most {MAX_SLIP}, got {slip}"
                ))
            }
            FaultKind::OdometryBias { bias } if !(bias.is_finite() && bias.abs() <= MAX_BIAS) => {
                Err(format!(
                    "bias must be within -{MAX_BIAS}..{MAX_BIAS}, got {bias}"
                ))
            }
            FaultKind::ActuatorDead { actuator } if actuator.trim().is_empty() => {
                Err("actuator must name `drive` or an actuator of the robot model".into())
            }
            FaultKind::ObstacleAppears { distance, .. }
                if !(distance.is_finite() && *distance > 0.0) =>
            {
                Err(format!(
                    "distance must be a positive number of metres, got {distance}"
                ))
            }
            FaultKind::ObstacleAppears { radius, .. } if !(radius.is_finite() && *radius > 0.0) => {
                Err(format!(
                    "radius must be a positive number of metres, got {radius}"
                ))
            }
            _ => Ok(()),
        }
    }
}

/// One fault with its window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FaultSpec {
    #[serde(flatten)]
    pub kind: FaultKind,
    /// Simulated time it starts, s.
    pub start: f64,
    /// How long it lasts, s; `None` to the end of the run.
    pub duration: Option<f64>,
}

impl FaultSpec {
    pub fn new(kind: FaultKind, start: f64, duration: Option<f64>) -> FaultSpec {
        FaultSpec {
            kind,
            start,
            duration,
        }
    }

    /// Checks the window and the parameters.
    pub fn check(&self) -> Result<(), String> {
        if !(self.start.is_finite() && self.start >= 0.0) {
            return Err(format!(
                "start must be a time of 0 s or later, got {}",
                self.start
            ));
        }
        if let Some(d) = self.duration
            && !(d.is_finite() && d > 0.0)
        {
            return Err(format!("duration must be a positive time, got {d}"));
        }
        self.kind.check()
    }

    /// The window in whole microseconds, as the simulator keeps time.
    pub(crate) fn window_us(&self) -> (u64, Option<u64>) {
        let us = |s: f64| (s * 1e6).round() as u64;
        (
            us(self.start),
            self.duration.map(|d| us(self.start) + us(d)),
        )
    }

    pub(crate) fn active_at(&self, t_us: u64) -> bool {
        let (start, end) = self.window_us();
        t_us >= start && end.is_none_or(|e| t_us < e)
    }
}

/// Written the way the flag reads it: `KIND@START+DURATION:PARAM`.
impl fmt::Display for FaultSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}@{}", self.kind.name(), self.start)?;
        if let Some(d) = self.duration {
            write!(f, "+{d}")?;
        }
        match &self.kind {
            FaultKind::OdometrySlip { slip } => write!(f, ":{slip}"),
            FaultKind::OdometryBias { bias } => write!(f, ":{bias}"),
            FaultKind::ActuatorDead { actuator } => write!(f, ":{actuator}"),
            FaultKind::ObstacleAppears { distance, .. } => write!(f, ":{distance}"),
            _ => Ok(()),
        }
    }
}
