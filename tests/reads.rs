//! Every file the tools are given is read through `ilmr-files`: a special file (a
//! device, a FIFO, a directory) or one above its kind's limit gets a clear message and
//! exit 2 at once, from every command that reads it, instead of a hang or memory that
//! grows without bound.

mod support;

use std::path::{Path, PathBuf};
use std::time::Duration;

use support::*;

/// Far above what refusing a file takes; only a hang or an unbounded read reaches it.
const LIMIT: Duration = Duration::from_secs(60);

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ilmr-reads-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn text(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// Runs ilmrc, expects exit 2 and `message` on stderr.
fn refused(args: &[&str], message: &str) {
    let (code, out, err) = ilmrc_within(args, LIMIT);
    assert_eq!(code, 2, "ilmrc {}: {out}{err}", args.join(" "));
    assert!(err.contains(message), "ilmrc {}: {err}", args.join(" "));
}

/// The commands and options that read a file, with `path` in the file's place.
fn readers(path: &str, dir: &Path) -> Vec<Vec<String>> {
    let plot = dir.join("out.svg").display().to_string();
    let task = "examples/short_task.ilmr".to_string();
    let own = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        own(&["check", path]),
        own(&["fmt", path]),
        own(&[
            "build",
            path,
            "-o",
            &dir.join("m.ilmb").display().to_string(),
        ]),
        own(&["disasm", path]),
        own(&["run", "--robot", "none", path]),
        own(&["replay", path, "--plot", &plot]),
        own(&["check", "--robot", path, &task]),
        own(&["run", "--robot", path, &task]),
        own(&["run", "--world", path, &task]),
        own(&["run", "--robot", "scripted", "--scenario", path, &task]),
        own(&["shell", "--task", path]),
        own(&["shell", "--history", path]),
        own(&[
            "serve",
            "--no-tls",
            "--listen",
            "127.0.0.1:0",
            "--world",
            path,
        ]),
    ]
}

#[cfg(unix)]
#[test]
fn a_device_is_refused_by_every_command_that_reads_a_file() {
    let dir = scratch("device");
    for args in readers("/dev/zero", &dir) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&args, "it is a character device, not a regular file");
    }
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_waiting_for_a_writer() {
    let dir = scratch("fifo");
    let fifo = dir.join("pipe.ilmr");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    for args in readers(text(&fifo), &dir) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&args, "it is a FIFO (named pipe), not a regular file");
    }
    // A skill directory holding one.
    refused(
        &["check", "--skills", text(&dir), "examples/short_task.ilmr"],
        "it is a FIFO (named pipe), not a regular file",
    );
}

#[test]
fn a_directory_is_said_to_be_one_by_check_and_run_alike() {
    let dir = scratch("dir");
    let robot = dir.join("robot.d");
    std::fs::create_dir_all(&robot).expect("dir");
    let expected = format!(
        "error: cannot read robot model `{}`: it is a directory, not a file",
        text(&robot)
    );
    for command in ["check", "run"] {
        let (code, _, err) = ilmrc_within(
            &[command, "--robot", text(&robot), "examples/short_task.ilmr"],
            LIMIT,
        );
        assert_eq!((code, err.trim()), (2, expected.as_str()), "{command}");
    }
    for args in readers(text(&robot), &dir) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&args, "it is a directory, not a file");
    }
}

#[test]
fn a_file_above_its_limit_is_refused_naming_the_limit() {
    let dir = scratch("large");
    let big = |name: &str, limit: u64| {
        let path = dir.join(name);
        let file = std::fs::File::create(&path).expect("create");
        // Sparse: no disk is written, yet the size is over the limit.
        file.set_len(limit + 1).expect("set_len");
        path
    };
    let task = big("big.ilmr", ilmr_files::MAX_SOURCE_BYTES);
    refused(
        &["check", text(&task)],
        "it is larger than 8 MiB, the limit for a task or skill file (MAX_SOURCE_BYTES)",
    );
    let module = big("big.ilmb", ilmr_files::MAX_MODULE_BYTES);
    refused(
        &["disasm", text(&module)],
        "the limit for a compiled module (MAX_MODULE_BYTES)",
    );
    let model = big("ROBO.INI", ilmr_files::MAX_ROBOT_MODEL_BYTES);
    refused(
        &["check", "--robot", text(&model), "examples/short_task.ilmr"],
        "the limit for a robot model (MAX_ROBOT_MODEL_BYTES)",
    );
    let world = big("big.toml", ilmr_files::MAX_WORLD_BYTES);
    refused(
        &["run", "--world", text(&world), "examples/short_task.ilmr"],
        "the limit for a world file (MAX_WORLD_BYTES)",
    );
}

#[test]
fn a_task_that_is_not_utf8_says_where() {
    let dir = scratch("utf8");
    let task = dir.join("bad.ilmr");
    std::fs::write(&task, b"speed(0.2)\ngo\xffahead(1)\n").expect("write");
    refused(
        &["check", text(&task)],
        "it is not UTF-8 text (invalid byte at line 2, column 3)",
    );
}

/// docs/run.md's table of limits quotes the constants `ilmr-files` reads with.
#[test]
fn the_documented_limits_are_the_ones_read_with() {
    let doc = std::fs::read_to_string(root().join("docs/run.md")).expect("docs/run.md");
    for kind in ilmr_files::Kind::ALL {
        let row = format!("| {} MiB | `{}` |", kind.limit() >> 20, kind.limit_name());
        assert!(doc.contains(&row), "docs/run.md lacks `{row}` for {kind:?}");
    }
}
