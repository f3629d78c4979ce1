//! `check_cost` on the system allocator, so that valgrind's heap tools see every
//! allocation: `valgrind --tool=dhat target/release/examples/check_heap /tmp/bc/task.ilmr /tmp/bc/skills.ilms`.

use ilmr_compiler::check::{Detail, Source, analyze_with};

fn main() -> std::process::ExitCode {
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
