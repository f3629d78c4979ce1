//! The robots `ilmrc run` can drive. Every backend is a [`Hal`]; the run loop sees only
//! [`Robot`]: the HAL, plus what a run records of a robot that has a world around it.

use ilmr_hal::{
    AsyncOp, BodyPose, Hal, HalError, KnownMap, OpId, OpStatus, Pose, ScriptedRobot, Snapshot,
};
use ilmr_sim::SimRobot;

/// What the run loop needs beyond the HAL: whether the robot has come to rest, since a
/// run does not end while it still moves, and, for a simulated robot, the ground truth
/// that the trace, the plot and the summary show.
pub trait Robot: Hal {
    fn at_rest(&self) -> bool;

    /// Where the robot really is, in the world frame; `None` without a world.
    fn true_pose(&self) -> Option<Pose> {
        None
    }

    /// Ground speed and curvature, m/s and 1/m; `None` without a world.
    fn true_motion(&self) -> Option<(f64, f64)> {
        None
    }

    /// The scan that arrived since the last call, placed in the world.
    fn new_scan(&mut self) -> Option<WorldScan> {
        None
    }

    /// Times the robot has run into something.
    fn contacts(&self) -> u64 {
        0
    }

    /// What went over the link to a ROS 2 robot.
    fn link_stats(&self) -> Option<ilmr_ros2::LinkStats> {
        None
    }

    /// Where a ROS 2 robot's scanner is on its body (from `tf`), for the VM's
    /// `scanner_offset`; `None` for the other robots, whose model or body says.
    fn scanner_mount(&self) -> Option<Pose> {
        None
    }

    /// Keep the ROS 2 messages that go over the link, for [`Robot::take_ros2_messages`].
    fn record_ros2_messages(&mut self) {}

    /// The ROS 2 messages taken and sent since the last call, when recording.
    fn take_ros2_messages(&mut self) -> Vec<ilmr_ros2::robot::Recorded> {
        Vec::new()
    }

    /// The run has written the tick's lines. A robot that records its inputs
    /// (`crate::tape::Taping`) hands over the tick's as one `input` line.
    fn end_tick(&mut self) -> Option<ilmr_trace::Input> {
        None
    }

    /// A robot played from a recording has no more ticks to play.
    fn inputs_exhausted(&self) -> bool {
        false
    }
}

/// A laser scan with its origin in the world frame (where the beams were cast from).
#[derive(Debug, Clone, PartialEq)]
pub struct WorldScan {
    pub t: f64,
    /// The scanner's pose in the world; beam `i` points at `origin.h + angle_min + i * angle_step`.
    pub origin: Pose,
    pub angle_min: f64,
    pub angle_step: f64,
    pub max_range: f64,
    /// Metres; `max_range` where a beam found nothing.
    pub ranges: Vec<f64>,
}

impl WorldScan {
    /// A simulated robot's last scan and its number. It was taken in the step the
    /// robot was just stepped to, so its beams were cast from that step's true pose.
    pub fn last_of(robot: &SimRobot) -> Option<(u64, WorldScan)> {
        let scan = robot.sim().snapshot().scan?;
        let p = robot.sim().true_pose();
        let o = p.to_world(&scan.mount);
        let world = WorldScan {
            t: scan.time,
            origin: Pose::new(o.x, o.y, p.h),
            angle_min: scan.angle_min,
            angle_step: scan.angle_increment,
            max_range: scan.max_range,
            ranges: scan.ranges.clone(),
        };
        Some((scan.seq, world))
    }

    /// The points the beams hit, in the world frame.
    pub fn hits(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.ranges
            .iter()
            .enumerate()
            .filter(|(_, r)| **r < self.max_range && **r > 0.0)
            .map(|(i, &r)| {
                let a = self.origin.h + self.angle_min + i as f64 * self.angle_step;
                (self.origin.x + r * a.cos(), self.origin.y + r * a.sin())
            })
    }
}

impl Robot for ScriptedRobot {
    fn at_rest(&self) -> bool {
        self.speed().abs() < 1e-9
    }
}

/// The simulated robot, with the sequence number of the last scan handed out.
pub struct Simulated {
    pub robot: SimRobot,
    seen_scan: Option<u64>,
}

impl Simulated {
    pub fn new(robot: SimRobot) -> Simulated {
        Simulated {
            robot,
            seen_scan: None,
        }
    }
}

impl Robot for Simulated {
    fn at_rest(&self) -> bool {
        self.robot.sim().true_speed().abs() < 1e-6
    }

    fn true_pose(&self) -> Option<Pose> {
        Some(self.robot.true_pose())
    }

    fn true_motion(&self) -> Option<(f64, f64)> {
        let sim = self.robot.sim();
        Some((sim.true_speed(), sim.true_curvature()))
    }

    fn new_scan(&mut self) -> Option<WorldScan> {
        let seq = self.robot.sim().snapshot().scan?.seq;
        if self.seen_scan == Some(seq) {
            return None;
        }
        self.seen_scan = Some(seq);
        WorldScan::last_of(&self.robot).map(|(_, scan)| scan)
    }

    fn contacts(&self) -> u64 {
        self.robot.sim().contact_count()
    }
}

macro_rules! forward_hal {
    ($ty:ty, $($field:tt).+) => {
        impl Hal for $ty {
            fn update(&mut self, t: f64) -> Result<(), HalError> {
                self.$($field).+.update(t)
            }
            fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
                self.$($field).+.snapshot(out)
            }
            fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
                self.$($field).+.set_motion(speed, curvature)
            }
            fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
                self.$($field).+.actuator(id, value)
            }
            fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
                self.$($field).+.locmode(mode)
            }
            fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
                self.$($field).+.bodypose(pose)
            }
            fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
                self.$($field).+.locate(pose)
            }
            fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
                self.$($field).+.start(op)
            }
            fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
                self.$($field).+.poll(op)
            }
            fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
                self.$($field).+.cancel(op)
            }
            fn known_map(&mut self) -> Option<KnownMap> {
                self.$($field).+.known_map()
            }
            fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
                self.$($field).+.actuator_range(id)
            }
        }
    };
}

forward_hal!(Simulated, robot);

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

/// A backend chosen at run time, behind one type for the VM; `Send`, since `serve` and
/// `shell` run it on the VM's own thread.
pub struct AnyRobot(Box<dyn Robot + Send>);

forward_hal!(AnyRobot, 0);

impl AnyRobot {
    pub fn new(robot: impl Robot + Send + 'static) -> AnyRobot {
        AnyRobot(Box::new(robot))
    }
}

impl Robot for AnyRobot {
    fn at_rest(&self) -> bool {
        self.0.at_rest()
    }
    fn true_pose(&self) -> Option<Pose> {
        self.0.true_pose()
    }
    fn true_motion(&self) -> Option<(f64, f64)> {
        self.0.true_motion()
    }
    fn new_scan(&mut self) -> Option<WorldScan> {
        self.0.new_scan()
    }
    fn contacts(&self) -> u64 {
        self.0.contacts()
    }
    fn link_stats(&self) -> Option<ilmr_ros2::LinkStats> {
        self.0.link_stats()
    }
    fn scanner_mount(&self) -> Option<Pose> {
        self.0.scanner_mount()
    }
    fn record_ros2_messages(&mut self) {
        self.0.record_ros2_messages()
    }
    fn take_ros2_messages(&mut self) -> Vec<ilmr_ros2::robot::Recorded> {
        self.0.take_ros2_messages()
    }
    fn end_tick(&mut self) -> Option<ilmr_trace::Input> {
        self.0.end_tick()
    }
    fn inputs_exhausted(&self) -> bool {
        self.0.inputs_exhausted()
    }
}

/// A ROS 2 robot. It has no ground truth: what the trace, the plot and the summary show
/// of it is its own odometry, in the task's frame.
pub struct Ros2 {
    robot: ilmr_ros2::Ros2Robot,
    /// When the last scan handed out arrived.
    seen_scan: Option<f64>,
}

impl Ros2 {
    pub fn new(robot: ilmr_ros2::Ros2Robot) -> Ros2 {
        Ros2 {
            robot,
            seen_scan: None,
        }
    }
}

forward_hal!(Ros2, robot);

/// Below this measured speed, m/s, and with no speed commanded, a ROS 2 robot is at
/// rest: odometry of a standing robot jitters by millimetres per second.
const ROS2_REST_SPEED: f64 = 0.005;

impl Robot for Ros2 {
    fn at_rest(&self) -> bool {
        let commanded = self.robot.twist().linear.x;
        let measured = self.robot.measured().map_or(0.0, |(v, _)| v);
        commanded == 0.0 && measured.abs() < ROS2_REST_SPEED
    }

    fn true_pose(&self) -> Option<Pose> {
        self.robot.pose()
    }

    fn true_motion(&self) -> Option<(f64, f64)> {
        self.robot.measured()
    }

    fn new_scan(&mut self) -> Option<WorldScan> {
        let (scan, max_range) = self.robot.scan()?;
        if self.seen_scan == Some(scan.t) {
            return None;
        }
        self.seen_scan = Some(scan.t);
        // From where the scanner is on the robot, when `tf` has said so.
        let p = self.robot.pose()?;
        let m = self.robot.scanner_mount().unwrap_or_default();
        let (s, c) = p.h.sin_cos();
        // The heading unfolded, as the beams' angles are counted from it.
        let origin = Pose {
            x: p.x + c * m.x - s * m.y,
            y: p.y + s * m.x + c * m.y,
            h: p.h + m.h,
        };
        Some(WorldScan {
            t: scan.t,
            origin,
            angle_min: scan.angle_min,
            angle_step: scan.angle_step,
            max_range,
            ranges: scan.ranges.clone(),
        })
    }

    fn link_stats(&self) -> Option<ilmr_ros2::LinkStats> {
        Some(self.robot.stats())
    }

    fn scanner_mount(&self) -> Option<Pose> {
        self.robot.scanner_mount()
    }

    fn record_ros2_messages(&mut self) {
        self.robot.record_messages();
    }

    fn take_ros2_messages(&mut self) -> Vec<ilmr_ros2::robot::Recorded> {
        self.robot.take_recorded()
    }
}
