//! Garbage at a real `ilmrc serve` over TCP, with the harness of tests/serve.rs (this
//! file is a module of that test, so it reuses `Server` and `Client`): mutated
//! requests, bytes that are not UTF-8 or JSON, deep nesting. Every line is answered
//! with one JSON object (an error object when it is not a request), the connection
//! stays usable, and other clients keep being served.

use std::time::Instant;

use serde_json::{Value, json};

use super::{PATIENCE, Server};

#[allow(dead_code)]
#[path = "engine.rs"]
mod engine;
#[allow(dead_code)]
#[path = "mutate.rs"]
mod mutate;

/// Garbage lines per run: each is a round trip to a server that ticks at 100 Hz.
const LINES: usize = 400;

const SEEDS: &[&str] = &[
    r#"{"ilmr": "speed(0.2)", "id": 1}"#,
    r#"{"ilmr": "if(door)\n  gotoxy(door)\nendif", "id": "x"}"#,
    r#"{"status": true}"#,
    r#"{"stop": true}"#,
    r#"{"cont": true, "id": [1, {"a": null}]}"#,
    r#"{"ilmr": "goahed(1)"}"#,
    r#"{"fly": true}"#,
];

/// A garbage request line: never empty, never holding the newline that ends it.
fn garbage(rng: &mut engine::Rng) -> Vec<u8> {
    let base = rng.pick(SEEDS).copied().unwrap_or("{}").as_bytes();
    let mut line = match rng.below(5) {
        0 => mutate::bytes(base.to_vec(), rng),
        1 => {
            let depth = 1 + rng.below(400);
            let mut v = "[".repeat(depth).into_bytes();
            v.extend(std::iter::repeat_n(b']', rng.below(depth + 1)));
            v
        }
        _ => mutate::json(base, rng),
    };
    line.retain(|&b| b != b'\n');
    if line.is_empty() {
        line.push(b'{');
    }
    line
}

fn is_answer(v: &Value) -> bool {
    match v.get("ok") {
        Some(Value::Bool(true)) => true,
        Some(Value::Bool(false)) => {
            v.get("error").is_some_and(Value::is_string) || v.get("diagnostics").is_some()
        }
        _ => false,
    }
}

#[test]
fn garbage_lines_are_each_answered_and_no_client_is_lost() {
    let server = Server::start(&["--world", "empty"]);
    let mut bystander = server.connect();
    assert_eq!(bystander.ask(r#"{"status": true}"#)["ok"], json!(true));

    let mut fuzzer = server.connect();
    let mut rng = engine::Rng::new(engine::Budget::from_env(0).seed);
    let mut errors = 0;
    for i in 0..LINES {
        let line = garbage(&mut rng);
        let mut bytes = line.clone();
        bytes.push(b'\n');
        fuzzer.send_raw(&bytes);
        let deadline = Instant::now() + PATIENCE;
        let answer = loop {
            let Some(v) = fuzzer.next_line(deadline) else {
                panic!(
                    "line {i} got no answer: {:?}",
                    String::from_utf8_lossy(&line)
                );
            };
            if v.get("event").is_none() {
                break v;
            }
        };
        assert!(
            is_answer(&answer),
            "line {i} {:?} got {answer}",
            String::from_utf8_lossy(&line)
        );
        errors += usize::from(answer["ok"] == json!(false));
        if i % 50 == 49 {
            // Others are served while the garbage flows.
            assert_eq!(bystander.ask(r#"{"status": true}"#)["ok"], json!(true));
        }
    }
    assert!(errors > LINES / 2, "only {errors} of {LINES} were refused");
    assert_eq!(fuzzer.ask(r#"{"status": true, "id": 5}"#)["id"], json!(5));
    let mut newcomer = server.connect();
    assert_eq!(newcomer.ask(r#"{"status": true}"#)["ok"], json!(true));
}
