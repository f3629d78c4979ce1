//! `ilmrc run` on the simulated robots and `ilmrc replay`, as a user runs them: the
//! dissertation's Figure 52 on MoRo in the office, Figure 58 in the office too (to
//! the end: the door found, out into its 2 m corridor and into the lobby), and test 1's turn on Workpartner in the yard (trace snapshots,
//! byte-identical per seed, plot, MCAP read back), and every failure a user can cause
//! with its message and exit code.

mod support;

use std::path::PathBuf;

use serde_json::json;
use support::{ilmrc, summary_exit};

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("ilmr-sim-run-{}-{name}", std::process::id()))
}

/// The outputs of one run: trace, MCAP, SVG bytes and the summary.
struct Outputs {
    trace: Vec<u8>,
    mcap: Vec<u8>,
    /// The MCAP file as `tools/read_mcap.py` read it.
    foxglove: serde_json::Value,
    svg: Vec<u8>,
    summary: String,
}

fn run_with_outputs(name: &str, args: &[&str]) -> Outputs {
    let (t, m, p) = (
        scratch(&format!("{name}.jsonl")),
        scratch(&format!("{name}.mcap")),
        scratch(&format!("{name}.svg")),
    );
    let (ts, ms, ps) = (
        t.display().to_string(),
        m.display().to_string(),
        p.display().to_string(),
    );
    let mut a = vec!["run"];
    a.extend_from_slice(args);
    a.extend(["--trace", &ts, "--mcap", &ms, "--plot", &ps]);
    let (code, out, err) = ilmrc(&a);
    // The snapshots hold the summary, and with it how each case must end.
    assert_eq!(Some(code), summary_exit(&out), "{name}: {out}{err}");
    assert!(!matches!(code, 1 | 2), "{name}: {out}{err}");
    let read = |p: &PathBuf| {
        let bytes = std::fs::read(p).expect("output written");
        let _ = std::fs::remove_file(p);
        bytes
    };
    // Every recording is read by Foxglove's own reader, every message decoded.
    let foxglove = support::foxglove_reads(&m);
    Outputs {
        trace: read(&t),
        mcap: read(&m),
        foxglove,
        svg: read(&p),
        summary: out,
    }
}

/// The trace without its scans (hundreds of hit coordinates a line), for reading.
fn readable(trace: &[u8]) -> String {
    String::from_utf8(trace.to_vec())
        .expect("UTF-8")
        .lines()
        .filter(|l| !l.contains("\"event\":\"scan\""))
        .map(|l| format!("{l}\n"))
        .collect()
}

const CASES: [(&str, &[&str]); 3] = [
    (
        "fig52_short_task",
        &["--pose-every", "100", "examples/short_task.ilmr"],
    ),
    (
        "fig58_way_out",
        &[
            "--world",
            "office",
            "--start",
            "4,6,0",
            "--max-time",
            "120",
            "--pose-every",
            "500",
            "examples/way_out.ilmr",
        ],
    ),
    (
        "test1_turn_workpartner_yard",
        &[
            "--robot",
            "workpartner",
            "--world",
            "yard",
            "--seed",
            "1",
            "--pose-every",
            "100",
            "tests/sim_run/test1_turn.ilmr",
        ],
    ),
];

#[test]
fn simulated_runs_are_snapshots_and_byte_identical_per_seed() {
    for (name, args) in CASES {
        let one = run_with_outputs(&format!("{name}-1"), args);
        let two = run_with_outputs(&format!("{name}-2"), args);
        assert!(one.trace == two.trace, "{name}: traces differ");
        assert!(one.mcap == two.mcap, "{name}: MCAP files differ");
        assert!(one.svg == two.svg, "{name}: plots differ");
        insta::assert_snapshot!(
            format!("trace_{name}"),
            format!("{}---\n{}", readable(&one.trace), one.summary)
        );
    }
}

#[test]
fn another_seed_gives_another_run() {
    let base = [
        "--pose-every",
        "100",
        "--max-time",
        "10",
        "examples/short_task.ilmr",
    ];
    let zero = run_with_outputs("seed0", &base);
    let mut seeded = vec!["--seed", "7"];
    seeded.extend(base);
    let seven = run_with_outputs("seed7", &seeded);
    assert!(zero.trace != seven.trace, "the seed reaches the simulator");
}

#[test]
fn figure_52_completes_with_the_defaults() {
    let (code, out, err) = ilmrc(&["run", "examples/short_task.ilmr"]);
    assert_eq!(code, 0, "{out}{err}");
    for expected in [
        "finished: no command left",
        "robot           moro (calibrated errors) in office",
        "7 completed, 0 broken, 0 refused",
        "contacts        0",
    ] {
        assert!(out.contains(expected), "{expected}: {out}");
    }
    assert!(err.is_empty(), "no progress line off a terminal: {err}");
}

#[test]
fn replay_draws_what_run_drew() {
    let run = run_with_outputs("replay", &["--max-time", "12", "examples/short_task.ilmr"]);
    let trace = scratch("replay-in.jsonl");
    let svg = scratch("replay-out.svg");
    std::fs::write(&trace, &run.trace).unwrap();
    let (code, out, err) = ilmrc(&[
        "replay",
        &trace.display().to_string(),
        "--plot",
        &svg.display().to_string(),
    ]);
    let drawn = std::fs::read(&svg).unwrap_or_default();
    let _ = (std::fs::remove_file(&trace), std::fs::remove_file(&svg));
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        drawn == run.svg,
        "replay draws the run's plot byte for byte"
    );
    let text = String::from_utf8(drawn).unwrap();
    assert!(text.starts_with("<svg"), "an SVG");
    for label in [
        "moro in office, seed 0",
        "true trajectory",
        "scanner hits",
        "speed (m/s)",
        "curvature (1/m)",
        "\n4\n</text>",
        "\n5\n</text>",
    ] {
        assert!(text.contains(label), "{label} is drawn");
    }
}

/// The ends of a task's movements in its trace: (line, t, x, linked).
fn movement_ends(trace: &[u8]) -> Vec<(u64, f64, f64, bool)> {
    let text = String::from_utf8(trace.to_vec()).unwrap();
    let events: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    events
        .iter()
        .filter(|v| v["event"] == "mark" && v["at"] == "end")
        .map(|v| {
            let line = v["line"].as_u64().unwrap();
            let end = events
                .iter()
                .find(|e| e["event"] == "end" && e["line"] == line)
                .unwrap();
            (
                line,
                v["t"].as_f64().unwrap(),
                v["x"].as_f64().unwrap(),
                end["linked"] == true,
            )
        })
        .collect()
}

#[test]
fn a_queued_movement_is_linked_and_wait_stops_on_the_point() {
    // The figures docs/language.md quotes, within a centimetre and a tick, on the
    // `basic` profile it quotes them for (a test of linking, not of the errors).
    let run_of = |name: &str, text: &str| {
        let task = scratch(&format!("{name}.ilmr"));
        std::fs::write(&task, text).unwrap();
        let run = run_with_outputs(
            name,
            &[
                "--world",
                "empty",
                "--sim-profile",
                "basic",
                task.to_str().unwrap(),
            ],
        );
        let _ = std::fs::remove_file(&task);
        movement_ends(&run.trace)
    };
    let close = |a: f64, b: f64, tolerance: f64| (a - b).abs() <= tolerance;
    let linked = run_of("linked", "speed(0.4)\ngotoxy(2,0)\ngotoxy(3.5,1.5,90)\n");
    assert_eq!(linked.len(), 2, "{linked:?}");
    let ((_, t1, x1, l1), (_, t2, _, l2)) = (linked[0], linked[1]);
    assert!(
        l1 && close(x1, 1.50, 0.01) && close(t1, 4.17, 0.011),
        "{linked:?}"
    );
    assert!(!l2 && close(t2, 11.50, 0.011), "{linked:?}");
    let waited = run_of(
        "waited",
        "speed(0.4)\nm=gotoxy(2,0)\nwait(m)\ngotoxy(3.5,1.5,90)\n",
    );
    let ((_, t1, x1, l1), (_, t2, _, _)) = (waited[0], waited[1]);
    assert!(
        !l1 && close(x1, 2.00, 0.01) && close(t1, 5.60, 0.011),
        "{waited:?}"
    );
    assert!(close(t2, 12.02, 0.011), "{waited:?}");
    // A successor that cannot start from the end of the path is refused before the
    // running movement would link to it: that one drives to its end.
    let refused = run_of("unlinked", "goahead(1)\ngotoxy(1.2,0.5)\n");
    let first = refused.iter().find(|m| m.0 == 1).expect("goahead(1) ended");
    assert!(!first.3 && close(first.2, 1.0, 0.01), "{refused:?}");
}

#[test]
fn the_mcap_log_says_what_each_refusal_and_fault_was_at_its_level() {
    let task = scratch("mcap-held.ilmr");
    // A refusal, then, with avoidance off, straight on at the lab's cabinet: a hold.
    std::fs::write(&task, "gotoxy(8.1,5.5)\nobsavoid(off)\ngoahead(10)\n").unwrap();
    let run = run_with_outputs("mcap-held", &["--hold-limit", "2", task.to_str().unwrap()]);
    let _ = std::fs::remove_file(&task);
    let logs = run.foxglove["/commands"]["logs"]
        .as_array()
        .expect("log messages")
        .clone();
    let said = |start: &str| {
        logs.iter()
            .find(|v| v["message"].as_str().is_some_and(|m| m.starts_with(start)))
            .unwrap_or_else(|| panic!("no `{start}` log in {logs:#?}"))
    };
    let held = said("held (R0206 obstacle_near): an obstacle");
    assert_eq!(held["level"], 4, "a hold halts the robot: an error");
    assert!(
        held["message"]
            .as_str()
            .unwrap()
            .contains("; way out: clear the way")
    );
    let refused = said("refused (R0110): the path needs curvature");
    assert_eq!(refused["level"], 3, "a refusal is a warning");
    assert_eq!(refused["line"], 1);
}

#[test]
fn the_mcap_file_reads_back_with_foxglove_schemas() {
    let run = run_with_outputs("mcap", &["--max-time", "8", "examples/short_task.ilmr"]);
    let mut last_time = 0;
    for m in mcap::MessageStream::new(&run.mcap).expect("an MCAP file") {
        let m = m.expect("a message");
        assert!(m.log_time >= last_time, "messages in time order");
        last_time = m.log_time;
    }
    let topics = &run.foxglove;
    let expect = [
        ("/commands", "foxglove.Log"),
        ("/motion", "motion.Motion"),
        ("/pose", "foxglove.PoseInFrame"),
        ("/tf", "foxglove.FrameTransforms"),
        ("/scan", "foxglove.LaserScan"),
        ("/world", "foxglove.SceneUpdate"),
        ("/paths", "foxglove.SceneUpdate"),
        ("/trajectory", "foxglove.SceneUpdate"),
        ("/variables", "variable.Variable"),
    ];
    for (topic, schema) in expect {
        let t = &topics[topic];
        assert_eq!(t["schema"], schema, "{topic}: {t}");
        assert_eq!(
            (&t["schema_encoding"], &t["message_encoding"]),
            (&json!("protobuf"), &json!("protobuf")),
            "{topic}"
        );
    }
    assert_eq!(topics["/world"]["count"], 1, "the world once");
    assert_eq!(
        topics["/pose"]["count"], 81,
        "8 s at 10 Hz, and the last tick's"
    );
    assert_eq!(topics["/tf"]["frames"], json!(["world", "base_link"]));
    assert_eq!(topics["/scan"]["beams"], 361);
    assert!(
        topics["/scan"]["count"].as_u64().unwrap() >= 32,
        "every scan at 4 Hz"
    );
    // The poses Foxglove's reader decodes are the trace's, sample for sample.
    let traced: Vec<(f64, f64, f64)> = String::from_utf8_lossy(&run.trace)
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).expect("JSON"))
        .filter(|v| v["event"] == "pose")
        .map(|v| {
            (
                v["t"].as_f64().unwrap(),
                v["x"].as_f64().unwrap(),
                v["y"].as_f64().unwrap(),
            )
        })
        .collect();
    let recorded: Vec<(f64, f64, f64)> = topics["/pose"]["poses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            (
                p[0].as_f64().unwrap(),
                p[1].as_f64().unwrap(),
                p[2].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(traced.len(), recorded.len());
    for (a, b) in traced.iter().zip(&recorded) {
        // The trace gives four decimals.
        assert!(
            (a.0 - b.0).abs() < 1e-6 && (a.1 - b.1).abs() < 6e-5 && (a.2 - b.2).abs() < 6e-5,
            "trace {a:?}, MCAP {b:?}"
        );
    }
    let steps = topics["/trajectory"]["entities"].as_array().unwrap();
    assert!(!steps.is_empty() && steps[0] == "trajectory-1", "{steps:?}");
}

#[test]
fn every_failure_a_user_can_cause_has_a_message_and_an_exit_code() {
    let bad_world = scratch("bad-world.toml");
    std::fs::write(
        &bad_world,
        "name = \"x\"\nbounds = { min = [0, 0], max = [1, 1] }\nstart = { x = 9, y = 9 }\n",
    )
    .unwrap();
    let not_a_trace = scratch("not-a-trace.jsonl");
    std::fs::write(&not_a_trace, "hello\n").unwrap();
    let bw = bad_world.display().to_string();
    let nt = not_a_trace.display().to_string();
    // A trace of before schema versions, and one of a newer schema.
    let unversioned = scratch("unversioned.jsonl");
    std::fs::write(
        &unversioned,
        "{\"t\":0,\"event\":\"pose\",\"x\":0,\"y\":0,\"h\":0,\"v\":0,\"c\":0,\"source\":\"true\"}\n",
    )
    .unwrap();
    let uv = unversioned.display().to_string();
    let newer = scratch("newer.jsonl");
    std::fs::write(&newer, "{\"t\":0,\"event\":\"trace\",\"version\":99}\n").unwrap();
    let nw = newer.display().to_string();
    let task = "examples/short_task.ilmr";
    let cases: Vec<(Vec<&str>, i32, &str)> = vec![
        (vec!["run", "no/such.ilmr"], 2, "cannot read"),
        (
            vec!["run", "tests/check/broken/commands.ilmr"],
            1,
            "error(s)",
        ),
        (
            vec!["run", "--robot", "r2d2", task],
            2,
            "unknown robot `r2d2`",
        ),
        (
            vec!["run", "--robot", "no/such.ini", task],
            2,
            "cannot read robot model",
        ),
        (vec!["run", "--robot", "tests", task], 2, "unknown robot"),
        (
            vec!["run", "--robot", "examples/", task],
            2,
            "cannot read robot model",
        ),
        (
            vec!["run", "--world", "moon", task],
            2,
            "unknown world `moon`",
        ),
        (
            vec!["run", "--world", "no/such.toml", task],
            2,
            "cannot read world",
        ),
        (vec!["run", "--world", &bw, task], 2, "bad world file"),
        (
            vec!["run", "--start", "1,2", task],
            2,
            "expected X,Y,HEADING",
        ),
        (
            vec!["run", "--start", "100,100,0", task],
            2,
            "outside the world",
        ),
        (vec!["run", "--start", "2.5,6,0", task], 2, "cannot start"),
        (
            vec!["run", "--robot", "scripted", "--world", "office", task],
            2,
            "has no world",
        ),
        (vec!["run", "--model", "moro", task], 2, "--model is for"),
        (
            vec!["run", "--trace", "no/such/dir/t.jsonl", task],
            2,
            "cannot write trace",
        ),
        (
            vec!["run", "--plot", "no/such/dir/p.svg", task],
            2,
            "cannot write plot",
        ),
        (
            vec!["run", "--mcap", "no/such/dir/m.mcap", task],
            2,
            "cannot write MCAP",
        ),
        (
            vec!["run", "--scenario", "tests/run/fig58_way_out.json", task],
            2,
            "only the scripted robot",
        ),
        (vec!["run", "--max-time=-1", task], 2, "not a time"),
        (vec!["run", "--seed", "x", task], 2, "invalid value"),
        (
            vec!["replay", "no/such.jsonl", "--plot", "x.svg"],
            2,
            "cannot read trace",
        ),
        (
            vec!["replay", &nt, "--plot", "no/such/dir/x.svg"],
            2,
            "is not a trace",
        ),
        (
            vec!["replay", &uv, "--plot", "x.svg"],
            2,
            "line 1: T0102 the first line is not `{\"t\":0,\"event\":\"trace\",\"version\":N}`",
        ),
        (
            vec!["replay", &nw, "--plot", "x.svg"],
            2,
            "line 1: T0103 the trace has schema version 99; this ilmrc reads version 1",
        ),
    ];
    for (args, code, message) in cases {
        let (got, out, err) = ilmrc(&args);
        assert_eq!(got, code, "{args:?}: {out}{err}");
        assert!(
            out.contains(message) || err.contains(message),
            "{args:?}: expected `{message}` in {out}{err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    let _ = (
        std::fs::remove_file(&bad_world),
        std::fs::remove_file(&not_a_trace),
        std::fs::remove_file(&unversioned),
        std::fs::remove_file(&newer),
    );
}

/// `--sim-profile` chooses the simulated robot's errors, `calibrated` when it is not
/// given: the run says which in its summary and its trace's `run` line (left out for
/// `basic`, so that the traces recorded before profiles existed read as they were);
/// `ideal` and `calibrated` runs of one seed differ, each is the same run again; a
/// robot that is not simulated refuses the flag.
#[test]
fn the_simulated_robots_errors_are_chosen_by_profile() {
    let run = |profile: &str| {
        let trace = scratch(&format!("profile-{profile}.jsonl"));
        let mut args = vec!["run"];
        if !profile.is_empty() {
            args.extend(["--sim-profile", profile]);
        }
        args.extend(["--seed", "3", "--trace", trace.to_str().unwrap()]);
        args.push("examples/short_task.ilmr");
        let (code, out, err) = ilmrc(&args);
        assert_eq!(code, 0, "{out}{err}");
        let text = std::fs::read_to_string(&trace).unwrap();
        let _ = std::fs::remove_file(&trace);
        (text, out)
    };
    let (ideal, said) = run("ideal");
    assert!(
        said.contains("robot           moro (ideal errors) in office, seed 3"),
        "{said}"
    );
    assert!(
        ideal.contains(r#""seed":3,"profile":"ideal","start""#),
        "{ideal}"
    );
    let (calibrated, said) = run("calibrated");
    assert!(said.contains("(calibrated errors)"), "{said}");
    assert_ne!(ideal, calibrated, "the errors change the run");
    assert_eq!(run("calibrated").0, calibrated, "one seed, one run");
    let (default, said) = run("");
    assert_eq!(
        default, calibrated,
        "calibrated unless another profile is given"
    );
    assert!(said.contains("(calibrated errors)"), "{said}");
    let (basic, said) = run("basic");
    assert!(!basic.contains("\"profile\""), "{basic}");
    assert!(said.contains("robot           moro in office"), "{said}");

    let (code, _, err) = ilmrc(&[
        "run",
        "--robot",
        "none",
        "--sim-profile",
        "ideal",
        "tests/run/counting.ilmr",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(
            "--sim-profile ideal sets a simulated robot's errors; --robot none is not simulated"
        ),
        "{err}"
    );
    let (code, _, err) = ilmrc(&["run", "--sim-profile", "rough", "examples/short_task.ilmr"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("no profile `rough`: use ideal, basic, calibrated"),
        "{err}"
    );
}
