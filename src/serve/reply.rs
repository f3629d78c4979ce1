//! The engine's typed answers as the protocol's answer objects (docs/serve.md).

use ilmr_compiler::Diagnostic;
use ilmr_compiler::render::{self, RenderFile};
use ilmr_vm::runtime::trace::fmt_num;
use serde_json::{Map, Value, json};

use super::protocol::error;
use crate::live::engine::{LineAnswer, Outcome, Status};

/// `{"ok": true, "t", "warnings"?}`, `{"ok": false, "t", "diagnostics"}` or an error
/// object. Positions in diagnostics are in `text`, the request's ILMR.
pub fn line(answer: &LineAnswer, text: &str) -> Map<String, Value> {
    match &answer.outcome {
        Outcome::Accepted { warnings } => {
            let mut m = ok(answer.t);
            if !warnings.is_empty() {
                m.insert("warnings".into(), diagnostics(warnings, text));
            }
            m
        }
        Outcome::Rejected { diagnostics: d } => {
            let mut m = Map::new();
            m.insert("ok".into(), json!(false));
            m.insert("t".into(), time(answer.t));
            m.insert("diagnostics".into(), diagnostics(d, text));
            m
        }
        Outcome::Failed(why) => error(why),
    }
}

fn diagnostics(d: &[Diagnostic], text: &str) -> Value {
    let files = [RenderFile {
        path: "<line>",
        text,
    }];
    json!(render::json(d, &files))
}

/// Simulated time, the robot's pose and speed, and what is live.
pub fn status(s: &Status) -> Map<String, Value> {
    let a = &s.activity;
    let mut m = ok(s.t);
    m.insert("ticks".into(), json!(s.ticks));
    m.insert(
        "pose".into(),
        json!({"x": s.pose.x, "y": s.pose.y, "h": s.pose.h}),
    );
    m.insert("speed".into(), json!(s.speed));
    m.insert("curvature".into(), json!(s.curvature));
    m.insert("longest_tick_gap".into(), json!(s.longest_tick_gap));
    m.insert(
        "faults".into(),
        s.faults
            .iter()
            .map(|f| {
                let code = ilmr_vm::runtime::safety::Code::Fault(*f);
                json!({"fault": f.name(), "code": code.code(), "reaction": f.reaction().name(), "help": code.help()})
            })
            .collect(),
    );
    m.insert(
        "activity".into(),
        json!({
            "running_commands": a.running_commands,
            "queued_movements": a.queued_movements,
            "waiting_guards": a.waiting_guards,
            "sleeping": a.sleeping,
            "issuing_blocks": a.issuing_blocks,
            "ready": a.ready,
            "robot_at_rest": a.robot_at_rest,
            "finished": s.finished,
        }),
    );
    m
}

/// The answer to a subscription, at the VM's time `t`.
pub fn subscribed(t: f64) -> Map<String, Value> {
    ok(t)
}

/// Times as the trace writes them (`fmt_num`), so answers and events agree.
fn time(t: f64) -> Value {
    serde_json::from_str(&fmt_num(t)).unwrap_or(json!(t))
}

fn ok(t: f64) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("ok".into(), json!(true));
    m.insert("t".into(), time(t));
    m
}
