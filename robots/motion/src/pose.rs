//! The pose, the angle helpers and the side of the robot every other module relies
//! on (ilmr-geometry's, shared with the HAL and the simulator).

pub use ilmr_geometry::{Pose, Side, angle_diff, wrap_angle};
