//! ILMR's link to ROS 2 robots. This first layer holds the ROS 2 messages the backend
//! speaks (`geometry_msgs/Twist` out on `cmd_vel`; `nav_msgs/Odometry`,
//! `sensor_msgs/LaserScan` and `sensor_msgs/BatteryState` in) as Rust types laid out
//! field for field as ROS 2's IDL, with the DDS type names ROS 2 registers, and their
//! encoding as DDS sends them: plain CDR behind a 4-byte encapsulation header. The DDS
//! transport and the HAL backend come on top (docs/ros2.md); `convert` is where ROS 2's
//! units and conventions become the HAL's, and where every velocity sent is bounded by
//! the robot's model.
//!
//! Decoding never panics and never allocates more than the message's own bytes allow:
//! a malformed, truncated or oversized message is an error value, to be logged and
//! dropped by the caller.

pub mod cdr;
pub mod convert;
pub mod msg;

pub use cdr::{DecodeError, MAX_MESSAGE_BYTES, decode, encode};
pub use msg::RosMessage;
