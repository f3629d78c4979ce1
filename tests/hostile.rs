//! The hostile-input corpus (issue 12): nesting at depths up to a million, huge and
//! non-finite numbers, and special files, through every entry point of `ilmrc` that
//! reads a program. Each run is bounded in time and address space, and must end with
//! exit 0, 1 or 2 and a message: never a panic (101), an abort (134), or a kill.
//! The limits themselves are in docs/reliability.md.

mod support;

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use support::root;

/// Address space one run may take: the stated memory bound of docs/reliability.md.
const ADDRESS_SPACE: u64 = 2 << 30;
/// Seconds one run may take in an unoptimised build before it counts as a hang.
const SECONDS: u32 = 120;

struct Ended {
    code: i32,
    stdout: String,
    stderr: String,
}

/// Runs `ilmrc args` under `prlimit` and `timeout`, with `input` on its stdin.
fn bounded(args: &[&str], input: Option<&[u8]>) -> Ended {
    let mut child = Command::new("timeout")
        .args(["-s", "KILL", &SECONDS.to_string(), "prlimit"])
        .arg(format!("--as={ADDRESS_SPACE}"))
        .arg(env!("CARGO_BIN_EXE_ilmrc"))
        .args(args)
        .current_dir(root())
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("timeout and prlimit (coreutils, util-linux) run");
    let mut stdin = child.stdin.take().unwrap();
    let input = input.map(<[u8]>::to_vec);
    // Written from a thread: a child that stops reading must not block the test.
    let writer = std::thread::spawn(move || {
        if let Some(input) = input {
            let _ = stdin.write_all(&input);
        }
    });
    let out = child.wait_with_output().unwrap();
    let _ = writer.join();
    Ended {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// Asserts a run ended as a tool should on bad input, and returns its exit code.
fn ends_cleanly(what: &str, ended: &Ended) -> i32 {
    let tail = |s: &str| {
        s.chars()
            .rev()
            .take(600)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect::<String>()
    };
    assert!(
        matches!(ended.code, 0..=5),
        "{what}: exit {} (0-5 are a run's or a check's ends; 101 panic, 134 abort, -1/137 killed by the bounds)\nstderr: {}",
        ended.code,
        tail(&ended.stderr)
    );
    if ended.code != 0 {
        assert!(
            !ended.stderr.trim().is_empty() || !ended.stdout.trim().is_empty(),
            "{what}: exit {} without a message",
            ended.code
        );
    }
    ended.code
}

/// A run took the task: it ran, however it ended (0, or 3-5 for refusals, a hold,
/// `--max-time`), rather than rejecting it (1) or its inputs (2).
fn accepted(run: i32) -> bool {
    !matches!(run, 1 | 2)
}

fn scratch() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("hostile");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(name: &str, text: &str) -> PathBuf {
    let path = scratch().join(name);
    std::fs::write(&path, text).unwrap();
    path
}

const DEPTHS: &[usize] = &[10, 256, 257, 10_000, 1_000_000];

/// Each shape of nesting, as a task of that depth.
fn nested(shape: &str, n: usize) -> String {
    match shape {
        "parens" => format!("x = {}1{}\nwait(x)\n", "(".repeat(n), ")".repeat(n)),
        "sum" => format!("x = 0{}\nwait(x)\n", "+0".repeat(n)),
        "minus" => format!("x = {}1\nwait(x + 2)\n", "-".repeat(n)),
        "unclosed" => format!("x = {}1\n", "(".repeat(n)),
        "if" => format!(
            "x = 1\n{}wait(0.1)\n{}",
            "if(x > 0)\n".repeat(n),
            "endif\n".repeat(n)
        ),
        "while" => format!(
            "x = 0\n{}x = x + 1\n{}",
            "while(x < 1)\n".repeat(n),
            "endwhile\n".repeat(n)
        ),
        "open if" => format!("x = 1\n{}", "if(x > 0)\n".repeat(n)),
        "stray endif" => "endif\n".repeat(n),
        _ => unreachable!(),
    }
}

const SHAPES: &[&str] = &[
    "parens",
    "sum",
    "minus",
    "unclosed",
    "if",
    "while",
    "open if",
    "stray endif",
];

/// Files at the size limit made of one broken line repeated: one diagnostic a line
/// would have been millions of them, and four million of these lines aborted `check`,
/// `parse` and `fmt` at the address-space bound. Every tool ends with its answer, and
/// `check` shows the first ones and counts the rest.
#[test]
fn millions_of_broken_lines_through_every_entry_point() {
    let limit = ilmr_compiler::limits::MAX_DIAGNOSTICS;
    let size = ilmr_files::MAX_SOURCE_BYTES as usize;
    // Whether the line is a syntax error, which `fmt` refuses to format.
    for (name, line, code, syntax) in [
        ("parens", "(\n", "E0101", true),
        ("unknown", "y\n", "E0301", false),
        ("stray_endif", "endif\n", "E0204", true),
    ] {
        let lines = size / line.len();
        let file = write(&format!("{name}_lines.ilmr"), &line.repeat(lines));
        let f = file.to_str().unwrap();
        let what = |tool: &str| format!("{tool} on {lines} lines of {line:?}");
        let json = bounded(&["check", "--format", "json", f], None);
        assert_eq!(ends_cleanly(&what("check --format json"), &json), 1);
        let found: Vec<serde_json::Value> = serde_json::from_str(&json.stdout).unwrap();
        assert_eq!(found.len(), limit + 1, "{}", what("check"));
        assert!(found[..limit].iter().all(|d| d["code"] == code));
        assert_eq!(found[limit - 1]["line"], limit);
        let note = &found[limit];
        assert_eq!(note["code"], "E0003");
        let message = note["message"].as_str().unwrap();
        assert!(
            message.starts_with(&format!("{} more problems", lines - limit)),
            "{}: {message}",
            what("check")
        );
        assert_eq!(
            ends_cleanly(&what("check"), &bounded(&["check", f], None)),
            1
        );
        ends_cleanly(&what("parse"), &bounded(&["parse", f], None));
        let fmt = ends_cleanly(&what("fmt --check"), &bounded(&["fmt", "--check", f], None));
        assert_eq!(
            fmt != 0,
            syntax,
            "{}",
            what("fmt refuses syntax errors only")
        );
        let ilmb = scratch().join(format!("{name}_lines.ilmb"));
        let build = bounded(&["build", f, "-o", ilmb.to_str().unwrap()], None);
        assert_eq!(ends_cleanly(&what("build"), &build), 1);
        let run = bounded(&["run", f, "--robot", "none", "--max-time", "2"], None);
        assert_eq!(ends_cleanly(&what("run"), &run), 1);
    }
}

/// The same file gets the same answer from every tool: what `check` accepts, `build`
/// builds and `run` runs; what it refuses, they refuse.
#[test]
fn nesting_through_every_entry_point() {
    for shape in SHAPES {
        for &n in DEPTHS {
            let file = write(
                &format!("{}_{n}.ilmr", shape.replace(' ', "_")),
                &nested(shape, n),
            );
            let f = file.to_str().unwrap();
            let what = |tool: &str| format!("{tool} on {shape} x{n}");
            let check = ends_cleanly(&what("check"), &bounded(&["check", f], None));
            ends_cleanly(
                &what("check --format json"),
                &bounded(&["check", "--format", "json", f], None),
            );
            ends_cleanly(&what("parse"), &bounded(&["parse", f], None));
            let fmt = ends_cleanly(&what("fmt --check"), &bounded(&["fmt", "--check", f], None));
            let ilmb = scratch().join(format!("{}_{n}.ilmb", shape.replace(' ', "_")));
            let build = ends_cleanly(
                &what("build"),
                &bounded(&["build", f, "-o", ilmb.to_str().unwrap()], None),
            );
            let run = ends_cleanly(
                &what("run"),
                &bounded(&["run", f, "--robot", "none", "--max-time", "2"], None),
            );
            assert_eq!(check == 0, build == 0, "{}", what("check and build agree"));
            assert_eq!(check == 0, accepted(run), "{}", what("check and run agree"));
            if check != 0 {
                assert_ne!(fmt, 0, "{}", what("fmt refuses what check refuses"));
            }
            if build == 0 {
                ends_cleanly(
                    &what("disasm"),
                    &bounded(&["disasm", ilmb.to_str().unwrap()], None),
                );
            }
            // The same program typed into a shell, line by line, then the shell goes on.
            let mut typed = nested(shape, n.min(10_000)).into_bytes();
            typed.extend_from_slice(b"\n:status\n:quit\n");
            let shell = bounded(&["shell"], Some(&typed));
            ends_cleanly(&what("shell"), &shell);
        }
    }
}

/// The shallow cases are accepted everywhere and the deep ones refused with the limit's
/// code: the limits sit where docs/reliability.md says.
#[test]
fn the_limits_are_where_the_docs_say() {
    let codes = |text: &str| {
        let file = write("limits_probe.ilmr", text);
        let out = bounded(&["check", "--format", "json", file.to_str().unwrap()], None);
        let json: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
        json.as_array()
            .unwrap()
            .iter()
            .filter(|d| d["severity"] == "error")
            .map(|d| d["code"].as_str().unwrap().to_string())
            .collect::<Vec<_>>()
    };
    assert!(codes(&nested("if", 256)).is_empty());
    assert_eq!(codes(&nested("if", 257)), ["E0210"]);
    assert!(codes(&nested("sum", 256)).is_empty());
    assert_eq!(codes(&nested("sum", 257)), ["E0104"]);
}

/// The limits table of docs/reliability.md quotes the constants the code uses.
#[test]
fn the_limits_table_quotes_the_constants() {
    use ilmr_compiler::{limits, render};
    use ilmr_sim::world::limits as world;
    let reliability = std::fs::read_to_string(root().join("docs/reliability.md")).unwrap();
    let table: Vec<&str> = reliability
        .split("## Limits")
        .nth(1)
        .expect("docs/reliability.md has a Limits section")
        .lines()
        .filter(|l| l.starts_with('|'))
        .collect();
    let mib = |bytes: u64| format!("{} MiB", bytes >> 20);
    let count = |n: usize| render::thousands(n as u64);
    let quoted = [
        (
            "MAX_BLOCK_DEPTH",
            format!("{} levels", limits::MAX_BLOCK_DEPTH),
        ),
        (
            "MAX_LINE_OPERATORS",
            format!("{} operators", limits::MAX_LINE_OPERATORS),
        ),
        (
            "EXPR_STACK",
            format!("{} values", ilmr_vm::bytecode::limits::EXPR_STACK),
        ),
        (
            "max_call_depth",
            format!("{} calls", ilmr_vm::Config::default().max_call_depth),
        ),
        (
            "COMPILER_STACK",
            format!("{} MB", limits::COMPILER_STACK >> 20),
        ),
        (
            "LONG_LINE",
            format!("longer than {} characters", render::LONG_LINE),
        ),
        (
            "AROUND_LABEL",
            format!("{} characters each side", render::AROUND_LABEL),
        ),
        (
            "MAX_WINDOWS",
            format!("at most {} such", render::MAX_WINDOWS),
        ),
        (
            "LONG_MESSAGE",
            format!("longer than {} characters", render::LONG_MESSAGE),
        ),
        (
            "MAX_DIAGNOSTICS",
            format!("{}, the first", count(limits::MAX_DIAGNOSTICS)),
        ),
        (
            "SUGGESTION_STEPS",
            format!("{} steps", count(limits::SUGGESTION_STEPS as usize)),
        ),
        (
            "SUGGESTION_COMPARISON",
            format!("an edit distance {}", limits::SUGGESTION_COMPARISON),
        ),
        (
            "PATTERN_MATCHES",
            format!("{} per program", count(limits::PATTERN_MATCHES as usize)),
        ),
        (
            "BREAK_TARGETS",
            format!("{} pairs", count(ilmr_vm::runtime::BREAK_TARGETS as usize)),
        ),
        (
            "MAX_PLACES_SHOWN",
            format!("{}, the last", ilmr_compiler::diagnostic::MAX_PLACES_SHOWN),
        ),
        ("MAX_SOURCE_BYTES", mib(ilmr_files::MAX_SOURCE_BYTES)),
        (
            "MAX_ROBOT_MODEL_BYTES",
            mib(ilmr_files::MAX_ROBOT_MODEL_BYTES),
        ),
        ("MAX_WORLD_BYTES", mib(ilmr_files::MAX_WORLD_BYTES)),
        ("MAX_SCENARIO_BYTES", mib(ilmr_files::MAX_SCENARIO_BYTES)),
        ("MAX_MODULE_BYTES", mib(ilmr_files::MAX_MODULE_BYTES)),
        ("MAX_TRACE_BYTES", mib(ilmr_files::MAX_TRACE_BYTES)),
        ("MAX_MCAP_BYTES", mib(ilmr_files::MAX_MCAP_BYTES)),
        ("MAX_HISTORY_BYTES", mib(ilmr_files::MAX_HISTORY_BYTES)),
        ("MAX_FLEET_BYTES", mib(ilmr_files::MAX_FLEET_BYTES)),
        (
            "MAX_TESTS",
            format!("{} tests", count(ilmr_testfile::file::MAX_TESTS)),
        ),
        (
            "MAX_PROBLEMS",
            format!("{}, the first", ilmr_testfile::file::MAX_PROBLEMS),
        ),
        (
            "MAX_MESSAGE",
            format!("cut to {} characters", ilmr_testfile::problem::MAX_MESSAGE),
        ),
        (
            "MAX_MESSAGE_BYTES",
            mib(ilmr_ros2::MAX_MESSAGE_BYTES as u64),
        ),
        (
            "MAX_SAMPLES_PER_TICK",
            format!("{} samples", ilmr_ros2::robot::MAX_SAMPLES_PER_TICK),
        ),
        (
            "MAX_SECTION_ENTRIES",
            count(ilmr_model::MAX_SECTION_ENTRIES),
        ),
        ("MAX_READINGS", count(ilmr_model::MAX_READINGS as usize)),
        ("MAX_WALLS", count(world::MAX_WALLS)),
        ("MAX_DOORS", count(world::MAX_DOORS)),
        ("MAX_OBSTACLES", count(world::MAX_OBSTACLES)),
        ("MAX_PLATES", count(world::MAX_PLATES)),
        ("MAX_PICKUP_BOXES", count(world::MAX_PICKUP_BOXES)),
        ("MAX_TARGETS", count(world::MAX_TARGETS)),
        ("MAX_FAULTS", count(world::MAX_FAULTS)),
        ("MAX_WAYPOINTS", count(world::MAX_WAYPOINTS)),
    ];
    for (name, value) in quoted {
        let row = table
            .iter()
            .find(|row| row.contains(name))
            .unwrap_or_else(|| panic!("no row of the limits table names {name}"));
        assert!(
            row.contains(&value),
            "the row of {name} does not say {value}: {row}"
        );
    }
}

/// Numbers no robot can use, in every numeric place of a command.
#[test]
fn huge_and_non_finite_numbers() {
    let numbers = [
        "1e308",
        "-1e308",
        "1e999",
        "-1e999",
        "0.0000000000000000000001",
        "1/0",
        "0/0",
        "-0",
    ];
    let places = [
        "speed({})",
        "goahead({})",
        "turn(d={},c=0.5)",
        "turn(d=90,c={})",
        "gotoxy({},1)",
        "gotorelxy(1,{})",
        "wait({})",
        "x = {}\nspeed(x)",
        "x = {}\ngoahead(x)",
        "x = {}\nwait(x)",
        "x = {}\nif(x > 0)\nspeed(0.1)\nendif",
    ];
    for place in places {
        for n in numbers {
            let text = format!("{}\n", place.replace("{}", n));
            let file = write("numbers.ilmr", &text);
            let f = file.to_str().unwrap();
            let what = format!("{text:?}");
            let check = ends_cleanly(&format!("check {what}"), &bounded(&["check", f], None));
            let run = ends_cleanly(
                &format!("run {what}"),
                &bounded(&["run", f, "--max-time", "3"], None),
            );
            assert_eq!(check == 0, accepted(run), "check and run agree on {what}");
            ends_cleanly(
                &format!("run --robot none {what}"),
                &bounded(&["run", f, "--robot", "none", "--max-time", "3"], None),
            );
        }
    }
}

/// Files that are not programs where a program is expected.
#[test]
fn special_and_missing_files() {
    let dir = scratch();
    let missing = dir.join("no such file.ilmr");
    for target in [
        "/dev/null",
        "/dev/zero",
        dir.to_str().unwrap(),
        missing.to_str().unwrap(),
    ] {
        for args in [
            vec!["check", target],
            vec!["fmt", "--check", target],
            vec!["parse", target],
            vec!["build", target, "-o", "/dev/null"],
            vec!["run", target, "--robot", "none", "--max-time", "1"],
            vec!["disasm", target],
            vec!["replay", target, "--plot", "/dev/null"],
        ] {
            let ended = bounded(&args, None);
            let code = ends_cleanly(&args.join(" "), &ended);
            // Refused for what it is, not read until memory ran out.
            assert!(
                !ended.stderr.contains("out of memory"),
                "{}: {}",
                args.join(" "),
                ended.stderr
            );
            if target != "/dev/null" {
                assert_ne!(code, 0, "{} succeeded", args.join(" "));
            }
        }
    }
}

/// Random bytes and invalid UTF-8 as programs.
#[test]
fn bytes_that_are_not_text() {
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    for case in 0..20 {
        let len = [0, 1, 17, 4096, 1 << 20][case % 5];
        let bytes: Vec<u8> = (0..len)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 24) as u8
            })
            .collect();
        let path = scratch().join("bytes.ilmr");
        std::fs::write(&path, &bytes).unwrap();
        let f = path.to_str().unwrap();
        ends_cleanly(
            &format!("check on {len} random bytes"),
            &bounded(&["check", f], None),
        );
        ends_cleanly(
            &format!("run on {len} random bytes"),
            &bounded(&["run", f, "--robot", "none", "--max-time", "1"], None),
        );
        let mut typed = bytes.clone();
        typed.extend_from_slice(b"\n:quit\n");
        ends_cleanly(
            &format!("shell on {len} random bytes"),
            &bounded(&["shell"], Some(&typed)),
        );
    }
}

/// Robot models with values out of every range, and worlds past their limits, given to
/// the commands that drive: each ends cleanly, and a run says which value it did not
/// take, with the file and line.
#[test]
fn hostile_models_and_worlds_through_run() {
    let moro = std::fs::read_to_string(root().join("robots/model/models/moro.ini")).unwrap();
    let task = write("short.ilmr", "goahead(0.5)\n");
    let task = task.to_str().unwrap();
    for (name, edit) in [
        ("stop_margin", "stop_margin 1e308"),
        ("stop_margin_nan", "stop_margin nan"),
        ("max_speed_inf", "max_speed inf"),
        ("beams", "scanner 1 0 30000 100000000"),
    ] {
        let key = edit.split(' ').next().unwrap();
        let mut text: String = moro
            .lines()
            .filter(|l| l.split_whitespace().next().is_none_or(|k| k != key))
            .map(|l| format!("{l}\n"))
            .collect();
        // Parameters go in their section; a scanner line replaces the scanner's.
        text = text.replace("[PARAMETERS]\n", &format!("[PARAMETERS]\n{edit}\n"));
        if key == "scanner" {
            text = text.replacen(
                "[SENSORSANDACTUATORS]\n",
                &format!("[SENSORSANDACTUATORS]\n{edit}\n"),
                1,
            );
        }
        let model = write(&format!("{name}.ini"), &text);
        let model = model.to_str().unwrap();
        for args in [
            vec!["check", "--robot", model, task],
            vec!["run", task, "--robot", model, "--max-time", "5"],
        ] {
            let ended = bounded(&args, None);
            ends_cleanly(&args.join(" "), &ended);
            assert!(
                ["out of range", "not a number"]
                    .iter()
                    .any(|said| ended.stderr.contains(said) || ended.stdout.contains(said)),
                "{}: the value out of range is not named\n{}{}",
                args.join(" "),
                ended.stdout,
                ended.stderr
            );
        }
    }
}

/// Files of one kind, each named by its shape.
type Cases = Vec<(&'static str, Vec<u8>)>;

/// Test files, scenarios and fleet files of hostile shapes and kinds (a line of
/// megabytes, a hundred thousand entries, nesting a million deep, bytes that are not
/// UTF-8, a directory, a FIFO), each given to the command that reads it: each is
/// refused at once, with a short message, never echoed back whole.
#[test]
fn hostile_test_scenario_and_fleet_files() {
    let dir = scratch().join("files");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let task = dir.join("go.ilmr");
    std::fs::write(&task, "goahead(0.5)\n").unwrap();
    let task = task.to_str().unwrap().to_string();
    let long = |limit: u64| "x".repeat(limit as usize * 5 / 8);
    // A test file is read within a scenario's limit (docs/testing.md).
    let test_limit = ilmr_files::MAX_SCENARIO_BYTES;
    let tests: Cases = vec![
        ("long line", format!("task = \"go.ilmr\"\n{} = 1\n", long(test_limit)).into_bytes()),
        ("long name", format!("task = \"go.ilmr\"\n[[test]]\nname = \"{}\"\nassert = [\"never: refused\"]\n[[test]]\nname = \"{0}\"\nassert = [\"never: refused\"]\n", long(test_limit / 2)).into_bytes()),
        (
            "many tests",
            format!(
                "task = \"go.ilmr\"\nseeds = \"0-9999\"\nassert = [\"never: refused\"]\n{}",
                (0..100_000).map(|i| format!("[[test]]\nname = \"t{i}\"\n")).collect::<String>()
            )
            .into_bytes(),
        ),
        ("deep arrays", format!("task = {}1{}\n", "[".repeat(1_000_000), "]".repeat(1_000_000)).into_bytes()),
        ("deep tables", format!("task = {}\n", "{a=".repeat(1_000_000)).into_bytes()),
        ("not UTF-8", b"task = \"go.ilmr\"\n[[test]]\nname = \"\xff\xfe\"\n".to_vec()),
    ];
    let scenario_limit = ilmr_files::MAX_SCENARIO_BYTES;
    let scenarios: Cases = vec![
        (
            "long line",
            format!("{{\"start\": \"{}\"}}", long(scenario_limit)).into_bytes(),
        ),
        (
            "long key",
            format!("{{\"{}\": 1}}", long(scenario_limit)).into_bytes(),
        ),
        (
            "many readings",
            format!(
                "{{\"readings\": [{}]}}",
                (0..100_000)
                    .map(|i| format!("{{\"t\": {i}, \"device\": \"battery\", \"value\": 24}}"))
                    .collect::<Vec<_>>()
                    .join(",")
            )
            .into_bytes(),
        ),
        (
            "deep arrays",
            format!("{{\"paths\": {}", "[".repeat(1_000_000)).into_bytes(),
        ),
        (
            "not UTF-8",
            b"{\"lines\": [{\"t\": 1, \"text\": \"\xff\"}]}".to_vec(),
        ),
    ];
    let fleet_limit = ilmr_files::MAX_FLEET_BYTES;
    let fleets: Cases = vec![
        (
            "long line",
            format!(
                "[[robot]]\nname = \"a\"\nrobot = \"{}\"\nbad = 1\n",
                long(fleet_limit)
            )
            .into_bytes(),
        ),
        (
            "long robot",
            format!(
                "[[robot]]\nname = \"a\"\nrobot = \"{}\"\nnamespace = \"/a\"\n",
                long(fleet_limit)
            )
            .into_bytes(),
        ),
        (
            "many robots",
            (0..20_000)
                .map(|i| format!("[[robot]]\nname=\"r{i}\"\nrobot=\"moro\"\n"))
                .collect::<String>()
                .into_bytes(),
        ),
        (
            "deep arrays",
            format!("x = {}", "[".repeat(fleet_limit as usize - 10)).into_bytes(),
        ),
        (
            "not UTF-8",
            b"[[robot]]\nname = \"\xff\"\nrobot = \"moro\"\n".to_vec(),
        ),
    ];
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success(), "mkfifo");
    let kinds: [(&str, &str, Cases); 3] = [
        ("test", ".test.toml", tests),
        ("scenario", ".json", scenarios),
        ("fleet", ".toml", fleets),
    ];
    for (kind, suffix, cases) in kinds {
        let args = |file: &str| -> Vec<String> {
            let v: Vec<&str> = match kind {
                "test" => vec!["test", file],
                "scenario" => vec![
                    "run",
                    &task,
                    "--robot",
                    "scripted",
                    "--scenario",
                    file,
                    "--max-time",
                    "1",
                ],
                _ => vec!["fleet", file, "--max-time", "1"],
            };
            v.into_iter().map(String::from).collect()
        };
        let mut files: Vec<(String, PathBuf)> = cases
            .into_iter()
            .map(|(name, bytes)| {
                let path = dir.join(format!("{}{suffix}", name.replace(' ', "_")));
                std::fs::write(&path, bytes).unwrap();
                (name.to_string(), path)
            })
            .collect();
        files.push(("a FIFO".into(), fifo.clone()));
        let folder = dir.join(format!("folder{suffix}"));
        std::fs::create_dir_all(&folder).unwrap();
        if kind != "test" {
            // `ilmrc test FOLDER` looks for test files in it.
            files.push(("a directory".into(), folder));
        }
        for (name, path) in files {
            let argv = args(path.to_str().unwrap());
            let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
            let what = format!("{kind} file: {name}");
            let started = std::time::Instant::now();
            let ended = bounded(&argv, None);
            let code = ends_cleanly(&what, &ended);
            // A hundred thousand readings is a scenario like any other: it runs.
            if name != "many readings" {
                assert_eq!(code, 2, "{what}: exit {code}\n{}", ended.stderr);
            }
            assert!(
                // At most a hundred problems (MAX_PROBLEMS) of a few lines each.
                ended.stderr.len() + ended.stdout.len() < 64 << 10,
                "{what}: {} bytes said\n{}",
                ended.stderr.len() + ended.stdout.len(),
                ended.stderr.chars().take(2000).collect::<String>()
            );
            eprintln!(
                "{what}: exit {code} in {:.2} s",
                started.elapsed().as_secs_f64()
            );
        }
    }
}
