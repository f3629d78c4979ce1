//! Lowering a checked task to bytecode, at two sizes of the counting-blocks task
//! (`blocks.rs`): linear lowering takes ten times as long for ten times the blocks, a
//! search per variable a hundred times (issue 14: 51 s at 100,000 blocks). The full
//! analysis the lowering reads is measured beside it, since `ilmrc build` does both.
//! Run with `cargo bench -p ilmr-compiler --bench lower`.

mod blocks;

use divan::{Bencher, black_box, counter::ItemsCount};
use ilmr_compiler::FileId;
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::lower::lower;
use ilmr_model::RobotModel;

fn main() {
    divan::main();
}

const SIZES: [usize; 2] = [10_000, 100_000];

#[divan::bench(args = SIZES, sample_count = 5)]
fn lower_blocks(bencher: Bencher, n: usize) {
    let task = blocks::generate(n);
    let sources = [Source::new("blocks.ilmr", task)];
    let model = RobotModel::builtin("moro").expect("shipped model");
    let analysis = analyze(&sources, &model);
    assert!(!analysis.has_errors());
    // The analysis shares its tables by `Rc`: one thread.
    bencher.counter(ItemsCount::new(n)).bench_local(|| {
        lower(black_box(&analysis), &model, FileId(0))
            .map(|m| m.code.len())
            .expect("the task lowers")
    });
}

#[divan::bench(args = SIZES, sample_count = 5)]
fn analyze_blocks(bencher: Bencher, n: usize) {
    let task = blocks::generate(n);
    let sources = [Source::new("blocks.ilmr", task)];
    let model = RobotModel::builtin("moro").expect("shipped model");
    bencher
        .counter(ItemsCount::new(n))
        .bench(|| analyze(black_box(&sources), &model).diagnostics.len());
}
