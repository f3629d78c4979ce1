//! Errors the simulator returns instead of panicking.

use crate::config::RobotKind;
use std::fmt;

/// What the robot touched: a solid of the world, or the edge of its bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Contact {
    Solid(crate::geometry::SolidRef),
    OutOfBounds,
}

#[derive(Debug, Clone, PartialEq)]
pub enum SimError {
    /// The robot configuration has a bad value (named in the text).
    Config(String),
    /// The world's start pose puts the robot's footprint into something.
    StartInCollision(Contact),
    /// `step` needs a finite dt of at least 1 microsecond and at most 1 s.
    BadTimeStep(f64),
    /// A setpoint was NaN or infinite.
    NotFinite(&'static str),
    /// The robot has no such device or mode.
    Unsupported {
        robot: RobotKind,
        what: &'static str,
    },
    /// A setting outside its range, such as a body roll of 40 degrees.
    OutOfRange(String),
    /// Taking or leaving a box was not possible now.
    Manipulation(String),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Config(m) => write!(f, "bad robot configuration: {m}"),
            SimError::StartInCollision(c) => write!(f, "the start pose collides: {c:?}"),
            SimError::BadTimeStep(dt) => write!(f, "time step {dt} s is not within 1 us..1 s"),
            SimError::NotFinite(what) => write!(f, "{what} must be a finite number"),
            SimError::Unsupported { robot, what } => write!(f, "{robot:?} has no {what}"),
            SimError::OutOfRange(m) => f.write_str(m),
            SimError::Manipulation(m) => write!(f, "cannot manipulate: {m}"),
        }
    }
}

impl std::error::Error for SimError {}
