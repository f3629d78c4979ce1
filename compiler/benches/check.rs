//! `check` of a generated 100,000-line program with skills, ifs and whiles; figures in
//! docs/performance.md. Run with `cargo bench -p ilmr-compiler --bench check`.

mod corpus;

use divan::{Bencher, black_box, counter::ItemsCount};
use ilmr_compiler::check::{Detail, Source, analyze_with};
use ilmr_model::RobotModel;

fn main() {
    divan::main();
}

/// What `ilmrc check` does: the diagnostics, without the resolutions the language
/// server and the lowering read.
#[divan::bench(sample_count = 10)]
fn check_100k_lines(bencher: Bencher) {
    analyze_corpus(bencher, Detail::Diagnostics);
}

/// The full analysis the language server keeps.
#[divan::bench(sample_count = 10)]
fn analyze_100k_lines(bencher: Bencher) {
    analyze_corpus(bencher, Detail::Full);
}

fn analyze_corpus(bencher: Bencher, detail: Detail) {
    let corpus = corpus::generate(100_000);
    let sources = [
        Source::new("task.ilmr", corpus.task.clone()),
        Source::new("skills.ilms", corpus.skills.clone()),
    ];
    let model = RobotModel::builtin("moro").unwrap();
    let analysis = analyze_with(&sources, &model, detail);
    assert!(
        !analysis.has_errors(),
        "{:?}",
        &analysis.diagnostics[..3.min(analysis.diagnostics.len())]
    );
    drop(analysis);
    bencher.counter(ItemsCount::new(corpus.lines)).bench(|| {
        analyze_with(black_box(&sources), &model, detail)
            .diagnostics
            .len()
    });
}

#[divan::bench(sample_count = 10)]
fn parse_100k_lines(bencher: Bencher) {
    let corpus = corpus::generate(100_000);
    bencher.counter(ItemsCount::new(corpus.lines)).bench(|| {
        ilmr_compiler::parser::parse(black_box(&corpus.task), ilmr_compiler::FileId(0))
            .diagnostics
            .len()
    });
}

#[divan::bench(sample_count = 10)]
fn lex_100k_lines(bencher: Bencher) {
    let corpus = corpus::generate(100_000);
    bencher.counter(ItemsCount::new(corpus.lines)).bench(|| {
        ilmr_compiler::lexer::lex(black_box(&corpus.task))
            .tokens
            .len()
    });
}

/// Each statement's moment (`check::schedule`, the language server's concurrency
/// lens), read from an analysis already made, at 10,000 and 100,000 lines: linear.
#[divan::bench(sample_count = 10, args = [10_000, 100_000, 400_000])]
fn schedule_of_the_task(bencher: Bencher, lines: usize) {
    let corpus = corpus::generate(lines);
    let sources = [
        Source::new("task.ilmr", corpus.task.clone()),
        Source::new("skills.ilms", corpus.skills.clone()),
    ];
    let model = RobotModel::builtin("moro").unwrap();
    let analysis = analyze_with(&sources, &model, Detail::Full);
    let task = ilmr_compiler::FileId(0);
    assert!(!ilmr_compiler::check::schedule::schedule(&analysis, &model, task).is_empty());
    // The analysis holds `Rc`s: measured on this thread.
    bencher
        .counter(ItemsCount::new(corpus.lines))
        .bench_local(|| {
            ilmr_compiler::check::schedule::schedule(black_box(&analysis), &model, task).len()
        });
}
