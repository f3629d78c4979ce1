//! AFL++ targets for everything `ilmrc` reads from outside. The targets are the seeded
//! loop's (`tests/fuzz/targets/`), compiled in by path, so that both engines feed the
//! same code the same way: one binary per target in `src/bin/`, and `seeds`, which
//! writes the seed corpora and the dictionaries (see `fuzz/README.md`).

#[path = "../../tests/fuzz/engine.rs"]
pub mod engine;
#[path = "../../tests/fuzz/mutate.rs"]
pub mod mutate;
#[path = "../../tests/fuzz/pipeline.rs"]
pub mod pipeline;
#[path = "../../tests/fuzz/targets/mod.rs"]
pub mod targets;
#[path = "../../tests/support/taskgen.rs"]
pub mod taskgen;

pub mod seeds;

/// Feeds AFL++'s inputs to `target`, each on a thread with the compiler's stack (as
/// `ilmrc` checks and lowers), so that a deep input overflows here exactly when it
/// would in the tool. A panic aborts the process: AFL++ records the input as a crash.
pub fn fuzz(target: impl Fn(&[u8]) + Sync + std::panic::RefUnwindSafe) {
    afl::fuzz!(|data: &[u8]| {
        engine::on_compiler_stack(|| target(data));
    });
}
