//! Fuzzing of everything `ilmrc` reads from outside: task and skill files, ROBO.INI
//! robot models, world files, `.ilmb` modules, `serve` request lines, traces (with
//! recorded inputs), test files, scenarios and fleet files. Each target must never
//! panic and must answer bad input with an error value.
//!
//! `cargo test --test fuzz` runs a fixed, seeded number of inputs per target (CI).
//! For a longer hunt (see tests/fuzz/README.md):
//!
//! ```sh
//! ILMR_FUZZ_SECS=600 ILMR_FUZZ_SEED=7 cargo test --release --test fuzz -- --nocapture
//! ```
//!
//! The compiler's own `never_panics.rs` throws token soup and random text at the
//! parser; these targets start from real files and keep their structure, so inputs
//! get past the parser into the checker, the lowering, the VM and the model loader.

mod engine;
mod mutate;
mod pipeline;
mod targets;
#[path = "../support/taskgen.rs"]
mod taskgen;

use engine::{Budget, on_compiler_stack};

#[test]
fn task_files_never_panic() {
    let stats = on_compiler_stack(|| targets::tasks::fuzz(Budget::from_env(300)));
    assert!(stats.corpus >= 10, "{stats:?}");
}

#[test]
fn skill_files_never_panic() {
    let stats = on_compiler_stack(|| targets::skills::fuzz(Budget::from_env(250)));
    assert!(stats.corpus >= 3, "{stats:?}");
}

#[test]
fn robot_models_never_panic() {
    let stats = on_compiler_stack(|| targets::models::fuzz(Budget::from_env(100)));
    assert!(stats.corpus >= 3, "{stats:?}");
}

#[test]
fn world_files_are_run_or_refused_with_their_line() {
    let stats = on_compiler_stack(|| targets::worlds::fuzz(Budget::from_env(2_000)));
    assert!(stats.corpus >= 5, "{stats:?}");
}

#[test]
fn bytecode_modules_are_checked_before_they_run() {
    let stats = on_compiler_stack(|| targets::modules::fuzz(Budget::from_env(1000)));
    assert!(stats.corpus >= 10, "{stats:?}");
}

#[test]
fn serve_requests_are_answered() {
    let stats = on_compiler_stack(|| targets::requests::fuzz(Budget::from_env(5000)));
    assert!(stats.corpus >= 5, "{stats:?}");
}

#[test]
fn traces_and_recorded_inputs_are_read_or_refused() {
    let stats = on_compiler_stack(|| targets::traces::fuzz(Budget::from_env(20_000)));
    assert!(stats.corpus >= 10, "{stats:?}");
}

#[test]
fn test_files_are_read_or_refused_with_their_places() {
    let stats = on_compiler_stack(|| targets::testfiles::fuzz(Budget::from_env(1_500)));
    assert!(stats.corpus >= 10, "{stats:?}");
}

#[test]
fn scenarios_are_read_or_refused_with_their_line() {
    let stats = on_compiler_stack(|| targets::scenarios::fuzz(Budget::from_env(1_000)));
    assert!(stats.corpus >= 5, "{stats:?}");
}

#[test]
fn fleet_files_are_read_or_refused_with_their_line() {
    let stats = on_compiler_stack(|| targets::fleets::fuzz(Budget::from_env(20_000)));
    assert!(stats.corpus >= 5, "{stats:?}");
}

#[test]
fn the_module_loader_says_what_is_wrong() {
    on_compiler_stack(targets::modules::errors_are_clear);
}
