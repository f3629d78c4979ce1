//! A ROS 2 robot behind the HAL: `cmd_vel` out, `odom`, `scan` and `battery_state` in.
//!
//! Safety over the network rests on three things here and one in the VM. Every twist
//! sent is within the model's limits (`convert::cmd_vel`). The last twist is sent
//! again every `keepalive` seconds, so a robot driver with a command timeout keeps
//! moving only while ILMR is alive, and a halt (a zero twist) is repeated until
//! commands resume. The time a sample *arrives* is what the VM's supervisor sees as the
//! stream's age, so a robot whose odometry or scan stops is held by the same
//! `odometry_lost`/`scanner_lost` faults as a simulated one; a robot clock that
//! disagrees with ours cannot hide a dead stream.

use std::time::{Duration, Instant};

use ilmr_hal::{
    AsyncOp, BodyPose, DeviceReading, Hal, HalError, OpId, OpStatus, Pose, Scan, Snapshot,
};

use crate::cdr;
use crate::convert::{self, Limits, Motion};
use crate::dds::{LinkError, Participant, Profile, Reach, Reader, Writer};
use crate::frame::Frame;
use crate::msg::{BatteryState, LaserScan, Odometry, RosMessage, TFMessage, Twist};
use crate::names::TopicName;

/// Samples taken from one topic in one tick at most: a peer that floods costs a
/// bounded time per tick, and what it sent beyond is left to DDS's history (which keeps
/// the last few) rather than read.
pub const MAX_SAMPLES_PER_TICK: usize = 64;

/// How often the last twist is sent again, s: within the command timeout of common
/// drivers (TurtleBot 3: 0.5 s; Nav2's `velocity_smoother`: 1 s).
pub const KEEPALIVE: f64 = 0.1;

/// Another participant's `cmd_vel` sample within this long, s, means another node
/// drives the robot (a teleop, a navigation stack): ILMR yields it, sending one zero
/// twist and then nothing, until that node has been silent this long.
pub const YIELD_WINDOW: f64 = 0.5;

/// Other writers on `cmd_vel` told apart at most (the rest are counted only).
const MAX_FOREIGN_WRITERS: usize = 16;

/// The topics, relative to the namespace unless absolute.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Topics {
    pub cmd_vel: String,
    pub odom: String,
    pub scan: String,
    pub battery: String,
}

impl Default for Topics {
    fn default() -> Topics {
        Topics {
            cmd_vel: "cmd_vel".into(),
            odom: "odom".into(),
            scan: "scan".into(),
            battery: "battery_state".into(),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Ros2Config {
    pub domain_id: u16,
    pub namespace: String,
    pub topics: Topics,
    pub reach: Reach,
    /// The frames `ilmrc sim` publishes the robot in.
    pub frames: crate::base::Frames,
    /// How odometry, scan and battery are read.
    pub sensor_profile: Profile,
    /// The model's name for its scanner; `None` for a robot without one (then no scan
    /// is waited for).
    pub scanner: Option<String>,
    pub limits: Limits,
    /// How long [`Ros2Robot::connect`] waits for the robot's first odometry and scan.
    pub wait: Duration,
    /// The model's `odometry_timeout` and `scanner_timeout`, s: older streams than
    /// these, and the backend itself sends only zero twists.
    pub odometry_timeout: f64,
    pub scanner_timeout: f64,
}

/// Counts of what went over the link, for the run's summary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LinkStats {
    pub twists_sent: u64,
    pub odometry: (u64, u64),
    pub scans: (u64, u64),
    pub battery: (u64, u64),
    /// Odometry samples that decoded but held NaN or infinity.
    pub odometry_unusable: u64,
    /// Times the backend itself held the robot (zero twists) for a stale stream.
    pub stale_holds: u64,
    /// `cmd_vel` samples from other participants, the writers they came from (up to
    /// 16 told apart), and the times ILMR yielded the robot to them.
    pub foreign_commands: u64,
    pub foreign_writers: usize,
    pub yields: u64,
    /// The most samples of one topic read in one tick (at most
    /// [`MAX_SAMPLES_PER_TICK`]).
    pub most_in_one_tick: usize,
}

/// A message as it went over the link, for a recording (an MCAP file's `ros2msg`
/// channels): its sample as DDS carries it, and when, on the VM's clock.
#[derive(Debug, Clone, PartialEq)]
pub struct Recorded {
    pub t: f64,
    /// `/robot1/odom`
    pub topic: String,
    pub ros_type: &'static str,
    pub definition: &'static str,
    pub sample: Vec<u8>,
}

impl Recorded {
    fn of<M: RosMessage>(t: f64, topic: &TopicName, message: &M) -> Recorded {
        Recorded {
            t,
            topic: topic.ros().to_string(),
            ros_type: M::ROS_TYPE,
            definition: M::DEFINITION,
            sample: cdr::encode(message),
        }
    }
}

struct Endpoints {
    // Dropped last: the readers and the writer belong to it.
    cmd_vel: Writer<Twist>,
    /// `cmd_vel` read back: any sample of another participant's is a second driver.
    cmd_vel_watch: Reader<Twist>,
    odom: Reader<Odometry>,
    scan: Reader<LaserScan>,
    battery: Reader<BatteryState>,
    tf: Reader<TFMessage>,
    tf_static: Reader<TFMessage>,
    participant: Participant,
}

/// Frames mounted on the robot's body frame, as `tf` and `tf_static` place them: where
/// the scanner is, to read its scans from there.
const MAX_MOUNTS: usize = 64;

/// How long [`Ros2Robot::connect`] waits, beyond the first scan, for the transform that
/// places the scanner on the robot.
const MOUNT_WAIT: Duration = Duration::from_secs(1);

/// `connect` returns only just after odometry and a scan arrived (within this): the
/// VM's supervisor watches a stream from its second stamp on, so a stream that had
/// already stopped when the task started would go unwatched.
const FRESH: Duration = Duration::from_millis(200);

pub struct Ros2Robot {
    link: Endpoints,
    scanner: Option<String>,
    limits: Limits,
    now: f64,
    frame: Frame,
    motion: Option<Motion>,
    odometry_t: Option<f64>,
    travelled: f64,
    scan: Option<Scan>,
    /// The latest scan's `range_max`, m: what a beam that found nothing reads.
    scan_range: f64,
    battery: Option<f64>,
    twist: Twist,
    sent_at: Option<f64>,
    twists_sent: u64,
    odometry_unusable: u64,
    /// `init` operations started: they are done at once (the robot's streams are up,
    /// or `connect` would have failed).
    inits: u32,
    /// What went over the link since the last [`Ros2Robot::take_recorded`], when
    /// recording (`None` otherwise).
    recorded: Option<Vec<Recorded>>,
    /// The robot's body frame, whose children `mounts` holds.
    base_frame: String,
    /// Frames on the body frame and where: (frame, pose on the body).
    mounts: Vec<(String, Pose)>,
    /// The frame of the latest scan.
    scan_frame: Option<String>,
    odometry_timeout: f64,
    scanner_timeout: f64,
    /// Holding the robot for a stale stream now, and how often it began.
    stale: bool,
    stale_holds: u64,
    /// When another participant's `cmd_vel` last arrived (VM clock), how many, from
    /// which writers; yielding the robot to it now, and how often that began.
    foreign_t: Option<f64>,
    foreign_commands: u64,
    foreign_writers: Vec<rustdds::GUID>,
    yielding: bool,
    yields: u64,
}

impl Ros2Robot {
    /// Joins the domain, opens the topics and waits for the robot's first odometry
    /// sample (and scan, when the model has a scanner), so that a task does not start
    /// on a robot that is not there.
    pub fn connect(config: &Ros2Config) -> Result<Ros2Robot, LinkError> {
        let topic = |name: &str| {
            TopicName::new(&config.namespace, name).map_err(|e| LinkError(e.to_string()))
        };
        let participant = Participant::join(config.domain_id, config.reach)?;
        let link = Endpoints {
            cmd_vel: participant.writer(&topic(&config.topics.cmd_vel)?, Profile::Reliable)?,
            cmd_vel_watch: participant
                .reader(&topic(&config.topics.cmd_vel)?, Profile::SensorData)?,
            odom: participant.reader(&topic(&config.topics.odom)?, config.sensor_profile)?,
            scan: participant.reader(&topic(&config.topics.scan)?, config.sensor_profile)?,
            battery: participant.reader(&topic(&config.topics.battery)?, config.sensor_profile)?,
            tf: participant.reader(&topic("tf")?, Profile::SensorData)?,
            tf_static: participant.reader(&topic("tf_static")?, Profile::Latched)?,
            participant,
        };
        let mut robot = Ros2Robot {
            link,
            scanner: config.scanner.clone(),
            limits: config.limits,
            now: 0.0,
            frame: Frame::default(),
            motion: None,
            odometry_t: None,
            travelled: 0.0,
            scan: None,
            scan_range: 0.0,
            battery: None,
            twist: Twist::default(),
            sent_at: None,
            twists_sent: 0,
            odometry_unusable: 0,
            inits: 0,
            recorded: None,
            base_frame: config.frames.base.clone(),
            mounts: Vec::new(),
            scan_frame: None,
            odometry_timeout: config.odometry_timeout,
            scanner_timeout: config.scanner_timeout,
            stale: false,
            stale_holds: 0,
            foreign_t: None,
            foreign_commands: 0,
            foreign_writers: Vec::new(),
            yielding: false,
            yields: 0,
        };
        robot.wait_for_streams(config)?;
        Ok(robot)
    }

    fn wait_for_streams(&mut self, config: &Ros2Config) -> Result<(), LinkError> {
        let start = Instant::now();
        let mut scanned_at: Option<Instant> = None;
        let mut last_scan: Option<Instant> = None;
        let mut last_odometry: Option<Instant> = None;
        let mut scans = self.link.scan.counts().0;
        let mut odometry = self.link.odom.counts().0;
        loop {
            self.receive(0.0);
            if self.link.scan.counts().0 != scans {
                scans = self.link.scan.counts().0;
                last_scan = Some(Instant::now());
            }
            if self.link.odom.counts().0 != odometry {
                odometry = self.link.odom.counts().0;
                last_odometry = Some(Instant::now());
            }
            let odometry_ready =
                self.motion.is_some() && last_odometry.is_some_and(|at| at.elapsed() <= FRESH);
            let scan_ready = self.scanner.is_none()
                || (self.scan.is_some() && last_scan.is_some_and(|at| at.elapsed() <= FRESH));
            if odometry_ready && scan_ready {
                // A scanner off the robot's origin is placed by a transform, which
                // comes with the robot's first `tf` or its latched `tf_static`.
                let placed = self.scanner_mount().is_some()
                    || self
                        .scan_frame
                        .as_deref()
                        .is_none_or(|f| f == self.base_frame);
                let scanned_at = *scanned_at.get_or_insert_with(Instant::now);
                if placed || scanned_at.elapsed() >= MOUNT_WAIT {
                    // What arrived while waiting is not fresh at the first tick; the
                    // first tick's samples will be.
                    self.odometry_t = None;
                    return Ok(());
                }
            }
            // Once both streams are up, only the (bounded) wait for the mount is left.
            if start.elapsed() >= config.wait && !(odometry_ready && scan_ready) {
                let (topic, what, seen) = if !odometry_ready {
                    let odometry = "odometry (nav_msgs/Odometry)";
                    (self.link.odom.topic(), odometry, self.motion.is_some())
                } else {
                    let scan = "scan (sensor_msgs/LaserScan)";
                    (self.link.scan.topic(), scan, self.scan.is_some())
                };
                if seen {
                    return Err(LinkError(format!(
                        "the robot's {what} on {topic} stopped while connecting: none came \
                         in the last {} ms of {:.0} s",
                        FRESH.as_millis(),
                        config.wait.as_secs_f64()
                    )));
                }
                return Err(LinkError(format!(
                    "no {what} on {topic} within {:.0} s in DDS domain {}: is the robot up, \
                     with ROS_DOMAIN_ID={} and namespace `{}`?",
                    config.wait.as_secs_f64(),
                    config.domain_id,
                    config.domain_id,
                    config.namespace,
                )));
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// Keeps every message taken and sent from now on, for [`Ros2Robot::take_recorded`]
    /// (which must then be called every tick).
    pub fn record_messages(&mut self) {
        self.recorded.get_or_insert_with(Vec::new);
    }

    /// The messages taken and sent since the last call.
    pub fn take_recorded(&mut self) -> Vec<Recorded> {
        self.recorded
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }

    /// Takes what arrived, stamping it with `now`.
    fn receive(&mut self, now: f64) {
        let mut latest = None;
        let mut unusable = 0;
        let mut recorded = self.recorded.take();
        let keep = |rec: &mut Option<Vec<Recorded>>, r: &dyn Fn() -> Recorded| {
            if let Some(list) = rec.as_mut() {
                list.push(r());
            }
        };
        let topic = self.link.odom.topic().clone();
        self.link.odom.drain(MAX_SAMPLES_PER_TICK, |m| {
            keep(&mut recorded, &|| Recorded::of(now, &topic, &m));
            match convert::motion(&m) {
                Some(motion) => latest = Some(motion),
                None => unusable += 1,
            };
        });
        self.odometry_unusable += unusable;
        if let Some(m) = latest {
            if let Some(last) = self.motion {
                let step = (m.pose.x - last.pose.x).hypot(m.pose.y - last.pose.y);
                self.travelled += step;
            }
            self.motion = Some(m);
            self.odometry_t = Some(now);
        }
        let mut scan = None;
        let topic = self.link.scan.topic().clone();
        self.link.scan.drain(MAX_SAMPLES_PER_TICK, |m| {
            keep(&mut recorded, &|| Recorded::of(now, &topic, &m));
            scan = Some(m);
        });
        if let Some(m) = &scan
            && self.scan_frame.as_deref() != Some(m.header.frame_id.as_str())
        {
            self.scan_frame = Some(m.header.frame_id.clone());
        }
        let mut transforms = Vec::new();
        self.link
            .tf
            .drain(MAX_SAMPLES_PER_TICK, |m| transforms.push(m));
        self.link
            .tf_static
            .drain(MAX_SAMPLES_PER_TICK, |m| transforms.push(m));
        for t in transforms.iter().flat_map(|m| &m.transforms) {
            if t.header.frame_id != self.base_frame {
                continue;
            }
            let at = &t.transform;
            let pose = Pose::new(at.translation.x, at.translation.y, at.rotation.yaw());
            if !(pose.x.is_finite() && pose.y.is_finite() && pose.h.is_finite()) {
                continue;
            }
            let known = self.mounts.len();
            match self.mounts.iter_mut().find(|(f, _)| *f == t.child_frame_id) {
                Some(slot) => slot.1 = pose,
                None if known < MAX_MOUNTS => {
                    self.mounts.push((t.child_frame_id.clone(), pose));
                }
                None => {}
            }
        }
        if let (Some(m), Some(device)) = (scan, &self.scanner) {
            let mut s = convert::scan(&m, device);
            s.t = now;
            self.scan = Some(s);
            self.scan_range = f64::from(m.range_max).max(0.0);
        }
        let mut voltage = None;
        let topic = self.link.battery.topic().clone();
        self.link.battery.drain(MAX_SAMPLES_PER_TICK, |m| {
            keep(&mut recorded, &|| Recorded::of(now, &topic, &m));
            voltage = convert::battery_voltage(m.voltage);
        });
        if voltage.is_some() {
            self.battery = voltage;
        }
        self.recorded = recorded;
        self.watch_cmd_vel(now);
    }

    /// Notes `cmd_vel` samples that another participant wrote.
    fn watch_cmd_vel(&mut self, now: f64) {
        let Endpoints {
            participant,
            cmd_vel_watch,
            ..
        } = &mut self.link;
        let (mut foreign, writers) = (0, &mut self.foreign_writers);
        cmd_vel_watch.drain_from(MAX_SAMPLES_PER_TICK, |_, writer| {
            if participant.is_own(writer) {
                return;
            }
            foreign += 1;
            if writers.len() < MAX_FOREIGN_WRITERS && !writers.contains(&writer) {
                writers.push(writer);
            }
        });
        if foreign > 0 {
            self.foreign_commands += foreign;
            self.foreign_t = Some(now);
        }
    }

    /// Why ILMR must not drive: another node has been commanding the robot.
    fn contender(&self) -> Option<String> {
        let at = self.foreign_t?;
        (self.now - at < YIELD_WINDOW).then(|| {
            format!(
                "another node publishes on {} ({} writer{} so far): ILMR yields the robot \
                 to it until it has been silent {YIELD_WINDOW} s",
                self.link.cmd_vel.topic(),
                self.foreign_writers.len(),
                if self.foreign_writers.len() == 1 {
                    ""
                } else {
                    "s"
                }
            )
        })
    }

    fn send(&mut self) -> Result<(), HalError> {
        self.sent_at = Some(self.now);
        self.twists_sent += 1;
        if let Some(list) = self.recorded.as_mut() {
            list.push(Recorded::of(
                self.now,
                self.link.cmd_vel.topic(),
                &self.twist,
            ));
        }
        self.link
            .cmd_vel
            .send(self.twist)
            .map_err(|e| HalError::Link(e.0))
    }

    /// The robot's pose as the task sees it: odometry in the frame `locate` set.
    pub fn pose(&self) -> Option<Pose> {
        self.motion.map(|m| self.frame.apply(m.pose))
    }

    /// Measured speed and curvature, m/s and 1/m.
    pub fn measured(&self) -> Option<(f64, f64)> {
        self.motion.map(|m| (m.speed, m.curvature))
    }

    /// The last twist sent.
    pub fn twist(&self) -> &Twist {
        &self.twist
    }

    /// Why the robot must stand: a stream older than its timeout.
    fn stale_stream(&self) -> Option<String> {
        // Arrival times on the VM's clock; what arrived while connecting (which
        // `connect` made sure was fresh) counts as arriving at 0.
        let odometry = self.now - self.odometry_t.unwrap_or(0.0);
        if odometry > self.odometry_timeout {
            return Some(format!(
                "no odometry on {} for {odometry:.2} s (odometry_timeout {} s): the robot is held",
                self.link.odom.topic(),
                self.odometry_timeout
            ));
        }
        let scan = self.now - self.scan.as_ref().map_or(0.0, |s| s.t);
        if self.scanner.is_some() && scan > self.scanner_timeout {
            return Some(format!(
                "no scan on {} for {scan:.2} s (scanner_timeout {} s): the robot is held",
                self.link.scan.topic(),
                self.scanner_timeout
            ));
        }
        None
    }

    /// Where the scanner is on the robot (its scans' frame on the body frame), once a
    /// transform has said so.
    pub fn scanner_mount(&self) -> Option<Pose> {
        let frame = self.scan_frame.as_deref()?;
        if frame == self.base_frame {
            return Some(Pose::default());
        }
        self.mounts
            .iter()
            .find(|(f, _)| f == frame)
            .map(|(_, p)| *p)
    }

    /// The latest scan, as the HAL has it, and its maximum range, m.
    pub fn scan(&self) -> Option<(&Scan, f64)> {
        self.scan.as_ref().map(|s| (s, self.scan_range))
    }

    pub fn stats(&self) -> LinkStats {
        LinkStats {
            twists_sent: self.twists_sent,
            odometry: self.link.odom.counts(),
            scans: self.link.scan.counts(),
            battery: self.link.battery.counts(),
            odometry_unusable: self.odometry_unusable,
            stale_holds: self.stale_holds,
            foreign_commands: self.foreign_commands,
            foreign_writers: self.foreign_writers.len(),
            yields: self.yields,
            most_in_one_tick: [
                self.link.odom.most_in_one_drain(),
                self.link.scan.most_in_one_drain(),
                self.link.battery.most_in_one_drain(),
            ]
            .into_iter()
            .max()
            .unwrap_or(0),
        }
    }
}

impl Drop for Ros2Robot {
    /// A run that ends while the robot moves (at `--max-time`) leaves it standing: the
    /// zero twist is handed to DDS's thread before the participant closes.
    fn drop(&mut self) {
        if self.twist != Twist::default() {
            self.twist = Twist::default();
            let _ = self.send();
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

fn unsupported(what: &str) -> HalError {
    HalError::Unsupported(format!(
        "{what}: a ROS 2 robot is driven through cmd_vel, odom, scan and battery_state only"
    ))
}

impl Hal for Ros2Robot {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        if !t.is_finite() {
            return Err(HalError::Link(format!("time {t} is not finite")));
        }
        self.now = t;
        self.receive(t);
        if self.contender().is_some() {
            // One zero twist, then silence: the other node drives.
            if self.twist != Twist::default() {
                self.twist = Twist::default();
                return self.send();
            }
            return Ok(());
        }
        if self.twist != Twist::default() && self.stale_stream().is_some() {
            self.twist = Twist::default();
            return self.send();
        }
        if self.sent_at.is_none_or(|at| t - at >= KEEPALIVE - 1e-9) {
            self.send()?;
        }
        Ok(())
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        out.t = self.now;
        out.true_pose = None;
        out.odometry_t = self.odometry_t;
        out.nav_t = None;
        if let Some(m) = self.motion {
            out.pose = self.frame.apply(m.pose);
            out.speed = m.speed;
            out.curvature = m.curvature;
        }
        match (&self.scan, &mut out.scan) {
            (Some(s), Some(o)) => o.clone_from(s),
            (Some(s), slot) => *slot = Some(s.clone()),
            (None, slot) => *slot = None,
        }
        out.battery = self.battery;
        out.detections.clear();
        out.devices.clear();
        let nearest = self
            .scan
            .as_ref()
            .map(|s| s.ranges.iter().copied().fold(f64::INFINITY, f64::min) * 1000.0);
        let heading = self.motion.map(|_| out.pose.h.to_degrees());
        for (name, value) in [
            ("battery", self.battery),
            ("gyro", heading),
            ("odometry", self.motion.map(|_| self.travelled)),
            (self.scanner.as_deref().unwrap_or("scanner"), nearest),
        ] {
            out.devices.push(DeviceReading {
                name: name.to_string(),
                value,
            });
        }
        Ok(())
    }

    /// Within the model's limits; and only zero while a stream is older than its
    /// timeout, whatever the VM asks: the VM's supervisor watches a stream from its
    /// second sample, and this holds the robot even for one that never got that far.
    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        let contender = self.contender();
        let stale = self.stale_stream();
        let twist = match (&contender, &stale) {
            (None, None) => convert::cmd_vel(speed, curvature, self.limits),
            _ => Twist::default(),
        };
        if twist != self.twist {
            self.twist = twist;
            self.send()?;
        }
        let yield_began = contender.is_some() && !self.yielding;
        self.yielding = contender.is_some();
        if let Some(why) = contender {
            if yield_began && speed != 0.0 {
                self.yields += 1;
                return Err(HalError::Refused(why));
            }
            return Ok(());
        }
        let began = stale.is_some() && !self.stale;
        self.stale = stale.is_some();
        match stale {
            Some(why) if began && speed != 0.0 => {
                self.stale_holds += 1;
                Err(HalError::Refused(why))
            }
            _ => Ok(()),
        }
    }

    fn actuator(&mut self, id: &str, _value: f64) -> Result<(), HalError> {
        Err(unsupported(id))
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        Err(unsupported(&format!("locmode({mode})")))
    }

    fn bodypose(&mut self, _pose: BodyPose) -> Result<(), HalError> {
        Err(unsupported("bodypose"))
    }

    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        let Some(m) = self.motion else {
            return Err(HalError::Refused(
                "locate: no odometry has arrived to place".into(),
            ));
        };
        self.frame = Frame::placing(m.pose, pose);
        Ok(())
    }

    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        match op {
            AsyncOp::Init(_) => {
                self.inits += 1;
                Ok(OpId(self.inits))
            }
            AsyncOp::Manipulate(_) => Err(unsupported("manipulate")),
            AsyncOp::MoveMode(_) => Err(unsupported("movemode")),
        }
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        if (1..=self.inits).contains(&op.0) {
            Ok(OpStatus::Done)
        } else {
            Err(HalError::UnknownOp(op))
        }
    }
}
