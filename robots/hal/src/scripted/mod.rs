//! [`ScriptedRobot`]: a deterministic robot for tests. It integrates speed and curvature
//! setpoints with rate limits and replays a script of timed sensor events.

mod kinematics;
mod script;

pub use kinematics::Limits;
pub use script::{Call, OpMatch, OpOutcome, Stream};

use std::collections::HashMap;

use ilmr_geometry::wrap_angle;
use kinematics::Kinematics;
use script::{OpRule, Periodic, Script, Sighting, TimedReading, TimedScan};

use crate::hal::Hal;
use crate::types::{
    AsyncOp, BodyPose, Detection, DeviceReading, HalError, KnownMap, OpId, OpStatus, Pose, Scan,
    Snapshot,
};

/// Largest integration step; `update` subdivides longer intervals.
const MAX_STEP: f64 = 0.01;

#[derive(Debug, Clone, PartialEq)]
struct RunningOp {
    op: AsyncOp,
    due_tick: u64,
    outcome: OpOutcome,
}

#[derive(Debug, Clone)]
pub struct ScriptedRobot {
    limits: Limits,
    kin: Kinematics,
    /// The frame `locate` sets, as a rigid transform of the true pose: the estimate is
    /// the true position rotated by `offset.h` and moved by (`offset.x`, `offset.y`),
    /// its heading turned by `offset.h`. Adding the offsets per component would skew
    /// the frame whenever the located heading differs from the true one.
    offset: Pose,
    t: f64,
    ticks: u64,
    script: Script,
    next_reading: usize,
    /// The scans due so far: the latest is the one before.
    next_scan: usize,
    devices: Vec<DeviceReading>,
    /// Each device's place in `devices` by its lower-cased name: a script of many
    /// devices would otherwise search them all for each reading.
    device_at: HashMap<String, usize>,
    ops: Vec<RunningOp>,
    actuator_log: Vec<(String, f64)>,
    locmode: Option<String>,
    bodypose: BodyPose,
    /// Scripted jumps of the estimate already applied.
    next_jump: usize,
    cancelled: Vec<OpId>,
    /// Every speed and curvature setpoint accepted, in order.
    setpoints: Vec<(f64, f64)>,
}

impl ScriptedRobot {
    pub fn new(limits: Limits) -> ScriptedRobot {
        ScriptedRobot {
            limits,
            kin: Kinematics::default(),
            offset: Pose::default(),
            t: 0.0,
            ticks: 0,
            script: Script::default(),
            next_reading: 0,
            next_scan: 0,
            devices: Vec::new(),
            device_at: HashMap::new(),
            ops: Vec::new(),
            actuator_log: Vec::new(),
            locmode: None,
            bodypose: BodyPose::default(),
            next_jump: 0,
            cancelled: Vec::new(),
            setpoints: Vec::new(),
        }
    }

    /// Starts the robot at `pose` (true and estimated).
    pub fn at(mut self, pose: Pose) -> ScriptedRobot {
        self.kin.pose = pose;
        self
    }

    /// From time `t` the device reads `value` (`None`: it gives no data).
    pub fn reading(mut self, t: f64, device: &str, value: Option<f64>) -> ScriptedRobot {
        self.script.readings.push(TimedReading {
            t,
            device: device.to_string(),
            value,
        });
        self.script.sorted = false;
        self
    }

    pub fn battery(self, t: f64, volts: f64) -> ScriptedRobot {
        self.reading(t, "battery", Some(volts))
    }

    /// The detection is in view from `from` to `until` seconds.
    pub fn sighting(mut self, from: f64, until: f64, detection: Detection) -> ScriptedRobot {
        self.script.sightings.push(Sighting {
            from,
            until,
            detection,
        });
        self
    }

    /// From time `scan.t` this is the latest scan.
    pub fn scan(mut self, scan: Scan) -> ScriptedRobot {
        self.script.scans.push(TimedScan { t: scan.t, scan });
        self.script.sorted = false;
        self
    }

    /// Operations matching `matcher` end with `outcome` `ticks` updates after they start.
    pub fn op(mut self, matcher: OpMatch, ticks: u32, outcome: OpOutcome) -> ScriptedRobot {
        self.script.op_rules.push(OpRule {
            matcher,
            ticks,
            outcome,
        });
        self
    }

    pub fn refuse_actuator(mut self, actuator: &str, reason: &str) -> ScriptedRobot {
        self.script
            .refused_actuators
            .push((actuator.to_string(), reason.to_string()));
        self
    }

    /// Restricts the navigation modes the robot accepts.
    pub fn locmodes(mut self, modes: &[&str]) -> ScriptedRobot {
        self.script.locmodes = modes.iter().map(|m| m.to_string()).collect();
        self
    }

    /// From time 0 a copy of `scan` is the latest every `period` seconds (stamped
    /// with the time it was taken), after any scans scripted one by one.
    pub fn scan_every(mut self, period: f64, scan: Scan) -> ScriptedRobot {
        self.script.scan_every = Some((
            Periodic {
                period,
                dropouts: Vec::new(),
            },
            scan,
        ));
        self
    }

    /// The robot reports an odometry sample every `period` seconds
    /// ([`Snapshot::odometry_t`]).
    pub fn odometry_every(mut self, period: f64) -> ScriptedRobot {
        self.script.odometry = Some(Periodic {
            period,
            dropouts: Vec::new(),
        });
        self
    }

    /// The robot reports a navigation fix every `period` seconds
    /// ([`Snapshot::nav_t`]).
    pub fn nav_every(mut self, period: f64) -> ScriptedRobot {
        self.script.nav = Some(Periodic {
            period,
            dropouts: Vec::new(),
        });
        self
    }

    /// The stream gives no new sample from `from` until `until` seconds: its latest
    /// sample stays the one before `from`. Only for a stream given with
    /// `scan_every`, `odometry_every` or `nav_every`.
    pub fn dropout(mut self, stream: Stream, from: f64, until: f64) -> ScriptedRobot {
        let periodic = match stream {
            Stream::Scanner => self.script.scan_every.as_mut().map(|(p, _)| p),
            Stream::Odometry => self.script.odometry.as_mut(),
            Stream::Nav => self.script.nav.as_mut(),
        };
        if let Some(p) = periodic {
            p.dropouts.push((from, until));
        }
        self
    }

    /// At time `t` the estimate jumps by `shift` (x, y in the estimate's frame,
    /// heading added), as a wrong navigation fix would move it.
    pub fn jump(mut self, t: f64, shift: Pose) -> ScriptedRobot {
        self.script.jumps.push((t, shift));
        self.script.jumps.sort_by(|a, b| a.0.total_cmp(&b.0));
        self
    }

    /// Calls of `call` fail with `error` from `from` until `until` seconds of robot
    /// time.
    pub fn fail(mut self, call: Call, from: f64, until: f64, error: HalError) -> ScriptedRobot {
        self.script.failures.push((call, from, until, error));
        self
    }

    /// The actuator admits `min..=max`, as its robot model says; the robot itself
    /// still accepts any value (the VM is what refuses).
    pub fn actuator_range(mut self, actuator: &str, min: f64, max: f64) -> ScriptedRobot {
        self.script
            .actuator_ranges
            .push((actuator.to_string(), min, max));
        self
    }

    pub fn known_map(mut self, map: KnownMap) -> ScriptedRobot {
        self.script.known_map = Some(map);
        self
    }

    /// Every speed and curvature setpoint accepted, in order.
    pub fn setpoints(&self) -> &[(f64, f64)] {
        &self.setpoints
    }

    /// Operations the VM gave up on.
    pub fn cancelled(&self) -> &[OpId] {
        &self.cancelled
    }

    pub fn true_pose(&self) -> Pose {
        self.kin.pose
    }

    pub fn speed(&self) -> f64 {
        self.kin.speed
    }

    /// Every accepted actuator call, in order.
    pub fn actuator_log(&self) -> &[(String, f64)] {
        &self.actuator_log
    }

    pub fn current_locmode(&self) -> Option<&str> {
        self.locmode.as_deref()
    }

    pub fn current_bodypose(&self) -> BodyPose {
        self.bodypose
    }

    fn estimated(&self) -> Pose {
        let p = self.kin.pose;
        let (sin, cos) = self.offset.h.sin_cos();
        Pose::new(
            cos * p.x - sin * p.y + self.offset.x,
            sin * p.x + cos * p.y + self.offset.y,
            p.h + self.offset.h,
        )
    }

    fn apply_jumps(&mut self) {
        while let Some(&(t, shift)) = self.script.jumps.get(self.next_jump) {
            if t > self.t + 1e-9 {
                break;
            }
            self.offset.x += shift.x;
            self.offset.y += shift.y;
            self.offset.h = wrap_angle(self.offset.h + shift.h);
            self.next_jump += 1;
        }
    }

    fn failing(&self, call: Call) -> Result<(), HalError> {
        match self.script.failure(call, self.t) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    fn apply_readings(&mut self) {
        self.script.sort(self.next_reading, self.next_scan);
        while let Some(r) = self.script.readings.get(self.next_reading) {
            if r.t > self.t + 1e-9 {
                break;
            }
            let key = r.device.to_ascii_lowercase();
            match self.device_at.get(&key) {
                Some(&at) => self.devices[at].value = r.value,
                None => {
                    self.device_at.insert(key, self.devices.len());
                    self.devices.push(DeviceReading {
                        name: r.device.clone(),
                        value: r.value,
                    });
                }
            }
            self.next_reading += 1;
        }
    }

    /// Counts the scans taken by now.
    fn catch_up_scans(&mut self) {
        self.script.sort(self.next_reading, self.next_scan);
        while (self.script.scans.get(self.next_scan)).is_some_and(|s| s.t <= self.t + 1e-9) {
            self.next_scan += 1;
        }
    }

    /// The latest scan taken by now (after [`Self::catch_up_scans`]).
    fn latest_scan(&self) -> Option<&Scan> {
        let latest = self.next_scan.checked_sub(1)?;
        self.script.scans.get(latest).map(|s| &s.scan)
    }
}

impl Hal for ScriptedRobot {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        if !t.is_finite() || t + 1e-12 < self.t {
            return Err(HalError::Link(format!(
                "time must not go backwards ({} after {})",
                t, self.t
            )));
        }
        // The robot's time goes on whether or not the call is answered.
        let failure = self.script.failure(Call::Update, t);
        let mut left = t - self.t;
        while left > 1e-12 {
            let dt = left.min(MAX_STEP);
            self.kin.step(&self.limits, dt);
            left -= dt;
        }
        self.t = t;
        self.ticks += 1;
        self.apply_readings();
        self.apply_jumps();
        match failure {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        self.failing(Call::Snapshot)?;
        out.t = self.t;
        out.odometry_t = self.script.odometry.as_ref().and_then(|p| p.latest(self.t));
        out.nav_t = self.script.nav.as_ref().and_then(|p| p.latest(self.t));
        out.pose = self.estimated();
        out.true_pose = Some(self.kin.pose);
        out.speed = self.kin.speed;
        out.curvature = self.kin.curvature;
        out.devices.clone_from(&self.devices);
        out.battery = self
            .device_at
            .get("battery")
            .and_then(|&at| self.devices[at].value);
        self.catch_up_scans();
        let latest_scan = self.latest_scan();
        match (latest_scan, out.scan.as_mut()) {
            (Some(s), Some(o)) => o.clone_from(s),
            (Some(s), None) => out.scan = Some(s.clone()),
            (None, _) => out.scan = None,
        }
        if let Some((periodic, scan)) = &self.script.scan_every
            && let Some(at) = periodic.latest(self.t)
            && latest_scan.is_none_or(|s| s.t <= at)
        {
            let o = out.scan.get_or_insert_with(Scan::default);
            o.clone_from(scan);
            o.t = at;
        }
        let t = self.t;
        let mut n = 0;
        for s in &self.script.sightings {
            if s.from <= t + 1e-9 && t <= s.until + 1e-9 {
                if let Some(slot) = out.detections.get_mut(n) {
                    slot.clone_from(&s.detection);
                } else {
                    out.detections.push(s.detection.clone());
                }
                n += 1;
            }
        }
        out.detections.truncate(n);
        Ok(())
    }

    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        if !speed.is_finite() || !curvature.is_finite() {
            return Err(HalError::Refused(format!(
                "setpoint is not a number (speed {speed}, curvature {curvature})"
            )));
        }
        self.failing(Call::SetMotion)?;
        self.kin.speed_set = speed;
        self.kin.curvature_set = curvature;
        self.setpoints.push((speed, curvature));
        Ok(())
    }

    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        self.failing(Call::Actuator)?;
        if let Some((_, why)) = self
            .script
            .refused_actuators
            .iter()
            .find(|(a, _)| a.eq_ignore_ascii_case(id))
        {
            return Err(HalError::Refused(why.clone()));
        }
        self.actuator_log.push((id.to_string(), value));
        Ok(())
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        let known = self.script.locmodes.is_empty()
            || self
                .script
                .locmodes
                .iter()
                .any(|m| m.eq_ignore_ascii_case(mode));
        if !known {
            return Err(HalError::Unsupported(format!("navigation mode {mode}")));
        }
        self.locmode = Some(mode.to_string());
        Ok(())
    }

    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
        self.failing(Call::BodyPose)?;
        self.bodypose = pose;
        Ok(())
    }

    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        if !(pose.x.is_finite() && pose.y.is_finite() && pose.h.is_finite()) {
            return Err(HalError::Refused("pose is not a number".into()));
        }
        let p = self.kin.pose;
        let turn = wrap_angle(pose.h - p.h);
        let (sin, cos) = turn.sin_cos();
        self.offset = Pose::new(
            pose.x - (cos * p.x - sin * p.y),
            pose.y - (sin * p.x + cos * p.y),
            turn,
        );
        Ok(())
    }

    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        self.failing(Call::Start)?;
        let rule = self.script.op_rules.iter().find(|r| r.matcher.matches(op));
        let (ticks, outcome) = match rule {
            Some(r) => (r.ticks, r.outcome.clone()),
            None => (1, OpOutcome::Done),
        };
        let id = u32::try_from(self.ops.len())
            .map_err(|_| HalError::Refused("too many operations".into()))?;
        self.ops.push(RunningOp {
            op: op.clone(),
            due_tick: self.ticks + u64::from(ticks),
            outcome,
        });
        Ok(OpId(id))
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        self.failing(Call::Poll)?;
        let running = self.ops.get(op.0 as usize).ok_or(HalError::UnknownOp(op))?;
        if self.cancelled.contains(&op) {
            return Ok(OpStatus::Failed("cancelled".into()));
        }
        if self.ticks < running.due_tick {
            return Ok(OpStatus::Pending);
        }
        Ok(match &running.outcome {
            OpOutcome::Done => OpStatus::Done,
            OpOutcome::Failed(why) => OpStatus::Failed(why.clone()),
        })
    }

    fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
        if self.ops.get(op.0 as usize).is_none() {
            return Err(HalError::UnknownOp(op));
        }
        if !self.cancelled.contains(&op) {
            self.cancelled.push(op);
        }
        Ok(())
    }

    fn known_map(&mut self) -> Option<KnownMap> {
        self.script.known_map.clone()
    }

    fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
        self.script
            .actuator_ranges
            .iter()
            .find(|(a, _, _)| a.eq_ignore_ascii_case(id))
            .map(|(_, min, max)| (*min, *max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::{ManipTask, Side};

    fn door() -> Detection {
        Detection {
            sensor: "scanner".into(),
            object: "door".into(),
            x: 3.0,
            y: 1.0,
            h: 0.0,
            side: Side::Left,
        }
    }

    fn run_to(robot: &mut ScriptedRobot, t: f64) -> Snapshot {
        let mut snap = Snapshot::default();
        robot.update(t).expect("monotonic time");
        robot.snapshot(&mut snap).expect("snapshot");
        snap
    }

    #[test]
    fn scripted_readings_and_sightings_appear_at_their_times() {
        let mut robot = ScriptedRobot::new(Limits::default())
            .battery(0.0, 25.0)
            .battery(1.0, 23.0)
            .sighting(0.5, 0.7, door());
        let s = run_to(&mut robot, 0.2);
        assert_eq!(s.battery, Some(25.0));
        assert!(s.detections.is_empty());
        let s = run_to(&mut robot, 0.6);
        assert_eq!(s.detections, vec![door()]);
        let s = run_to(&mut robot, 1.0);
        assert_eq!(s.battery, Some(23.0));
        assert!(s.detections.is_empty());
    }

    #[test]
    fn readings_scripted_out_of_order_come_in_time_order_ties_as_written() {
        let mut robot = ScriptedRobot::new(Limits::default())
            .battery(1.0, 23.0)
            .battery(0.0, 25.0)
            .battery(1.0, 22.0)
            .battery(0.5, 24.0);
        assert_eq!(run_to(&mut robot, 0.2).battery, Some(25.0));
        assert_eq!(run_to(&mut robot, 0.6).battery, Some(24.0));
        assert_eq!(run_to(&mut robot, 1.0).battery, Some(22.0), "the later tie");
    }

    #[test]
    fn a_device_is_one_whatever_the_letter_case_among_many() {
        let mut robot = ScriptedRobot::new(Limits::default())
            .reading(0.0, "Battery", Some(25.0))
            .reading(0.5, "BATTERY", Some(24.0));
        for i in 0..10_000 {
            robot = robot.reading(0.0, &format!("sonar{i}"), Some(f64::from(i)));
        }
        robot = robot.reading(0.5, "SONAR9999", None);
        let s = run_to(&mut robot, 0.2);
        assert_eq!(s.battery, Some(25.0));
        assert_eq!(s.devices.len(), 10_001);
        assert_eq!(s.devices[0].name, "Battery", "named as first read");
        let s = run_to(&mut robot, 0.6);
        assert_eq!(s.battery, Some(24.0));
        assert_eq!(s.devices.len(), 10_001);
        assert_eq!(s.devices[10_000].value, None);
        assert_eq!(s.devices[9_999].value, Some(9_998.0));
    }

    #[test]
    fn the_latest_scan_is_the_last_taken_by_now_whatever_the_order_scripted() {
        let scan = |t: f64, r: f64| Scan {
            device: "scanner".into(),
            t,
            angle_min: 0.0,
            angle_step: 0.1,
            ranges: vec![r],
        };
        let mut robot = ScriptedRobot::new(Limits::default())
            .scan(scan(1.0, 3.0))
            .scan(scan(0.0, 1.0))
            .scan(scan(1.0, 4.0))
            .scan(scan(0.5, 2.0));
        let mut snap = Snapshot::default();
        robot.snapshot(&mut snap).expect("snapshot");
        assert_eq!(
            snap.scan.map(|s| s.ranges),
            Some(vec![1.0]),
            "before any update"
        );
        let range = |s: Snapshot| s.scan.map(|s| s.ranges[0]);
        assert_eq!(range(run_to(&mut robot, 0.7)), Some(2.0));
        assert_eq!(range(run_to(&mut robot, 1.0)), Some(4.0), "the later tie");
    }

    #[test]
    fn operations_complete_or_fail_after_their_ticks() {
        let mut robot = ScriptedRobot::new(Limits::default()).op(
            OpMatch::Manipulate(ManipTask::Take),
            3,
            OpOutcome::Failed("gripper empty".into()),
        );
        let take = robot
            .start(&AsyncOp::Manipulate(ManipTask::Take))
            .expect("start");
        let init = robot.start(&AsyncOp::Init(vec![])).expect("start");
        robot.update(0.01).expect("time");
        assert_eq!(robot.poll(init), Ok(OpStatus::Done));
        assert_eq!(robot.poll(take), Ok(OpStatus::Pending));
        robot.update(0.02).expect("time");
        robot.update(0.03).expect("time");
        assert_eq!(
            robot.poll(take),
            Ok(OpStatus::Failed("gripper empty".into()))
        );
        assert_eq!(robot.poll(OpId(9)), Err(HalError::UnknownOp(OpId(9))));
    }

    #[test]
    fn streams_stop_in_their_dropouts_and_calls_fail_when_scripted() {
        let mut robot = ScriptedRobot::new(Limits::default())
            .odometry_every(0.1)
            .dropout(Stream::Odometry, 1.0, 2.0)
            .nav_every(0.5)
            .fail(Call::SetMotion, 0.5, 0.6, HalError::Link("cable".into()))
            .jump(0.3, Pose::new(1.0, 0.0, 0.0));
        let s = run_to(&mut robot, 0.25);
        assert_eq!((s.odometry_t, s.nav_t), (Some(0.2), Some(0.0)));
        assert_eq!(s.pose, Pose::default());
        let s = run_to(&mut robot, 1.55);
        assert_eq!(
            s.odometry_t,
            Some(0.9),
            "the last sample before the dropout"
        );
        assert_eq!(s.nav_t, Some(1.5));
        assert_eq!(s.pose.x, 1.0, "the estimate jumped at 0.3 s");
        let s = run_to(&mut robot, 2.05);
        assert_eq!(s.odometry_t, Some(2.0));
        robot.update(2.1).expect("time");
        assert!(robot.set_motion(0.1, 0.0).is_ok());
        let mut early = ScriptedRobot::new(Limits::default()).fail(
            Call::SetMotion,
            0.0,
            1.0,
            HalError::Link("cable".into()),
        );
        assert_eq!(
            early.set_motion(0.1, 0.0),
            Err(HalError::Link("cable".into()))
        );
        assert!(early.setpoints().is_empty());
    }

    #[test]
    fn a_known_map_measures_from_its_solids_surface() {
        let map = KnownMap {
            bounds: Some((0.0, 0.0, 10.0, 5.0)),
            solids: vec![
                crate::types::Solid {
                    a: (2.0, 0.0),
                    b: (2.0, 4.0),
                    radius: 0.1,
                    name: None,
                },
                crate::types::Solid {
                    a: (6.0, 2.0),
                    b: (6.0, 2.0),
                    radius: 0.5,
                    name: None,
                },
            ],
        };
        let (i, d) = map.nearest((1.0, 2.0)).expect("solids");
        assert_eq!(i, 0);
        assert!((d - 0.9).abs() < 1e-12);
        let (i, d) = map.nearest((6.0, 2.2)).expect("solids");
        assert_eq!(i, 1);
        assert!(d < 0.0, "inside the round obstacle");
        assert!(map.contains((9.0, 4.0)) && !map.contains((11.0, 1.0)));
        assert!(KnownMap::default().contains((1e9, -1e9)), "unbounded");
    }

    #[test]
    fn bad_inputs_are_errors_not_panics() {
        let mut robot = ScriptedRobot::new(Limits::default()).refuse_actuator("brake", "locked");
        assert!(robot.set_motion(f64::NAN, 0.0).is_err());
        assert!(robot.update(1.0).is_ok());
        assert!(robot.update(0.5).is_err());
        assert_eq!(
            robot.actuator("BRAKE", 1.0),
            Err(HalError::Refused("locked".into()))
        );
    }

    #[test]
    fn locate_shifts_the_estimate_not_the_truth() {
        let mut robot = ScriptedRobot::new(Limits::default());
        robot.locate(Pose::new(2.0, 3.0, 0.5)).expect("finite pose");
        let s = run_to(&mut robot, 0.1);
        assert_eq!(s.pose, Pose::new(2.0, 3.0, 0.5));
        assert_eq!(s.true_pose, Some(Pose::default()));
    }

    #[test]
    fn after_locate_the_robot_moves_along_its_located_heading() {
        let mut robot = ScriptedRobot::new(Limits::default());
        // Truly at the origin facing +x; told it stands at (5, 1) facing -x.
        robot
            .locate(Pose::new(5.0, 1.0, std::f64::consts::PI))
            .expect("finite pose");
        robot.set_motion(0.5, 0.0).expect("drives");
        let s = run_to(&mut robot, 4.0);
        let truth = s.true_pose.expect("scripted robots know the truth");
        let travelled = truth.x;
        assert!(travelled > 0.5, "it moved: {truth:?}");
        // Forward in the located frame is -x: x falls by what was travelled, y stays.
        assert!((s.pose.x - (5.0 - travelled)).abs() < 1e-9, "{:?}", s.pose);
        assert!((s.pose.y - 1.0).abs() < 1e-9, "{:?}", s.pose);
    }
}
