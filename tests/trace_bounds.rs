//! A task's trace cannot grow without bound: a tight loop's thousands of statements a
//! tick become one event per statement and variable a tick (`vm/src/runtime/trace.rs`),
//! and the files stop at their caps (`src/run/record.rs`, `src/run/mcap/`).

mod support;

use support::ilmrc_within;

#[test]
fn a_tight_loop_traces_one_event_per_statement_a_tick_and_every_overrun() {
    let dir = std::env::temp_dir().join(format!("ilmr-trace-bounds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let task = dir.join("tight.ilmr");
    std::fs::write(&task, "x=0\nwhile(x>-1)\nx=x+1\nendwhile\n").expect("task");
    let trace = dir.join("tight.jsonl");
    let mcap = dir.join("tight.mcap");
    let (code, out, err) = ilmrc_within(
        &[
            "run",
            task.to_str().unwrap(),
            "--max-time",
            "3",
            "--trace",
            trace.to_str().unwrap(),
            "--mcap",
            mcap.to_str().unwrap(),
        ],
        std::time::Duration::from_secs(120),
    );
    // The loop never ends: the run stops at --max-time with it live.
    assert_eq!(code, 5, "{out}{err}");
    let text = std::fs::read_to_string(&trace).expect("trace");
    let mcap_len = std::fs::metadata(&mcap).expect("mcap").len();
    let foxglove = support::foxglove_reads(&mcap);
    let _ = std::fs::remove_dir_all(&dir);
    let overruns = foxglove["/commands"]["logs"]
        .as_array()
        .expect("log messages")
        .iter()
        .filter(|l| {
            l["message"]
                .as_str()
                .is_some_and(|m| m.starts_with("overrun"))
        })
        .count();
    assert_eq!(overruns, 300, "every overrun is in the recording too");
    // 300 ticks of 25,000 statements each were 7.5 million events, about 1.5 GB.
    assert!(text.len() < 200_000, "{} bytes of trace", text.len());
    assert!(mcap_len < 2_000_000, "{mcap_len} bytes of MCAP");
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON"))
        .collect();
    let of = |name: &'static str| lines.iter().filter(move |v| v["event"] == name);
    assert_eq!(of("overrun").count(), 300, "every tick's overrun is kept");
    let writes: u64 = of("var").map(|v| v["count"].as_u64().unwrap_or(1)).sum();
    let last = of("var").next_back().expect("a var event");
    assert_eq!(
        last["value"].as_u64(),
        Some(writes - 1),
        "x=0 and every x=x+1 counted; the last value kept: {last}"
    );
    assert!(writes > 300 * 1000, "{writes} writes");
    assert!(out.contains("overruns        300"), "{out}");
}
