//! Writes the benchmark corpus to a directory, for measuring `ilmrc check` and
//! `luac5.4 -p` side by side: `cargo run --release -p ilmr-compiler --example bench_corpus DIR`.

#[path = "../benches/corpus.rs"]
mod corpus;

fn main() -> std::io::Result<()> {
    let dir = std::path::PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "bench-corpus".into()),
    );
    std::fs::create_dir_all(&dir)?;
    let c = corpus::generate(100_000);
    std::fs::write(dir.join("task.ilmr"), &c.task)?;
    std::fs::write(dir.join("skills.ilms"), &c.skills)?;
    std::fs::write(dir.join("task.lua"), &c.lua)?;
    println!(
        "{} lines of ILMR, {} of Lua in {}",
        c.lines,
        c.lua.lines().count(),
        dir.display()
    );
    Ok(())
}
