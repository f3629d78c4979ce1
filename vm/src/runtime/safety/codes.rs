//! The stable codes of run-time refusals (`R01xx`) and supervisor faults (`R02xx`),
//! with the names and reactions `docs/reliability.md` lists. Tools may match on the
//! codes; `vm/tests/safety.rs` checks that the docs list every one of [`CODES`].

/// Why the VM refused a command at run time, or which supervisor fault ended it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Code {
    /// A speed beyond `max_speed`, or not a number.
    SpeedLimit,
    /// An actuator value outside the model's range for it.
    ActuatorRange,
    /// A body pose outside the model's roll, pitch or clearance limits.
    BodyPoseRange,
    /// A body pose the robot cannot take in its current movement mode.
    BodyPoseMode,
    /// A movement target inside a solid of the known map.
    TargetInWall,
    /// A movement target outside the known map's bounds.
    TargetOffMap,
    /// A movement target on an obstacle the scanner has mapped.
    TargetOnObstacle,
    /// A movement while a fault locks movement.
    MovementLocked,
    /// A movement in `parking` mode, where every joint is locked.
    Parked,
    /// A path to a target pose that bends more than `max_curvature` allows.
    PathTooCurved,
    Fault(Fault),
}

/// A condition the supervisor watches every tick.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Fault {
    BatteryLow,
    ScannerLost,
    OdometryLost,
    NavLost,
    LocalizationJump,
    ObstacleNear,
    OperationTimeout,
    RobotLink,
}

/// What the VM does while a fault is active.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reaction {
    /// Raise the event; the task decides (Figure 20's battery check).
    Raise,
    /// Limit the speed to `degraded_speed`.
    SlowDown,
    /// Brake within the deceleration limit and hold the running movement (as `stop`)
    /// until the fault clears; then it goes on by itself.
    Hold,
    /// Brake, end the running movement as refused, and refuse movements until the
    /// fault clears.
    Lockout,
    /// Brake and end the running movement as refused (its path is in a frame that is
    /// no longer the robot's); new movements may start.
    EndMovement,
    /// Cancel the operation and end its command as refused.
    GiveUp,
}

impl Reaction {
    pub fn name(self) -> &'static str {
        match self {
            Reaction::Raise => "raise",
            Reaction::SlowDown => "slow_down",
            Reaction::Hold => "hold",
            Reaction::Lockout => "lockout",
            Reaction::EndMovement => "end_movement",
            Reaction::GiveUp => "give_up",
        }
    }
}

pub const FAULTS: [Fault; 8] = [
    Fault::BatteryLow,
    Fault::ScannerLost,
    Fault::OdometryLost,
    Fault::NavLost,
    Fault::LocalizationJump,
    Fault::ObstacleNear,
    Fault::OperationTimeout,
    Fault::RobotLink,
];

impl Fault {
    /// The value `sensor(supervisor)` reads while this is the most urgent fault.
    pub fn number(self) -> u32 {
        match self {
            Fault::BatteryLow => 1,
            Fault::ScannerLost => 2,
            Fault::OdometryLost => 3,
            Fault::NavLost => 4,
            Fault::LocalizationJump => 5,
            Fault::ObstacleNear => 6,
            Fault::OperationTimeout => 7,
            Fault::RobotLink => 8,
        }
    }

    /// Higher is more urgent: what `sensor(supervisor)` reports when several are
    /// active. Losing the robot or its position outranks losing the view ahead,
    /// which outranks anything the robot can still drive with.
    pub fn urgency(self) -> u8 {
        match self {
            Fault::RobotLink => 7,
            Fault::OdometryLost => 6,
            Fault::LocalizationJump => 5,
            Fault::ScannerLost => 4,
            Fault::ObstacleNear => 3,
            Fault::NavLost => 2,
            Fault::OperationTimeout => 1,
            Fault::BatteryLow => 0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Fault::BatteryLow => "battery_low",
            Fault::ScannerLost => "scanner_lost",
            Fault::OdometryLost => "odometry_lost",
            Fault::NavLost => "nav_lost",
            Fault::LocalizationJump => "localization_jump",
            Fault::ObstacleNear => "obstacle_near",
            Fault::OperationTimeout => "operation_timeout",
            Fault::RobotLink => "robot_link",
        }
    }

    pub fn reaction(self) -> Reaction {
        match self {
            Fault::BatteryLow => Reaction::Raise,
            Fault::NavLost => Reaction::SlowDown,
            Fault::ScannerLost | Fault::ObstacleNear | Fault::RobotLink => Reaction::Hold,
            Fault::OdometryLost => Reaction::Lockout,
            Fault::LocalizationJump => Reaction::EndMovement,
            Fault::OperationTimeout => Reaction::GiveUp,
        }
    }
}

/// Every code, in the order of the docs table.
pub const CODES: [Code; 18] = [
    Code::SpeedLimit,
    Code::ActuatorRange,
    Code::BodyPoseRange,
    Code::BodyPoseMode,
    Code::TargetInWall,
    Code::TargetOffMap,
    Code::TargetOnObstacle,
    Code::MovementLocked,
    Code::Parked,
    Code::PathTooCurved,
    Code::Fault(Fault::BatteryLow),
    Code::Fault(Fault::ScannerLost),
    Code::Fault(Fault::OdometryLost),
    Code::Fault(Fault::NavLost),
    Code::Fault(Fault::LocalizationJump),
    Code::Fault(Fault::ObstacleNear),
    Code::Fault(Fault::OperationTimeout),
    Code::Fault(Fault::RobotLink),
];

impl Code {
    /// The stable code: `R01xx` refusals, `R02xx` faults (`xx` the fault's number).
    pub fn code(self) -> &'static str {
        match self {
            Code::SpeedLimit => "R0101",
            Code::ActuatorRange => "R0102",
            Code::BodyPoseRange => "R0103",
            Code::BodyPoseMode => "R0104",
            Code::TargetInWall => "R0105",
            Code::TargetOffMap => "R0106",
            Code::TargetOnObstacle => "R0107",
            Code::MovementLocked => "R0108",
            Code::Parked => "R0109",
            Code::PathTooCurved => "R0110",
            Code::Fault(f) => match f {
                Fault::BatteryLow => "R0201",
                Fault::ScannerLost => "R0202",
                Fault::OdometryLost => "R0203",
                Fault::NavLost => "R0204",
                Fault::LocalizationJump => "R0205",
                Fault::ObstacleNear => "R0206",
                Fault::OperationTimeout => "R0207",
                Fault::RobotLink => "R0208",
            },
        }
    }

    /// One line for the docs table.
    pub fn title(self) -> &'static str {
        match self {
            Code::SpeedLimit => "speed beyond `max_speed` (or not a number)",
            Code::ActuatorRange => "actuator value outside the device's range",
            Code::BodyPoseRange => "body pose outside `max_roll`, `max_pitch`, `max_clearance`",
            Code::BodyPoseMode => "body pose not possible in the current movement mode",
            Code::TargetInWall => "movement target inside a wall of the known map",
            Code::TargetOffMap => "movement target outside the known map",
            Code::TargetOnObstacle => "movement target on a scanned obstacle",
            Code::MovementLocked => "movement while a fault locks movement",
            Code::Parked => "movement in `parking` mode",
            Code::PathTooCurved => "path to the target bends more than `max_curvature`",
            Code::Fault(f) => match f {
                Fault::BatteryLow => "battery below `LowBattery`",
                Fault::ScannerLost => "no new scan for `scanner_timeout`",
                Fault::OdometryLost => "no odometry sample for `odometry_timeout`",
                Fault::NavLost => "no navigation fix for `nav_timeout`",
                Fault::LocalizationJump => "the pose estimate jumped",
                Fault::ObstacleNear => "obstacle inside the stopping distance, avoidance off",
                Fault::OperationTimeout => "an operation did not answer in `operation_timeout`",
                Fault::RobotLink => "a call to update or read the robot failed",
            },
        }
    }
}

impl Code {
    /// The way out: what the task can change so that the command is not refused, or
    /// what clears the fault. Traces carry it in `end` and `fault` events, and
    /// `docs/reliability.md` lists it beside each code.
    pub fn help(self) -> &'static str {
        match self {
            Code::SpeedLimit => {
                "compute a speed within max_speed of the robot model (negative drives backwards)"
            }
            Code::ActuatorRange => {
                "keep the value within the actuator's min..max in [SENSORSANDACTUATORS] of the robot model"
            }
            Code::BodyPoseRange => {
                "keep r and p within max_roll and max_pitch, and rc within 0..max_clearance"
            }
            Code::BodyPoseMode => {
                "change the movement mode first (movemode) or, in rolking, change only rc"
            }
            Code::TargetInWall => {
                "move the target away from the wall by at least half the robot's width"
            }
            Code::TargetOffMap => "choose a target inside the known map, or locate the robot first",
            Code::TargetOnObstacle => {
                "choose a target clear of the obstacle, or approach it with approach(..,d)"
            }
            Code::MovementLocked => {
                "wait for the fault to clear (sensor(supervisor) reads 0), then start the movement again"
            }
            Code::Parked => "leave parking mode with movemode(..) before moving",
            Code::PathTooCurved => {
                "give a heading the robot can reach (gotoxy(x,y,h)), allow reversing with r where the command takes it (gotoxy(x,y,r)), or put the target further off"
            }
            Code::Fault(f) => match f {
                Fault::BatteryLow => "drive to the charger (go_charger) or end the task",
                Fault::ScannerLost => {
                    "the movement goes on when scans arrive again; check the scanner"
                }
                Fault::OdometryLost => "start the movement again once odometry is back",
                Fault::NavLost => "the robot drives slowly on dead reckoning until a fix arrives",
                Fault::LocalizationJump => {
                    "start the movement again from where the robot now knows it is"
                }
                Fault::ObstacleNear => {
                    "clear the way, turn obsavoid(on) so the robot drives round it, or break the movement and plan another"
                }
                Fault::OperationTimeout => "check the device and give the operation again",
                Fault::RobotLink => "the movement goes on when the robot answers again",
            },
        }
    }
}

/// The table of `docs/reliability.md` that gives each refusal and fault its way out
/// (`vm/tests/safety.rs` keeps it fresh).
pub fn ways_out_markdown() -> String {
    let mut out = String::from("| code | what | way out |\n| --- | --- | --- |\n");
    for c in CODES {
        out.push_str(&format!(
            "| {} | {} | {} |\n",
            c.code(),
            c.title(),
            c.help()
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_faults_number_their_codes() {
        let mut seen: Vec<&str> = CODES.iter().map(|c| c.code()).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), CODES.len());
        for f in FAULTS {
            assert_eq!(Code::Fault(f).code(), format!("R02{:02}", f.number()));
            assert!(CODES.contains(&Code::Fault(f)));
        }
        for c in CODES {
            assert!(
                !c.help().is_empty() && !c.help().contains('"'),
                "{}",
                c.code()
            );
        }
        let mut urgency: Vec<u8> = FAULTS.iter().map(|f| f.urgency()).collect();
        urgency.sort_unstable();
        urgency.dedup();
        assert_eq!(urgency.len(), FAULTS.len(), "urgency orders them all");
        assert_eq!(
            FAULTS.len() as u32,
            ilmr_model::SUPERVISOR_FAULTS,
            "the model's supervisor device reads every number"
        );
    }
}
