//! What `ilmrc check FILE...` does short of rendering: read, lex, parse, check against
//! MoRo, and leave the analysis to the OS at exit. Shared by `check_cost` (mimalloc, as
//! `ilmrc`) and `check_heap` (the system allocator, for valgrind's heap tools).

use ilmr_compiler::check::{Detail, Source, analyze_with};

pub fn run() -> std::process::ExitCode {
    let model = ilmr_model::RobotModel::builtin("moro").expect("MoRo ships with the toolchain");
    let mut sources = Vec::new();
    for path in std::env::args().skip(1) {
        match std::fs::read_to_string(&path) {
            Ok(text) => sources.push(Source::new(path, text)),
            Err(e) => {
                eprintln!("cannot read `{path}`: {e}");
                return std::process::ExitCode::from(2);
            }
        }
    }
    let analysis = analyze_with(&sources, &model, Detail::Diagnostics);
    let errors = analysis.diagnostics.iter().filter(|d| d.is_error()).count();
    println!(
        "{} file(s): {errors} error(s), {} diagnostic(s)",
        sources.len(),
        analysis.diagnostics.len()
    );
    std::mem::forget(analysis);
    std::mem::forget(sources);
    std::process::ExitCode::from(u8::from(errors > 0))
}
