//! Times the front end's phases on a file: `cargo run --release -p ilmr-compiler --example phases FILE...`.
use std::time::Instant;
fn main() {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    let texts: Vec<String> = paths
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    let model = ilmr_model::RobotModel::builtin("moro").unwrap();
    for _ in 0..3 {
        let t = Instant::now();
        let lexed = ilmr_compiler::lexer::lex(&texts[0]);
        let lex = t.elapsed();
        drop(lexed);
        let t = Instant::now();
        let parsed = ilmr_compiler::parser::parse(&texts[0], ilmr_compiler::FileId(0));
        let parse = t.elapsed();
        drop(parsed);
        let sources: Vec<_> = paths
            .iter()
            .zip(&texts)
            .map(|(p, t)| ilmr_compiler::check::Source::new(p.clone(), t.clone()))
            .collect();
        let t = Instant::now();
        let a = ilmr_compiler::check::analyze(&sources, &model);
        let check = t.elapsed();
        println!(
            "lex {lex:?} parse {parse:?} analyze(all) {check:?} diags {}",
            a.diagnostics.len()
        );
    }
}
