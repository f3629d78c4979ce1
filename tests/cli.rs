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
