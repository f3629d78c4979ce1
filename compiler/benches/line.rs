//! Requirement 6: text to a running command. One interactive line is parsed, checked
//! against the live task, lowered, joined to the running VM and started by one tick.
//! The bar is 50 microseconds. Run with `cargo bench -p ilmr-compiler --bench line`.

use divan::{Bencher, black_box};
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::lower::{LineOptions, lower, lower_line, lower_line_into};
use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_model::RobotModel;
use ilmr_vm::{Config, SimClock, TraceLevel, Vm};

fn main() {
    divan::main();
}

const TASK: &str = include_str!("../../examples/fetch_boxes.ilmr");
const SKILLS: &str = include_str!("../../examples/skills/boxes.ilms");

/// Figure 20 running for two seconds on the scripted robot.
fn running(model: &RobotModel) -> Vm<ScriptedRobot, SimClock> {
    let sources = [
        Source::new("fetch_boxes.ilmr", TASK),
        Source::library("boxes.ilms", SKILLS),
    ];
    let analysis = analyze(&sources, model);
    let module = lower(&analysis, model, ilmr_compiler::FileId(0)).expect("figure 20 lowers");
    let robot = ScriptedRobot::new(Limits::default()).battery(0.0, 25.0);
    let config = Config {
        trace: TraceLevel::Off,
        ..Config::default()
    };
    let mut vm = Vm::new(module, robot, SimClock, config).expect("valid module");
    vm.run_for(2.0);
    vm
}

fn text_to_running(bencher: Bencher, line: &str) {
    let model = RobotModel::builtin("workpartner").expect("shipped model");
    bencher
        .with_inputs(|| running(&model))
        .bench_local_values(|mut vm| {
            vm.add_line(|b| lower_line_into(black_box(line), b, &model, LineOptions::default()))
                .map_err(|_| "the line checks and joins")
                .expect("the line joins the task");
            vm.tick();
            vm
        });
}

#[divan::bench]
fn a_command(bencher: Bencher) {
    text_to_running(bencher, "speed(0.2)");
}

#[divan::bench]
fn a_guard_on_live_variables(bencher: Bencher) {
    text_to_running(
        bencher,
        "if(Turns >= 1)\n    Battery2 = sensor(battery)\nendif",
    );
}

/// The parts, to tell where the time goes.
#[divan::bench]
fn lower_line_only(bencher: Bencher) {
    let model = RobotModel::builtin("workpartner").expect("shipped model");
    let vm = running(&model);
    bencher.bench_local(|| {
        lower_line(
            black_box("speed(0.2)"),
            vm.module(),
            &model,
            LineOptions::default(),
        )
        .expect("the line checks")
    });
}
