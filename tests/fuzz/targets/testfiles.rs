//! Test files (`*.test.toml`, `ilmrc test`), through `ilmr_testfile::file`: the
//! reader as `ilmrc test` and the language server call it, beside the example tasks
//! (so that `task = "short_task.ilmr"` is found), and the editor's completion and
//! hover at places of what it read. A file it accepts keeps within the documented
//! limits; each problem of one it refuses has a code of a file or an assertion, a span
//! of the file on characters' edges and a short message.

use std::path::PathBuf;
use std::sync::OnceLock;

use ilmr_testfile::complete::{self, Spot};
use ilmr_testfile::file::{self, MAX_SEEDS, MAX_TIME, Outline, TestFile};
use ilmr_testfile::problem::{MAX_MESSAGE, Problem};

use crate::engine::{self, Budget, Stats};
use crate::mutate;

/// The fuzzed file's path: beside the example tasks it names.
fn path() -> &'static PathBuf {
    static PATH: OnceLock<PathBuf> = OnceLock::new();
    PATH.get_or_init(|| engine::root().join("examples/fuzz.test.toml"))
}

/// The examples' test files and the fixtures of `tests/testing` (whose tasks, named
/// from beside the examples, are mostly not found: the missing-file problem).
pub fn seeds() -> Vec<Vec<u8>> {
    ["examples", "tests/testing"]
        .iter()
        .flat_map(|d| engine::files(d, &["toml"]))
        .filter(|(p, _)| p.ends_with(ilmr_testfile::SUFFIX))
        .map(|(_, bytes)| bytes)
        .collect()
}

/// The keys, the assertion language's words and TOML's punctuation.
pub fn dictionary() -> Vec<String> {
    let mut words: Vec<String> = file::KEYS
        .iter()
        .flat_map(|(k, _)| [format!("{k} = "), k.to_string()])
        .collect();
    words.extend(
        [
            "[[test]]",
            "[test]",
            "eventually",
            "within",
            "always",
            "never",
            "at end:",
            "while",
            "from",
            "until",
            "before(",
            "during(",
            "ends",
            "completed",
            "broken",
            "refused",
            "overrun",
            "error",
            "fault",
            "speed",
            "clearance",
            "robot",
            "inside",
            "heading",
            "of",
            "line ",
            "`goahead(1.2)`",
            "m.status",
            "==",
            "<=",
            ">=",
            "!=",
            "<",
            ">",
            "..",
            ":",
            "(8, 5)",
            "lab_door",
            "charger",
            "\"moro\"",
            "\"workpartner\"",
            "\"scripted\"",
            "\"none\"",
            "\"office\"",
            "\"yard\"",
            "\"empty\"",
            "\"ideal\"",
            "\"0-1\"",
            "\"0-10000\"",
            "\"short_task.ilmr\"",
            "\"loop.ilmr\"",
            "\"skills\"",
            "\"../tests/run/counting.json\"",
            "{ t = 5, text = \"speed(0.2)\" }",
            "{ precision = 0.01, scans = true }",
            "true",
            "false",
            "1e9",
            "nan",
            "inf",
            "-inf",
            "0x10",
            "1_000",
            "[",
            "]",
            "{",
            "}",
            "=",
            ",",
            "\"",
            "'",
            "'''",
            "\"\"\"",
            "#",
            "\\u0000",
        ]
        .iter()
        .map(|w| w.to_string()),
    );
    mutate::with_numbers_and_spacing(words)
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/testfile.rs`).
pub fn feed(input: &[u8]) {
    // `ilmrc test` reads text (`ilmr_files::read_text`); the editor sends text.
    let Ok(text) = std::str::from_utf8(input) else {
        return;
    };
    let read = file::check(path(), text.to_string());
    match &read.file {
        Ok(f) => accepted(f, text),
        Err(problems) => refused(problems, text),
    }
    edit(text, &read.outlines);
}

fn accepted(f: &TestFile, text: &str) {
    assert_eq!(f.text, text);
    for (i, t) in f.tests.iter().enumerate() {
        assert!(
            f.tests[..i].iter().all(|o| o.name != t.name),
            "two tests named {:?}",
            t.name
        );
        inside(text, &t.span, "a test's name");
        assert!(
            !t.seeds.is_empty() && t.seeds.len() as u64 <= MAX_SEEDS,
            "{} seeds",
            t.seeds.len()
        );
        assert!(!t.assertions.is_empty(), "a test that asserts nothing");
        for a in &t.assertions {
            inside(text, &a.span, "an assertion");
        }
        for l in &t.lines {
            assert!(l.t.is_finite() && l.t >= 0.0, "a line at {}", l.t);
        }
        if let Some(s) = &t.snapshot {
            assert!(
                s.precision.is_finite() && s.precision > 0.0,
                "{}",
                s.precision
            );
            inside(text, &s.span, "a snapshot");
        }
        // `ilmrc run`'s arguments: flags each with its value, then the task; a time is
        // in range.
        let Some((task, flags)) = t.argv.split_last() else {
            panic!("a test without a task: {:?}", t.name);
        };
        assert!(!task.starts_with("--"), "{:?}", t.argv);
        assert!(
            flags.len() % 2 == 0,
            "a flag without its value: {:?}",
            t.argv
        );
        for pair in flags.chunks(2) {
            assert!(pair[0].starts_with("--"), "{:?} in {:?}", pair[0], t.argv);
            if pair[0] == "--max-time" {
                let s: f64 = pair[1].parse().expect("a number");
                assert!(s > 0.0 && s <= MAX_TIME, "--max-time {s}");
            }
        }
    }
}

fn refused(problems: &[Problem], text: &str) {
    assert!(!problems.is_empty(), "refused without a problem");
    for p in problems {
        let code = p.code.as_str();
        assert!(
            code.starts_with("A01") || code.starts_with("A02"),
            "{code} is a failure's code, not a file's: {p:?}"
        );
        inside(text, &p.span, "a problem");
        assert!(!p.message.is_empty(), "a problem says why: {p:?}");
        for said in std::iter::once(&p.message).chain(&p.help) {
            assert!(
                said.chars().count() <= MAX_MESSAGE,
                "{} characters: {:?}",
                said.chars().count(),
                said.chars().take(400).collect::<String>()
            );
        }
    }
    assert!(
        problems.is_sorted_by_key(|p| (p.span.start, p.span.end)),
        "problems in the file's order"
    );
}

fn inside(text: &str, span: &std::ops::Range<usize>, what: &str) {
    assert!(
        text.get(span.clone()).is_some(),
        "{what} at {span:?}: outside the file of {} bytes, or inside a character",
        text.len()
    );
}

/// What the editor does at a cursor: completion and hover, at the places of each
/// assertion string and at a few spread over the file.
fn edit(text: &str, outlines: &[Outline]) {
    let mut offsets: Vec<usize> = (0..=8).map(|k| text.len() * k / 8).collect();
    for o in outlines {
        inside(text, &o.span, "an outline");
        for (span, base) in &o.asserts {
            inside(text, span, "an assertion's string");
            if let Some(b) = *base {
                assert!(span.contains(&b) || b == span.end, "{b} outside {span:?}");
                offsets.extend([b, b + 1, (b + span.end) / 2, span.end.saturating_sub(1)]);
            }
        }
    }
    for offset in offsets {
        if !text.is_char_boundary(offset) {
            continue;
        }
        let hover = match complete::spot(text, outlines, offset) {
            Spot::Assertion { outline, base } => {
                let _ = complete::assertion(text, outline, base, offset);
                let end = outline
                    .asserts
                    .iter()
                    .find(|(_, b)| *b == Some(base))
                    .map(|(s, _)| s.end.saturating_sub(1));
                end.and_then(|end| complete::hover_assertion(text, outline, base, end, offset))
            }
            Spot::Key => {
                let _ = complete::keys(text, offset);
                complete::hover_key(text, offset)
            }
            Spot::Elsewhere => complete::hover_key(text, offset),
        };
        if let Some((_, span)) = hover {
            inside(text, &span, "a hover");
        }
    }
}

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = seeds();
    let words = dictionary();
    engine::run(
        "testfile",
        &corpus,
        budget,
        |base, rng| mutate::text(base, rng, &corpus, &words),
        feed,
    )
}
