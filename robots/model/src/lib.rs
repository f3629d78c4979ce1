//! Robot models in the ROBO.INI format of the ILMR dissertation (Figure 39,
//! sections 4.5 and 5.1.2): the sensors and actuators, recognisable objects,
//! colours, identifiers and parameters that the compiler, VM, simulator and
//! language server read, and how a ROS 2 robot is reached (`[ROS2]`).
//!
//! Reading a model never fails on its content: [`RobotModel::parse`] and
//! [`RobotModel::load`] return a usable model together with warnings that
//! say which line was wrong and what stood in for it. See
//! `docs/robot-model.md` for the format and every parameter.

mod docs;
mod entry;
mod limits;
mod load;
mod model;
mod names;
mod params;
mod parse;
mod ros2;
mod write;

pub use docs::{field_table_markdown, parameter_table_markdown};
pub use limits::{MAX_DEVICE_ID, MAX_MAGNITUDE, MAX_READINGS, MAX_SECTION_ENTRIES};
pub use model::{Device, ModelName, ModelWarning, NamedValue, Object, RobotModel};
pub use names::{SUPERVISOR, SUPERVISOR_FAULTS};
pub use params::{PARAMETER_SPECS, ParamDefault, ParamSpec, Valid, parameter_spec};
pub use ros2::{ROS2_SETTINGS, Ros2Setting, ros2_setting, ros2_table_markdown};
