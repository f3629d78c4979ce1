//! A whole run of Figure 52 among walls: the VM and the simulator (scanner on)
//! together, in the office.

use ilmr_sim::{Pose, SimRobot};
use ilmr_vm::{Config, SimClock, Vm};

fn main() {
    divan::main();
}

fn office() -> ilmr_sim::World {
    ilmr_experiments::harness::shipped("office").unwrap_or_else(|e| panic!("{e}"))
}

/// Figure 52's task compiled for MoRo, as `ilmrc run` compiles it.
fn figure_52() -> ilmr_vm::Module {
    use ilmr_compiler::check::{Source, analyze};
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/short_task.ilmr");
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => panic!("{path}: {e}"),
    };
    let Some(model) = ilmr_model::RobotModel::builtin("moro") else {
        panic!("MoRo's model ships with the crate");
    };
    let sources = [Source::new("examples/short_task.ilmr", text)];
    let analysis = analyze(&sources, &model);
    match ilmr_compiler::lower::lower(&analysis, &model, ilmr_compiler::FileId(0)) {
        Ok(m) => m,
        Err(d) => panic!("the task does not compile: {d:?}"),
    }
}

/// The whole of Figure 52 (26.55 s simulated, 2,655 ticks) on MoRo in the
/// office from (8, 5, 0 deg), where `ilmrc run` starts it: every tick of the
/// VM (map, avoider, supervisor's checks among the walls) and of the
/// simulator (a 361-beam scan at 4 Hz). Simulated seconds over this time is
/// the real-time factor.
#[divan::bench(sample_count = 10, sample_size = 1)]
fn whole_run_figure_52_office(b: divan::Bencher) {
    let module = figure_52();
    b.with_inputs(|| {
        let mut world = office();
        world.start = Pose::new(8.0, 5.0, 0.0);
        let robot = match SimRobot::moro(world, 0) {
            Ok(r) => r,
            Err(e) => panic!("{e}"),
        };
        let config = Config::for_robot(robot.model(), Some(robot.sim().config().offsets()));
        match Vm::new(module.clone(), robot, SimClock, config) {
            Ok(vm) => vm,
            Err(e) => panic!("{e}"),
        }
    })
    .bench_local_values(|mut vm| {
        while !vm.finished() && vm.ticks() < 6_000 {
            vm.tick();
        }
        assert!(vm.finished(), "the task ends within a minute");
        vm
    });
}
