//! `SimRobot`: the HAL of `ilmr-hal` implemented over the simulator for
//! MoRo and Workpartner, so the VM drives a simulated robot exactly as it
//! would drive a real one through its driver.
//!
//! The VM calls `update(t)` at the start of every 10 ms tick; the simulator
//! is stepped in 10 ms steps up to `t`, so both run in lockstep.

mod detect;
mod doors;
mod known_map;
mod model;
mod objects;
mod ops;

pub use model::config_from_model;
pub use ops::{BALL_SECONDS, INIT_SECONDS, LEAVE_SECONDS, MOVEMODE_SECONDS, TAKE_SECONDS};

use crate::config::RobotKind;
use crate::kinematics::{BodyPose as SimBodyPose, MovementMode};
use crate::sim::{SimError, Simulator};
use crate::world::World;
use ilmr_hal::{
    AsyncOp, BodyPose, DeviceReading, Hal, HalError, KnownMap, ManipTask, OpId, OpStatus, Pose,
    Scan, Snapshot,
};
use ilmr_model::RobotModel;
use ops::Ops;

/// The simulator's step, s: the VM's tick.
pub const STEP: f64 = 0.01;

/// A simulated robot behind the HAL.
#[derive(Debug, Clone)]
pub struct SimRobot {
    sim: Simulator,
    model: RobotModel,
    ops: Ops,
    locmode: String,
    actuators: Vec<(String, f64)>,
    /// Speed and curvature last asked for; a brake holds the speed at 0.
    setpoint: (f64, f64),
    /// Sequence number of the last scan searched for doors and objects.
    seen_scan: u64,
    /// Operations whose answer a silent manipulator lost: they never complete.
    lost_ops: Vec<OpId>,
}

fn hal_err(e: SimError) -> HalError {
    match e {
        SimError::Unsupported { .. } => HalError::Unsupported(e.to_string()),
        _ => HalError::Refused(e.to_string()),
    }
}

impl SimRobot {
    /// `kind` in `world`, configured from `model`; every noise source seeded
    /// from `seed`.
    pub fn new(
        model: RobotModel,
        kind: RobotKind,
        world: World,
        seed: u64,
    ) -> Result<SimRobot, SimError> {
        let cfg = config_from_model(&model, kind);
        SimRobot::from_config(model, cfg, world, seed)
    }

    /// As [`SimRobot::new`], with `profile`'s errors (`basic` is what `new` builds).
    pub fn with_profile(
        model: RobotModel,
        kind: RobotKind,
        profile: crate::SimProfile,
        world: World,
        seed: u64,
    ) -> Result<SimRobot, SimError> {
        let cfg = profile.apply(config_from_model(&model, kind));
        SimRobot::from_config(model, cfg, world, seed)
    }

    /// A robot with a simulator configuration of its own (for fitting the
    /// error model); `model` is what its software is told.
    pub fn from_config(
        model: RobotModel,
        cfg: crate::RobotConfig,
        world: World,
        seed: u64,
    ) -> Result<SimRobot, SimError> {
        let sim = Simulator::new(cfg, world, seed)?;
        Ok(SimRobot {
            sim,
            model,
            ops: Ops::default(),
            locmode: "automatic".into(),
            actuators: Vec::new(),
            setpoint: (0.0, 0.0),
            seen_scan: u64::MAX,
            lost_ops: Vec::new(),
        })
    }

    /// MoRo with its shipped model.
    pub fn moro(world: World, seed: u64) -> Result<SimRobot, SimError> {
        let model = RobotModel::builtin("moro")
            .ok_or_else(|| SimError::Config("no built-in model moro".into()))?;
        SimRobot::new(model, RobotKind::Moro, world, seed)
    }

    /// Workpartner with its shipped model (Figure 39 and additions).
    pub fn workpartner(world: World, seed: u64) -> Result<SimRobot, SimError> {
        let model = RobotModel::builtin("workpartner")
            .ok_or_else(|| SimError::Config("no built-in model workpartner".into()))?;
        SimRobot::new(model, RobotKind::Workpartner, world, seed)
    }

    pub fn sim(&self) -> &Simulator {
        &self.sim
    }

    /// For tests that inject faults, move the estimate or drain the battery.
    pub fn sim_mut(&mut self) -> &mut Simulator {
        &mut self.sim
    }

    pub fn model(&self) -> &RobotModel {
        &self.model
    }

    /// Ground truth in the world frame, for traces.
    pub fn true_pose(&self) -> Pose {
        self.sim.true_pose()
    }

    pub fn locmode_name(&self) -> &str {
        &self.locmode
    }

    /// Actuator references in the order they were first set.
    pub fn actuator_values(&self) -> &[(String, f64)] {
        &self.actuators
    }

    fn braked(&self) -> bool {
        self.actuators
            .iter()
            .any(|(n, v)| n.eq_ignore_ascii_case("brake") && *v != 0.0)
    }

    fn apply_setpoints(&mut self) -> Result<(), HalError> {
        let (v, c) = self.setpoint;
        let v = if self.braked() { 0.0 } else { v };
        self.sim.set_setpoints(v, c).map_err(hal_err)
    }

    /// Ends the operations that are due, deciding their outcome now.
    fn complete_ops(&mut self) {
        for (id, op) in self.ops.due(self.sim.time()) {
            if self.lost_ops.contains(&id) {
                continue;
            }
            if self.sim.faults.manipulator_silent && matches!(op, AsyncOp::Manipulate(_)) {
                self.lost_ops.push(id);
                continue;
            }
            let status = match op {
                AsyncOp::Init(_) => OpStatus::Done,
                AsyncOp::Manipulate(ManipTask::Take) => outcome(self.sim.take_box().map(drop)),
                AsyncOp::Manipulate(ManipTask::Leave) => outcome(self.sim.leave_box().map(drop)),
                AsyncOp::Manipulate(ManipTask::GetBall | ManipTask::GiveBall) => OpStatus::Done,
                AsyncOp::MoveMode(name) => match movement_mode(&name) {
                    Some(mode) => outcome(self.sim.set_movement_mode(mode)),
                    None => OpStatus::Failed(format!("no movement mode {name}")),
                },
            };
            self.ops.finish(id, status);
        }
    }

    fn device_values(&self, out: &mut Vec<DeviceReading>) {
        let seen = self.sim.snapshot();
        out.clear();
        for d in &self.model.devices {
            let value = match d.name.to_ascii_lowercase().as_str() {
                "battery" => Some(seen.battery.voltage),
                "gyro" => seen.gyro.map(|g| g.heading.to_degrees()),
                "frontwheel" => Some(seen.steering_angle.to_degrees()),
                "plates" => Some(f64::from(u8::from(
                    seen.plate.is_some_and(|p| p.time >= seen.time - STEP / 2.0),
                ))),
                "odometry" => Some(seen.odometry.distance),
                "ultrasonic" => seen
                    .ultrasonic
                    .map(|u| u.ranges.iter().copied().fold(f64::INFINITY, f64::min) * 1000.0),
                "laser" => seen
                    .camera
                    .as_ref()
                    .and_then(|c| c.laser)
                    .map(|m| m * 1000.0),
                "camera" => seen
                    .camera
                    .as_ref()
                    .and_then(|c| c.detections.first())
                    .map(|d| d.bearing.to_degrees()),
                "inclinometer" => seen.body_pose.map(|b| b.roll.to_degrees()),
                "scanner" => seen
                    .scan
                    .as_ref()
                    .map(|s| s.ranges.iter().copied().fold(f64::INFINITY, f64::min) * 1000.0),
                _ => self
                    .actuators
                    .iter()
                    .find(|(n, _)| n.eq_ignore_ascii_case(&d.name))
                    .map(|(_, v)| *v),
            };
            out.push(DeviceReading {
                name: d.name.clone(),
                value,
            });
        }
    }
}

fn outcome(r: Result<(), SimError>) -> OpStatus {
    match r {
        Ok(()) => OpStatus::Done,
        Err(e) => OpStatus::Failed(e.to_string()),
    }
}

fn movement_mode(name: &str) -> Option<MovementMode> {
    [
        ("wheels", MovementMode::Wheels),
        ("rolking", MovementMode::Rolking),
        ("parking", MovementMode::Parking),
    ]
    .into_iter()
    .find(|(n, _)| n.eq_ignore_ascii_case(name))
    .map(|(_, m)| m)
}

impl Hal for SimRobot {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        if !t.is_finite() {
            return Err(HalError::Link(format!("time {t} is not finite")));
        }
        // Whole steps up to t; the last one shorter when t is off the grid.
        while self.sim.time() < t - 1e-9 {
            let dt = (t - self.sim.time()).clamp(1e-6, STEP);
            self.sim.step(dt).map_err(hal_err)?;
            self.complete_ops();
        }
        self.complete_ops();
        Ok(())
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        let seen = self.sim.snapshot();
        let stamp = seen.pose;
        out.t = seen.time;
        out.pose = stamp;
        out.true_pose = Some(self.true_pose());
        out.speed = seen.speed;
        out.curvature = seen.curvature;
        out.battery = Some(seen.battery.voltage);
        out.odometry_t = Some(seen.odometry_time);
        out.nav_t = seen.nav_fix.map(|f| f.time);
        match &seen.scan {
            Some(s) => {
                let scan = out.scan.get_or_insert_with(Scan::default);
                if scan.device != "scanner" {
                    scan.device = "scanner".into();
                }
                scan.t = s.time;
                scan.angle_min = s.angle_min;
                scan.angle_step = s.angle_increment;
                scan.ranges.clone_from(&s.ranges);
            }
            None => out.scan = None,
        }
        let mut devices = std::mem::take(&mut out.devices);
        self.device_values(&mut devices);
        out.devices = devices;
        out.detections.clear();
        if let Some(scan) = &seen.scan {
            // Doors and objects are reported once, when the scan that shows them arrives.
            if scan.seq != self.seen_scan {
                self.seen_scan = scan.seq;
                doors::doors(&self.model, scan, stamp, &mut out.detections);
                objects::objects(&self.model, scan, stamp, &mut out.detections);
            }
            if let (Some(frame), Some(cam)) = (&seen.camera, &self.sim.config().camera) {
                let eye = stamp.to_world(&cam.head);
                let found = &mut out.detections;
                detect::camera_objects(&self.model, frame, eye, stamp, scan, found);
            }
        }
        if let (Some(frame), Some(cam)) = (&seen.camera, &self.sim.config().camera) {
            let eye = stamp.to_world(&cam.head);
            detect::laser_spot(&self.model, frame, eye, stamp, &mut out.detections);
        }
        Ok(())
    }

    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        if !(speed.is_finite() && curvature.is_finite()) {
            return Err(HalError::Refused(
                "speed and curvature must be finite".into(),
            ));
        }
        if self.sim.faults.drive_unresponsive {
            return Err(HalError::Timeout(
                "the drive controller does not answer".into(),
            ));
        }
        self.setpoint = (speed, curvature);
        self.apply_setpoints()
    }

    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        let Some(d) = self.model.device(id) else {
            return Err(HalError::Unsupported(format!("no actuator {id}")));
        };
        if !(value.is_finite() && value >= d.min && value <= d.max) {
            return Err(HalError::Refused(format!(
                "{} takes {}..{}, not {value}",
                d.name, d.min, d.max
            )));
        }
        if self.sim.faults.actuator_dead(&d.name) {
            return Err(HalError::Timeout(format!("{} does not answer", d.name)));
        }
        let name = d.name.clone();
        match self.actuators.iter_mut().find(|(n, _)| *n == name) {
            Some(entry) => entry.1 = value,
            None => self.actuators.push((name, value)),
        }
        self.apply_setpoints()
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        match self.model.identifier(mode) {
            Some(_) => {
                self.locmode = mode.to_ascii_lowercase();
                Ok(())
            }
            None => Err(HalError::Unsupported(format!(
                "no localisation mode {mode}"
            ))),
        }
    }

    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
        let now = self
            .sim
            .snapshot()
            .body_pose
            .ok_or_else(|| HalError::Unsupported("this robot has no body pose".into()))?;
        let target = SimBodyPose {
            roll: pose.roll.map_or(now.roll, f64::to_radians),
            pitch: pose.pitch.map_or(now.pitch, f64::to_radians),
            clearance: pose.clearance.unwrap_or(now.clearance),
        };
        self.sim.set_body_pose(target).map_err(hal_err)
    }

    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        self.sim
            // A pose from a task (`setpose`) may give its heading beyond a half turn.
            .locate(pose.wrapped())
            .map_err(hal_err)
    }

    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        let workpartner = self.sim.config().kind == RobotKind::Workpartner;
        match op {
            AsyncOp::Init(names) => {
                if let Some(unknown) = names.iter().find(|n| self.model.lookup(n).is_none()) {
                    return Err(HalError::Unsupported(format!(
                        "nothing called {unknown} to initialise"
                    )));
                }
            }
            AsyncOp::Manipulate(task) => {
                if self.model.device("manipulator").is_none() {
                    return Err(HalError::Unsupported(format!(
                        "{task:?}: this robot has no manipulator"
                    )));
                }
                if self.ops.manipulating() {
                    return Err(HalError::Refused("the manipulator is busy".into()));
                }
            }
            AsyncOp::MoveMode(name) => {
                if movement_mode(name).is_none() {
                    return Err(HalError::Unsupported(format!("no movement mode {name}")));
                }
                if !workpartner && !name.eq_ignore_ascii_case("wheels") {
                    return Err(HalError::Unsupported(format!(
                        "this robot has no {name} mode"
                    )));
                }
                if self.sim.true_speed().abs() > 0.01 {
                    return Err(HalError::Refused(
                        "change the movement mode standing still".into(),
                    ));
                }
            }
        }
        Ok(self.ops.push(op.clone(), self.sim.time()))
    }

    fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
        let pending = self.ops.get(op).ok_or(HalError::UnknownOp(op))?;
        if pending.status == OpStatus::Pending {
            self.ops
                .finish(op, OpStatus::Failed("cancelled by the VM".into()));
        }
        Ok(())
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        self.ops
            .get(op)
            .map(|p| p.status.clone())
            .ok_or(HalError::UnknownOp(op))
    }

    fn known_map(&mut self) -> Option<KnownMap> {
        Some(known_map::known_map(self.sim.world()))
    }

    fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
        self.model.device(id).map(|d| (d.min, d.max))
    }
}

/// What the simulated MoRo's scanner reads, noise-free, standing at `pose` in `scene`:
/// the detectors' tests build their scans with it.
#[cfg(test)]
fn scan_at(scene: &crate::geometry::Scene, pose: crate::geometry::Pose) -> crate::sensors::Scan {
    let cfg = crate::config::RobotConfig::moro().scanner;
    let fov = cfg.fov_deg.to_radians();
    crate::sensors::Scan {
        seq: 0,
        time: 0.0,
        pose,
        angle_min: -fov / 2.0,
        angle_increment: fov / (cfg.readings - 1) as f64,
        max_range: cfg.max_range,
        mount: cfg.mount,
        ranges: crate::sensors::cast_scan(scene, &cfg, pose),
    }
}
