//! `serve` request lines through the protocol parser (src/serve/protocol.rs, compiled
//! in here since the root package has no library), and every answer as one JSON line.

use serde_json::Value;

use crate::engine::{self, Budget, Rng, Stats};
use crate::mutate;

#[allow(dead_code)]
#[path = "../../../src/serve/protocol.rs"]
mod protocol;

use protocol::Request;

/// Requests as clients send them (docs/serve.md), good and bad.
const SEEDS: &[&str] = &[
    r#"{"ilmr": "goahead(1)", "id": 1}"#,
    r#"{"ilmr": "speed(0.2)\ngoahead(0.5)", "id": "two"}"#,
    r#"{"status": true}"#,
    r#"{"stop": true}"#,
    r#"{"cont": true, "id": [1, {"a": null}]}"#,
    r#"{"subscribe": "events", "id": 9}"#,
    r#"{"ilmr": "if(door)\n  gotoxy(door)\nendif"}"#,
    r#"{"fly": true}"#,
    r#"[1, 2]"#,
    "this is not json",
];

pub fn seeds() -> Vec<Vec<u8>> {
    SEEDS.iter().map(|s| s.as_bytes().to_vec()).collect()
}

pub fn fuzz(budget: Budget) -> Stats {
    engine::run("request", &seeds(), budget, mutation, feed)
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/request.rs`).
pub fn feed(input: &[u8]) {
    // The connection answers bytes that are not UTF-8 itself; the parser sees text.
    let Ok(line) = std::str::from_utf8(input) else {
        return;
    };
    let parsed = protocol::parse(line);
    let body = match &parsed.request {
        Request::Invalid(why) => {
            assert!(!why.is_empty(), "an invalid request says why");
            protocol::error(why)
        }
        _ => serde_json::Map::new(),
    };
    let answer = protocol::answer(body.clone(), parsed.id.as_ref());
    assert!(!answer.contains('\n'), "an answer is one line: {answer}");
    let back: Value = match serde_json::from_str(&answer) {
        Ok(v) => v,
        Err(e) => panic!("the answer is not JSON ({e}): {answer}"),
    };
    assert_eq!(back.get("id"), parsed.id.as_ref(), "the id is echoed");
    assert_eq!(back.get("error"), body.get("error"));
}

fn mutation(base: &[u8], rng: &mut Rng) -> Vec<u8> {
    match rng.below(4) {
        0 => mutate::bytes(base.to_vec(), rng),
        1 => {
            // Nesting beyond serde_json's recursion limit, and wide objects.
            let depth = 1 + rng.below(300);
            let mut out = "[".repeat(depth).into_bytes();
            out.extend_from_slice(base);
            out.extend(std::iter::repeat_n(b']', depth));
            out
        }
        _ => mutate::json(base, rng),
    }
}
