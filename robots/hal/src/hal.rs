use crate::types::{AsyncOp, BodyPose, HalError, KnownMap, OpId, OpStatus, Pose, Snapshot};

/// What the VM needs from a robot. The VM calls [`Hal::update`] once at the start of
/// every tick with the logical time, then [`Hal::snapshot`], then whatever setpoints and
/// requests the tick's commands produce. A real robot's implementation reads and writes
/// its shared memory; a simulated one advances its world to `t`.
///
/// Every call may fail; the VM turns failures into trace events and variable states.
pub trait Hal {
    /// Brings the robot side up to logical time `t` in seconds (monotonic).
    fn update(&mut self, t: f64) -> Result<(), HalError>;

    /// Fills `out` with the latest sensor data. Implementations should reuse `out`'s
    /// buffers (`clone_from`) so that a steady run does not allocate.
    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError>;

    /// Speed (m/s, negative backwards) and steering curvature (1/m) setpoints.
    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError>;

    /// A reference value for a named actuator (`on` is 1, `off` is 0).
    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError>;

    /// The navigation mode (`automatic`, `scanner`, `gps`, `odo`).
    fn locmode(&mut self, mode: &str) -> Result<(), HalError>;

    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError>;

    /// Resets dead reckoning to `pose`.
    fn locate(&mut self, pose: Pose) -> Result<(), HalError>;

    /// Starts an operation that takes time; its outcome is read with [`Hal::poll`].
    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError>;

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError>;

    /// Gives up an operation that has not answered; the robot side should stop it.
    /// The default does nothing: a robot without cancellation lets it run out.
    fn cancel(&mut self, _op: OpId) -> Result<(), HalError> {
        Ok(())
    }

    /// The static map of the robot's surroundings, if it has one. The VM asks once,
    /// when it starts, and refuses movement targets inside its solids or outside its
    /// bounds.
    fn known_map(&mut self) -> Option<KnownMap> {
        None
    }

    /// The admissible reference values `(min, max)` of an actuator, from the robot
    /// model; `None` when the robot does not say (the VM then leaves the check to
    /// [`Hal::actuator`]).
    fn actuator_range(&mut self, _id: &str) -> Option<(f64, f64)> {
        None
    }
}
