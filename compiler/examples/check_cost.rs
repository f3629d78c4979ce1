//! What `ilmrc check FILE...` does short of rendering (read, lex, parse, check against
//! MoRo; the analysis left to the OS at exit; mimalloc), for counting instructions
//! without building the whole toolchain:
//! `valgrind --tool=callgrind target/release/examples/check_cost /tmp/bc/task.ilmr /tmp/bc/skills.ilms`.

#[path = "support/check.rs"]
mod check;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    check::run()
}
