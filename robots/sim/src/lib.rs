//! A deterministic 2D simulator of ILMR's two robots, MoRo and Workpartner
//! (Kauppi 2004, chapter 5), stepped by the caller with a fixed dt.
//!
//! ```
//! use ilmr_sim::{RobotConfig, Simulator, world};
//! let office = world::shipped("office").unwrap().unwrap();
//! let mut sim = Simulator::new(RobotConfig::moro(), office, 7).unwrap();
//! sim.set_setpoints(0.3, 0.0).unwrap();
//! for _ in 0..100 {
//!     sim.step(0.01).unwrap();
//! }
//! let seen = sim.snapshot();
//! assert!(seen.scan.is_some());
//! assert!(sim.true_pose().x > 4.0);
//! ```

pub mod config;
pub mod faults;
pub mod geometry;
pub mod kinematics;
pub mod profile;
mod robot;
pub mod sensors;
mod sim;
pub mod world;

/// The seeded generator behind every noise source (ilmr-geometry's, shared with the
/// layers above so that a seed means the same thing everywhere).
pub use ilmr_geometry::rng;

pub use config::{RobotConfig, RobotKind};
pub use faults::{FaultKind, FaultPlan, FaultSpec};
pub use geometry::{PlaneVector, Point2, Pose, Vector2};
pub use kinematics::{BodyPose, MovementMode};
pub use profile::SimProfile;
pub use robot::{
    BALL_SECONDS, INIT_SECONDS, LEAVE_SECONDS, MOVEMODE_SECONDS, STEP, SimRobot, TAKE_SECONDS,
    config_from_model,
};
pub use sim::{Contact, EventKind, Faults, SensorSnapshot, SimError, SimEvent, Simulator};
pub use world::{World, WorldError};
