//! The timed script of a [`super::ScriptedRobot`]: what its sensors report when, and
//! how its asynchronous operations end.

use crate::types::{AsyncOp, Detection, HalError, KnownMap, ManipTask, Pose, Scan};

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TimedReading {
    pub t: f64,
    pub device: String,
    pub value: Option<f64>,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Sighting {
    pub from: f64,
    pub until: f64,
    pub detection: Detection,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TimedScan {
    pub t: f64,
    pub scan: Scan,
}

/// Which operations a rule applies to.
#[derive(Debug, Clone, PartialEq)]
pub enum OpMatch {
    Init,
    Manipulate(ManipTask),
    MoveMode(String),
    Any,
}

impl OpMatch {
    pub(crate) fn matches(&self, op: &AsyncOp) -> bool {
        match (self, op) {
            (OpMatch::Any, _) | (OpMatch::Init, AsyncOp::Init(_)) => true,
            (OpMatch::Manipulate(a), AsyncOp::Manipulate(b)) => a == b,
            (OpMatch::MoveMode(a), AsyncOp::MoveMode(b)) => a.eq_ignore_ascii_case(b),
            _ => false,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum OpOutcome {
    Done,
    Failed(String),
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct OpRule {
    pub matcher: OpMatch,
    pub ticks: u32,
    pub outcome: OpOutcome,
}

/// A stream of samples a [`super::ScriptedRobot`] can report and lose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stream {
    Scanner,
    Odometry,
    Nav,
}

/// A HAL call a [`super::ScriptedRobot`] can be scripted to fail.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    Update,
    Snapshot,
    SetMotion,
    Actuator,
    BodyPose,
    Start,
    Poll,
}

/// Samples every `period` seconds from time 0, except in its dropouts.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Periodic {
    pub period: f64,
    pub dropouts: Vec<(f64, f64)>,
}

impl Periodic {
    /// When the latest sample at or before `t` was taken: the last multiple of the
    /// period outside every dropout `[from, until)`.
    pub fn latest(&self, t: f64) -> Option<f64> {
        if self.period.is_nan() || self.period <= 0.0 || t < 0.0 {
            return None;
        }
        let mut at = (t / self.period + 1e-9).floor() * self.period;
        while at >= 0.0 {
            match self
                .dropouts
                .iter()
                .find(|(from, until)| at >= *from - 1e-9 && at < *until - 1e-9)
            {
                // Back to the last sample before the dropout began.
                Some((from, _)) => {
                    at = ((from / self.period) - 1e-9).ceil() * self.period - self.period
                }
                None => return Some(at),
            }
        }
        None
    }
}

/// The script, sorted by time where order matters.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Script {
    pub readings: Vec<TimedReading>,
    pub sightings: Vec<Sighting>,
    pub scans: Vec<TimedScan>,
    /// `readings` and `scans` are in time order: they are sorted once, when the robot
    /// first runs, rather than after each is scripted (100,000 readings made that a
    /// quadratic wait).
    pub sorted: bool,
    /// First matching rule wins; without one an operation is done after one tick.
    pub op_rules: Vec<OpRule>,
    /// `(actuator, reason)`: actuators that refuse every value.
    pub refused_actuators: Vec<(String, String)>,
    /// Navigation modes the robot has; empty means any.
    pub locmodes: Vec<String>,
    /// A scan repeated every period (its `t` restamped), after the scripted ones.
    pub scan_every: Option<(Periodic, Scan)>,
    pub odometry: Option<Periodic>,
    pub nav: Option<Periodic>,
    /// `(t, shift)`: from time `t` the estimate is moved by `shift` (a bad fix).
    pub jumps: Vec<(f64, Pose)>,
    /// `(call, from, until, error)`.
    pub failures: Vec<(Call, f64, f64, HalError)>,
    /// `(actuator, min, max)`.
    pub actuator_ranges: Vec<(String, f64, f64)>,
    pub known_map: Option<KnownMap>,
}

impl Script {
    /// Puts what is still to come of the readings and scans in time order, keeping
    /// those of the same time in the order they were scripted.
    pub fn sort(&mut self, next_reading: usize, next_scan: usize) {
        if self.sorted {
            return;
        }
        if let Some(rest) = self.readings.get_mut(next_reading..) {
            rest.sort_by(|a, b| a.t.total_cmp(&b.t));
        }
        if let Some(rest) = self.scans.get_mut(next_scan..) {
            rest.sort_by(|a, b| a.t.total_cmp(&b.t));
        }
        self.sorted = true;
    }

    pub fn failure(&self, call: Call, t: f64) -> Option<HalError> {
        self.failures
            .iter()
            .find(|(c, from, until, _)| *c == call && t >= *from - 1e-9 && t < *until - 1e-9)
            .map(|(_, _, _, e)| e.clone())
    }
}
