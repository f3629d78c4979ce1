//! The ILMR side of `tools/blocks_vs_lua.sh`: the counting-blocks task of issue 14
//! (`benches/blocks.rs`, each block `cN=0` / `while(cN<100)` / `cN=cN+1` /
//! `wait(0.01)` / `endwhile`) checked and lowered by the real compiler, then ticked by
//! the VM as `ilmrc run --robot none` would, but in process: a task of 1,000,000 blocks
//! is 71 MB, past the 8 MiB `ilmrc` reads from a file. The budget is unlimited (the
//! workload would otherwise overrun `--robot none`'s budget past 6,000 blocks) and the
//! trace is off, as for a run without `--trace`.
//!
//! `cargo run --release -p ilmr-compiler --example blocks_run -- N TICKS` prints one
//! line: `ilmr N ns_per_step bytes_per_block wall_ns_per_step`, ns_per_step the time
//! on the CPU (Lua's `os.clock` in `tools/blocks.lua` reads the same), the bytes being the VM's run-time state
//! (`Vm::footprint`: nodes, variables, queues, timers) over the blocks, after the timed
//! ticks; the module (the program's code) is not counted, as Lua's function is not. A step is one
//! block's tick: wake from `wait`, `cN=cN+1`, the `while` re-evaluated, `wait` again.
//! The timed ticks are all within the 100 iterations, so every block steps in each.

use std::time::Instant;

use ilmr_compiler::FileId;
use ilmr_compiler::check::{Source, analyze};
use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_vm::{Config, SimClock, TraceLevel, Vm};

#[path = "../benches/blocks.rs"]
mod blocks;

// The allocator `ilmrc` uses, so that the figures are its.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.replace('_', "").parse().ok())
        .collect();
    let (n, ticks) = match args[..] {
        [n, ticks] if n > 0 && (1..=95).contains(&ticks) => (n, ticks),
        _ => {
            eprintln!("usage: blocks_run BLOCKS TICKS (TICKS 1 to 95: a block counts to 100)");
            std::process::exit(2);
        }
    };
    let model = ilmr_model::RobotModel::builtin("moro").expect("shipped model");
    let module = {
        let sources = [Source::new("blocks.ilmr", blocks::generate(n))];
        let analysis = analyze(&sources, &model);
        assert!(!analysis.has_errors());
        ilmr_compiler::lower::lower(&analysis, &model, FileId(0)).expect("lowers")
    };
    let cfg = Config {
        trace: TraceLevel::Off,
        budget_ops: u32::MAX,
        ..Config::default()
    };
    let robot = ScriptedRobot::new(Limits::default());
    let mut vm = Vm::new(module, robot, SimClock, cfg).expect("valid");
    // The first tick runs `cN=0` and starts every loop; the second is the first
    // ordinary step.
    vm.tick();
    vm.tick();
    let start = Instant::now();
    let cpu_start = cpu_ns();
    for _ in 0..ticks {
        vm.tick();
    }
    let cpu = cpu_ns().zip(cpu_start).map(|(b, a)| b.saturating_sub(a));
    let elapsed = start.elapsed();
    let live = vm.live();
    assert!(live >= n, "{live} live nodes for {n} blocks");
    // A step is only a step if it counted: every block has added one per tick, the two
    // untimed ticks included, so the figure below divides by work that was done.
    let mut counters = 0;
    for (global, var) in vm.globals() {
        let name = &global.name;
        assert_eq!(var.value, ticks as f64 + 2.0, "{name} after {ticks} ticks");
        counters += 1;
    }
    assert_eq!(counters, n, "one counter per block");
    let steps = ticks as f64 * n as f64;
    let wall = elapsed.as_secs_f64() * 1e9 / steps;
    // The time on the CPU, the clock `tools/blocks.lua` reads (`os.clock`): on a
    // machine shared by other builds the wall clock also counts the time others ran.
    // The process's clock, as Lua's: the VM runs on this one thread.
    let per_step = cpu.map_or(wall, |c| c as f64 / steps);
    println!(
        "ilmr {n} {per_step:.1} {:.0} {wall:.1}",
        vm.footprint() as f64 / n as f64
    );
    // Where the bytes go, for docs/performance.md (BLOCKS_PARTS=1).
    if std::env::var_os("BLOCKS_PARTS").is_some() {
        for (part, bytes) in vm.footprint_parts() {
            eprintln!("{part}: {:.1} bytes per block", bytes as f64 / n as f64);
        }
    }
}

/// Nanoseconds this process has run on a CPU: `CLOCK_PROCESS_CPUTIME_ID`, what C's
/// `clock()` and so Lua's `os.clock` read. (`/proc/thread-self/schedstat` counted in
/// scheduler ticks here: 0.0 and 13.3 ns per step for the same 10,000-block run.)
fn cpu_ns() -> Option<u64> {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec for the call's duration.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    if rc != 0 {
        return None;
    }
    Some(u64::try_from(t.tv_sec).ok()? * 1_000_000_000 + u64::try_from(t.tv_nsec).ok()?)
}
