//! Run-time refusal of harmful commands whose values are computed (the compiler
//! refuses the literal ones): a speed beyond `max_speed`, an actuator value out of
//! its range, a body pose out of its limits or impossible in the movement mode, a
//! movement target inside a wall, off the known map or on a scanned obstacle, a
//! movement while parked or locked out. A refused command ends `refused` with its
//! code before anything is sent to the robot.

use ilmr_hal::Hal;
use ilmr_stdlib::Command;

use super::codes::{Code, Fault};
use crate::bytecode::{Arg, ArgRange};
use crate::runtime::Vm;
use crate::runtime::clock::Clock;
use crate::runtime::trace::fmt_num;

/// Why a command is refused: a stable code when the refusal is one of issue 7's
/// guarantees, and the message for the trace.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Refusal {
    pub code: Option<Code>,
    pub message: String,
}

impl Refusal {
    pub fn new(code: Code, message: String) -> Refusal {
        Refusal {
            code: Some(code),
            message,
        }
    }
}

impl From<String> for Refusal {
    fn from(message: String) -> Refusal {
        Refusal {
            code: None,
            message,
        }
    }
}

/// Room the body pose limits leave for rounding, degrees or metres.
const POSE_SLACK: f64 = 1e-9;

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Checks an instant command's computed values before it is decoded and sent.
    pub(in crate::runtime) fn refuse_unsafe(
        &mut self,
        command: Command,
        r: ArgRange,
    ) -> Result<(), Refusal> {
        match command {
            Command::Speed => {
                let v = self.number(self.arg(r, 0))?;
                self.check_speed(v)
            }
            Command::Actuator => self.check_actuator(r),
            Command::BodyPose => self.check_bodypose(r),
            _ => Ok(()),
        }
    }

    fn check_speed(&self, v: f64) -> Result<(), Refusal> {
        let max = self.cfg.safety.max_speed;
        if v.is_finite() && v.abs() <= max + POSE_SLACK {
            return Ok(());
        }
        Err(Refusal::new(
            Code::SpeedLimit,
            format!("speed {} m/s is beyond max_speed {max} m/s", fmt_num(v)),
        ))
    }

    fn check_actuator(&mut self, r: ArgRange) -> Result<(), Refusal> {
        let Some(Arg::Word(id)) = self.arg(r, 0) else {
            return Ok(());
        };
        let value = match self.arg(r, 1) {
            // `on`/`off` are 1 and 0; decode refuses other words.
            Some(Arg::Word(_)) => return Ok(()),
            a => self.number(a)?,
        };
        let name = self.module.name(id).to_string();
        let range = self.hal.actuator_range(&name);
        match range {
            _ if !value.is_finite() => Err(Refusal::new(
                Code::ActuatorRange,
                format!("{name} value {value} is not a number"),
            )),
            Some((min, max)) if !(min..=max).contains(&value) => Err(Refusal::new(
                Code::ActuatorRange,
                format!("{name} takes {min}..{max}, not {}", fmt_num(value)),
            )),
            _ => Ok(()),
        }
    }

    fn check_bodypose(&mut self, r: ArgRange) -> Result<(), Refusal> {
        let roll = self.setting(r, "r")?;
        let pitch = self.setting(r, "p")?;
        let clearance = self.setting(r, "rc")?;
        let Some(limits) = self.cfg.safety.body else {
            return Err(Refusal::new(
                Code::BodyPoseRange,
                "this robot has no body pose".into(),
            ));
        };
        let checks = [
            ("roll", roll, -limits.max_roll, limits.max_roll, "deg"),
            ("pitch", pitch, -limits.max_pitch, limits.max_pitch, "deg"),
            ("road clearance", clearance, 0.0, limits.max_clearance, "m"),
        ];
        for (what, value, min, max, unit) in checks {
            if let Some(v) = value
                && !(v.is_finite() && v >= min - POSE_SLACK && v <= max + POSE_SLACK)
            {
                return Err(Refusal::new(
                    Code::BodyPoseRange,
                    format!(
                        "{what} {} {unit} is outside {min}..{max} {unit}",
                        fmt_num(v)
                    ),
                ));
            }
        }
        // Section 5.1: in parking every joint is locked; in rolking the legs slide
        // along the ground to drive, so they carry the body level and only its
        // height can change.
        match self.movement_mode() {
            Some(m) if m.eq_ignore_ascii_case("parking") => Err(Refusal::new(
                Code::BodyPoseMode,
                "every joint is locked in parking mode".into(),
            )),
            Some(m)
                if m.eq_ignore_ascii_case("rolking")
                    && [roll, pitch].iter().flatten().any(|a| a.abs() > POSE_SLACK) =>
            {
                Err(Refusal::new(
                    Code::BodyPoseMode,
                    "in rolking mode the legs drive and keep the body level: only rc may change"
                        .into(),
                ))
            }
            _ => Ok(()),
        }
    }

    /// The movement mode the robot is in, as far as the VM has seen `movemode`
    /// complete; `None` before any.
    fn movement_mode(&self) -> Option<&str> {
        self.move_mode.map(|n| self.module.name(n))
    }

    /// May a movement take the reservation now?
    pub(in crate::runtime) fn check_movement_allowed(&self) -> Result<(), Refusal> {
        if let Some(f) = self.supervisor.locking() {
            return Err(Refusal::new(
                Code::MovementLocked,
                format!("movement is locked while {} lasts", f.name()),
            ));
        }
        if self
            .movement_mode()
            .is_some_and(|m| m.eq_ignore_ascii_case("parking"))
        {
            return Err(Refusal::new(
                Code::Parked,
                "every joint and actuator is locked in parking mode".into(),
            ));
        }
        Ok(())
    }

    /// A `gotoxy`/`gotorelxy` target: inside the known map's bounds, clear of its
    /// solids and of the scanned points by half the robot's width.
    pub(in crate::runtime) fn check_target(&self, x: f64, y: f64) -> Result<(), Refusal> {
        let half = 0.5 * self.cfg.robot_width;
        if let Some(map) = &self.known_map {
            let on_map = super::frame::to_map(self.map_from_estimate, (x, y));
            if !map.contains(on_map) {
                return Err(Refusal::new(
                    Code::TargetOffMap,
                    format!("({x:.2}, {y:.2}) is outside the known map"),
                ));
            }
            if let Some((i, d)) = map.nearest(on_map)
                && d < half
            {
                // The site plan's name for the solid where it gives one.
                let what = match map.solids.get(i).and_then(|s| s.name.as_deref()) {
                    Some(name) => format!("the wall `{name}`"),
                    None => format!("solid {i} of the known map"),
                };
                return Err(Refusal::new(
                    Code::TargetInWall,
                    format!(
                        "({x:.2}, {y:.2}) is {:.2} m from {what}; the robot needs {half:.2} m",
                        d.max(0.0)
                    ),
                ));
            }
        }
        let near = self
            .motion
            .map_points()
            .iter()
            .map(|p| (p.x - x).hypot(p.y - y))
            .fold(f64::INFINITY, f64::min);
        if near < half {
            return Err(Refusal::new(
                Code::TargetOnObstacle,
                format!(
                    "({x:.2}, {y:.2}) is {near:.2} m from a scanned obstacle; the robot needs {half:.2} m"
                ),
            ));
        }
        Ok(())
    }

    /// Ends the running movement as refused by a supervisor fault.
    pub(in crate::runtime) fn end_movement_for(&mut self, fault: Fault, message: String) {
        if let Some(head) = self.motion.head
            && self.nodes.alive(head)
        {
            self.end_coded(head.idx, Code::Fault(fault), message);
        }
    }
}
