//! docs/tutorial.md is run as written: its files (fenced `ilmr file=NAME`, `ilms
//! file=NAME`, `json file=NAME`, `python file=NAME`) are written to a fresh directory,
//! and each `console` block's `$ ilmrc ...` commands are run there, their stdout and
//! stderr (one stream, as a terminal shows them) compared with the lines under them;
//! `$ echo $?` shows the last exit code. The `serve` step runs `ilmrc serve` as the
//! tutorial starts it and its Python client against it.
//!
//! `ILMR_UPDATE_DOCS=1` writes the outputs into the tutorial instead of comparing: read
//! the diff before committing it.

mod support;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const TUTORIAL: &str = "docs/tutorial.md";

/// A fenced block: its info string, its body, and the line range of the body.
struct Block {
    info: String,
    body: String,
    lines: std::ops::Range<usize>,
}

fn blocks(text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<(String, usize, String)> = None;
    for (i, line) in text.lines().enumerate() {
        let fence = line.trim_start().strip_prefix("```");
        match (&mut open, fence) {
            (None, Some(info)) => open = Some((info.trim().to_string(), i + 1, String::new())),
            (Some(_), Some(_)) => {
                let (info, start, body) = open.take().unwrap();
                out.push(Block {
                    info,
                    body,
                    lines: start..i,
                });
            }
            (Some((_, _, body)), None) => {
                body.push_str(line);
                body.push('\n');
            }
            (None, None) => {}
        }
    }
    assert!(
        open.is_none(),
        "a fenced block of the tutorial is not closed"
    );
    out
}

fn file_name(info: &str) -> Option<&str> {
    info.split_whitespace()
        .find_map(|w| w.strip_prefix("file="))
}

/// A fresh directory of this test's own (the tests run in parallel).
fn workdir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("tutorial")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `ilmrc` with `args` in `dir`, stdout and stderr into one stream.
fn ilmrc_in(dir: &Path, args: &[&str]) -> (String, i32) {
    let out = dir.join(".output");
    let file = std::fs::File::create(&out).unwrap();
    let status = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(file.try_clone().unwrap())
        .stderr(file)
        .status()
        .expect("ilmrc runs");
    let text = std::fs::read_to_string(&out).unwrap();
    (text, status.code().unwrap_or(-1))
}

/// The output of a console block's commands, in the block's own layout.
fn run_console(dir: &Path, body: &str) -> String {
    let mut out = String::new();
    let mut last = 0;
    for line in body.lines().filter(|l| l.starts_with("$ ")) {
        out.push_str(line);
        out.push('\n');
        let command = &line[2..];
        if command == "echo $?" {
            out.push_str(&format!("{last}\n"));
            continue;
        }
        let args: Vec<&str> = command
            .strip_prefix("ilmrc ")
            .unwrap_or_else(|| panic!("the tutorial runs only ilmrc: `{command}`"))
            .split_whitespace()
            .collect();
        let (text, code) = ilmrc_in(dir, &args);
        out.push_str(&text);
        last = code;
    }
    out
}

#[test]
fn the_tutorial_runs_as_written() {
    let root = support::root();
    let path = root.join(TUTORIAL);
    let text = std::fs::read_to_string(&path).unwrap();
    let dir = workdir("steps");
    let update = std::env::var_os("ILMR_UPDATE_DOCS").is_some();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut replaced: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    let (mut files, mut consoles) = (0, 0);
    for block in blocks(&text) {
        if let Some(name) = file_name(&block.info) {
            let file = dir.join(name);
            std::fs::create_dir_all(file.parent().unwrap()).unwrap();
            std::fs::write(&file, &block.body).unwrap();
            files += 1;
        } else if block.info == "console" {
            let got = run_console(&dir, &block.body);
            if update {
                replaced.push((block.lines.clone(), got));
            } else {
                assert_eq!(
                    block.body, got,
                    "{TUTORIAL} line {}: the output differs (ILMR_UPDATE_DOCS=1 rewrites it)",
                    block.lines.start
                );
            }
            consoles += 1;
        }
    }
    assert!(
        files >= 8 && consoles >= 8,
        "{files} files, {consoles} consoles"
    );
    if update {
        for (range, got) in replaced.into_iter().rev() {
            lines.splice(range, got.lines().map(str::to_string));
        }
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    }
}

/// The serve step: `ilmrc serve` started as the tutorial starts it (on a free port),
/// and the tutorial's planner, whose answers must be what the tutorial says.
#[test]
fn the_tutorials_planner_drives_serve() {
    let root = support::root();
    let text = std::fs::read_to_string(root.join(TUTORIAL)).unwrap();
    let dir = workdir("serve");
    let all = blocks(&text);
    let client = all
        .iter()
        .find(|b| file_name(&b.info) == Some("planner.py"))
        .expect("the tutorial's planner");
    std::fs::write(dir.join("planner.py"), &client.body).unwrap();
    let start = all
        .iter()
        .flat_map(|b| b.body.lines())
        .find(|l| l.starts_with("$ ilmrc serve"))
        .expect("the tutorial starts serve");
    let args: Vec<String> = start[2..]
        .split_whitespace()
        .skip(1)
        .map(|a| a.replace("127.0.0.1:7878", "127.0.0.1:0"))
        .collect();
    let mut server = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(&args)
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("serve starts");
    let mut first = String::new();
    BufReader::new(server.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    let port = first
        .strip_prefix("listening on 127.0.0.1:")
        .and_then(|r| r.split_whitespace().next())
        .unwrap_or_else(|| panic!("serve said: {first}"))
        .to_string();
    let mut planner = Command::new("python3")
        .args(["planner.py", &port])
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .spawn()
        .expect("python3 runs");
    let deadline = Instant::now() + Duration::from_secs(60);
    while planner.try_wait().unwrap().is_none() {
        assert!(Instant::now() < deadline, "the planner did not finish");
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = planner.wait_with_output().unwrap();
    let _ = server.kill();
    let _ = server.wait();
    assert!(out.status.success(), "the planner failed");
    let answers: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|_| panic!("not JSON: {l}")))
        .collect();
    // As the tutorial says: the movement joins, the status has a pose, the typo is
    // refused with the checker's suggestion, and stop is acknowledged.
    assert_eq!(answers.len(), 4, "{answers:?}");
    assert_eq!(answers[0]["ok"], true, "{}", answers[0]);
    assert!(answers[1]["pose"]["x"].is_number(), "{}", answers[1]);
    let typo = &answers[2];
    assert_eq!(typo["ok"], false, "{typo}");
    assert_eq!(typo["diagnostics"][0]["code"], "E0301", "{typo}");
    assert_eq!(
        typo["diagnostics"][0]["fix"]["replacement"], "goahead",
        "{typo}"
    );
    assert_eq!(answers[3]["ok"], true, "{}", answers[3]);
}
