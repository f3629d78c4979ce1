//! `check` of a generated 100,000-line program with skills, ifs and whiles; figures in
//! docs/performance.md. Run with `cargo bench -p ilmr-compiler`.

mod corpus;

use divan::{Bencher, black_box, counter::ItemsCount};
use ilmr_compiler::check::{Source, analyze};
use ilmr_model::RobotModel;

fn main() {
    divan::main();
}

#[divan::bench(sample_count = 10)]
fn check_100k_lines(bencher: Bencher) {
    let corpus = corpus::generate(100_000);
    let sources = [
        Source::new("task.ilmr", corpus.task.clone()),
        Source::new("skills.ilms", corpus.skills.clone()),
    ];
    let model = RobotModel::builtin("moro").unwrap();
    let analysis = analyze(&sources, &model);
    assert!(
        !analysis.has_errors(),
        "{:?}",
        &analysis.diagnostics[..3.min(analysis.diagnostics.len())]
    );
    drop(analysis);
    bencher
        .counter(ItemsCount::new(corpus.lines))
        .bench(|| analyze(black_box(&sources), &model).diagnostics.len());
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
