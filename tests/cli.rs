//! `ilmrc` as a user runs it: exit codes, JSON output, robot model warnings.

mod support;

use support::ilmrc;

#[test]
fn clean_files_exit_zero_and_say_so() {
    let (code, out, _) = ilmrc(&["check", "examples/short_task.ilmr"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 error(s), 0 warning(s)"), "{out}");
}

#[test]
fn warnings_alone_exit_zero() {
    let (code, out, _) = ilmrc(&[
        "check",
        "--robot",
        "workpartner",
        "examples/short_task.ilmr",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("W0405"), "{out}");
}

#[test]
fn errors_exit_one() {
    let (code, _, _) = ilmrc(&["check", "tests/check/broken/commands.ilmr"]);
    assert_eq!(code, 1);
}

#[test]
fn usage_and_unreadable_files_exit_two() {
    assert_eq!(ilmrc(&["check"]).0, 2);
    assert_eq!(
        ilmrc(&["check", "--format", "xml", "examples/short_task.ilmr"]).0,
        2
    );
    let (code, _, err) = ilmrc(&["check", "no/such/file.ilmr"]);
    assert_eq!(code, 2);
    assert!(err.contains("cannot read"), "{err}");
    let (code, _, err) = ilmrc(&["check", "--robot", "r2d2", "examples/short_task.ilmr"]);
    assert_eq!(code, 2);
    assert!(err.contains("unknown robot"), "{err}");
}

/// An unreadable or non-UTF-8 file is a diagnostic of the JSON output (E0001, E0002 at
/// the line and column of the bad byte), the other files are still checked, and the
/// exit code is 2.
#[test]
fn unreadable_files_are_diagnostics_in_json() {
    let dir = std::env::temp_dir().join(format!("ilmr-cli-unread-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("latin1.ilmr");
    std::fs::write(&bad, b"speed(0.2)\ngo\xe4ahead(1)\n").unwrap();
    let (code, out, err) = ilmrc(&[
        "check",
        "--format",
        "json",
        "no/such/file.ilmr",
        bad.to_str().unwrap(),
        "tests/check/broken/commands.ilmr",
    ]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains("cannot read `no/such/file.ilmr`: no such file"),
        "{err}"
    );
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let all = v.as_array().unwrap();
    let missing = all.iter().find(|d| d["code"] == "E0001").expect("E0001");
    assert_eq!(missing["file"], "no/such/file.ilmr");
    assert_eq!(
        (missing["line"].as_u64(), missing["column"].as_u64()),
        (Some(1), Some(1))
    );
    let latin = all.iter().find(|d| d["code"] == "E0002").expect("E0002");
    assert_eq!(latin["file"], bad.to_str().unwrap());
    assert_eq!(
        (latin["line"].as_u64(), latin["column"].as_u64()),
        (Some(2), Some(3))
    );
    assert!(
        latin["message"]
            .as_str()
            .unwrap()
            .contains("line 2, column 3"),
        "{latin}"
    );
    assert!(
        all.iter().any(|d| d["code"] == "E0301"),
        "the readable file is checked"
    );
    // Human output says it on stderr, with the same place, and counts only what it read.
    let (code, out, err) = ilmrc(&["check", bad.to_str().unwrap(), "examples/short_task.ilmr"]);
    assert_eq!(code, 2);
    assert!(err.contains("invalid byte at line 2, column 3"), "{err}");
    assert!(
        out.contains(
            "1 file(s) checked against robot `moro`: 0 error(s), 0 warning(s); 1 could not be read"
        ),
        "{out}"
    );
}

/// `--skills` takes one skill file as well as a directory, and names the files of a
/// directory it does not read.
#[test]
fn skills_take_a_file_and_name_what_a_directory_leaves_out() {
    let dir = std::env::temp_dir().join(format!("ilmr-cli-skills-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    let skill = lib.join("hello.ilms");
    std::fs::write(&skill, "Hello:\nspeed(0.2)\n").unwrap();
    std::fs::write(lib.join("notes.txt"), "not a skill").unwrap();
    std::fs::write(lib.join("old.ilm"), "Old:\nspeed(0.1)\n").unwrap();
    let task = dir.join("task.ilmr");
    std::fs::write(&task, "Hello\n").unwrap();
    let (code, out, err) = ilmrc(&[
        "check",
        "--skills",
        skill.to_str().unwrap(),
        task.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.is_empty(), "{err}");
    let (code, out, err) = ilmrc(&[
        "check",
        "--skills",
        lib.to_str().unwrap(),
        task.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        err.contains(
            "`notes.txt`, `old.ilm` not read (only `.ilms` and `.ilmr` files hold skills)"
        ),
        "{err}"
    );
}

#[test]
fn json_has_the_documented_fields_with_one_based_positions() {
    let (code, out, _) = ilmrc(&[
        "check",
        "--format",
        "json",
        "tests/check/broken/unicode.ilmr",
    ]);
    assert_eq!(code, 1);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let d = &v.as_array().unwrap()[0];
    for field in [
        "code",
        "severity",
        "message",
        "file",
        "line",
        "column",
        "end_line",
        "end_column",
    ] {
        assert!(d.get(field).is_some(), "missing {field} in {d}");
    }
    assert_eq!(d["code"], "E0501");
    assert_eq!(d["severity"], "error");
    assert_eq!(d["line"], 7);
    // `gotoxy(` is 7 characters: the name starts in column 8 (characters, not bytes).
    assert_eq!(d["column"], 8);
    assert_eq!(d["end_column"], 16);
}

#[test]
fn json_of_a_clean_file_is_an_empty_array() {
    let (code, out, _) = ilmrc(&["check", "--format", "json", "examples/short_task.ilmr"]);
    assert_eq!(code, 0);
    assert_eq!(out.trim(), "[]");
}

#[test]
fn skills_directory_and_robot_model_file() {
    let (code, out, _) = ilmrc(&[
        "check",
        "--robot",
        "workpartner",
        "--skills",
        "examples/skills",
        "examples/fetch_boxes.ilmr",
        "examples/loop.ilmr",
    ]);
    assert_eq!(code, 0, "{out}");
    let dir = std::env::temp_dir().join(format!("ilmr-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ini = dir.join("ROBO.INI");
    std::fs::write(&ini, "[PARAMETERS]\nmax_speed fast\n[END]\n").unwrap();
    let ini = ini.display().to_string();
    let (code, out, _) = ilmrc(&[
        "check",
        "--format",
        "json",
        "--robot",
        &ini,
        "examples/short_task.ilmr",
    ]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("W0801"), "{out}");
    let missing = dir.join("MISSING.INI").display().to_string();
    let (code, out, _) = ilmrc(&["check", "--robot", &missing, "examples/short_task.ilmr"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("W0801"), "{out}");
}

#[test]
fn fmt_rewrites_to_the_canonical_form_and_check_reports_it() {
    let dir = std::env::temp_dir().join(format!("ilmr-fmt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("task.ilmr");
    std::fs::write(&file, "Speed(0.4)\nIF(x=>1)\nGoahead(1)\nENDIF\n").unwrap();
    let path = file.display().to_string();
    let (code, out, _) = ilmrc(&["fmt", "--check", &path]);
    assert_eq!(code, 1);
    assert!(out.contains("would reformat"), "{out}");
    assert_eq!(ilmrc(&["fmt", &path]).0, 0);
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        "speed(0.4)\nif(x >= 1)\n    goahead(1)\nendif\n"
    );
    assert_eq!(ilmrc(&["fmt", "--check", &path]).0, 0);
    std::fs::write(&file, "goahead(1\n").unwrap();
    let (code, out, _) = ilmrc(&["fmt", &path]);
    assert_eq!(code, 1);
    assert!(out.contains("E0102"), "{out}");
}

/// A path a scenario teaches is known to the check `run` makes: Figure 56's `PATH` is
/// W0903 for `check` alone and for a run without the scenario, not with it.
#[test]
fn a_scenario_path_is_known_to_the_check_of_a_run() {
    let (_, out, _) = ilmrc(&["check", "--skills", "examples/skills", "examples/loop.ilmr"]);
    assert!(out.contains("W0903"), "{out}");
    let (_, out, err) = ilmrc(&[
        "run",
        "--robot",
        "scripted",
        "--model",
        "workpartner",
        "--skills",
        "examples/skills",
        "--scenario",
        "tests/run/fig56_loop.json",
        "--max-time",
        "0.1",
        "examples/loop.ilmr",
    ]);
    assert!(
        !out.contains("W0903") && !err.contains("W0903"),
        "{out}{err}"
    );
    let (_, out, _) = ilmrc(&[
        "run",
        "--world",
        "empty",
        "--skills",
        "examples/skills",
        "--max-time",
        "0.1",
        "examples/loop.ilmr",
    ]);
    assert!(out.contains("W0903"), "{out}");
}

/// `ilmrc parse BIG | head -1`: when the reader goes away the command ends as `cat`
/// does, by SIGPIPE, without a panic (it was exit 101 with a backtrace).
#[cfg(unix)]
#[test]
fn a_closed_stdout_ends_a_command_quietly() {
    use std::io::Read;
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Stdio};

    let big = std::env::temp_dir().join(format!("ilmr-cli-{}-big.ilmr", std::process::id()));
    std::fs::write(&big, "speed(0.4)\n".repeat(20_000)).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["parse", big.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    let out = child.wait_with_output().unwrap();
    let _ = std::fs::remove_file(&big);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{stderr}");
}
