//! Latency of a test file (`*.test.toml`) in the engine: the re-check after an edit
//! (it reads the named task from disk, places the robot in its world and parses every
//! assertion), and completion of a line reference (capped at
//! `ilmr_testfile::complete::MAX_CANDIDATES`) and of an object name, for a test file
//! naming a task of 10,000 and of 100,000 lines. Figures in docs/performance.md
//! ("Test files in the language server"). Run with
//! `cargo bench -p ilmr-lsp --bench test_files`.

use std::path::PathBuf;

use divan::{Bencher, black_box};
use ilmr_lsp::{Engine, Settings};
use tower_lsp_server::ls_types::{Position, Range, TextDocumentContentChangeEvent, Uri};

fn main() {
    divan::main();
}

const LINES: [usize; 2] = [10_000, 100_000];

/// Assertions of the kinds a test holds, each naming a line, a text or an object.
const ASSERTS: [&str; 6] = [
    "eventually within 60 s: line 7 ends completed",
    "before(line 3, line 9)",
    "never: refused",
    "always while `speed(0.3)`: speed <= 0.5",
    "eventually: robot within 2 of lab_door",
    "at end: n == 3",
];

struct Setup {
    engine: Engine,
    test: Uri,
    /// The line of the first test's `assert = [` (each assertion on its own line).
    assert_line: u32,
    _dir: Scratch,
}

/// A folder removed when the bench ends.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn setup(lines: usize) -> Setup {
    let dir = std::env::temp_dir().join(format!(
        "ilmr-lsp-bench-tests-{}-{lines}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let mut task = String::from("n = 0\n");
    while task.lines().count() < lines {
        task.push_str(
            "speed(0.3)\ng = goahead(1)\nwait(g)\nn = n + 1\nt = turn(d=90,c=0.5)\nwait(t)\n\n",
        );
    }
    std::fs::write(dir.join("task.ilmr"), task).expect("the task is written");
    let mut text = String::from("task = \"task.ilmr\"\nseeds = \"1-5\"\n");
    for t in 0..3 {
        text.push_str(&format!("\n[[test]]\nname = \"test {t}\"\nassert = [\n"));
        for a in ASSERTS {
            text.push_str(&format!("    \"{a}\",\n"));
        }
        text.push_str("]\n");
    }
    let test: Uri = format!("file://{}/task.test.toml", dir.display())
        .parse()
        .expect("a URI");
    let mut engine = Engine::new(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: true,
            ilmrc: None,
        },
    );
    engine.open(test.clone(), 1, text);
    let problems = engine.diagnostics(&test);
    assert!(problems.is_empty(), "the test file is clean: {problems:?}");
    Setup {
        engine,
        test,
        assert_line: 5,
        _dir: Scratch(dir),
    }
}

/// Retypes the `7` of the first assertion's `line 7`: the file stays clean.
fn retyped(s: &Setup) -> TextDocumentContentChangeEvent {
    let col = 5 + ASSERTS[0].find("line 7").expect("a line") as u32 + 5;
    TextDocumentContentChangeEvent {
        range: Some(Range::new(
            Position::new(s.assert_line + 1, col),
            Position::new(s.assert_line + 1, col + 1),
        )),
        range_length: None,
        text: "7".into(),
    }
}

#[divan::bench(args = LINES, sample_count = 20)]
fn recheck_after_an_edit(bencher: Bencher, lines: usize) {
    let mut s = setup(lines);
    let mut version = 1;
    bencher.bench_local(|| {
        version += 1;
        black_box(s.engine.change(&s.test, version, vec![retyped(&s)]))
    });
}

#[divan::bench(args = LINES, sample_count = 100)]
fn completion_of_a_line_reference(bencher: Bencher, lines: usize) {
    let s = setup(lines);
    // After `before(line `.
    let at = Position::new(s.assert_line + 2, 5 + "before(line ".len() as u32);
    let list = s.engine.completion_list(&s.test, at);
    assert!(
        list.is_incomplete && list.items.len() == 100,
        "{}",
        list.items.len()
    );
    bencher.bench_local(|| black_box(s.engine.completion_list(&s.test, at)));
}

#[divan::bench(args = LINES, sample_count = 100)]
fn completion_of_an_object(bencher: Bencher, lines: usize) {
    let s = setup(lines);
    // After `robot within 2 of `.
    let at = Position::new(
        s.assert_line + 5,
        5 + ASSERTS[4].find("lab_door").expect("an object") as u32,
    );
    let list = s.engine.completion_list(&s.test, at);
    assert!(list.items.iter().any(|i| i.label == "lab_door"));
    bencher.bench_local(|| black_box(s.engine.completion_list(&s.test, at)));
}
