//! What an editor gets of a test file: every problem with its code and span (the
//! reader `ilmrc test` uses), and at a place in an assertion what the grammar allows
//! there, named from the test's own task and world.

use std::path::{Path, PathBuf};

use ilmr_testfile::codes::Code;
use ilmr_testfile::complete::{self, Spot, What};
use ilmr_testfile::file::{self, Outline};

const TASK: &str = "// a task of four statements
speed(0.4)
goahead(1.2)

m=goahead(0.7)
wait(m)
";

const WORLD: &str = r#"name = "room"
description = "A room with one door."
bounds = { min = [-10.0, -10.0], max = [10.0, 10.0] }
start = { x = 0.0, y = 0.0, heading = 0.0 }

[[wall]]
id = "north_wall"
from = [-5.0, 5.0]
to = [5.0, 5.0]

[[door]]
id = "exit_door"
wall = "north_wall"
at = 5.0
width = 1.2
"#;

fn folder(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("task.ilmr"), TASK).unwrap();
    std::fs::write(dir.join("room.toml"), WORLD).unwrap();
    dir
}

fn read(dir: &Path, text: &str) -> file::Read {
    file::check(&dir.join("t.test.toml"), text.to_string())
}

/// A file with one test, `assert = ["<assertion>"]`: the outline and where the
/// assertion's content starts.
fn outline(dir: &Path, assertion: &str) -> (String, Outline, usize) {
    let text = format!(
        "task = \"task.ilmr\"\nworld = \"room.toml\"\n\n[[test]]\nname = \"t\"\nassert = [\"{assertion}\"]\n"
    );
    let read = read(dir, &text);
    let outline = read.outlines.into_iter().next().expect("one test");
    let base = text.find("assert = [\"").expect("an assert") + "assert = [\"".len();
    (text, outline, base)
}

/// The labels offered at the end of `assertion`.
fn offered(dir: &Path, assertion: &str) -> Vec<(String, What, Option<String>)> {
    let (text, outline, base) = outline(dir, assertion);
    let end = base + assertion.len();
    let Spot::Assertion { base: b, .. } =
        complete::spot(&text, std::slice::from_ref(&outline), end)
    else {
        panic!("{assertion}: the end is not in the assertion");
    };
    assert_eq!(b, base);
    complete::assertion(&text, &outline, base, end)
        .items
        .into_iter()
        .map(|c| (c.label, c.what, c.detail))
        .collect()
}

fn labels(items: &[(String, What, Option<String>)]) -> Vec<&str> {
    items.iter().map(|(l, ..)| l.as_str()).collect()
}

#[test]
fn every_problem_has_its_code_and_span() {
    let dir = folder("problems");
    let text = "task = \"missing.ilmr\"\nseed = 3\n\n[[test]]\nname = \"t\"\nseeds = \"9-1\"\nassert = [\"never: refused\"]\n";
    let problems = read(&dir, text).file.err().expect("problems");
    let said: Vec<(Code, &str)> = problems
        .iter()
        .map(|p| (p.code, &text[p.span.clone()]))
        .collect();
    assert_eq!(
        said,
        [
            (Code::MissingFile, "\"missing.ilmr\""),
            (Code::UnknownKey, "seed"),
            (Code::BadValue, "\"9-1\""),
        ]
    );
    assert_eq!(problems[1].help.as_deref(), Some("did you mean `seeds`?"));

    let text = "task = \"task.ilmr\"\n[[test]]\nname = \"t\"\nassert = [\"eventualy: line 4 ends\", \"eventually: line 4 ends\"]\n";
    let problems = read(&dir, text).file.err().expect("problems");
    let said: Vec<(Code, &str)> = problems
        .iter()
        .map(|p| (p.code, &text[p.span.clone()]))
        .collect();
    assert_eq!(
        said,
        [(Code::Syntax, "eventualy"), (Code::UnknownLine, "4")]
    );
    assert_eq!(
        problems[0].help.as_deref(),
        Some("did you mean `eventually`?")
    );
}

#[test]
fn an_assertion_is_completed_with_what_the_grammar_allows_there() {
    let dir = folder("complete");
    assert_eq!(
        labels(&offered(&dir, "")),
        [
            "eventually",
            "always",
            "never",
            "before",
            "during",
            "at end:"
        ]
    );
    // Those that begin with what is typed come first, then those that contain it.
    assert_eq!(labels(&offered(&dir, "ev")), ["eventually", "never"]);
    let goal = offered(&dir, "eventually within 5 s: ");
    assert_eq!(
        labels(&goal),
        [
            "line",
            "robot",
            "refused",
            "broken",
            "overrun",
            "error",
            "fault",
            "m",
            "speed(0.4)",
            "goahead(1.2)",
            "m=goahead(0.7)",
            "wait(m)"
        ],
        "contacts are not traced, so `contact` is not offered"
    );
    assert_eq!(
        goal[7],
        (
            "m".into(),
            What::Variable,
            Some("a variable the task assigns".into())
        )
    );
    assert_eq!(goal[8].2.as_deref(), Some("line 2"));
    assert_eq!(
        labels(&offered(&dir, "eventually within 5 s: line 5 ends ")),
        ["completed", "broken", "refused"]
    );
    assert_eq!(
        labels(&offered(&dir, "always from 2 s ")),
        ["from", "until", "while", ":"]
            .into_iter()
            .filter(|w| *w != ":")
            .collect::<Vec<_>>()
    );
    assert_eq!(
        labels(&offered(&dir, "at end: m.")),
        ["value", "status", "x", "y", "h", "dist"]
    );
}

#[test]
fn line_references_are_the_tasks_statements() {
    let dir = folder("lines");
    let lines = offered(&dir, "before(line ");
    assert_eq!(
        lines,
        [
            ("2".into(), What::Line, Some("speed(0.4)".into())),
            ("3".into(), What::Line, Some("goahead(1.2)".into())),
            ("5".into(), What::Line, Some("m=goahead(0.7)".into())),
            ("6".into(), What::Line, Some("wait(m)".into())),
        ]
    );
    // A digit typed narrows them; a text in backticks is completed inside them.
    assert_eq!(labels(&offered(&dir, "before(line 5")), ["5"]);
    assert_eq!(
        labels(&offered(&dir, "before(`go")),
        ["goahead(1.2)", "m=goahead(0.7)"]
    );
}

#[test]
fn object_names_are_the_worlds() {
    let dir = folder("objects");
    let objects = offered(&dir, "eventually: robot within 1 of ");
    assert_eq!(
        objects,
        [
            ("exit_door".into(), What::Object, Some("at (0, 5)".into())),
            (
                "north_wall".into(),
                What::Object,
                Some("a wall from (-5, 5) to (5, 5)".into())
            ),
        ]
    );
    assert_eq!(
        labels(&offered(&dir, "always: ")),
        ["speed", "robot", "clearance"]
    );
    assert_eq!(
        labels(&offered(&dir, "always: robot ")),
        ["inside", "within"]
    );
}

#[test]
fn without_a_robot_nothing_of_poses_is_offered() {
    let dir = folder("no_robot");
    let text =
        "task = \"task.ilmr\"\nrobot = \"none\"\n[[test]]\nname = \"t\"\nassert = [\"always: \"]\n";
    let read = read(&dir, text);
    let base = text.find("always").unwrap();
    let end = base + "always: ".len();
    let items = complete::assertion(text, &read.outlines[0], base, end);
    assert!(items.items.is_empty(), "{:?}", items.items);
}

#[test]
fn hover_says_what_a_line_an_object_and_a_key_are() {
    let dir = folder("hover");
    let (text, outline, base) = outline(&dir, "before(line 5, `wait(m)`) ");
    let end = base + "before(line 5, `wait(m)`) ".len();
    let at = |s: &str| text.find(s).unwrap();
    let (said, span) =
        complete::hover_assertion(&text, &outline, base, end, at("5,")).expect("a line");
    assert_eq!(said, "line 5 of the task: `m=goahead(0.7)`");
    assert_eq!(&text[span], "5");
    let (said, _) =
        complete::hover_assertion(&text, &outline, base, end, at("wait(m)") + 1).expect("a text");
    assert_eq!(said, "the statement at\n\nline 6: `wait(m)`");
    let (said, span) = complete::hover_key(&text, at("world") + 2).expect("a key");
    assert!(said.starts_with("`world`: "), "{said}");
    assert_eq!(&text[span], "world");
}

#[test]
fn many_lines_are_cut_to_the_cap_and_marked_incomplete() {
    let dir = folder("many");
    let task: String = (0..1000).map(|i| format!("t{i}=goahead(0.1)\n")).collect();
    std::fs::write(dir.join("task.ilmr"), task).unwrap();
    let (text, outline, base) = outline(&dir, "before(line ");
    let end = base + "before(line ".len();
    let got = complete::assertion(&text, &outline, base, end);
    let lines = got.items.iter().filter(|c| c.what == What::Line).count();
    assert_eq!(lines, complete::MAX_CANDIDATES);
    assert!(got.incomplete);
}

#[test]
fn hover_in_a_multi_line_string_reads_past_its_quotes() {
    let dir = folder("hover_literal");
    let text =
        "task = \"task.ilmr\"\n[[test]]\nname = \"t\"\nassert = ['''eventually: line 5 ends''']\n";
    let read = read(&dir, text);
    assert!(read.file.is_ok());
    let outline = &read.outlines[0];
    let (span, base) = outline.asserts[0].clone();
    let base = base.expect("a literal string's content is its bytes");
    let at = text.find("5 ends").unwrap();
    let (said, _) =
        complete::hover_assertion(text, outline, base, span.end - 1, at).expect("a line reference");
    assert_eq!(said, "line 5 of the task: `m=goahead(0.7)`");
}
