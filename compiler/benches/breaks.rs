//! `break(pattern)` among many live blocks: `n` counting blocks (`blocks.rs`) and a
//! block of `n` breaks, run for the tick that runs the breaks. Patterns found only in
//! breaks (`zz0`, `zz1`, ...) end nothing and look at no node; a pattern found in a
//! statement that runs but is not live looks at every node once per break, so that
//! shape grows as blocks x breaks. Both read every live node's text at every break
//! before (20,000 of each: 9.5 s of a 0.5 s run; docs/performance.md).
//! Run with `cargo bench -p ilmr-compiler --bench breaks`.

mod blocks;

use divan::{Bencher, counter::ItemsCount};
use ilmr_compiler::FileId;
use ilmr_compiler::check::{Source, analyze};
use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_vm::{Config, SimClock, TraceLevel, Vm};

fn main() {
    divan::main();
}

const SIZES: [usize; 2] = [2_000, 20_000];

fn task(n: usize, pattern: impl Fn(usize) -> String) -> ilmr_vm::Module {
    let mut text = blocks::generate(n);
    for i in 0..n {
        text.push_str(&format!("break({})\n", pattern(i)));
    }
    text.push_str("later=1\n");
    let model = ilmr_model::RobotModel::builtin("moro").expect("shipped model");
    let sources = [Source::new("breaks.ilmr", text)];
    let analysis = analyze(&sources, &model);
    assert!(!analysis.has_errors());
    ilmr_compiler::lower::lower(&analysis, &model, FileId(0)).expect("lowers")
}

fn run(bencher: Bencher, n: usize, module: ilmr_vm::Module) {
    let cfg = Config {
        trace: TraceLevel::Off,
        budget_ops: u32::MAX,
        ..Config::default()
    };
    bencher
        .counter(ItemsCount::new(n))
        .with_inputs(|| {
            let robot = ScriptedRobot::new(Limits::default());
            Vm::new(module.clone(), robot, SimClock, cfg).expect("valid")
        })
        // The first tick starts the loops and runs every break.
        .bench_local_values(|mut vm| {
            vm.tick();
            vm.break_looks()
        });
}

#[divan::bench(args = SIZES, sample_count = 5)]
fn patterns_only_breaks_hold(bencher: Bencher, n: usize) {
    run(bencher, n, task(n, |i| format!("zz{i}")));
}

#[divan::bench(args = SIZES, sample_count = 5)]
fn a_pattern_of_a_statement_not_live(bencher: Bencher, n: usize) {
    run(bencher, n, task(n, |_| "later".to_string()));
}
