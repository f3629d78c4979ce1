//! The other side of the link: what a ROS 2 robot base offers, so that a robot that is
//! not one (ILMR's simulator) can be driven by any ROS 2 node, and seen by Foxglove or
//! RViz. It reads `cmd_vel` as a base driver does, stopping on its own command timeout,
//! and publishes `odom`, `tf` (`odom` -> `base_link` -> the scanner), `scan`,
//! `battery_state`, `ground_truth` (the true pose in `world`, as Gazebo's `p3d` plugin
//! does) and, for nodes on simulated time, `/clock`.

use ilmr_hal::{Pose, Scan};

use crate::convert::{self, Limits};
use crate::dds::{LinkError, Participant, Profile, Reach, Reader, Writer};
use crate::msg::{BatteryState, Clock, LaserScan, Odometry, TFMessage, Time, Twist};
use crate::names::TopicName;
use crate::robot::{MAX_SAMPLES_PER_TICK, Topics};

/// The frames of REP 105.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Frames {
    pub world: String,
    pub odom: String,
    pub base: String,
    pub scanner: String,
}

impl Default for Frames {
    fn default() -> Frames {
        Frames {
            world: "world".into(),
            odom: "odom".into(),
            base: "base_link".into(),
            scanner: "laser".into(),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct BaseConfig {
    pub domain_id: u16,
    pub namespace: String,
    pub reach: Reach,
    /// `cmd_vel`, `odom`, `scan` and `battery_state`'s names.
    pub topics: Topics,
    pub frames: Frames,
    /// What the base accepts: a faster or sharper `cmd_vel` is clamped.
    pub limits: Limits,
    /// A `cmd_vel` older than this, s, is no longer obeyed: the base stops.
    pub cmd_timeout: f64,
    /// Publish `/clock` (simulated time).
    pub clock: bool,
}

/// Counts of what went over the link.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BaseStats {
    pub commands: (u64, u64),
    pub odometry: u64,
    pub scans: u64,
    pub battery: u64,
    pub clock: u64,
}

pub struct Base {
    cmd_vel: Reader<Twist>,
    odom: Writer<Odometry>,
    ground_truth: Writer<Odometry>,
    tf: Writer<TFMessage>,
    scan: Writer<LaserScan>,
    battery: Writer<BatteryState>,
    clock: Option<Writer<Clock>>,
    config: BaseConfig,
    /// The last command and when it arrived, s.
    command: Option<(Twist, f64)>,
    stats: BaseStats,
    _participant: Participant,
}

impl Base {
    pub fn open(config: BaseConfig) -> Result<Base, LinkError> {
        let topic = |name: &str| TopicName::new(&config.namespace, name).map_err(LinkError);
        let participant = Participant::join(config.domain_id, config.reach)?;
        // Writers are reliable, which matches readers of either kind (RViz's are
        // reliable, Nav2's sensor readers best effort); the command reader is best
        // effort, which matches teleop nodes of either kind too.
        let reliable = Profile::Reliable;
        Ok(Base {
            cmd_vel: participant.reader(&topic(&config.topics.cmd_vel)?, Profile::SensorData)?,
            odom: participant.writer(&topic(&config.topics.odom)?, reliable)?,
            ground_truth: participant.writer(&topic("ground_truth")?, reliable)?,
            tf: participant.writer(&topic("tf")?, reliable)?,
            scan: participant.writer(&topic(&config.topics.scan)?, reliable)?,
            battery: participant.writer(&topic(&config.topics.battery)?, reliable)?,
            clock: match config.clock {
                true => Some(participant.writer(&topic("/clock")?, reliable)?),
                false => None,
            },
            config,
            command: None,
            stats: BaseStats::default(),
            _participant: participant,
        })
    }

    /// The speed and curvature to drive at `now`: the last command's, within the
    /// limits, or a stop when none came within the command timeout.
    pub fn command(&mut self, now: f64) -> (f64, f64) {
        let mut latest = None;
        self.cmd_vel
            .drain(MAX_SAMPLES_PER_TICK, |t| latest = Some(t));
        if let Some(t) = latest {
            self.command = Some((t, now));
        }
        self.stats.commands = self.cmd_vel.counts();
        match self.command {
            Some((t, at)) if now - at <= self.config.cmd_timeout => {
                convert::setpoint(&t, self.config.limits)
            }
            _ => (0.0, 0.0),
        }
    }

    /// Odometry, and the `tf` that places `base_link` in `odom` and the scanner (at
    /// `scanner`, in the robot's frame) on `base_link`.
    pub fn odometry(
        &mut self,
        pose: Pose,
        speed: f64,
        curvature: f64,
        scanner: Option<Pose>,
        stamp: Time,
    ) -> Result<(), LinkError> {
        let f = &self.config.frames;
        self.odom.send(convert::odometry(
            pose, speed, curvature, stamp, &f.odom, &f.base,
        ))?;
        let mut transforms = vec![convert::transform(pose, stamp, &f.odom, &f.base)];
        if let Some(mount) = scanner {
            transforms.push(convert::transform(mount, stamp, &f.base, &f.scanner));
        }
        self.tf.send(TFMessage { transforms })?;
        self.stats.odometry += 1;
        Ok(())
    }

    /// Where the robot really is, in `world`.
    pub fn ground_truth(
        &mut self,
        pose: Pose,
        speed: f64,
        curvature: f64,
        stamp: Time,
    ) -> Result<(), LinkError> {
        let f = &self.config.frames;
        self.ground_truth.send(convert::odometry(
            pose, speed, curvature, stamp, &f.world, &f.base,
        ))
    }

    pub fn scan(
        &mut self,
        scan: &Scan,
        max_range: f64,
        period: f64,
        stamp: Time,
    ) -> Result<(), LinkError> {
        let frame = &self.config.frames.scanner;
        self.scan
            .send(convert::laser_scan(scan, max_range, period, stamp, frame))?;
        self.stats.scans += 1;
        Ok(())
    }

    pub fn battery(&mut self, voltage: f64, percentage: f64, stamp: Time) -> Result<(), LinkError> {
        let frame = &self.config.frames.base;
        self.battery
            .send(convert::battery_state(voltage, percentage, stamp, frame))?;
        self.stats.battery += 1;
        Ok(())
    }

    pub fn clock(&mut self, now: Time) -> Result<(), LinkError> {
        if let Some(w) = &self.clock {
            w.send(Clock { clock: now })?;
            self.stats.clock += 1;
        }
        Ok(())
    }

    pub fn stats(&self) -> BaseStats {
        self.stats
    }
}
