//! The experiments' harness (`ilmr_experiments::harness`) for these tests: the VM
//! configured as `ilmrc run` configures it, tasks compiled from `examples/` or
//! assembled over `ModuleBuilder`, runs and their measures. The harness returns its
//! errors (a missing file, a task that does not compile); here they fail the test.
#![allow(dead_code, unused_imports)]

use ilmr_experiments::harness as h;
use ilmr_model::RobotModel;
use ilmr_sim::{SimRobot, World};
use ilmr_vm::Module;

pub use h::{
    A, Run, SimVm, Task, distance_to_polyline, ended, examples, length, linked_ends, mean_std, run,
    run_watched, speed, vm_config,
};

fn ok<T>(r: Result<T, String>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

pub fn compile_example(file: &str, model: &RobotModel) -> Module {
    ok(h::compile_example(file, model))
}

pub fn compile(name: &str, text: &str, model: &RobotModel) -> Module {
    ok(h::compile(name, text, model))
}

/// A world of `tests/worlds/` by file name.
pub fn world(file: &str) -> World {
    ok(h::world(file))
}

pub fn shipped(name: &str) -> World {
    ok(h::shipped(name))
}

pub fn moro(world: World, seed: u64) -> SimRobot {
    ok(h::moro(world, seed))
}

/// MoRo with `profile`'s errors.
pub fn moro_with(world: World, seed: u64, profile: ilmr_sim::SimProfile) -> SimRobot {
    ok(h::moro_with(world, seed, profile))
}

pub fn workpartner(world: World, seed: u64) -> SimRobot {
    ok(h::workpartner(world, seed))
}

pub fn vm(module: Module, robot: SimRobot) -> SimVm {
    ok(h::vm(module, robot))
}
