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
        out.contains("test result: ok. 7 passed; 0 failed; 8 run(s)"),
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
