//! `ilmrc test`: the shipped examples' tests pass; the fixtures under `tests/testing`
//! show what a failing test, a task that does not check and a test file with mistakes
//! look like (snapshots), and the JUnit XML is read back by Python's XML parser.

mod support;

use support::*;

/// The output with each test's and the whole run's wall time taken out.
fn untimed(stdout: &str) -> String {
    stdout
        .lines()
        .map(|l| {
            let timed =
                l.starts_with("ok ") || l.starts_with("FAILED ") || l.starts_with("test result:");
            match l.rfind(' ').filter(|_| timed && l.ends_with(" s")) {
                Some(_) => {
                    let head = l.trim_end_matches(" s");
                    let cut = head.rfind(' ').unwrap_or(head.len());
                    format!("{} [time]", &head[..cut])
                }
                None => l.to_string(),
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn scratch(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("ilmr-testing-{}-{name}", std::process::id()))
}

#[test]
fn every_example_has_a_test_file_and_they_pass() {
    let examples: Vec<String> = std::fs::read_dir(root().join("examples"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    for task in examples.iter().filter(|n| n.ends_with(".ilmr")) {
        let test = task.replace(".ilmr", ".test.toml");
        assert!(examples.contains(&test), "{task} has no {test}");
    }
    let (code, out, err) = ilmrc(&["test", "examples"]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(
        out.contains("test result: ok. 7 passed; 0 failed; 46 run(s)"),
        "{out}"
    );
}

#[test]
fn failing_tests_show_the_assertion_the_time_and_the_values() {
    let (code, out, err) = ilmrc(&[
        "test",
        "tests/testing/failing.test.toml",
        "tests/testing/rejected.test.toml",
    ]);
    assert_eq!(code, 1, "{out}\n{err}");
    insta::assert_snapshot!("testing_failures", untimed(&out));
}

#[test]
fn passing_fixtures_pass() {
    let (code, out, err) = ilmrc(&["test", "--jobs", "2", "tests/testing/passing.test.toml"]);
    assert_eq!(code, 0, "{out}\n{err}");
    insta::assert_snapshot!("testing_passing", untimed(&out));
}

#[test]
fn every_mistake_of_a_test_file_is_shown_with_exit_2() {
    let (code, out, err) = ilmrc(&["test", "tests/testing/errors.test.toml"]);
    assert_eq!(code, 2, "{out}\n{err}");
    insta::assert_snapshot!("testing_errors", out);
    let (code, out, _) = ilmrc(&["test", "tests/testing/not_toml.test.toml"]);
    assert_eq!(code, 2);
    insta::assert_snapshot!("testing_not_toml", out);
}

#[test]
fn usage_errors_are_exit_2() {
    let (code, _, err) = ilmrc(&["test", "tests/testing/no_such.test.toml"]);
    assert_eq!(code, 2);
    assert!(err.contains("no file or folder"), "{err}");
    let (code, _, err) = ilmrc(&["test", "docs"]);
    assert_eq!(code, 2);
    assert!(err.contains("no `*.test.toml` file under `docs`"), "{err}");
    let (code, _, _) = ilmrc(&["test"]);
    assert_eq!(code, 2);
    let (code, _, _) = ilmrc(&["test", "--jobs", "0", "examples"]);
    assert_eq!(code, 2);
}

#[test]
fn junit_xml_is_read_by_python() {
    let xml = scratch("junit.xml");
    let (code, out, err) = ilmrc(&[
        "test",
        "--junit",
        xml.to_str().unwrap(),
        "tests/testing/failing.test.toml",
        "tests/testing/passing.test.toml",
    ]);
    assert_eq!(code, 1, "{out}\n{err}");
    // Python's own XML parser, not ours: the file is well-formed and says what ran.
    let script = r#"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
assert root.tag == "testsuites", root.tag
cases = root.findall("./testsuite/testcase")
failed = [c.get("name") for c in cases if c.find("failure") is not None]
print(root.get("tests"), root.get("failures"), len(cases), len(root.findall("testsuite")))
print("|".join(sorted(failed)))
f = [c for c in cases if c.get("name") == "too slow, too fast, out of order"][0].find("failure")
assert "always: speed <= 0.3" in f.text and "speed 0.305 m/s" in f.text, f.text
assert "\x1b" not in f.text
"#;
    let py = std::process::Command::new("python3")
        .args(["-c", script, xml.to_str().unwrap()])
        .output()
        .expect("python3 runs");
    let _ = std::fs::remove_file(&xml);
    let said = String::from_utf8_lossy(&py.stdout);
    assert!(
        py.status.success(),
        "{said}{}",
        String::from_utf8_lossy(&py.stderr)
    );
    assert_eq!(
        said,
        "11 4 11 2\ncut short by max_time|every seed must pass|the scanner drops out|too slow, too fast, out of order\n"
    );
}

#[test]
fn a_stored_snapshot_is_the_same_bytes_from_anywhere() {
    let (code, out, err) = ilmrc(&["test", "tests/testing/snapshot.test.toml"]);
    assert_eq!(code, 0, "{out}\n{err}");
    let absolute = root().join("tests/testing/snapshot.test.toml");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["test", absolute.to_str().unwrap()])
        .current_dir(std::env::temp_dir())
        .output()
        .expect("ilmrc runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}

#[test]
fn snapshots_are_pending_then_reviewed_accepted_and_compared() {
    let dir = scratch("snapshots");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        root().join("examples/short_task.ilmr"),
        dir.join("task.ilmr"),
    )
    .unwrap();
    let file = dir.join("s.test.toml");
    std::fs::write(
        &file,
        "task = \"task.ilmr\"\nmax_time = 2\n\n[[test]]\nname = \"Two seconds, seed 3\"\nseeds = 3\nsnapshot = true\nassert = [\"never: refused\"]\n",
    )
    .unwrap();
    let f = file.to_str().unwrap();
    let stored = dir.join("snapshots/s__two_seconds_seed_3__seed3.jsonl");
    let pending = dir.join("snapshots/s__two_seconds_seed_3__seed3.jsonl.new");

    let (code, out, _) = ilmrc(&["test", f]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("[A0304]") && out.contains("yet; the run's is pending"),
        "{out}"
    );
    let first = std::fs::read(&pending).expect("pending written");
    let (code, _, _) = ilmrc(&["test", f]);
    assert_eq!(code, 1);
    assert_eq!(
        std::fs::read(&pending).unwrap(),
        first,
        "same run, same bytes"
    );
    let text = String::from_utf8(first).unwrap();
    assert!(text.starts_with("{\"t\":0,\"event\":\"trace\",\"version\":1}\n{\"t\":0,\"event\":\"run\",\"task\":\"task.ilmr\""), "{text}");
    assert!(!text.contains("\"scan\""), "scans are left out");
    assert!(
        text.contains("{\"t\":0.1,\"event\":\"pose\"")
            && !text.contains("{\"t\":0.01,\"event\":\"pose\""),
        "poses ten a second"
    );

    let (code, out, _) = ilmrc(&["test", "--review", f]);
    assert_eq!(code, 0);
    assert!(
        out.contains("new snapshot") && out.contains("1 pending snapshot(s)"),
        "{out}"
    );
    let (code, out, _) = ilmrc(&["test", "--accept", f]);
    assert_eq!(code, 0, "{out}");
    assert!(stored.exists() && !pending.exists());
    let (code, out, _) = ilmrc(&["test", f]);
    assert_eq!(code, 0, "{out}");

    // A stored snapshot that differs: the test fails, and --review shows the lines.
    let changed = text.replacen("\"source\":\"true\"", "\"source\":\"estimated\"", 1);
    std::fs::write(&stored, &changed).unwrap();
    let (code, out, _) = ilmrc(&["test", f]);
    assert_eq!(code, 1);
    assert!(
        out.contains("the trace differs from") && out.contains("on; the run's is pending"),
        "{out}"
    );
    let (_, out, _) = ilmrc(&["test", "--review", f]);
    assert!(out.contains("1 line(s) stored, 1 line(s) now"), "{out}");
    assert!(
        out.contains("- {\"t\":0,\"event\":\"pose\"") && out.contains("\"source\":\"estimated\"}"),
        "{out}"
    );
    assert!(out.contains("+ {\"t\":0,\"event\":\"pose\""), "{out}");
    let (code, _, _) = ilmrc(&["test", "--review", "--accept", f]);
    assert_eq!(code, 2, "--review and --accept together are a usage error");
    let _ = std::fs::remove_dir_all(&dir);
}
