//! `--scenario FILE.json`: what the scripted robot's world does during a run (sensor
//! readings, objects in view, how long operations take, paths taught beforehand) and
//! interactive lines typed at given times. Every field is optional.
//!
//! ```json
//! {
//!   "start": {"x": 0, "y": 0, "h": 0},
//!   "readings": [{"t": 0, "device": "battery", "value": 25.0}],
//!   "sightings": [{"from": 2, "until": 60, "sensor": "scanner", "object": "door",
//!                  "x": 4, "y": 1, "h": 90, "side": "left"}],
//!   "ops": [{"match": "manipulate take", "seconds": 3.0}],
//!   "paths": {"PATH": [[0, 0], [10, 0]]},
//!   "lines": [{"t": 5, "text": "speed(0.2)"}]
//! }
//! ```
//!
//! Headings (`start.h`, `sightings[].h`) are in degrees, as in ILMR source. An op
//! matches `init`, `manipulate TASK`, `movemode MODE` or `any`; it ends after `seconds`
//! (at 100 Hz), failing with `fail` when given.

use std::collections::BTreeMap;

use ilmr_hal::{Detection, Limits, ManipTask, OpMatch, OpOutcome, Pose, ScriptedRobot, Side};
use serde::Deserialize;

use crate::problem::clip;

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    #[serde(default)]
    pub start: Option<Start>,
    #[serde(default)]
    pub readings: Vec<Reading>,
    #[serde(default)]
    pub sightings: Vec<Sighting>,
    #[serde(default)]
    pub ops: Vec<OpRule>,
    /// Paths taught beforehand, for `followpath(NAME)`.
    #[serde(default)]
    pub paths: BTreeMap<String, Vec<(f64, f64)>>,
    #[serde(default)]
    pub lines: Vec<Line>,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Start {
    pub x: f64,
    pub y: f64,
    /// Degrees.
    #[serde(default)]
    pub h: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reading {
    pub t: f64,
    pub device: String,
    /// `null`: the device gives no data from `t` on.
    pub value: Option<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sighting {
    pub from: f64,
    pub until: f64,
    pub sensor: String,
    pub object: String,
    pub x: f64,
    pub y: f64,
    /// Degrees.
    #[serde(default)]
    pub h: f64,
    pub side: Side,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OpRule {
    #[serde(rename = "match")]
    pub matcher: String,
    pub seconds: f64,
    #[serde(default)]
    pub fail: Option<String>,
}

/// An interactive line typed at `t` seconds.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Line {
    pub t: f64,
    pub text: String,
}

/// The bounds a scripted robot of `model` moves within: the model's own, as
/// `ilmrc run --robot scripted` drives it.
pub fn scripted_limits(model: &ilmr_model::RobotModel) -> Limits {
    Limits {
        acceleration: model.max_acceleration(),
        deceleration: model.max_deceleration(),
        curvature_rate: model.curinc(),
        max_curvature: model.max_curvature(),
        max_speed: model.max_speed(),
    }
}

impl Scenario {
    pub fn load(path: &std::path::Path) -> Result<Scenario, String> {
        let text = ilmr_files::read_text(path, ilmr_files::Kind::Scenario)
            .map_err(|e| format!("cannot read scenario `{}`: {e}", path.display()))?;
        Scenario::parse(&text).map_err(|e| format!("scenario `{}`: {e}", path.display()))
    }

    /// A scenario's text; its lines in the order of their times. A refusal names
    /// its line and column.
    pub fn parse(text: &str) -> Result<Scenario, String> {
        let mut s: Scenario = serde_json::from_str(text).map_err(|e| {
            // serde_json quotes a string or key it does not take whole: the message
            // alone, cut short, and its place in front.
            let full = e.to_string();
            let at = format!(" at line {} column {}", e.line(), e.column());
            let message = full.strip_suffix(&at).unwrap_or(&full).to_string();
            format!(
                "line {}, column {}: {}",
                e.line().max(1),
                e.column(),
                clip(message)
            )
        })?;
        s.lines.sort_by(|a, b| a.t.total_cmp(&b.t));
        Ok(s)
    }

    /// Whether anything here needs a robot.
    pub fn drives_a_robot(&self) -> bool {
        self.start.is_some()
            || !self.readings.is_empty()
            || !self.sightings.is_empty()
            || !self.ops.is_empty()
            || !self.paths.is_empty()
    }

    /// Whether anything here stands in for a world (what a simulated robot senses).
    pub fn scripts_the_world(&self) -> bool {
        self.start.is_some()
            || !self.readings.is_empty()
            || !self.sightings.is_empty()
            || !self.ops.is_empty()
    }

    pub fn robot(&self, limits: Limits) -> Result<ScriptedRobot, String> {
        let mut r = ScriptedRobot::new(limits);
        if let Some(s) = self.start {
            // The heading as the test file gives it (270 degrees, say): the
            // scripted robot folds it as it drives.
            r = r.at(Pose {
                x: s.x,
                y: s.y,
                h: s.h.to_radians(),
            });
        }
        for reading in &self.readings {
            r = r.reading(reading.t, &reading.device, reading.value);
        }
        for s in &self.sightings {
            r = r.sighting(
                s.from,
                s.until,
                Detection {
                    sensor: s.sensor.clone(),
                    object: s.object.clone(),
                    x: s.x,
                    y: s.y,
                    h: s.h.to_radians(),
                    side: s.side,
                },
            );
        }
        for op in &self.ops {
            let ticks = (op.seconds / 0.01).round();
            if !(0.0..=f64::from(u32::MAX)).contains(&ticks) {
                return Err(clip(format!("op `{}`: seconds out of range", op.matcher)));
            }
            let outcome = match &op.fail {
                Some(why) => OpOutcome::Failed(why.clone()),
                None => OpOutcome::Done,
            };
            r = r.op(op_match(&op.matcher).map_err(clip)?, ticks as u32, outcome);
        }
        Ok(r)
    }
}

fn op_match(text: &str) -> Result<OpMatch, String> {
    let mut words = text.split_whitespace();
    let (kind, arg) = (words.next().unwrap_or(""), words.next());
    match (kind.to_ascii_lowercase().as_str(), arg) {
        ("any", None) => Ok(OpMatch::Any),
        ("init", None) => Ok(OpMatch::Init),
        ("movemode", Some(mode)) => Ok(OpMatch::MoveMode(mode.to_string())),
        ("manipulate", Some(task)) => ManipTask::from_name(task)
            .map(OpMatch::Manipulate)
            .ok_or_else(|| format!("no manipulation task `{task}`")),
        _ => Err(format!(
            "op `{text}`: expected `init`, `manipulate TASK`, `movemode MODE` or `any`"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// serde_json's message quoted a string it did not take whole: a megabyte of
    /// `start` was a megabyte of message.
    #[test]
    fn a_refusal_names_its_line_and_quotes_little() {
        let long = "x".repeat(1 << 20);
        let e = Scenario::parse(&format!("{{\n\"start\": \"{long}\"}}")).unwrap_err();
        assert!(e.starts_with("line 2, column "), "{}", &e[..100]);
        assert!(e.contains("invalid type: string"), "{}", &e[..100]);
        assert!(
            e.chars().count() < crate::problem::MAX_MESSAGE + 40,
            "{} chars",
            e.len()
        );
        let e = Scenario::parse("{\"ops\": [{\"match\": \"fly\", \"seconds\": 1}]}\n")
            .unwrap()
            .robot(Limits::default())
            .err()
            .unwrap();
        assert!(e.contains("op `fly`: expected"), "{e}");
        let op = format!("{{\"ops\": [{{\"match\": \"{long}\", \"seconds\": 1}}]}}");
        let e = Scenario::parse(&op)
            .unwrap()
            .robot(Limits::default())
            .err()
            .unwrap();
        assert!(
            e.chars().count() <= crate::problem::MAX_MESSAGE,
            "{} chars",
            e.len()
        );
    }

    #[test]
    fn lines_are_read_in_the_order_of_their_times() {
        let s = Scenario::parse(r#"{"lines": [{"t": 2, "text": "b"}, {"t": 1, "text": "a"}]}"#)
            .unwrap();
        let texts: Vec<&str> = s.lines.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(texts, ["a", "b"]);
    }
}
