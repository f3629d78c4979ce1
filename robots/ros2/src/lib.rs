//! ILMR's link to ROS 2 robots (docs/ros2.md).
//!
//! - `msg`: the ROS 2 messages the backend speaks (`geometry_msgs/Twist` out on
//!   `cmd_vel`; `nav_msgs/Odometry`, `sensor_msgs/LaserScan` and
//!   `sensor_msgs/BatteryState` in), laid out field for field as ROS 2's IDL, with the
//!   DDS type names ROS 2 registers; `cdr`: their encoding as DDS carries them.
//! - `convert`: where ROS 2's units and conventions become the HAL's, and where every
//!   velocity sent is bounded by the robot's model.
//! - `names`: ROS 2 topic names and their DDS form; `dds`: the RustDDS transport.
//! - `robot`: [`Ros2Robot`], the HAL over all of it.
//!
//! Decoding never panics and never allocates more than the message's own bytes allow:
//! a malformed, truncated or oversized message is an error value, logged and dropped.

pub mod base;
pub mod cdr;
pub mod convert;
pub mod dds;
pub mod definition;
mod frame;
pub mod msg;
pub mod names;
pub mod robot;

pub use cdr::{DecodeError, MAX_MESSAGE_BYTES, decode, encode};
pub use dds::{LinkError, Reach};
pub use msg::RosMessage;
pub use robot::{KEEPALIVE, LinkStats, Ros2Config, Ros2Robot, Topics};
