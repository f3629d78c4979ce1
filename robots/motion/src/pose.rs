//! The pose and angle helpers every other module relies on (ilmr-geometry's,
//! shared with the HAL and the simulator), and the side of the robot.

use serde::{Deserialize, Serialize};

pub use ilmr_geometry::{Pose, angle_diff, wrap_angle};

/// A side of the robot, as `followwall(left)` or `turn(right)` name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Side {
    Left,
    Right,
}

impl Side {
    /// +1 for left (the positive y of the robot frame), -1 for right.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }

    pub fn opposite(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}
