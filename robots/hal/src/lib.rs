//! The hardware abstraction layer: everything the ILMR VM asks of a robot goes through
//! the [`Hal`] trait (the role of the dissertation's shared memory and intermediate
//! process, section 4.2). [`ScriptedRobot`] is a deterministic implementation for tests:
//! a kinematic integrator plus a script of timed sensor events, dropouts and failing
//! calls. [`Deadline`] runs any driver on its own thread and gives each call a
//! deadline, so that a driver that hangs cannot stop the VM's tick.
//!
//! Invariant: no call panics on any input; every failure is a [`HalError`] value.

mod deadline;
mod hal;
mod recorded;
mod scripted;
mod types;

pub use deadline::Deadline;
pub use hal::Hal;
pub use recorded::Recorded;
pub use scripted::{Call, Limits, OpMatch, OpOutcome, ScriptedRobot, Stream};
pub use types::{
    AsyncOp, BodyOffsets, BodyPose, Detection, DeviceReading, HalError, KnownMap, ManipTask, OpId,
    OpStatus, Pose, Scan, Side, Snapshot, Solid, segment_distance,
};
