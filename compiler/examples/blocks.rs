//! Writes the task of N counting blocks (`benches/blocks.rs`) to stdout, for timing
//! `ilmrc check` and `ilmrc build` on it (`tools/lower_scaling.sh`):
//! `cargo run --release -p ilmr-compiler --example blocks 100000 > blocks.ilmr`.

use std::io::Write;

#[path = "../benches/blocks.rs"]
mod blocks;

fn main() {
    let Some(n) = std::env::args()
        .nth(1)
        .and_then(|a| a.parse::<usize>().ok())
    else {
        eprintln!("usage: blocks N");
        std::process::exit(2);
    };
    let task = blocks::generate(n);
    if let Err(e) = std::io::stdout().lock().write_all(task.as_bytes()) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}
