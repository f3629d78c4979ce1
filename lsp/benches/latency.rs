//! Latency of the engine on a 10,000-line task with a skill file: a full re-check after a
//! one-character edit (what every keystroke costs), completion, hover and the concurrency
//! lens's inlay hints, workspace symbols and highlights. Figures in
//! docs/performance.md ("Language server"). Run with `cargo bench -p ilmr-lsp`.

use divan::{Bencher, black_box};
use ilmr_lsp::{Engine, Settings};
use tower_lsp_server::ls_types::{Position, Range, TextDocumentContentChangeEvent, Uri};

fn main() {
    divan::main();
}

const SKILLS: usize = 50;

/// Task blocks of the shape real tasks have (searches, guards, waits, counting loops,
/// skill calls), twelve lines each, with Finnish names.
fn task(lines: usize) -> String {
    let mut task = String::new();
    let mut i = 0;
    while i * 12 < lines {
        let k = i % SKILLS;
        task.push_str(&format!(
            "ovi_ö{i} = sensor(scanner,door,left)\nif(ovi_ö{i})\n    speed(0.3)\n    g{i} = gotoxy(ovi_ö{i})\n    wait(g{i})\n    taito{k}\nendif\nkäännös{i} = 0\nwhile(käännös{i} < 3)\n    käännös{i} = käännös{i} + 1\nendwhile\n\n"
        ));
        i += 1;
    }
    task
}

fn skills() -> String {
    (0..SKILLS)
        .map(|k| format!("taito{k}:\nspeed(-0.3)\nt{k}=turn(d=90,c=0.5)\nwait(t{k})\n\n"))
        .collect()
}

struct Setup {
    engine: Engine,
    task: Uri,
    /// A line in the middle of the task: `    g416 = gotoxy(ovi_ö416)`.
    middle: u32,
}

fn setup() -> Setup {
    let mut engine = Engine::new(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: true,
            ilmrc: None,
        },
    );
    let task: Uri = "file:///bench/task.ilmr".parse().expect("a URI");
    let text = task_text();
    assert!(text.lines().count() >= 10_000);
    engine.open(
        "file:///bench/skills.ilms".parse().expect("a URI"),
        1,
        skills(),
    );
    engine.open(task.clone(), 1, text);
    let errors: Vec<_> = engine
        .diagnostics(&task)
        .into_iter()
        .filter(|d| d.severity == Some(tower_lsp_server::ls_types::DiagnosticSeverity::ERROR))
        .take(3)
        .collect();
    assert!(
        errors.is_empty(),
        "the corpus is a valid program: {errors:?}"
    );
    Setup {
        engine,
        task,
        middle: 5_000 / 12 * 12 + 3,
    }
}

fn task_text() -> String {
    task(10_000)
}

/// An edit that replaces one character in the middle of the task by itself: the text
/// stays valid, the work of a re-check is all there.
fn retyped(s: &Setup) -> TextDocumentContentChangeEvent {
    TextDocumentContentChangeEvent {
        range: Some(Range::new(
            Position::new(s.middle, 4),
            Position::new(s.middle, 5),
        )),
        range_length: None,
        text: "g".into(),
    }
}

#[divan::bench(sample_count = 20)]
fn recheck_after_an_edit(bencher: Bencher) {
    let mut s = setup();
    let mut version = 1;
    bencher.bench_local(|| {
        version += 1;
        black_box(s.engine.change(&s.task, version, vec![retyped(&s)]))
    });
}

#[divan::bench(sample_count = 100)]
fn completion_in_arguments(bencher: Bencher) {
    let s = setup();
    // After `gotoxy(`: the variables holding positions, then numbers.
    let at = Position::new(s.middle, 18);
    assert!(!s.engine.completion(&s.task, at).is_empty());
    bencher.bench_local(|| black_box(s.engine.completion(&s.task, at)));
}

#[divan::bench(sample_count = 100)]
fn completion_at_statement_start(bencher: Bencher) {
    let s = setup();
    let at = Position::new(s.middle, 4);
    bencher.bench_local(|| black_box(s.engine.completion(&s.task, at)));
}

#[divan::bench(sample_count = 100)]
fn hover_on_a_variable(bencher: Bencher) {
    let s = setup();
    let at = Position::new(s.middle, 20);
    assert!(s.engine.hover(&s.task, at).is_some());
    bencher.bench_local(|| black_box(s.engine.hover(&s.task, at)));
}

#[divan::bench(sample_count = 100)]
fn hover_on_a_command(bencher: Bencher) {
    let s = setup();
    let at = Position::new(s.middle, 11);
    assert!(s.engine.hover(&s.task, at).is_some());
    bencher.bench_local(|| black_box(s.engine.hover(&s.task, at)));
}

#[divan::bench(sample_count = 20)]
fn semantic_tokens(bencher: Bencher) {
    let s = setup();
    bencher.bench_local(|| black_box(s.engine.semantic_tokens(&s.task)));
}

/// The 60 lines round the middle: what a screen shows.
fn screen(s: &Setup) -> Range {
    Range::new(
        Position::new(s.middle - 30, 0),
        Position::new(s.middle + 30, 0),
    )
}

#[divan::bench(sample_count = 100)]
fn inlay_hints_of_a_screen(bencher: Bencher) {
    let s = setup();
    let range = screen(&s);
    assert!(!s.engine.inlay_hints(&s.task, range).is_empty());
    bencher.bench_local(|| black_box(s.engine.inlay_hints(&s.task, range)));
}

/// An edit's re-check and then a screen's hints, which compute the file's schedule
/// again: less `recheck_after_an_edit` is what the lens adds to a keystroke.
#[divan::bench(sample_count = 20)]
fn recheck_then_inlay_hints(bencher: Bencher) {
    let mut s = setup();
    let range = screen(&s);
    let mut version = 1;
    bencher.bench_local(|| {
        version += 1;
        black_box(s.engine.change(&s.task, version, vec![retyped(&s)]));
        black_box(s.engine.inlay_hints(&s.task, range))
    });
}

#[divan::bench(sample_count = 20)]
fn inlay_hints_of_the_whole_file(bencher: Bencher) {
    let s = setup();
    let whole = Range::new(Position::new(0, 0), Position::new(u32::MAX, 0));
    bencher.bench_local(|| black_box(s.engine.inlay_hints(&s.task, whole)));
}

#[divan::bench(sample_count = 100)]
fn workspace_symbols(bencher: Bencher) {
    let s = setup();
    assert!(!s.engine.workspace_symbols("käännös4").is_empty());
    bencher.bench_local(|| black_box(s.engine.workspace_symbols("käännös4")));
}

#[divan::bench(sample_count = 100)]
fn document_highlights(bencher: Bencher) {
    let s = setup();
    let at = Position::new(s.middle, 20);
    assert!(!s.engine.document_highlights(&s.task, at).is_empty());
    bencher.bench_local(|| black_box(s.engine.document_highlights(&s.task, at)));
}
