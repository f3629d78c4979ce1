//! The timed script of a [`super::ScriptedRobot`]: what its sensors report when, and
//! how its asynchronous operations end.

use crate::types::{AsyncOp, Detection, ManipTask, Scan};

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

/// The script, kept sorted by time where order matters.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Script {
    pub readings: Vec<TimedReading>,
    pub sightings: Vec<Sighting>,
    pub scans: Vec<TimedScan>,
    /// First matching rule wins; without one an operation is done after one tick.
    pub op_rules: Vec<OpRule>,
    /// `(actuator, reason)`: actuators that refuse every value.
    pub refused_actuators: Vec<(String, String)>,
    /// Navigation modes the robot has; empty means any.
    pub locmodes: Vec<String>,
}
