//! The corpus of broken programs: every diagnostic code fires at least once, and each
//! file's rendered and JSON output are snapshots.

mod support;

use std::collections::BTreeSet;

use ilmr_compiler::Code;
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::render;
use support::*;

fn corpus() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(root().join("tests/check/broken"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
}

fn load(path: &std::path::Path) -> Vec<Source> {
    let text = std::fs::read_to_string(path).unwrap();
    let display = path.strip_prefix(root()).unwrap().display().to_string();
    vec![Source::new(display, text)]
}

#[test]
fn broken_programs_render_for_people_and_tools() {
    for path in corpus() {
        let sources = load(&path);
        let robot = intended_robot(&sources[0].text).to_string();
        let (analysis, _) = check(&sources, &robot);
        let name = path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .replace('.', "_");
        insta::assert_snapshot!(format!("human_{name}"), human(&analysis));
        let json = render::json(&analysis.diagnostics, &render_files(&analysis));
        insta::assert_snapshot!(
            format!("json_{name}"),
            serde_json::to_string_pretty(&json).unwrap()
        );
    }
}

#[test]
fn every_code_is_exercised_by_the_corpus() {
    let mut seen = BTreeSet::new();
    for path in corpus() {
        let sources = load(&path);
        let robot = intended_robot(&sources[0].text).to_string();
        let (analysis, _) = check(&sources, &robot);
        seen.extend(analysis.diagnostics.iter().map(|d| d.code));
    }
    // The robot model's own warnings come from loading a model file (tests/cli.rs).
    seen.insert(Code::RobotModel);
    let missing: Vec<&str> = Code::ALL
        .iter()
        .filter(|c| !seen.contains(c))
        .map(|c| c.as_str())
        .collect();
    assert!(missing.is_empty(), "no corpus file produces {missing:?}");
}

#[test]
fn several_independent_mistakes_give_one_diagnostic_each() {
    let path = root().join("tests/check/broken/syntax.ilmr");
    let sources = load(&path);
    let (analysis, _) = check(&sources, "moro");
    let lines: BTreeSet<usize> = analysis
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| {
            ilmr_compiler::LineIndex::new(&sources[0].text)
                .line_col(&sources[0].text, d.span.start as usize)
                .0
        })
        .collect();
    let errors = analysis.diagnostics.iter().filter(|d| d.is_error()).count();
    assert_eq!(lines.len(), errors, "one error per broken line");
    assert_eq!(errors, 6);
    // The last line is still read and checked.
    assert!(
        analysis.files[0].tree.blocks[0]
            .stmts
            .iter()
            .any(|s| s.span.slice(&sources[0].text) == "goahead(1)")
    );
}

#[test]
fn diagnostics_reference_is_fresh() {
    let path = root().join("docs/diagnostics.md");
    let expected = ilmr_compiler::diagnostic::reference_markdown();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, &expected).unwrap();
    }
    let actual = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        actual == expected,
        "docs/diagnostics.md is stale: run `UPDATE_DOCS=1 cargo test --test diagnostics`"
    );
}

#[test]
fn checking_an_empty_program_is_clean() {
    let sources = vec![Source::new("empty.ilmr", "")];
    let m = model("moro");
    assert!(analyze(&sources, &m).diagnostics.is_empty());
}
