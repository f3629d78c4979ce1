//! The hardware abstraction layer: everything the ILMR VM asks of a robot goes through
//! the [`Hal`] trait (the role of the dissertation's shared memory and intermediate
//! process, section 4.2). [`ScriptedRobot`] is a deterministic implementation for tests:
//! a kinematic integrator plus a script of timed sensor events.
//!
//! Invariant: no call panics on any input; every failure is a [`HalError`] value.

mod hal;
mod scripted;
mod types;

pub use hal::Hal;
pub use scripted::{Limits, OpMatch, OpOutcome, ScriptedRobot};
pub use types::{
    AsyncOp, BodyPose, Detection, DeviceReading, HalError, ManipTask, OpId, OpStatus, Pose, Scan,
    Side, Snapshot,
};
