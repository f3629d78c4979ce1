//! A fixed number of ticks of one benchmark program, for instruction counts that a
//! loaded machine does not disturb:
//!
//! ```text
//! cargo bench -p ilmr-vm --bench ticks --no-run
//! valgrind --tool=callgrind --toggle-collect='*Vm*tick*' \
//!     target/release/deps/ticks-HASH guards 1000000 10
//! ```
//!
//! Arguments: shape (`searches`, `guards`, `sleepers`, `counting`), live commands, ticks. Setup
//! (building the program and the three settling ticks) runs before the counted ticks;
//! with `--toggle-collect` on `tick` callgrind counts only ticks, so instructions per
//! command per tick = (Ir - 3 settling ticks' Ir) / ticks / n; the difference of two
//! runs with different tick counts removes setup exactly.

#[path = "shapes.rs"]
mod shapes;
use shapes::{Shape, vm};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shape = match args.first().map(String::as_str) {
        Some("searches") => Shape::Searches,
        Some("guards") => Shape::Guards,
        Some("sleepers") => Shape::Sleepers,
        Some("counting") => Shape::Counting,
        // `cargo bench` runs every bench target with `--bench`: nothing to count then.
        _ => return,
    };
    let number = |i: usize, default: usize| {
        args.get(i)
            .and_then(|s| s.replace('_', "").parse().ok())
            .unwrap_or(default)
    };
    let (n, ticks) = (number(1, 1_000), number(2, 10));
    let mut vm = vm(shape, n);
    for _ in 0..ticks {
        vm.tick();
    }
    println!(
        "{n} commands, {ticks} ticks, {} live nodes after, {:.1} bytes per live node",
        vm.live(),
        vm.footprint() as f64 / vm.live().max(1) as f64
    );
}
