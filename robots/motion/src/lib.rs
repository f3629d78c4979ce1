//! Robot-independent motion algorithms of ILMR (dissertation section 4.5):
//! Bezier reference paths, the predictive curvature position controller,
//! obstacle avoidance and wall following. Pure functions and plain state
//! machines over poses, paths and point clouds: no I/O, no robot, no VM.

pub mod arc;
pub mod bezier;
pub mod controller;
pub mod obstacle;
pub mod path;
pub mod pose;
pub mod wall;

pub use bezier::{CubicBezier, Plan, PlanError, PlanParams, plan_to_pose, plan_with};
pub use path::{Direction, Path, PathError, PathPoint};
pub use pose::{Pose, Side};
