//! `check_cost` on the system allocator, so that valgrind's heap tools see every
//! allocation: `valgrind --tool=dhat target/release/examples/check_heap /tmp/bc/task.ilmr /tmp/bc/skills.ilms`.

#[path = "support/check.rs"]
mod check;

fn main() -> std::process::ExitCode {
    check::run()
}
