//! The robots `ilmrc run` can drive. Every backend is a [`Hal`]; the run loop sees only
//! [`Robot`], so a simulated robot (`--robot moro|workpartner`, from `ilmr-sim`) plugs in
//! here as one more arm of [`open`].

use ilmr_hal::{
    AsyncOp, BodyPose, Hal, HalError, Limits, OpId, OpStatus, Pose, ScriptedRobot, Snapshot,
};
use ilmr_model::RobotModel;
use ilmr_vm::Config;

use super::scenario::Scenario;

/// What the run loop needs beyond the HAL: whether the robot has come to rest, since a
/// run does not end while it still moves.
pub trait Robot: Hal {
    fn at_rest(&self) -> bool;
}

impl Robot for ScriptedRobot {
    fn at_rest(&self) -> bool {
        self.speed().abs() < 1e-9
    }
}

/// `--robot none`: nothing to move or read. The checker has refused every command that
/// would ask for something; a bare `break` still commands speed 0, which is granted.
#[derive(Debug, Default)]
pub struct NoRobot;

fn none(what: &str) -> HalError {
    HalError::Unsupported(format!("{what}: the task runs with --robot none"))
}

impl Hal for NoRobot {
    fn update(&mut self, _t: f64) -> Result<(), HalError> {
        Ok(())
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        out.true_pose = None;
        Ok(())
    }

    fn set_motion(&mut self, speed: f64, _curvature: f64) -> Result<(), HalError> {
        if speed == 0.0 {
            Ok(())
        } else {
            Err(none("moving"))
        }
    }

    fn actuator(&mut self, id: &str, _value: f64) -> Result<(), HalError> {
        Err(none(id))
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        Err(none(mode))
    }

    fn bodypose(&mut self, _pose: BodyPose) -> Result<(), HalError> {
        Err(none("bodypose"))
    }

    fn locate(&mut self, _pose: Pose) -> Result<(), HalError> {
        Err(none("locate"))
    }

    fn start(&mut self, _op: &AsyncOp) -> Result<OpId, HalError> {
        Err(none("operation"))
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        Err(HalError::UnknownOp(op))
    }
}

impl Robot for NoRobot {
    fn at_rest(&self) -> bool {
        true
    }
}

/// A backend chosen at run time, behind one type for the VM.
pub struct AnyRobot(Box<dyn Robot>);

impl Hal for AnyRobot {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        self.0.update(t)
    }
    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        self.0.snapshot(out)
    }
    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        self.0.set_motion(speed, curvature)
    }
    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        self.0.actuator(id, value)
    }
    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        self.0.locmode(mode)
    }
    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
        self.0.bodypose(pose)
    }
    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        self.0.locate(pose)
    }
    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        self.0.start(op)
    }
    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        self.0.poll(op)
    }
}

impl Robot for AnyRobot {
    fn at_rest(&self) -> bool {
        self.0.at_rest()
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Backend {
    /// No robot: only control flow, arithmetic, waits and skills.
    None,
    /// The deterministic scripted robot of `ilmr-hal`, driven by `--scenario`.
    Scripted,
}

/// Opens a backend for a run. `seed` is for backends with noise; the scripted robot
/// has none and replays its scenario exactly.
pub fn open(
    backend: Backend,
    model: &RobotModel,
    scenario: &Scenario,
    _seed: u64,
) -> Result<AnyRobot, String> {
    match backend {
        Backend::None => {
            if scenario.drives_a_robot() {
                return Err(
                    "the scenario scripts a robot, but the task runs with --robot none".into(),
                );
            }
            Ok(AnyRobot(Box::new(NoRobot)))
        }
        Backend::Scripted => Ok(AnyRobot(Box::new(scenario.robot(limits(model))?))),
    }
}

/// The scripted robot moves within the model's limits.
fn limits(model: &RobotModel) -> Limits {
    Limits {
        acceleration: model.max_acceleration(),
        deceleration: model.max_deceleration(),
        curvature_rate: model.curinc(),
        max_curvature: model.max_curvature(),
        max_speed: model.max_speed(),
    }
}

/// The VM's physical tunables from the robot model (each `Config` field names the
/// ROBO.INI parameter it stands for).
pub fn config(model: &RobotModel) -> Config {
    let base = Config::default();
    Config {
        default_speed: model.default_speed(),
        max_curvature: model.max_curvature(),
        curinc: model.curinc(),
        turn_curvature: base.turn_curvature.min(model.max_curvature()),
        acceleration: model.max_acceleration(),
        deceleration: model.max_deceleration(),
        robot_width: model.robot_width(),
        robot_length: model.robot_length(),
        followwall_d: model.followwall_d(),
        obstacle_curvature: model.omax_curvature(),
        ..base
    }
}
