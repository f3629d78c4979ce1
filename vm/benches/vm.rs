//! Cost of a tick per live command. Run in release: `cargo bench -p ilmr-vm`.
//!
//! The programs are in `shapes.rs`; `ticks.rs` runs them a fixed number of ticks for
//! callgrind.
//!
//! Divan prints the time of one tick; its throughput column is live commands stepped
//! per second, so ns per command step = 1e9 / throughput. Bytes per live command are
//! printed before the benchmarks.

use divan::{Bencher, counter::ItemsCount};

#[path = "shapes.rs"]
mod shapes;
use shapes::{Shape, vm};

const SIZES: [usize; 4] = [10, 1_000, 100_000, 1_000_000];

fn run(bencher: Bencher, shape: Shape, n: usize) {
    let mut vm = vm(shape, n);
    bencher
        .counter(ItemsCount::new(n))
        .bench_local(|| vm.tick());
}

#[divan::bench(args = SIZES, sample_count = 30)]
fn searches(bencher: Bencher, n: usize) {
    run(bencher, Shape::Searches, n);
}

#[divan::bench(args = SIZES, sample_count = 30)]
fn guards(bencher: Bencher, n: usize) {
    run(bencher, Shape::Guards, n);
}

#[divan::bench(args = SIZES, sample_count = 30)]
fn sleepers(bencher: Bencher, n: usize) {
    run(bencher, Shape::Sleepers, n);
}

/// Issue 14's general path: a block steps each tick (wake, `cN=cN+1`, the `while`
/// re-evaluated, `wait` again).
#[divan::bench(args = SIZES, sample_count = 30)]
fn counting(bencher: Bencher, n: usize) {
    run(bencher, Shape::Counting, n);
}

fn main() {
    println!("bytes per live command (runtime state / live nodes):");
    for shape in [
        ("searches", Shape::Searches),
        ("guards", Shape::Guards),
        ("sleepers", Shape::Sleepers),
        ("counting", Shape::Counting),
    ] {
        let vm = vm(shape.1, 100_000);
        println!(
            "  {:<9} {:>6.1}",
            shape.0,
            vm.footprint() as f64 / vm.live() as f64
        );
    }
    divan::main();
}
