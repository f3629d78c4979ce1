//! What `ilmrc check FILE...` does short of rendering (read, lex, parse, check against
//! MoRo; the analysis left to the OS at exit; mimalloc), for counting instructions
//! without building the whole toolchain:
//! `valgrind --tool=callgrind target/release/examples/check_cost /tmp/bc/task.ilmr /tmp/bc/skills.ilms`.

use ilmr_compiler::check::{Detail, Source, analyze_with};

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

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
