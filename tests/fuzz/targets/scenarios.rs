//! Scenario files (`--scenario FILE.json`, and a test file's `scenario`), through
//! `ilmr_testfile::scenario`: the reader, the scripted robot built from what it
//! accepts on both robots' limits, and that robot driven by the VM running an
//! example task, with the scenario's interactive lines offered at their times, as
//! `ilmrc run --robot scripted` does. A refusal names its line and is short.

use ilmr_compiler::lower::{LineOptions, lower_line_into};
use ilmr_model::RobotModel;
use ilmr_testfile::problem::MAX_MESSAGE;
use ilmr_testfile::scenario::{Scenario, scripted_limits};
use ilmr_vm::{Config, SimClock, TraceLevel, Vm};

use super::corpus::{self, ROBOTS};
use crate::engine::{self, Budget, Rng, Stats};
use crate::mutate;

/// Ticks the scripted robot runs: two seconds, so that early readings, sightings,
/// operations and lines come due.
const TICKS: u32 = 200;

/// The run fixtures' scenarios and the format's documented example.
pub fn seeds() -> Vec<Vec<u8>> {
    let mut out: Vec<Vec<u8>> = engine::files("tests/run", &["json"])
        .into_iter()
        .map(|(_, bytes)| bytes)
        .collect();
    out.push(EXAMPLE.as_bytes().to_vec());
    out
}

/// testfile/src/scenario.rs's example, every field given.
const EXAMPLE: &str = r#"{
  "start": {"x": 0, "y": 0, "h": 0},
  "readings": [{"t": 0, "device": "battery", "value": 25.0},
               {"t": 0.5, "device": "battery", "value": null}],
  "sightings": [{"from": 0.2, "until": 60, "sensor": "scanner", "object": "door",
                 "x": 4, "y": 1, "h": 90, "side": "left"}],
  "ops": [{"match": "manipulate take", "seconds": 0.3},
          {"match": "init", "seconds": 0.1, "fail": "stuck"},
          {"match": "movemode fast", "seconds": 0},
          {"match": "any", "seconds": 1}],
  "paths": {"PATH": [[0, 0], [10, 0]]},
  "lines": [{"t": 0.5, "text": "speed(0.2)"}, {"t": 0.1, "text": "x = 1"}]
}"#;

/// The models' limits, and the task each runs (Figure 52 on MoRo, Figure 20 on
/// Workpartner), compiled before the first input.
pub fn load() {
    for robot in ROBOTS {
        corpus::live_module(robot);
    }
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/scenario.rs`).
pub fn feed(input: &[u8]) {
    // `ilmr_files::read_text` refuses other bytes before the reader sees them.
    let Ok(text) = std::str::from_utf8(input) else {
        return;
    };
    let scenario = match Scenario::parse(text) {
        Ok(s) => s,
        Err(e) => {
            assert!(e.starts_with("line "), "a refusal names its line: {e}");
            short(&e);
            return;
        }
    };
    finite(&scenario);
    assert!(
        scenario.lines.is_sorted_by(|a, b| a.t <= b.t),
        "lines in the order of their times"
    );
    for robot in ROBOTS {
        let model = corpus::model(robot);
        match scenario.robot(scripted_limits(&model)) {
            Ok(scripted) => drive(&scenario, scripted, robot, &model),
            Err(e) => short(&e),
        }
    }
}

fn short(message: &str) {
    assert!(!message.is_empty(), "a refusal says why");
    assert!(
        message.chars().count() <= MAX_MESSAGE + 40,
        "a refusal of {} characters: {:?}",
        message.chars().count(),
        message.chars().take(400).collect::<String>()
    );
}

/// JSON has no infinity or NaN: every number the reader takes is finite.
fn finite(s: &Scenario) {
    let mut numbers: Vec<f64> = Vec::new();
    if let Some(st) = s.start {
        numbers.extend([st.x, st.y, st.h]);
    }
    for r in &s.readings {
        numbers.push(r.t);
        numbers.extend(r.value);
    }
    for g in &s.sightings {
        numbers.extend([g.from, g.until, g.x, g.y, g.h]);
    }
    numbers.extend(s.ops.iter().map(|o| o.seconds));
    numbers.extend(s.paths.values().flatten().flat_map(|&(x, y)| [x, y]));
    numbers.extend(s.lines.iter().map(|l| l.t));
    assert!(numbers.iter().all(|n| n.is_finite()), "{s:?}");
}

fn drive(scenario: &Scenario, scripted: ilmr_hal::ScriptedRobot, robot: &str, model: &RobotModel) {
    let config = Config {
        budget_ops: 500,
        trace: TraceLevel::Full,
        ..Config::default()
    };
    let mut vm = match Vm::new(corpus::live_module(robot), scripted, SimClock, config) {
        Ok(vm) => vm,
        Err(e) => panic!("the example task does not start on the scripted robot: {e}"),
    };
    let mut next = 0;
    for _ in 0..TICKS {
        while let Some(line) = scenario.lines.get(next).filter(|l| l.t <= vm.time() + 1e-9) {
            next += 1;
            let _ = vm.add_line(|b| lower_line_into(&line.text, b, model, LineOptions::default()));
        }
        vm.tick();
    }
    crate::pipeline::trace_is_json(&mut vm);
}

fn mutation(base: &[u8], rng: &mut Rng, corpus: &[Vec<u8>], words: &[String]) -> Vec<u8> {
    match rng.below(3) {
        0 => mutate::text(base, rng, corpus, words),
        _ => mutate::json(base, rng),
    }
}

/// The format's keys and JSON's words.
pub fn dictionary() -> Vec<String> {
    let mut words: Vec<String> = [
        "\"start\":",
        "\"readings\":",
        "\"sightings\":",
        "\"ops\":",
        "\"paths\":",
        "\"lines\":",
        "\"x\":",
        "\"y\":",
        "\"h\":",
        "\"t\":",
        "\"device\":",
        "\"value\":",
        "\"from\":",
        "\"until\":",
        "\"sensor\":",
        "\"object\":",
        "\"side\":",
        "\"match\":",
        "\"seconds\":",
        "\"fail\":",
        "\"text\":",
        "\"left\"",
        "\"right\"",
        "\"init\"",
        "\"any\"",
        "\"manipulate take\"",
        "\"movemode fast\"",
        "\"battery\"",
        "\"scanner\"",
        "{",
        "}",
        "[",
        "]",
        ",",
        "\"",
        "null",
        "true",
        "false",
        "1e308",
        "-1e308",
        "1e400",
        "4294967296",
        "42949672.96",
        "\\u0000",
        "\\ud800",
    ]
    .iter()
    .map(|w| w.to_string())
    .collect();
    words.extend(mutate::NUMBERS.iter().map(|w| w.to_string()));
    words
}

pub fn fuzz(budget: Budget) -> Stats {
    load();
    let corpus = seeds();
    let words = dictionary();
    engine::run(
        "scenario",
        &corpus,
        budget,
        |base, rng| mutation(base, rng, &corpus, &words),
        feed,
    )
}
