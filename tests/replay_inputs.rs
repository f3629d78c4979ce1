//! `ilmrc run --record-inputs` and `ilmrc replay --inputs` (`src/tape`): a run replayed
//! from its recorded inputs, without robot or simulator, gives its trace byte for
//! byte; a changed task is shown where it parts from the recording; a recording that
//! is not one is refused with a clear message.

mod support;

use std::path::{Path, PathBuf};

use support::{ilmrc, root};

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("ilmr-replay-{}-{name}", std::process::id()))
}

/// Runs `ilmrc run ARGS --record-inputs --trace OUT`; the trace's path.
fn record(name: &str, args: &[String]) -> PathBuf {
    let trace = scratch(&format!("{name}.jsonl"));
    let mut argv = vec!["run"];
    argv.extend(args.iter().map(String::as_str));
    argv.extend(["--record-inputs", "--trace", trace.to_str().unwrap()]);
    let (code, out, err) = ilmrc(&argv);
    assert!(
        matches!(code, 0 | 3 | 5),
        "ilmrc run {argv:?}: exit {code}\n{out}{err}"
    );
    trace
}

/// `ilmrc replay --inputs RECORDING TASK [EXTRA] --trace OUT`; the exit code, what
/// it said, and the replayed trace.
fn replay(recording: &Path, task: &str, extra: &[&str]) -> (i32, String, Vec<u8>) {
    let out = recording.with_extension("replayed.jsonl");
    let mut argv = vec![
        "replay",
        "--inputs",
        recording.to_str().unwrap(),
        task,
        "--trace",
        out.to_str().unwrap(),
    ];
    argv.extend_from_slice(extra);
    let (code, stdout, stderr) = ilmrc(&argv);
    let replayed = std::fs::read(&out).unwrap_or_default();
    let _ = std::fs::remove_file(&out);
    (code, format!("{stdout}{stderr}"), replayed)
}

/// The run cases of `tests/run/` (the scripted robot with readings, sightings,
/// operations, taught paths and interactive lines; `--robot none`), a simulated MoRo
/// and Workpartner, and a simulated run with an injected fault.
fn cases() -> Vec<(String, Vec<String>)> {
    let mut cases = Vec::new();
    let dir = root().join("tests/run");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "args"))
        .collect();
    files.sort();
    for f in files {
        let args = std::fs::read_to_string(&f)
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect();
        cases.push((f.file_stem().unwrap().to_string_lossy().into_owned(), args));
    }
    let owned = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    cases.push((
        "sim_moro".into(),
        owned(&["--seed", "4", "examples/short_task.ilmr"]),
    ));
    cases.push((
        "sim_fault".into(),
        owned(&[
            "--fault",
            "scanner_dropout@3+2",
            "--max-time",
            "20",
            "examples/short_task.ilmr",
        ]),
    ));
    cases.push((
        "sim_workpartner".into(),
        owned(&[
            "--robot",
            "workpartner",
            "--skills",
            "examples/skills",
            "--max-time",
            "40",
            "examples/concurrency.ilmr",
        ]),
    ));
    cases
}

#[test]
fn every_recorded_run_replays_to_its_own_trace_byte_for_byte() {
    for (name, args) in cases() {
        let recording = record(&name, &args);
        let recorded = std::fs::read(&recording).unwrap();
        let task = args.last().unwrap();
        let skills: Vec<&str> = args
            .iter()
            .position(|a| a == "--skills")
            .map(|i| vec!["--skills", args[i + 1].as_str()])
            .unwrap_or_default();
        let (code, said, replayed) = replay(&recording, task, &skills);
        let _ = std::fs::remove_file(&recording);
        assert_eq!(code, 0, "{name}: {said}");
        assert!(
            said.contains("the trace is the recording's, byte for byte"),
            "{name}: {said}"
        );
        assert!(replayed == recorded, "{name}: the replayed trace differs");
        let text = String::from_utf8(recorded).unwrap();
        assert!(text.contains(r#""event":"tape""#), "{name}");
        assert!(text.contains(r#""event":"input""#), "{name}");
    }
}

#[test]
fn a_changed_task_is_shown_where_it_parts_from_the_recording() {
    let recording = record("changed", &["examples/short_task.ilmr".to_string()]);
    let changed = scratch("changed.ilmr");
    let text = std::fs::read_to_string(root().join("examples/short_task.ilmr")).unwrap();
    std::fs::write(
        &changed,
        text.replace("turn(d=90,c=0.5)\nm=", "turn(d=45,c=0.5)\nm="),
    )
    .unwrap();
    let (code, said, _) = replay(&recording, changed.to_str().unwrap(), &[]);
    let _ = std::fs::remove_file(&recording);
    let _ = std::fs::remove_file(&changed);
    assert_eq!(code, 1, "{said}");
    assert!(
        said.contains("the replay parts from the recording"),
        "{said}"
    );
    // The first call that differs is a steering command: the shorter turn asks for
    // a straight path sooner.
    assert!(
        said.contains("first call to the robot that differs: at t = ")
            && said.contains("the recorded run called set_motion(speed "),
        "{said}"
    );
    assert!(
        said.contains(r#"B: {"t":0,"event":"issue","line":5,"text":"turn(d=45,c=0.5)"}"#),
        "{said}"
    );
    assert!(
        said.contains("statement: line 5 `turn(d=90,c=0.5)`"),
        "{said}"
    );
}

#[test]
fn a_trace_without_inputs_or_with_broken_ones_is_refused() {
    let plain = scratch("plain.jsonl");
    let (code, out, err) = ilmrc(&[
        "run",
        "--robot",
        "none",
        "--trace",
        plain.to_str().unwrap(),
        "tests/run/counting.ilmr",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let (code, said, _) = replay(&plain, "tests/run/counting.ilmr", &[]);
    assert_eq!(code, 2, "{said}");
    assert!(
        said.contains("has no recorded inputs: record them with `ilmrc run --record-inputs"),
        "{said}"
    );

    let recording = record(
        "broken",
        &["--robot", "none", "tests/run/counting.ilmr"].map(String::from),
    );
    let text = std::fs::read_to_string(&recording).unwrap();
    let broken = scratch("broken-input.jsonl");
    std::fs::write(
        &broken,
        text.replacen(r#""call":"update""#, r#""call":"teleport""#, 1),
    )
    .unwrap();
    let (code, said, _) = replay(&broken, "tests/run/counting.ilmr", &[]);
    assert_eq!(code, 2, "{said}");
    assert!(said.contains("T0101"), "{said}");

    let future = scratch("future.jsonl");
    std::fs::write(&future, text.replacen(r#""format":1"#, r#""format":99"#, 1)).unwrap();
    let (code, said, _) = replay(&future, "tests/run/counting.ilmr", &[]);
    assert_eq!(code, 2, "{said}");
    assert!(
        said.contains("records its inputs in form 99; this ilmrc replays form 1"),
        "{said}"
    );
    let endless = scratch("endless.jsonl");
    std::fs::write(
        &endless,
        text.replacen(r#""max_time":600.0"#, r#""max_time":"nan""#, 1),
    )
    .unwrap();
    let (code, said, _) = replay(&endless, "tests/run/counting.ilmr", &[]);
    assert_eq!(code, 2, "{said}");
    assert!(
        said.contains("the recording's `tape` line: --max-time NaN is not a time"),
        "{said}"
    );
    for p in [&plain, &recording, &broken, &future, &endless] {
        let _ = std::fs::remove_file(p);
    }
}

/// A recording cut short (its end lost) replays up to where it ends, says so, and
/// differs from it only by what the cut took.
#[test]
fn a_recording_cut_short_replays_to_its_end() {
    let recording = record(
        "cut",
        &["--seed", "2", "examples/short_task.ilmr"].map(String::from),
    );
    let text = std::fs::read_to_string(&recording).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let cut = scratch("cut-short.jsonl");
    std::fs::write(&cut, lines[..lines.len() / 2].join("\n") + "\n").unwrap();
    let (code, said, _) = replay(&cut, "examples/short_task.ilmr", &[]);
    for p in [&recording, &cut] {
        let _ = std::fs::remove_file(p);
    }
    assert_eq!(code, 1, "{said}");
    assert!(
        said.contains("recording ended: no recorded inputs after t="),
        "{said}"
    );
    assert!(
        said.contains("every call to the robot was the recording's"),
        "{said}"
    );
}

#[test]
fn recording_inputs_needs_a_trace_and_replay_options_need_inputs() {
    let (code, _, err) = ilmrc(&["run", "--record-inputs", "examples/short_task.ilmr"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--trace"), "{err}");
    let (code, _, err) = ilmrc(&["replay", "x.jsonl", "--skills", "examples/skills"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--inputs"), "{err}");
    let (code, _, err) = ilmrc(&["replay", "x.jsonl"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("give --plot OUT.svg"), "{err}");
}

/// `--record-inputs --mcap` puts the same lines on `/ilmr/inputs` (JSON, with the
/// trace's JSON Schema), which Foxglove's Python reader decodes; a replay from the MCAP
/// file runs the task as the trace's replay does, and tells a changed task's first
/// differing call (an MCAP file has no trace to compare events with).
#[test]
fn a_recording_in_mcap_replays_too() {
    let mcap = scratch("run.mcap");
    let trace = record(
        "mcap",
        &[
            "--robot",
            "none",
            "--scenario",
            "tests/run/counting.json",
            "--mcap",
            mcap.to_str().unwrap(),
            "tests/run/counting.ilmr",
        ]
        .map(String::from),
    );
    let recorded = std::fs::read(&trace).unwrap();
    let topics = support::foxglove_reads(&mcap);
    let inputs = &topics["/ilmr/inputs"];
    assert_eq!(inputs["schema"], "ilmr.trace.Line", "{topics}");
    assert_eq!(inputs["message_encoding"], "json", "{topics}");
    let events = &inputs["events"];
    assert_eq!(events["tape"], 1, "{inputs}");
    assert_eq!(events["line"], 3, "the scenario's three lines: {inputs}");
    let ticks = events["input"].as_u64().unwrap_or(0);
    assert!(ticks > 100, "{inputs}");

    let (code, said, replayed) = replay(&mcap, "tests/run/counting.ilmr", &[]);
    assert_eq!(code, 0, "{said}");
    assert!(
        said.contains(&format!(
            "replayed {ticks} ticks of recorded inputs; every call to the robot was the recording's"
        )),
        "{said}"
    );
    assert!(
        replayed == recorded,
        "the replay from MCAP differs from the trace"
    );

    let changed = scratch("counting-changed.ilmr");
    let text = std::fs::read_to_string(root().join("tests/run/counting.ilmr")).unwrap();
    std::fs::write(&changed, text.replacen("wait(", "wait(0.5+", 1)).unwrap();
    let (code, said, _) = replay(&mcap, changed.to_str().unwrap(), &[]);
    for p in [&mcap, &trace, &changed] {
        let _ = std::fs::remove_file(p);
    }
    assert_eq!(code, 1, "{said}");
    assert!(
        said.contains("the replay parts from the recording"),
        "{said}"
    );
    // Without a robot every tick's calls are the same two; the slower count outlives
    // the recording.
    assert!(
        said.contains("every call to the robot was the recording's, but the task had not ended when the recording did"),
        "{said}"
    );
}
