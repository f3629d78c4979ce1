//! Times what `ilmrc check` and `ilmrc build` do, in process, on the counting-blocks
//! task (`benches/blocks.rs`) of each size given: check is the analysis `check` asks for
//! (`Detail::Diagnostics`); build is the full analysis, the lowering and the `.ilmb`
//! encoding. In process, because a task past 1,000,000 lines is larger than the 8 MiB
//! `ilmrc` reads from a file (`MAX_SOURCE_BYTES`). Fastest of three runs each:
//! `cargo run --release -p ilmr-compiler --example build_cost 10000 100000 1000000`.

use std::time::{Duration, Instant};

use ilmr_compiler::FileId;
use ilmr_compiler::check::{Detail, Source, analyze, analyze_with};

#[path = "../benches/blocks.rs"]
mod blocks;

// The allocator `ilmrc` uses, so that the figures are its.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn fastest(mut f: impl FnMut()) -> Duration {
    (0..3)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .min()
        .unwrap_or_default()
}

fn main() {
    let model = ilmr_model::RobotModel::builtin("moro").expect("shipped model");
    println!(
        "| blocks | lines | check | build | build / check | of which full analysis | lowering | encoding | .ilmb bytes |"
    );
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for arg in std::env::args().skip(1) {
        let Ok(n) = arg.parse::<usize>() else {
            eprintln!("usage: build_cost N...");
            std::process::exit(2);
        };
        let sources = [Source::new("blocks.ilmr", blocks::generate(n))];
        let check = fastest(|| {
            let a = analyze_with(&sources, &model, Detail::Diagnostics);
            assert!(!a.has_errors());
        });
        let mut bytes = 0;
        let build = fastest(|| {
            let a = analyze(&sources, &model);
            let m = ilmr_compiler::lower::lower(&a, &model, FileId(0)).expect("lowers");
            bytes = m.to_bytes().len();
        });
        let full = fastest(|| {
            analyze(&sources, &model);
        });
        let analysis = analyze(&sources, &model);
        let lower = fastest(|| {
            ilmr_compiler::lower::lower(&analysis, &model, FileId(0)).expect("lowers");
        });
        let module = ilmr_compiler::lower::lower(&analysis, &model, FileId(0)).expect("lowers");
        let encode = fastest(|| {
            module.to_bytes();
        });
        let ms = |d: Duration| format!("{:.1} ms", d.as_secs_f64() * 1e3);
        println!(
            "| {n} | {} | {} | {} | {:.2} | {} | {} | {} | {bytes} |",
            n * 6,
            ms(check),
            ms(build),
            build.as_secs_f64() / check.as_secs_f64(),
            ms(full),
            ms(lower),
            ms(encode),
        );
    }
}
